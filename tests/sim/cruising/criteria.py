"""How the cruising-day suite judges one run (docs/deviations.md).

Every figure comes from the daemon's telemetry CSV (docs/simulator.md columns) and
the plant's truth columns; nothing here knows how the regulator works.
"""
from __future__ import annotations

import csv
import statistics
from dataclasses import dataclass, field

TRIP_MODES = {"MODE_WARNING_RAMP_AND_LOCKOUT", "MODE_LOCKOUT_RAMP", "MODE_CRITICAL_RAMP"}
HOLDING_STAGES = {"ABSORPTION", "FLOAT"}
# Rows where the engine is stopped, or has just restarted with the
# alternator still heat-soaked from it (docs/deviations.md "Heat soak after an
# engine stop"): the field is off and no regulator action reaches the case
# temperature, so the temperature target does not judge them.
ENGINE_STOPPED_REASONS = {"REASON_RPM_LOW", "REASON_IGNITION_OFF", "REASON_TEMP_SOAK"}


@dataclass
class Run:
    """The CSV of one run as columns of floats (or strings for the names)."""

    t: list[float] = field(default_factory=list)
    mode: list[str] = field(default_factory=list)
    stage: list[str] = field(default_factory=list)
    reason: list[str] = field(default_factory=list)
    v: list[float] = field(default_factory=list)  # plant truth: battery terminals
    target_v: list[float] = field(default_factory=list)
    bcur: list[float] = field(default_factory=list)
    alt_a: list[float] = field(default_factory=list)
    alt_temp_f: list[float] = field(default_factory=list)
    duty: list[float] = field(default_factory=list)
    field_on: list[int] = field(default_factory=list)
    setpoint_a: list[float] = field(default_factory=list)
    target_a: list[float] = field(default_factory=list)
    soc: list[float] = field(default_factory=list)
    rpm: list[float] = field(default_factory=list)
    bms_state: list[str] = field(default_factory=list)
    bms_ccl: list[float] = field(default_factory=list)
    bms_connected: list[int] = field(default_factory=list)
    belt_slips: list[float] = field(default_factory=list)  # the lifetime BeltSlip count
    alarm: list[int] = field(default_factory=list)
    bms_mismatch: list[str] = field(default_factory=list)
    charge_held_by: list[str] = field(default_factory=list)
    charge_held_min: list[float] = field(default_factory=list)


def _num(s: str) -> float:
    return float(s) if s not in ("", None) else float("nan")


def load_csv(path: str) -> Run:
    r = Run()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            r.t.append(float(row["t_s"]))
            r.mode.append(row["mode"])
            r.stage.append(row["stage"])
            r.reason.append(row["reason"])
            r.v.append(_num(row["sim_battery_v"]))
            r.target_v.append(_num(row["target_v"]))
            r.bcur.append(_num(row["bcur_a"]))
            r.alt_a.append(_num(row["sim_alt_a"]))
            r.alt_temp_f.append(_num(row["sim_alt_temp_f"]))
            r.duty.append(_num(row["duty_pct"]))
            r.field_on.append(int(row["field_enable"] or 0))
            r.setpoint_a.append(_num(row["setpoint_a"]))
            r.target_a.append(_num(row["target_a"]))
            r.soc.append(_num(row["sim_soc_pct"]))
            r.rpm.append(_num(row["rpm"]))
            r.bms_state.append(row.get("bms_state", ""))
            r.bms_ccl.append(_num(row.get("bms_ccl_a", "")))
            r.bms_connected.append(int(row.get("sim_bms_connected") or 1))
            r.belt_slips.append(_num(row.get("belt_slip_events", "")))
            r.alarm.append(int(row.get("alarm") or 0))
            r.bms_mismatch.append(row.get("bms_mismatch", ""))
            r.charge_held_by.append(row.get("charge_held_by", ""))
            r.charge_held_min.append(_num(row.get("charge_held_min", "")))
    if not r.t:
        raise ValueError(f"{path}: no telemetry rows")
    return r


@dataclass
class Verdict:
    figures: dict[str, str] = field(default_factory=dict)  # name -> shown value
    failures: list[str] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return not self.failures


def belt_slips(run: Run) -> int:
    """BeltSlip events during the run (no scenario here slips its belt)."""
    seen = [x for x in run.belt_slips if x == x]
    return int(max(seen) - min(seen)) if seen else 0


def count_trips(run: Run, before_s: float = float("inf")) -> int:
    """Entries into a warning, lockout or critical ramp before `before_s`."""
    trips, prev = 0, ""
    for t, m in zip(run.t, run.mode):
        if t >= before_s:
            break
        if m in TRIP_MODES and prev not in TRIP_MODES:
            trips += 1
        prev = m
    return trips


def settled_mask(run: Run, settle_s: float, event_times: list[float]) -> list[bool]:
    """True where the stage has not changed, and no event happened, for settle_s."""
    out, since = [], run.t[0]
    events = sorted(event_times)
    ei = 0
    for i, t in enumerate(run.t):
        if i > 0 and run.stage[i] != run.stage[i - 1]:
            since = t
        while ei < len(events) and events[ei] <= t:
            since = max(since, events[ei])
            ei += 1
        out.append(t - since >= settle_s)
    return out


def voltage_loop_holds(run: Run, i: int) -> bool:
    """The voltage loop, not a current cap, decides the field at row i: the
    field is on and the governed setpoint sits below the current target by
    more than 1 A. (A resting field holds nothing: a full bank then sits at
    its own voltage, which may be above the target.)"""
    return (run.field_on[i] == 1 and run.setpoint_a[i] < run.target_a[i] - 1.0
            and run.mode[i] == "MODE_NORMAL_AUTO_PID")


def regulation_error_mv(run: Run, settled: list[bool]) -> float | None:
    errs = [
        abs(run.v[i] - run.target_v[i]) * 1000.0
        for i in range(len(run.t))
        if settled[i] and run.stage[i] in HOLDING_STAGES and voltage_loop_holds(run, i)
    ]
    return statistics.median(errs) if errs else None


def float_creep_mv(run: Run, float_v: float, window_s: float = 600.0) -> float | None:
    """Highest mean of V - FloatVoltage over any window_s of continuous FLOAT
    in which the field was on at least half the time (the regulator, not the
    bank's own rest voltage, set the level)."""
    best, start, acc, n, on = None, 0, 0.0, 0, 0
    for i in range(len(run.t)):
        if run.stage[i] != "FLOAT":
            start, acc, n, on = i + 1, 0.0, 0, 0
            continue
        acc += run.v[i]
        n += 1
        on += run.field_on[i]
        while run.t[i] - run.t[start] > window_s:
            acc -= run.v[start]
            on -= run.field_on[start]
            n -= 1
            start += 1
        if run.t[i] - run.t[start] >= window_s * 0.95 and on * 2 >= n:
            mean_mv = (acc / n - float_v) * 1000.0
            best = mean_mv if best is None else max(best, mean_mv)
    return best


def absorption_exits(run: Run, tail_a: float, timeout_s: float) -> list[tuple[float, str]]:
    """Each ABSORPTION -> FLOAT change (IDLE for a LiFePO4 bank that rests
    instead of floating), judged: 'tail' when the bank was
    charging at or under the tail current at the target voltage over the last
    30 s (or held the target with the field resting), 'timeout' when
    absorption lasted its timeout, else 'early'."""
    out, entered = [], None
    for i in range(1, len(run.t)):
        if run.stage[i] == "ABSORPTION" and run.stage[i - 1] != "ABSORPTION":
            entered = run.t[i]
        if run.stage[i - 1] == "ABSORPTION" and run.stage[i] in ("FLOAT", "IDLE"):
            t = run.t[i]
            idx = [j for j in range(i) if t - 30.0 <= run.t[j] < t]
            cur = statistics.mean(run.bcur[j] for j in idx) if idx else float("nan")
            dv = statistics.mean(abs(run.v[j] - run.target_v[j]) for j in idx) if idx else float("nan")
            lasted = t - entered if entered is not None else 0.0
            if lasted >= timeout_s - 1.0:
                kind = "timeout"
            elif -tail_a <= cur <= tail_a * 1.5 and dv <= 0.1:
                kind = "tail"
            elif idx and all(run.field_on[j] == 0 and run.v[j] >= run.target_v[j] - 0.05 for j in idx):
                # The field rested and the bank still held the target with
                # no charge at all: it accepts nothing more, the fullest tail.
                kind = "tail"
            else:
                kind = "early"
            out.append((t, kind))
    return out


def load_dump(run: Run, at_s: float) -> tuple[float, float | None]:
    """Peak of V - target in the 30 s after at_s (mV), and how long until V
    is back, and stays for 5 s, within 20 mV of the target (s; None = never)."""
    idx = [i for i in range(len(run.t)) if at_s <= run.t[i] <= at_s + 30.0]
    if not idx:
        return float("nan"), None
    rise = [(run.v[i] - run.target_v[i]) * 1000.0 for i in idx]
    peak = max(rise)
    back = None
    # From the peak on: before it, a bank at its target is "within 20 mV" too.
    for k in range(rise.index(peak), len(idx)):
        i = idx[k]
        if all(abs(run.v[j] - run.target_v[j]) <= 0.020 for j in idx[k:] if run.t[j] <= run.t[i] + 5.0):
            back = run.t[i] - at_s
            break
    return peak, back


def field_off_after(run: Run, at_s: float) -> float | None:
    for t, on in zip(run.t, run.field_on):
        if t >= at_s and not on:
            return t - at_s
    return None


def thermal_utilisation(run: Run, ambient_f: float, limit_f: float, window_s: float) -> float:
    """Mean plant temperature rise over the last window_s, as a share of the
    rise TemperatureLimitF allows above ambient."""
    end = run.t[-1]
    temps = [x for t, x in zip(run.t, run.alt_temp_f) if t >= end - window_s]
    return (statistics.mean(temps) - ambient_f) / (limit_f - ambient_f)


def hottest_while_running(run: Run) -> float:
    """Highest plant alternator temperature over the rows where the field can
    act on it (see ENGINE_STOPPED_REASONS); every row when there are none."""
    acting = [x for x, r in zip(run.alt_temp_f, run.reason) if r not in ENGINE_STOPPED_REASONS]
    return max(acting) if acting else max(run.alt_temp_f)


def resumed_after(run: Run, at_s: float) -> float | None:
    """Seconds from at_s until the regulator drives the field again in AUTO
    (field on, MODE_NORMAL_AUTO_PID); None if it never does."""
    for t, on, m in zip(run.t, run.field_on, run.mode):
        if t >= at_s and on == 1 and m == "MODE_NORMAL_AUTO_PID":
            return t - at_s
    return None
