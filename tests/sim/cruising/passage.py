"""Criteria of the LiFePO4 passage and BMS scenarios (docs/batteries.md
"After absorption", docs/integrations.md "CAN"): how often a full bank is
re-absorbed and how low it gets, a BMS's current limit and silence, and the
highest cell's constant voltage. Like criteria.py, only the CSV is read.
"""
from __future__ import annotations

import math

from criteria import Run, Verdict


def absorptions(run: Run) -> int:
    """Entries into ABSORPTION."""
    return sum(1 for a, b in zip(run.stage, run.stage[1:]) if b == "ABSORPTION" and a != "ABSORPTION")


def first_charge_end(run: Run) -> float | None:
    """When the first absorption ended (the bank's first full charge)."""
    for i in range(1, len(run.t)):
        if run.stage[i - 1] == "ABSORPTION" and run.stage[i] != "ABSORPTION":
            return run.t[i]
    return None


def lowest_soc_after(run: Run, from_s: float) -> float:
    """The plant's lowest SoC from `from_s` on, while the engine runs."""
    socs = [s for t, s, r in zip(run.t, run.soc, run.rpm) if t >= from_s and r > 0]
    return min(socs) if socs else math.nan


def ccl_overshoot(run: Run, step_at: float, ccl: float, until: float) -> tuple[float, float] | None:
    """(t, battery current) of the first row over CCL + 2 A from step_at + 1 s to `until`."""
    for t, b in zip(run.t, run.bcur):
        if step_at + 1.0 <= t <= until and b > ccl + 2.0:
            return t, b
    return None


def stale_after(run: Run, silent_at: float) -> float | None:
    """Seconds from silent_at to the first row with bms_state STALE."""
    for t, st in zip(run.t, run.bms_state):
        if t >= silent_at and st == "STALE":
            return t - silent_at
    return None


def field_offs(run: Run, a: float, b: float) -> int:
    """Field enable 1 -> 0 edges in [a, b]."""
    return sum(1 for i in range(1, len(run.t))
               if a <= run.t[i] <= b and run.field_on[i - 1] == 1 and run.field_on[i] == 0)


def current_swings(run: Run, a: float, b: float, high_a: float = 20.0, low_a: float = 2.0) -> int:
    """Changes between alternator current above high_a and below low_a in [a, b]."""
    state, swings = None, 0
    for t, i in zip(run.t, run.alt_a):
        if not a <= t <= b:
            continue
        now = "high" if i > high_a else ("low" if i < low_a else state)
        if state is not None and now != state:
            swings += 1
        state = now
    return swings


def cell_limit_reached(run: Run, cells: int, spread_v: float, limit_v: float) -> float | None:
    """When the plant's highest cell (pack / cells + spread, the simulated
    BMS's model) first reached limit_v."""
    for t, v in zip(run.t, run.v):
        if v / cells + spread_v >= limit_v:
            return t
    return None


def judge_passage(run: Run, crit: dict, v: Verdict) -> None:
    """The criteria of this module that `crit` names, into `v`."""
    if "max_absorptions" in crit:
        n = absorptions(run)
        v.figures["absorptions"] = str(n)
        if n > crit["max_absorptions"]:
            v.failures.append(f"{n} absorptions (max {crit['max_absorptions']})")
    if "min_soc_after_charge_pct" in crit:
        end = first_charge_end(run)
        if end is None:
            v.failures.append("the first charge never ended")
        else:
            low = lowest_soc_after(run, end)
            v.figures["min SoC"] = f"{low:.1f}%"
            if not low >= crit["min_soc_after_charge_pct"]:
                v.failures.append(f"SoC fell to {low:.1f} % after the first charge (min {crit['min_soc_after_charge_pct']})")
    if "ccl_step_at_s" in crit:
        bad = ccl_overshoot(run, crit["ccl_step_at_s"], crit["ccl_step_a"], crit["ccl_until_s"])
        if bad:
            v.failures.append(f"battery current {bad[1]:.1f} A at {bad[0]:.2f} s, over CCL {crit['ccl_step_a']} A + 2 A")
    if crit.get("bms_never_opens"):
        opened = [t for t, c in zip(run.t, run.bms_connected) if c != 1]
        if opened:
            v.failures.append(f"the simulated BMS opened its contactor at {opened[0]:.2f} s")
    if "silent_at_s" in crit:
        d = stale_after(run, crit["silent_at_s"])
        v.figures["stale s"] = "never" if d is None else f"{d:.2f}"
        if d is None or d > crit["stale_within_s"]:
            v.failures.append(f"not stale within {crit['stale_within_s']} s of the BMS falling silent")
    if "cell_limit_v" in crit:
        at = cell_limit_reached(run, crit["cells"], crit["cell_spread_v"], crit["cell_limit_v"])
        if at is None:
            v.failures.append("the highest cell never reached its limit")
            return
        end = at + crit["cell_window_s"]
        offs, swings = field_offs(run, at, end), current_swings(run, at, end)
        v.figures["cell offs/swings"] = f"{offs}/{swings}"
        if offs > crit["max_field_offs"]:
            v.failures.append(f"field switched off {offs} times at the cell limit (max {crit['max_field_offs']})")
        if swings > crit["max_current_swings"]:
            v.failures.append(f"alternator current swung {swings} times (max {crit['max_current_swings']})")
