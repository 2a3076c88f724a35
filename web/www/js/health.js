// What the regulator has learned (docs/batteries.md "Measured capacity",
// "Internal resistance"; docs/operations.md "Alternator wear"): the Battery
// page's health table with the offer to use a measured capacity, and the
// Alternator page.
import { getJson } from "./api.js";
import { fToC, hminFromSeconds, isNum, plain } from "./format.js";
import { tempUnit } from "./live.js";
import { kvTable } from "./pages.js";
import { setParam } from "./settings.js";

const $ = (id) => document.getElementById(id);

// The capacity the owner set (BatteryCapacity_Ah), read when the Battery page opens.
let configuredAh = null;
let capacityRange = null;
export async function loadCapacitySetting() {
  const { params } = await getJson("/api/params");
  const p = params.find((x) => x.name === "BatteryCapacity_Ah");
  configuredAh = p && isNum(p.value) ? p.value : null;
  capacityRange = p && isNum(p.min) && isNum(p.max) ? { min: p.min, max: p.max } : null;
}

// A measured capacity more than 10 % away from the setting: say so and offer
// it, but only a value the set-up would take: within the parameter's range
// and within 0.3x-2x of the setting, as the daemon checks its stored ledger
// (store/ledger_check.h); anything else is a damaged measurement, not an offer.
export function capacityOffer(measuredAh, setAh, range = null) {
  if (!isNum(measuredAh) || !isNum(setAh) || setAh <= 0) return null;
  const off = (measuredAh - setAh) / setAh;
  if (Math.abs(off) <= 0.10) return null;
  if (measuredAh < 0.3 * setAh || measuredAh > 2 * setAh) return null;
  const useAh = Math.round(measuredAh);
  if (range && (useAh < range.min || useAh > range.max)) return null;
  return { useAh, pct: Math.round(off * 100) };
}

export function renderHealth(s) {
  const b = s.battery || {};
  const cycles = b.capacity_cycles || 0;
  const cap = isNum(s.capacity_measured_ah) ? `${plain(s.capacity_measured_ah, 0)} (from ${cycles} swings)`
    : cycles ? `measuring: ${cycles} swing so far, 2 needed` : "not measured yet: needs two swings of 30 % or more between known points";
  const r = isNum(s.battery_r_mohm) ? `${plain(s.battery_r_mohm, 2)} ± ${plain(s.battery_r_spread_mohm, 2)}`
    : `not measured yet (${b.battery_r_samples || 0} of 5 load steps seen)`;
  kvTable("health-table", [
    ["measured capacity (Ah)", cap],
    ["capacity set (Ah)", configuredAh === null ? "—" : plain(configuredAh, 0)],
    ["internal resistance at 25 °C (mΩ)", r],
  ]);
  const offer = capacityOffer(s.capacity_measured_ah, configuredAh, capacityRange);
  const el = $("capacity-offer");
  el.hidden = !offer;
  if (offer) {
    $("capacity-offer-text").textContent =
      `The bank measures ${offer.useAh} Ah over ${cycles} swings, ${Math.abs(offer.pct)} % ${offer.pct < 0 ? "less" : "more"} ` +
      `than the ${plain(configuredAh, 0)} Ah set. The state of charge and the time to empty count from the setting.`;
    $("capacity-use").textContent = `Use ${offer.useAh} Ah`;
    $("capacity-use").dataset.ah = offer.useAh;
  }
}

export async function useMeasuredCapacity() {
  const ah = Number($("capacity-use").dataset.ah);
  if (!isNum(ah)) return;
  await setParam("BatteryCapacity_Ah", ah);
  await loadCapacitySetting();
}

// The regulator counts the bands at these sensor temperatures in °F; in °C
// they read rounded to 5 (65.6, 79.4, 93.3, 107.2 -> 65, 80, 95, 105), the
// numbers an owner thinks in (docs/operations.md "Alternator wear").
const BANDS = [150, 175, 200, 225];
export const bandLabel = (f, unit) => (unit === "F" ? `${f} °F` : `${Math.round(fToC(f) / 5) * 5} °C`);
export function renderAlternator(s, unit = tempUnit()) {
  const rows = [
    ["running", hminFromSeconds((s.alt_run_hours || 0) * 3600)],
    ...BANDS.map((f) => [`at or above ${bandLabel(f, unit)}`, hminFromSeconds((s[`alt_hours_above_${f}f`] || 0) * 3600)]),
    ["insulation life used (%)", plain(s.alt_life_used_pct, 3)],
    ["belt slips seen", plain(s.belt_slip_events, 0), s.belt_slip_events ? "warn" : ""],
  ];
  kvTable("alt-table", rows);
}
