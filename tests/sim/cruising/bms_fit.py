"""Criteria of the BMS-fit scenarios (docs/protections.md "BMS plausibility",
"Charging held"): a BMS that fits the bank charges it with no warning and no
mismatch; one set up for another cell count is told to the owner (an alarm
naming the mismatch within a minute, a "charging held" incident) in a few
journal lines, not one every 30 s. Only the CSV and the daemon's log are read.
"""
from __future__ import annotations

import re
from pathlib import Path

from criteria import Run, Verdict

# A log line about the BMS: its events, its bad frames, its alarm rows.
BMS_LINE = re.compile(r"\bBMS\b", re.IGNORECASE)


def first_mismatch_alarm(run: Run) -> tuple[float, str] | None:
    """(t, kind) of the first row with a BMS mismatch reported and the alarm on."""
    for t, m, a in zip(run.t, run.bms_mismatch, run.alarm):
        if m not in ("", "NONE") and a == 1:
            return t, m
    return None


def first_held(run: Run, cause: str) -> float | None:
    """When charge_held_by first named `cause` with the alarm on and at least 15 min held."""
    for t, c, mins, a in zip(run.t, run.charge_held_by, run.charge_held_min, run.alarm):
        if c == cause and mins >= 15.0 and a == 1:
            return t
    return None


def bms_log_lines(log: Path) -> list[str]:
    return [line for line in log.read_text(errors="replace").splitlines() if BMS_LINE.search(line)]


def judge_bms_fit(run: Run, crit: dict, v: Verdict, log: Path | None) -> None:
    """The criteria of this module that `crit` names, into `v`."""
    if crit.get("bms_fits"):
        warned = [t for t, s in zip(run.t, run.bms_state) if s in ("WARNING", "CHARGE_DISABLED")]
        if warned:
            v.failures.append(f"the BMS warned at {warned[0]:.0f} s on a bank it fits")
        told = [(t, m) for t, m in zip(run.t, run.bms_mismatch) if m not in ("", "NONE")]
        if told:
            v.failures.append(f"mismatch {told[0][1]} reported at {told[0][0]:.0f} s for a BMS that fits")
        held = [(t, c) for t, c, m in zip(run.t, run.charge_held_by, run.charge_held_min)
                if c not in ("", "NONE") and m >= 15.0]
        if held:
            v.failures.append(f"charging held by {held[0][1]} for 15 min at {held[0][0]:.0f} s on a bank it fits")
    if "mismatch_within_s" in crit:
        got = first_mismatch_alarm(run)
        v.figures["mismatch"] = "never" if got is None else f"{got[1]} {got[0]:.0f}s"
        if got is None or got[0] > crit["mismatch_within_s"]:
            v.failures.append(f"no alarm naming the BMS mismatch within {crit['mismatch_within_s']} s")
        elif got[1] != crit["mismatch_kind"]:
            v.failures.append(f"mismatch {got[1]} reported, want {crit['mismatch_kind']}")
    if "held_by" in crit:
        at = first_held(run, crit["held_by"])
        v.figures["held alarm"] = "never" if at is None else f"{at:.0f}s"
        if at is None or at > crit["held_within_s"]:
            v.failures.append(f"no 'charging held by {crit['held_by']}' alarm within {crit['held_within_s']} s")
    if "max_bms_lines" in crit:
        # The console log carries no simulated time: the whole run's lines
        # about the BMS, at most max_bms_lines, bounds every hour of it.
        if log is None or not log.exists():
            v.failures.append("no daemon log to count the BMS lines in")
            return
        lines = bms_log_lines(log)
        v.figures["BMS lines"] = str(len(lines))
        if len(lines) > crit["max_bms_lines"]:
            v.failures.append(f"{len(lines)} log lines about the BMS (max {crit['max_bms_lines']}): "
                              + " | ".join(lines[:3]))
