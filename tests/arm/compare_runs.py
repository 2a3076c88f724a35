#!/usr/bin/env python3
"""Compares two telemetry CSVs of the same scenario, run by builds for two
architectures (the arm64 daemon under qemu-user against amd64).

Floating-point results may differ in the last bits between architectures
(aarch64 GCC contracts a*b+c into one fused instruction, libm differs), so
the comparison is on what a boat owner sees: the same sequence of charging
stages, each entered at about the same time, and the same energy.

A run that never leaves its first stage would compare one stage and prove
little about the charge algorithm on the other architecture: --min-stages N
fails unless the reference run went through at least N stage entries.

Usage: compare_runs.py REFERENCE.csv OTHER.csv [--energy-tol 0.001] [--stage-time-tol-s 60]
                       [--min-stages N]
Exit 0 when they agree, 1 otherwise; prints one line per figure.
"""
import argparse
import csv
import sys


def read(path):
    stages = []  # (t_s, stage) at each change
    last = None
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            stage = row["stage"]
            if stage != last:
                stages.append((float(row["t_s"]), stage))
                last = stage
            final = row
    return stages, float(final["charged_wh_lifetime"]), float(final["t_s"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("reference")
    ap.add_argument("other")
    ap.add_argument("--energy-tol", type=float, default=0.001)
    ap.add_argument("--stage-time-tol-s", type=float, default=60.0)
    ap.add_argument("--min-stages", type=int, default=1)
    a = ap.parse_args()
    ref_st, ref_wh, ref_t = read(a.reference)
    oth_st, oth_wh, oth_t = read(a.other)
    ok = True
    seq_ref = [s for _, s in ref_st]
    seq_oth = [s for _, s in oth_st]
    print(f"stages reference: {' -> '.join(f'{s}@{t:.0f}s' for t, s in ref_st)}")
    print(f"stages other:     {' -> '.join(f'{s}@{t:.0f}s' for t, s in oth_st)}")
    if len(seq_ref) < a.min_stages:
        print(f"FAIL: the reference run has {len(seq_ref)} stage entries, fewer than {a.min_stages}:"
              " the scenario does not exercise the stages")
        ok = False
    if seq_ref != seq_oth:
        print("FAIL: different stage sequences")
        ok = False
    else:
        worst = max(abs(t1 - t2) for (t1, _), (t2, _) in zip(ref_st, oth_st))
        print(f"largest stage-entry time difference: {worst:.1f} s")
        if worst > a.stage_time_tol_s:
            print(f"FAIL: a stage entered more than {a.stage_time_tol_s} s apart")
            ok = False
    if ref_t != oth_t:
        print(f"FAIL: runs end at different times ({ref_t} vs {oth_t} s)")
        ok = False
    rel = abs(oth_wh - ref_wh) / max(abs(ref_wh), 1e-9)
    print(f"energy: reference {ref_wh:.3f} Wh, other {oth_wh:.3f} Wh, difference {rel * 100:.4f} %")
    if rel > a.energy_tol:
        print(f"FAIL: energy differs by more than {a.energy_tol * 100:.2f} %")
        ok = False
    print("ok: the runs agree" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
