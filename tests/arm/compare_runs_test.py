#!/usr/bin/env python3
"""ctest arm.compare_runs: compare_runs.py, which judges the arm64 build
against amd64 in make test-arm64, accepts agreeing runs and rejects each kind
of disagreement, at and beyond its tolerances."""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
HEADER = "t_s,mode,stage,charged_wh_lifetime\n"


def csv_text(stages, wh_end):
    rows = [HEADER]
    n = len(stages)
    for i, (t, stage) in enumerate(stages):
        wh = wh_end * (i + 1) / n
        rows.append(f"{t},MODE_NORMAL_AUTO_PID,{stage},{wh}\n")
    return "".join(rows)


def run(ref, other, *extra):
    with tempfile.TemporaryDirectory() as d:
        a, b = os.path.join(d, "a.csv"), os.path.join(d, "b.csv")
        open(a, "w").write(ref)
        open(b, "w").write(other)
        return subprocess.run([sys.executable, os.path.join(HERE, "compare_runs.py"), a, b, *extra],
                              capture_output=True, text=True).returncode


base = [(0, "BULK"), (100, "BULK"), (200, "ABSORPTION"), (300, "FLOAT")]
ref = csv_text(base, 1000.0)
cases = [
    ("identical runs agree", ref, 0),
    ("energy 0.09 % apart agrees", csv_text(base, 1000.9), 0),
    ("energy 0.2 % apart fails", csv_text(base, 1002.0), 1),
    ("a missing stage fails", csv_text([(0, "BULK"), (100, "BULK"), (200, "BULK"), (300, "FLOAT")], 1000.0), 1),
    ("absorption entered 50 s late agrees",
     csv_text([(0, "BULK"), (100, "BULK"), (200, "BULK"), (250, "ABSORPTION"), (300, "FLOAT")], 1000.0), 0),
    ("absorption entered 70 s late fails",
     csv_text([(0, "BULK"), (100, "BULK"), (200, "BULK"), (270, "ABSORPTION"), (300, "FLOAT")], 1000.0), 1),
    ("a shorter run fails", csv_text(base[:3], 1000.0 * 3 / 4), 1),
]
# --min-stages: base enters BULK, ABSORPTION, FLOAT (3 entries).
bulk_only = csv_text([(0, "BULK"), (100, "BULK"), (200, "BULK"), (300, "BULK")], 1000.0)
min_stage_cases = [
    ("three stage entries meet --min-stages 3", ref, ref, ["--min-stages", "3"], 0),
    ("three stage entries fail --min-stages 4", ref, ref, ["--min-stages", "4"], 1),
    ("identical bulk-only runs fail --min-stages 3", bulk_only, bulk_only, ["--min-stages", "3"], 1),
    ("identical bulk-only runs agree without it", bulk_only, bulk_only, [], 0),
]
failed = 0
for name, ref_text, other, extra, want in min_stage_cases:
    got = run(ref_text, other, *extra)
    print(f"{'ok' if got == want else 'FAIL'}: {name} (exit {got}, want {want})")
    failed += got != want
for name, other, want in cases:
    got = run(ref, other)
    print(f"{'ok' if got == want else 'FAIL'}: {name} (exit {got}, want {want})")
    failed += got != want
sys.exit(1 if failed else 0)
