#!/usr/bin/env python3
"""Closed loop through the daemon with a BMS on CAN (docs/integrations.md).

Runs one scenarios/bms-can-*.toml through the real daemon
(xregulatord --sim --scenario FILE --speed max --telemetry-csv ...), reads
its CSV telemetry (and stderr, for the rate-limited bad-frame reports) and
checks what docs/integrations.md says of that scenario:

  ccl-step    battery current <= CCL + 2 A within 1 s of each CCL step down;
              the BMS never opens
  cvl         IBV <= CVL + 20 mV once in CV (CVL followed as a ceiling)
  warn        a normal charge to full and a forced warning: the BMS never
              opens, and the warning ramps the charge down
  ignored     the same charge NOT following the BMS: it opens (the checks
              above can fail)
  silent      stale within BmsStaleS + 1 s, battery current at the fallback
              cap, limits back once it talks again
  bad-frames  a CCL of 6 000 A and short frames never reach the limits;
              counted and reported at most once per 30 s
  rec         a REC BMS with an unbalanced pack: its highest cell (0x373,
              read back from the --can-log here, not from the daemon)
              reaches BmsCellHighV, the charge is held on it (constant voltage), so the cell
              never reaches the BMS's own 3.65 V warning and the BMS never
              opens; the charge still goes on

  check.py --daemon build/daemon/app/xregulatord --out DIR --scenario ccl-step
Exit 0 when every check holds, 1 with the failures listed.
"""
from __future__ import annotations

import argparse
import csv
import math
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
RATE_HZ = 20


def run(daemon: str, name: str, out: Path, tag: str = "") -> tuple[list[dict], str, bytes, bytes]:
    """Rows, the daemon's output, and the raw CSV and --can-log bytes."""
    out.mkdir(parents=True, exist_ok=True)
    csv_path = out / f"bms-can-{name}{tag}.csv"
    log_path = out / f"bms-can-{name}{tag}.candump"
    cmd = [daemon, "--sim", "--scenario", str(ROOT / "scenarios" / f"bms-can-{name}.toml"), "--speed", "max",
           "--telemetry-csv", str(csv_path), "--telemetry-rate", str(RATE_HZ), "--log-level", "warn",
           "--can-log", str(log_path)]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    if p.returncode != 0:
        sys.exit(f"daemon exited {p.returncode}:\n{p.stderr[-3000:]}")
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("no telemetry rows")
    return rows, p.stdout + p.stderr, csv_path.read_bytes(), log_path.read_bytes()


def num(row: dict, key: str) -> float:
    v = row[key]
    return float(v) if v not in ("", "nan") else math.nan


def t(row: dict) -> float:
    return float(row["t_s"])


def window(rows, a, b):
    return [r for r in rows if a <= t(r) <= b]


def bms_never_opens(rows) -> list[str]:
    opened = [t(r) for r in rows if r["sim_bms_connected"] != "1"]
    return [f"the simulated BMS opened its contactor at {opened[0]:.2f} s"] if opened else []


def ccl_met(rows, step_at: float, ccl: float, until: float) -> list[str]:
    """Battery current <= CCL + 2 A from step_at + 1 s to `until`."""
    bad = [r for r in window(rows, step_at + 1.0, until) if num(r, "bcur_a") > ccl + 2.0]
    if bad:
        return [f"CCL {ccl} A from {step_at} s: battery current {num(bad[0], 'bcur_a'):.1f} A at {t(bad[0]):.2f} s"]
    return []


def check_ccl_step(rows, log) -> list[str]:
    f = []
    f += ccl_met(rows, 60, 30, 120)
    f += ccl_met(rows, 120, 60, 180)
    f += ccl_met(rows, 180, 5, 240)
    # The CCL is followed, not just undershot: the bank takes what it may.
    mid = window(rows, 100, 119)
    if not mid or max(num(r, "bcur_a") for r in mid) < 20:
        f.append("with CCL 30 A the battery took under 20 A: the cap is not followed, only undershot")
    # No battery DS18B20 in this scenario: the BMS's 0x356 temperature (0.1
    # degC) is the battery temperature input.
    # The bank warms a little while it charges.
    temps = [num(r, "battery_temp_c") for r in window(rows, 2, 300)]
    if not temps or not all(17.95 <= x <= 18.5 for x in temps):
        f.append(f"battery_temp_c {min(temps, default=None)}..{max(temps, default=None)} is not the BMS's ~18 degC")
    shown = {round(num(r, "bms_ccl_a")) for r in window(rows, 62, 118)}
    if shown != {30}:
        f.append(f"bms_ccl_a shows {sorted(shown)} under CCL 30 A")
    return f + bms_never_opens(rows)


def check_cvl(rows, log) -> list[str]:
    f = []
    for start, end, cvl in ((0, 300, 13.7), (300, 600, 13.5)):
        # In CV: once IBV has reached CVL - 20 mV (5 s after a step down).
        seg = window(rows, start + (5 if start else 0), end)
        reached = [r for r in seg if num(r, "ibv_v") >= cvl - 0.02]
        if not reached:
            f.append(f"IBV never reached CVL {cvl} V between {start} and {end} s (not in CV)")
            continue
        over = [r for r in seg if t(r) >= t(reached[0]) and num(r, "ibv_v") > cvl + 0.020]
        if over:
            worst = max(over, key=lambda r: num(r, "ibv_v"))
            f.append(f"CVL {cvl} V: IBV {num(worst, 'ibv_v'):.3f} V at {t(worst):.2f} s ({len(over)} rows over)")
        if t(reached[0]) > end - 60:
            f.append(f"CVL {cvl} V reached only at {t(reached[0]):.0f} s: under a minute in CV")
        if any(abs(num(r, "bms_cvl_v") - cvl) > 0.05 for r in seg):
            f.append(f"bms_cvl_v does not show CVL {cvl} V")
    return f + bms_never_opens(rows)


def check_warn(rows, log) -> list[str]:
    f = bms_never_opens(rows)
    late = window(rows, 602.5, 700)
    if not late or max(num(r, "bcur_a") for r in late) > 2.0:
        f.append("a warning did not stop the charge within 2.5 s (battery current above 2 A)")
    if not any(r["bms_state"] == "WARNING" for r in window(rows, 600, 700)):
        f.append("bms_state never WARNING during the forced warning")
    # A normal charge into the BMS's taper (CCL 100 A under 85 %, 20 A at 95 %).
    if num(rows[-1], "sim_soc_pct") < 94:
        f.append(f"the charge did not get into the taper (SoC {num(rows[-1], 'sim_soc_pct'):.1f} %)")
    if not num(rows[-1], "bms_ccl_a") < 30:
        f.append(f"the BMS's CCL did not taper (CCL {num(rows[-1], 'bms_ccl_a')} A at the end)")
    over = [r for r in window(rows, 1, 1800) if num(r, "bcur_a") > num(r, "bms_ccl_a") + 2.0]
    if over:
        f.append(f"battery current {num(over[0], 'bcur_a'):.1f} A over CCL {num(over[0], 'bms_ccl_a')} A "
                 f"at {t(over[0]):.2f} s")
    return f


def check_ignored(rows, log) -> list[str]:
    return [] if bms_never_opens(rows) else ["the BMS never opened although its limits were ignored"]


def check_silent(rows, log) -> list[str]:
    f = []
    # Silent from 60 s; the last limits arrived before that, so stale by
    # 60 + BmsStaleS (5) + 1 s at the latest.
    stale = [t(r) for r in window(rows, 60, 150) if r["bms_state"] == "STALE"]
    if not stale or stale[0] > 66.0:
        f.append(f"stale at {stale[0] if stale else 'never'} s, expected by 66 s")
    else:
        f += ccl_met(rows, stale[0], 10.0, 150)  # BmsFallbackCapA
        if any(r["reason"] != "REASON_BMS_STALE" for r in window(rows, stale[0] + 0.2, 150)):
            f.append("reason is not REASON_BMS_STALE while stale")
    back = [t(r) for r in window(rows, 150, 240) if r["bms_state"] == "OK"]
    if not back or back[0] > 152.0:
        f.append("the limits did not come back within 2 s of the BMS talking again")
    return f + bms_never_opens(rows)


def check_bad_frames(rows, log) -> list[str]:
    f = []
    if any(num(r, "bms_ccl_a") > 2000 for r in rows):
        f.append("a CCL above 2000 A reached the limits")
    held = {round(num(r, "bms_ccl_a")) for r in window(rows, 50, 64) if r["bms_state"] == "OK"}
    if held != {40}:
        f.append(f"the good CCL (40 A) did not stand after the bad frames: {sorted(held)}")
    stale = [t(r) for r in window(rows, 60, 120) if r["bms_state"] == "STALE"]
    if not stale or stale[0] > 66.0:
        f.append("only bad 0x351 frames: not stale within BmsStaleS + 1 s")
    if not any(r["bms_state"] == "STALE" for r in window(rows, 150, 200)):
        f.append("short frames only: not stale")
    if not any(r["bms_state"] == "OK" for r in window(rows, 200, 240)):
        f.append("good frames again: the limits did not come back")
    reports = re.findall(r"BMS CAN: (\d+) bad frame\(s\) ignored \(last: 0x351, ([^)]*)\)", log)
    if not reports:
        f.append("no bad-frame report in the log")
    elif len(reports) > 240 / 30 + 1:
        f.append(f"{len(reports)} bad-frame reports in 240 s: not rate limited (30 s)")
    whys = {w for _, w in reports}
    for want in ("CCL out of range", "short DLC"):
        if want not in whys:
            f.append(f"no report of '{want}' (reports: {reports})")
    return f + bms_never_opens(rows)


def can_frames(can_log: bytes, can_id: str) -> list[tuple[float, bytes]]:
    """(time, payload) of every logged frame with this id."""
    out = []
    for m in re.finditer(rf"^\((\S+)\) \S+ {can_id}#([0-9A-Fa-f]*)$", can_log.decode(), re.M):
        out.append((float(m.group(1)), bytes.fromhex(m.group(2))))
    return out


def check_rec(rows, log, can_log: bytes) -> list[str]:
    f = bms_never_opens(rows)
    # 0x373 as REC sends it: lowest, highest cell in mV (little-endian u16).
    cells = [(t_, int.from_bytes(d[2:4], "little") / 1000.0) for t_, d in can_frames(can_log, "373")]
    if not cells:
        return f + ["no 0x373 frames in the CAN log"]
    high = [t_ for t_, v in cells if v >= 3.60]
    if not high:
        f.append(f"the highest cell never reached BmsCellHighV 3.60 V (max {max(v for _, v in cells):.3f} V): "
                 "the scenario does not exercise the cell limit")
    worst = max(v for _, v in cells)
    if worst > 3.65:
        f.append(f"the highest cell reached {worst:.3f} V, over the BMS's own 3.65 V warning")
    # 0x35A warnings, byte 4 bits 2-3 = 01: the BMS's high-voltage warning.
    warned = [t_ for t_, d in can_frames(can_log, "35A") if len(d) == 8 and (d[4] >> 2) & 3 == 1]
    if warned:
        f.append(f"the BMS raised its high-voltage warning at {warned[0]:.1f} s")
    # Held at the limit (a constant voltage on that cell): a minute after it
    # first reached 3.60 V it stays within 20 mV of it.
    held = [v for t_, v in cells if high and t_ >= high[0] + 60.0]
    if held and max(held) > 3.62:
        f.append(f"the high cell was not held at 3.60 V: {max(held):.3f} V a minute after it reached it")
    # SoC from the REC's 0x355 (0.01 % in bytes 4-5) is what the daemon shows.
    socs = [int.from_bytes(d[4:6], "little") / 100.0 for _, d in can_frames(can_log, "355") if len(d) >= 6]
    if not socs or abs(socs[-1] - num(rows[-1], "bms_soc_pct")) > 0.6:
        f.append(f"bms_soc_pct {num(rows[-1], 'bms_soc_pct')} is not the REC's 0.01 % SoC {socs[-1:]}")
    gained = num(rows[-1], "sim_soc_pct") - num(rows[0], "sim_soc_pct")
    if gained < 3.0:
        f.append(f"the charge stalled on the cell limit: SoC gained {gained:.1f} %")
    return f


CHECKS = {"ccl-step": check_ccl_step, "cvl": check_cvl, "warn": check_warn, "ignored": check_ignored,
          "silent": check_silent, "bad-frames": check_bad_frames, "rec": check_rec}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--daemon", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--scenario", required=True, choices=sorted(CHECKS))
    ap.add_argument("--twice", action="store_true", help="run again and compare CSV and CAN log bytes")
    a = ap.parse_args()
    rows, log, csv_bytes, can_bytes = run(a.daemon, a.scenario, Path(a.out))
    check = CHECKS[a.scenario]
    failures = check(rows, log, can_bytes) if check is check_rec else check(rows, log)
    if not can_bytes.startswith(b"("):
        failures.append("--can-log wrote no candump lines")
    if a.twice:
        # The same seed: byte-identical CSV and CAN log (the CAN side runs on
        # the loop's thread in virtual time).
        _, _, csv2, can2 = run(a.daemon, a.scenario, Path(a.out), tag="-again")
        if csv2 != csv_bytes:
            failures.append("a second run with the same seed wrote a different CSV")
        if can2 != can_bytes:
            failures.append("a second run with the same seed wrote a different CAN log")
    for x in failures:
        print(f"FAIL bms-can-{a.scenario}: {x}")
    if not failures:
        print(f"ok bms-can-{a.scenario}: {len(rows)} rows")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
