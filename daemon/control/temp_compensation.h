#pragma once
// Lead-acid charge-voltage temperature compensation (docs/batteries.md,
// docs/batteries.md; docs/sources.md P3.7.1: about -4 to -5 mV/degC per cell
// around 25 degC). Compensation changes the targets the stage machine and the
// voltage loop see, so telemetry target_v shows the compensated target.
#include "params/params.h"

namespace xr {

// Cells the coefficient is multiplied by: BatteryCells, else lead-acid cells
// of the voltage class (6 per 12 V): compensation is a lead-acid rule.
int compensationCells(const Params& p);

// The voltage added to the charge targets at tempC (NaN: 0, uncompensated).
// The temperature is clamped to TempCompMinC..TempCompMaxC.
double temperatureCompensationV(const Params& p, double tempC);

// The highest a compensated target may be: TEMP_COMP_TRIP_MARGIN_V under the
// lower of the hard-shutdown trip and the INA228 hardware limit.
double compensationCeilingV(const Params& p);

// p with BulkVoltage, AbsorptionVoltage and FloatVoltage moved by offsetV
// (each held under compensationCeilingV(p)). Everything else unchanged.
void compensateTargets(const Params& p, double offsetV, Params& out);

}  // namespace xr
