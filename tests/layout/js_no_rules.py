#!/usr/bin/env python3
"""The dashboard knows no rule of the catalogue or the battery profiles
(docs/dashboard.md "Set-up"): the daemon validates a change once and the
pages ask it (a dry run) what a chemistry and a bank give. This check refuses
a copy of those rules in the shipped JavaScript: a table of charge voltages
(BulkVoltage: 14.4), a table keyed by bank voltage ({12: ..., 24: ...}), cells
per chemistry ({lifepo4: 4}), or the bank-class split (bulk < 18 ? 12 : ...).

  js_no_rules.py check ROOT   exit 1 and a list when web/www/js holds one
  js_no_rules.py self-test    each pattern catches a planted copy
"""
import os
import re
import sys
import tempfile

JS_DIR = os.path.join("web", "www", "js")
RULES = [
    (re.compile(r"\b(Bulk|Absorption|Float|Rebulk|Charged)Voltage\s*:\s*\d"), "a charge voltage written in"),
    (re.compile(r"[{,]\s*(12|24|48)\s*:\s*[{\d]"), "a table keyed by bank voltage"),
    (re.compile(r"\b(lifepo4|agm|flooded|gel)\s*:\s*\d"), "a number per chemistry"),
    (re.compile(r"<\s*18\s*\?\s*12\b|<=?\s*36\s*\?\s*24\b"), "the bank-class split"),
    (re.compile(r"\*\s*1\.05\b|\bBatteryCells\s*[:=]\s*\(?\s*\w+\s*\*"), "an alarm margin or a cell count computed"),
]


def problems(root):
    out = []
    base = os.path.join(root, JS_DIR)
    for d, _, files in os.walk(base):
        for f in sorted(files):
            if not f.endswith(".js"):
                continue
            path = os.path.join(d, f)
            rel = os.path.relpath(path, root).replace(os.sep, "/")
            with open(path, encoding="utf-8") as fh:
                for n, line in enumerate(fh, 1):
                    if line.lstrip().startswith("//"):
                        continue
                    for rx, what in RULES:
                        if rx.search(line):
                            out.append(f"{rel}:{n}: {what}: ask the daemon (PATCH /api/params?dry_run=1) instead")
    return out


def self_test():
    planted = [
        "const BANK = { 12: { BulkVoltage: 14.4, AbsorptionVoltage: 14.4 } };\n",
        "const t = { FloatVoltage: 13.5 };\n",
        "const CELLS = { lifepo4: 4, agm: 6 };\n",
        "const bankOf = (bulk) => (bulk < 18 ? 12 : bulk <= 36 ? 24 : 48);\n",
        "if (alarm < cap * 1.05) body.CurrentAlarmHigh = 1;\n",
    ]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        os.makedirs(os.path.join(tmp, JS_DIR))
        path = os.path.join(tmp, JS_DIR, "page.js")
        with open(path, "w") as fh:
            fh.write("// BulkVoltage: 14.4 in a comment is not a table\nconst x = values.BulkVoltage;\n")
        if problems(tmp):
            failures.append(f"a clean page is reported: {problems(tmp)}")
        for text in planted:
            with open(path, "w") as fh:
                fh.write(text)
            if not problems(tmp):
                failures.append(f"not caught: {text.strip()}")
    return failures


def main(argv):
    if len(argv) == 3 and argv[1] == "check":
        found = problems(argv[2])
        for p in found:
            print(p)
        return 1 if found else 0
    if len(argv) == 2 and argv[1] == "self-test":
        failures = self_test()
        for f in failures:
            print(f)
        print(f"self-test: {len(failures)} problem(s)")
        return 1 if failures else 0
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
