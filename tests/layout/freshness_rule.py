#!/usr/bin/env python3
"""One freshness rule per input (docs/architecture.md "Freshness").

How old a reading may be before the regulator stops acting on it is decided
in daemon/core/freshness.h and nowhere else: the protections, the stages,
the SoC counter, the health estimators and the runtime call it. A reading's
age compared against a limit anywhere else is a second rule for the same
input, which drifts (an engine speed fresh for 2 s in one place and 1 s in
another). This check refuses such a comparison outside the files that hold
the rule.

  freshness_rule.py check ROOT   exit 1 and list the places when one is found
  freshness_rule.py self-test    the check catches a planted comparison
"""
import pathlib
import re
import sys
import tempfile

FOLDERS = ["daemon/core", "daemon/control", "daemon/protection", "daemon/battery", "daemon/health",
           "daemon/owner", "daemon/runtime", "daemon/integrations", "daemon/canlink"]
# Where the rule lives: freshness.h, and the alternator temperature rule it wraps.
HOMES = {"daemon/core/freshness.h", "daemon/core/alternator_temperature.h"}
# `now - x.stamp <= limit`, `in.now - r.stamp > fromSec(2.0)`, ...
AGE_RE = re.compile(r"\bnow\w*\s*-\s*[\w.\->\[\]()*]*stamp\w*\s*(<=|<|>=|>)")


def offences(root):
    root = pathlib.Path(root)
    found = []
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".h", ".cpp"):
                continue
            rel = path.relative_to(root).as_posix()
            if rel in HOMES:
                continue
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                code = line.split("//", 1)[0]
                if AGE_RE.search(code):
                    found.append(f"{rel}:{n}: a reading's age is judged here; call core/freshness.h instead")
    return found


def check(root):
    found = offences(root)
    for f in found:
        print(f)
    print(f"freshness rule: {len(found)} problem(s)")
    return 1 if found else 0


def self_test():
    with tempfile.TemporaryDirectory() as d:
        root = pathlib.Path(d)
        (root / "daemon/core").mkdir(parents=True)
        (root / "daemon/health").mkdir(parents=True)
        (root / "daemon/core/freshness.h").write_text("return now - r.stamp <= maxAge;\n")
        clean = root / "daemon/health/belt.cpp"
        clean.write_text("const bool f = fresh::engineRpm(in.engineRpm, in.now);  // now - stamp <= 1 s\n")
        if offences(root):
            print("self-test: a clean tree was refused")
            return 1
        clean.write_text("const bool f = in.now - in.engineRpm.stamp <= fromSec(2.0);\n")
        if len(offences(root)) != 1:
            print("self-test: a planted second rule was not caught")
            return 1
    print("self-test: the planted second rule is caught, the clean tree passes")
    return 0


def main(argv):
    if len(argv) == 3 and argv[1] == "check":
        return check(argv[2])
    if len(argv) == 2 and argv[1] == "self-test":
        return self_test()
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
