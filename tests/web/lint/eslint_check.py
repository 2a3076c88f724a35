#!/usr/bin/env python3
"""The dashboard's JavaScript to the project's standard (docs/dashboard.md
"Code standard"): ESLint from the npm registry (web/package.json, installed
by `make deps`) with web/eslint.config.js over web/www/js and the browser
tests.

  eslint_check.py ESLINT CONFIG ROOT check       the tree passes
  eslint_check.py ESLINT CONFIG ROOT self-test   each rule catches a planted
                                                 file (through --stdin, as if
                                                 it were web/www/js/planted.js)
"""
import json
import os
import subprocess
import sys

LINTED = ["web/www/js", "tests/web/browser"]

# (what, rule that must fire, the planted source)
PLANTED = [
    ("data into innerHTML", "no-restricted-syntax",
     'export function show(el, probe) { el.innerHTML = `<b>${probe}</b>`; }\n'),
    ("a function over 80 lines", "max-lines-per-function",
     "export function long() {\n" + "  console.log(1);\n" * 80 + "}\n"),
    ("a test hook in a shipped page", "no-restricted-properties",
     "window.xrDebug = { points: () => 1 };\n"),
    ("an undefined name", "no-undef", "export const x = () => missingName + 1;\n"),
]
CLEAN = 'import { html, setHtml } from "./format.js";\nexport const show = (el, p) => setHtml(el, html`<b>${p}</b>`);\n'


def lint_text(eslint, config, root, text):
    r = subprocess.run([eslint, "-c", config, "--format", "json", "--stdin", "--stdin-filename",
                        "web/www/js/planted.js"], input=text, capture_output=True, text=True, cwd=root)
    try:
        results = json.loads(r.stdout)
    except ValueError:
        raise SystemExit(f"eslint did not answer JSON (exit {r.returncode}): {r.stderr[:2000]}")
    return [m.get("ruleId") for res in results for m in res["messages"]]


def self_test(eslint, config, root):
    failures = []
    found = lint_text(eslint, config, root, CLEAN)
    if found:
        failures.append(f"a clean file is reported: {found}")
    for what, rule, text in PLANTED:
        found = lint_text(eslint, config, root, text)
        if rule not in found:
            failures.append(f"{what}: expected {rule}, got {found}")
    return failures


def main(argv):
    if len(argv) != 5 or argv[4] not in ("check", "self-test"):
        sys.stderr.write(__doc__)
        return 2
    eslint, config, root, what = argv[1:]
    if not os.access(eslint, os.X_OK):
        print(f"FAIL: {eslint} is not installed: run `make deps` (web/package.json devDependencies)")
        return 1
    if what == "check":
        return subprocess.run([eslint, "-c", config, "--max-warnings", "0", *LINTED], cwd=root).returncode
    failures = self_test(eslint, config, root)
    for f in failures:
        print("FAIL:", f)
    print(f"self-test: {len(PLANTED)} planted files, {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
