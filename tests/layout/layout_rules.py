#!/usr/bin/env python3
"""The layers of xregulator as data, and the checks that keep the code in them.

The table LAYERS below is the picture in docs/architecture.md: each folder,
its job, and the folders its files may #include (besides their own). The
picture (docs/architecture.dot, rendered to docs/architecture.svg) is
generated from this table, so the two cannot drift apart.

  layout_rules.py check ROOT      every include follows the table, no source
                                  includes a .cpp, no non-test source over
                                  MAX_LINES lines, no function over
                                  MAX_FUNCTION_LINES, no clock in the pure
                                  layers; and in every CMake file, the
                                  README, docs/, the tests, the dashboard's
                                  JavaScript: no reference to a file outside
                                  the repository, no "seed"/"Ours" for the
                                  original firmware or this project beyond
                                  SPEC_WORD_ALLOWANCE (exit 1 and a list if not)
  layout_rules.py dot             print the Graphviz source of the picture
  layout_rules.py dot-check ROOT  docs/architecture.dot matches this table
  layout_rules.py self-test       the checks catch a planted violation of each
                                  rule in a scratch tree
"""
import os
import re
import sys
import tempfile

# (folder, job, folders it may include). Include paths are written from
# daemon/ ("core/...", "runtime/...") or from the repository root
# ("drivers/...", "web/..."); a folder may always include itself.
CORE = ["daemon/params", "daemon/core"]
DRIVERS = [
    "drivers/hal", "drivers/i2c", "drivers/ina228", "drivers/ads1115", "drivers/frontend",
    "drivers/pwm", "drivers/gpio", "drivers/watchdog", "drivers/onewire", "drivers/vedirect",
    "drivers/can", "drivers/probe", "drivers/sim",
]
LAYERS = [
    ("daemon/params", "parameter catalogue, seed constants, derived values", []),
    ("daemon/core", "shared vocabulary: time, modes, reasons, inputs, outputs, events, commands",
     ["daemon/params"]),
    ("daemon/protection", "detectors, fast over-voltage, mode selection, shutdown sequencer (pure)", CORE),
    ("daemon/battery", "SoC, Peukert, energy, auto-zero, auto-gain, measured capacity and resistance (pure)", CORE),
    ("daemon/health", "alternator wear and belt slip (pure)", CORE + ["daemon/battery"]),
    ("daemon/control", "loops, governor, stages, tuning; the Regulator and its telemetry (pure)",
     CORE + ["daemon/protection", "daemon/battery", "daemon/health"]),
    ("daemon/owner", "the owner model: state, SoC, limits in words from the telemetry (pure, off the RT loop)",
     CORE + ["daemon/protection", "daemon/battery", "daemon/health", "daemon/control"]),
    ("daemon/config", "TOML settings: loading and checks", ["daemon/params"]),
    ("daemon/logging", "spdlog / journald", CORE + ["daemon/config"]),
    ("drivers/hal", "small device interfaces: I2C bus, outputs, clock", ["daemon/core"]),
    ("drivers/i2c", "Linux i2c-dev bus", ["drivers/hal"]),
    ("drivers/frontend", "analog front end: raw codes to volts, amps, rpm", CORE + ["daemon/config"]),
    ("drivers/ina228", "INA228 driver", ["daemon/core", "drivers/hal", "drivers/i2c"]),
    ("drivers/ads1115", "ADS1115 driver and its pacing",
     CORE + ["daemon/config", "drivers/hal", "drivers/i2c", "drivers/frontend"]),
    ("drivers/pwm", "sysfs PWM", ["drivers/hal"]),
    ("drivers/gpio", "libgpiod lines and edges", CORE + ["daemon/config", "drivers/hal"]),
    ("drivers/watchdog", "/dev/watchdog", ["drivers/hal"]),
    ("drivers/onewire", "DS18B20 reader (w1 sysfs)", CORE),
    ("drivers/can", "CAN buses: SocketCAN, simulated segment, candump logs", ["drivers/hal"]),
    ("daemon/can", "CAN protocol codecs: BMS set, NMEA 2000 (pure)", CORE + ["drivers/hal"]),
    ("drivers/vedirect", "VE.Direct serial reader", CORE + ["drivers/onewire"]),
    ("drivers/probe", "--probe: which devices answer",
     CORE + ["daemon/config", "drivers/i2c", "drivers/ina228", "drivers/ads1115", "drivers/onewire",
             "drivers/vedirect"]),
    ("drivers/sim", "chip models, plant, simulated world and clock, scenarios, simulated BMS",
     CORE + ["daemon/config", "drivers/hal", "drivers/frontend", "daemon/can"]),
    ("daemon/runtime", "RT loop and cycle, hand-offs, thread setup; adapts drivers to the hand-offs",
     CORE + ["daemon/config", "daemon/battery", "daemon/control", "drivers/hal", "drivers/i2c",
             "drivers/ina228", "drivers/ads1115", "drivers/onewire", "drivers/vedirect"]),
    ("daemon/canlink", "the CAN service: BMS link, buses opened with retry (off the RT loop)",
     CORE + ["daemon/config", "daemon/control", "daemon/runtime", "daemon/can", "drivers/hal", "drivers/can"]),
    ("daemon/sim_rig", "the one simulator rig (--sim, headless runs, tests)",
     CORE + ["daemon/config", "daemon/control", "daemon/runtime", "drivers/hal", "drivers/onewire",
             "drivers/ads1115", "drivers/sim", "drivers/can", "daemon/can", "daemon/canlink"]),
    ("daemon/store", "SQLite persistence", CORE + ["daemon/battery"]),
    ("web/server", "HTTP / WebSocket API and dashboard server",
     CORE + ["daemon/config", "daemon/control", "daemon/owner"]),
    ("daemon/integrations", "Signal K, Home Assistant (MQTT), Victron GX: their own thread, off the RT loop",
     CORE + ["daemon/config", "daemon/battery", "daemon/protection", "daemon/control", "daemon/owner",
             "daemon/runtime"]),
    ("daemon/app", "xregulatord: command line and wiring",
     CORE + ["daemon/config", "daemon/logging", "daemon/protection", "daemon/battery", "daemon/control",
             "daemon/runtime", "daemon/sim_rig", "daemon/store", "web/server", "daemon/integrations", "daemon/can", "daemon/canlink",
             "daemon/owner"] + DRIVERS),
    ("tools", "xr_gendocs, xregulator-field-off, xr_plant_curves (plots)", CORE + ["daemon/config", "drivers/sim"]),
]

SOURCE_ROOTS = ["daemon", "drivers", "web", "tools"]
SOURCE_EXT = (".h", ".cpp", ".def")
MAX_LINES = 400
# Non-test sources allowed over MAX_LINES for now, with the reason.
LONG_FILE_EXEMPTIONS: dict = {}
# Sources allowed to include a .cpp for now, with the reason.
CPP_INCLUDE_EXEMPTIONS: dict = {}
# Functions longer than this (a definition's first line to its closing brace
# at column 0) are split along their steps (the developers' guide).
MAX_FUNCTION_LINES = 80
# Functions allowed over MAX_FUNCTION_LINES, by "file:first line text", with
# the length each may not exceed. None today: every function outside the
# tests reads in one screen.
LONG_FUNCTION_EXEMPTIONS: dict = {}
# The pure layers take time as an input (TimeNs from the loop's monotonic
# clock): none of them may read a clock, so a wall-clock jump cannot move a
# stage timer, a protection's debounce or the SoC integration
# (docs/security.md "The clock").
PURE_FOLDERS = {"daemon/params", "daemon/core", "daemon/protection", "daemon/battery", "daemon/health",
                "daemon/control"}
CLOCK_RE = re.compile(r"\b(system_clock|steady_clock|high_resolution_clock|gettimeofday|clock_gettime|"
                      r"CLOCK_REALTIME|CLOCK_MONOTONIC|localtime|gmtime)\b|\btime\s*\(\s*(nullptr|NULL|0)?\s*\)")
# A comment says why and points into the repository: an issue tracker's
# numbers mean nothing to a reader of the code (the developers' guide).
ISSUE_TAG_RE = re.compile(r"\b[Ii]ssues? #?\d+")
# ... and points into the repository: the specification and fact files the
# project started from are not part of it (docs/control.md, docs/protections.md,
# docs/batteries.md and docs/sources.md say the same in the repository).
OUTSIDE_REF_RE = re.compile(r"\b(field-control|safeties-and-protections|architecture-legacy|battery-management|"
                            r"DESIGN)\.md|\b[\w-]+-facts\b|\.\./shared\b|/work/\w|\bseeds/")
# The words "seed" and "Ours" for the original firmware and for this project:
# a reader who clones the repository has neither; say "the original
# firmware", "the specification" or what was added here. A random
# generator's seed is not meant.
SPEC_WORD_RE = re.compile(r"\b[Ss]eeds?\b(?!\s*(=|\(|:\s*\d|corpus|files?\b|value|for the|of the (noise|PRNG|random)))"
                          r"|\bOurs\b|\(ours\b(?!,)")
# A random generator's seed (a scenario's `seed`, a field or variable of
# that name) and a control loop's integrator seed are not meant.
SPEC_WORD_CONTEXT_OK = re.compile(r"random|PRNG|prng|rng\b|corpus|fuzz|--seed|seed_|determinis|same seed|"
                                  r"mt19937|splitmix|xorshift|Seed\(|seed\)|"
                                  r"[.`'\"]seed\b|\bseed[`\"]|\bseed\s*[;%{]|\bseed \* \d|<<\s*seed\b|uint64_t seed\b|"
                                  r"noise seeds?\b|seed drives the noise|bumpless|reseed|integrator", re.I)
# Files that still use those words, with how many lines may (a ratchet: the
# count may only go down; the files of the control, protection and battery
# cores and their tests are reworded as those are split).
SPEC_WORD_ALLOWANCE = {
    "tests/unit/control/charging_stage_test.cpp": 1,
    "tests/unit/control/command_path_test.cpp": 1,
    "tests/unit/control/cv_loop_test.cpp": 2,
    "tests/unit/control/handover_test.cpp": 1,
    "tests/unit/control/override_modes_test.cpp": 3,
    "web/www/js/settings.js": 1,
}
# Beyond the C++ sources, these files are read for references outside the
# repository and for those words: every CMake file, the README, docs/, the
# tests, the scenarios, the dashboard's JavaScript and the packaging.
TEXT_ROOTS = ["docs", "tests", "scenarios", "web/www", "config", "debian", "systemd", "venus", "cmake", "tools"]
TEXT_EXT = (".md", ".txt", ".cmake", ".py", ".mjs", ".js", ".sh", ".toml", ".cpp", ".h", ".def", ".service")
SIGNATURE_SKIP = ("#", "//", "namespace", "}", "using", "class", "struct", "enum", "extern", "template", "static_assert")


def long_functions(text):
    """(first line number, first line text, length) of each function over
    MAX_FUNCTION_LINES: a definition starts at column 0 and ends at the next
    '}' at column 0 (clang-format's layout of this code)."""
    lines = text.split("\n")
    out, start = [], None
    for i, line in enumerate(lines):
        if start is None:
            if not line or line[0].isspace() or line.startswith(SIGNATURE_SKIP) or "(" not in line:
                continue
            j = i
            while j < len(lines) and not lines[j].rstrip().endswith(("{", ";", "}")):
                j += 1
            if j < len(lines) and lines[j].rstrip().endswith("{") and "=" not in lines[j].split("(")[0]:
                start = i
        elif line.startswith("}"):
            n = i - start + 1
            if n > MAX_FUNCTION_LINES:
                out.append((start + 1, lines[start], n))
            start = None
    return out


def exemption_of(rel, first_line):
    for key, limit in LONG_FUNCTION_EXEMPTIONS.items():
        f, head = key.split(":", 1)
        if f == rel and first_line.startswith(head):
            return limit
    return None
DAEMON_FOLDERS = {f.split("/")[1] for f, _, _ in LAYERS if f.startswith("daemon/")}
INCLUDE_RE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def folder_of_file(rel):
    parts = rel.split("/")
    if parts[0] in ("daemon", "drivers", "web") and len(parts) > 2:
        return parts[0] + "/" + parts[1]
    return parts[0]


def folder_of_include(inc):
    """The folder an include names, or None (system or generated header)."""
    parts = inc.split("/")
    if len(parts) < 2:
        return None
    if parts[0] in DAEMON_FOLDERS:
        return "daemon/" + parts[0]
    if parts[0] in ("drivers", "web", "daemon") and len(parts) > 2:
        return parts[0] + "/" + parts[1]
    return None


def sources(root):
    for top in SOURCE_ROOTS:
        for d, dirs, files in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(x for x in dirs if x not in ("node_modules", "www"))
            for f in sorted(files):
                if f.endswith(SOURCE_EXT):
                    path = os.path.join(d, f)
                    yield os.path.relpath(path, root).replace(os.sep, "/"), path


def text_files(root):
    """Every file read for outside references and the specification's words."""
    seen = set()
    for top in [""] + TEXT_ROOTS + SOURCE_ROOTS:
        base = os.path.join(root, top)
        if top == "":
            names = ["README.md", "CMakeLists.txt", "Makefile"]
            for n in names:
                if os.path.isfile(os.path.join(root, n)):
                    seen.add(n)
                    yield n, os.path.join(root, n)
            continue
        for d, dirs, files in os.walk(base):
            dirs[:] = sorted(x for x in dirs if x not in ("node_modules", "__pycache__", "build"))
            for f in sorted(files):
                if f == "CMakeLists.txt" or f.endswith(TEXT_EXT) or f.endswith(SOURCE_EXT):
                    path = os.path.join(d, f)
                    rel = os.path.relpath(path, root).replace(os.sep, "/")
                    if rel not in seen:
                        seen.add(rel)
                        yield rel, path


def spec_word_lines(text):
    out = []
    for i, line in enumerate(text.split("\n"), 1):
        if SPEC_WORD_RE.search(line) and not SPEC_WORD_CONTEXT_OK.search(line):
            out.append(i)
    return out


def check_text(root):
    """References outside the repository and the specification's words,
    in every file text_files() reads."""
    problems = []
    for rel, path in text_files(root):
        if rel == "tests/layout/layout_rules.py":
            continue  # the rules name what they look for
        try:
            with open(path, encoding="utf-8") as fh:
                text = fh.read()
        except (UnicodeDecodeError, OSError):
            continue
        for m in OUTSIDE_REF_RE.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            problems.append(f"{rel}:{line}: a file outside the repository ({m.group(0)}): cite docs/")
        lines = spec_word_lines(text)
        allowed = SPEC_WORD_ALLOWANCE.get(rel, 0)
        if len(lines) > allowed:
            problems.append(f"{rel}:{lines[0]}: 'seed'/'Ours' for the original firmware or this project on "
                            f"{len(lines)} line(s) (allowed {allowed}): say 'the original firmware', "
                            f"'the specification' or 'added here'")
    return problems


def check(root):
    return check_code(root) + check_text(root)


def check_code(root):
    allowed = {f: set(deps) | {f} for f, _, deps in LAYERS}
    problems = []
    for rel, path in sources(root):
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
        here = folder_of_file(rel)
        if here not in allowed:
            problems.append(f"{rel}: folder {here} is not in the layer table (tests/layout/layout_rules.py)")
            continue
        for m in INCLUDE_RE.finditer(text):
            inc = m.group(1)
            line = text.count("\n", 0, m.start()) + 1
            if inc.endswith(".cpp") and rel not in CPP_INCLUDE_EXEMPTIONS:
                problems.append(f"{rel}:{line}: includes a source file ({inc})")
            target = folder_of_include(inc)
            if target is not None and target not in allowed[here]:
                problems.append(f"{rel}:{line}: {here} may not include {target} ({inc})")
        lines = text.count("\n")
        if rel.endswith((".h", ".cpp")) and lines > MAX_LINES and rel not in LONG_FILE_EXEMPTIONS:
            problems.append(f"{rel}: {lines} lines (more than {MAX_LINES}: split it along its jobs)")
        if rel.endswith((".h", ".cpp")):
            for line, head, n in long_functions(text):
                limit = exemption_of(rel, head)
                if limit is None or n > limit:
                    problems.append(f"{rel}:{line}: a function of {n} lines (more than {MAX_FUNCTION_LINES}: "
                                    f"split it along its steps): {head.strip()[:60]}")
        for m in ISSUE_TAG_RE.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            problems.append(f"{rel}:{line}: an issue number ({m.group(0)}): say the reason and cite docs/")
        if here in PURE_FOLDERS:
            for m in CLOCK_RE.finditer(text):
                line = text.count("\n", 0, m.start()) + 1
                problems.append(f"{rel}:{line}: the pure layers read no clock ({m.group(0)}): take TimeNs as input")
    return problems


def transitive_reduction(graph):
    """Edges a -> b not implied by a longer path: the picture shows these."""
    def reach(start, skip_edge):
        seen, todo = set(), [n for n in graph[start] if (start, n) != skip_edge]
        while todo:
            n = todo.pop()
            if n not in seen:
                seen.add(n)
                todo.extend(graph.get(n, ()))
        return seen
    return {a: [b for b in deps if b not in reach(a, (a, b))] for a, deps in graph.items()}


def dot():
    graph = {f: sorted(set(deps)) for f, _, deps in LAYERS}
    direct = transitive_reduction(graph)
    out = [
        "// Generated by tests/layout/layout_rules.py dot (the layer table); do not edit.",
        "// Render: dot -Tsvg docs/architecture.dot -o docs/architecture.svg",
        "digraph layers {",
        '  graph [rankdir=BT, fontname="Helvetica", nodesep=0.25, ranksep=0.45,',
        '         label="An arrow A -> B: files in A may include B (and whatever B may include).", labelloc=b];',
        '  node [shape=box, style="rounded,filled", fontname="Helvetica", fontsize=10];',
        '  edge [color="#555555", arrowsize=0.6];',
    ]
    colour = {"daemon/params": "#e8f0fe", "daemon/core": "#e8f0fe", "daemon/protection": "#d2e3fc",
              "daemon/battery": "#d2e3fc", "daemon/control": "#d2e3fc"}
    for f, job, _ in LAYERS:
        fill = colour.get(f, "#fef7e0" if f.startswith("drivers/") else "#e6f4ea")
        label = f"{f}\\n{job}"
        out.append(f'  "{f}" [label="{label}", fillcolor="{fill}"];')
    for f, _, _ in LAYERS:
        for b in direct[f]:
            out.append(f'  "{f}" -> "{b}";')
    out.append("}")
    return "\n".join(out) + "\n"


def dot_check(root):
    path = os.path.join(root, "docs", "architecture.dot")
    try:
        with open(path, encoding="utf-8") as fh:
            current = fh.read()
    except OSError as e:
        return [f"{path}: {e}"]
    if current != dot():
        return ["docs/architecture.dot differs from the layer table: run "
                "tests/layout/layout_rules.py dot > docs/architecture.dot and render the SVG again"]
    return []


def self_test():
    """Each rule must catch a planted violation (and a clean tree passes)."""
    cases = {
        "drivers/ina228/x.h": '#include "runtime/handoffs.h"\n',        # driver reaching up
        "drivers/sim/y.cpp": '#include "app/cli.h"\n',                  # driver reaching the app
        "drivers/i2c/z.cpp": '#include "web/server/auth.h"\n',          # driver reaching the web
        "daemon/core/a.h": '#include "control/control_telemetry.h"\n',  # core reaching up
        "daemon/core/b.h": '#include "runtime/seqlock.h"\n',
        "daemon/store/c.cpp": '#include "store/other.cpp"\n',           # a .cpp included
        "web/server/d.cpp": "// long\n" * (MAX_LINES + 1),             # too long
        "daemon/nowhere/e.h": "",                                     # folder not in the table
        "daemon/control/f.cpp": "int f() {\n" + "  g();\n" * MAX_FUNCTION_LINES + "}\n",  # a long function
        "daemon/battery/g.cpp": "auto t = std::chrono::system_clock::now();\n",  # a clock in the core
        "daemon/app/h.cpp": "// The retry (issue 12, item 3).\n",  # an issue number instead of a reason
        "drivers/sim/i.h": "// 1.2 A (plant-facts 2.4).\n",  # a file outside the repository
        "daemon/battery/CMakeLists.txt": "# Pure battery management (plant-facts 3.1).\n",  # outside, in CMake
        "README.md": "The design is in ../shared/DESIGN notes.\n",  # outside, in the README
        "docs/new-page.md": "The seed's gain is 3.\n",  # the specification's word
        "tests/unit/x_test.cpp": "// Ours: a margin the original firmware lacks.\n",  # and this project's
    }
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        clean = os.path.join(tmp, "daemon", "core", "ok.h")
        os.makedirs(os.path.dirname(clean))
        with open(clean, "w") as fh:
            fh.write('#include "core/time.h"\n#include "params/params.h"\n#include <vector>\n')
        if check(tmp):
            failures.append(f"a clean tree is reported: {check(tmp)}")
        for rel, text in cases.items():
            path = os.path.join(tmp, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as fh:
                fh.write(text)
            found = [p for p in check(tmp) if p.startswith(rel)]
            if len(found) != 1:
                failures.append(f"{rel}: expected one problem, got {found}")
            os.remove(path)
        # Not violations: a random generator's seed, and the words the
        # project uses for its sources.
        for rel, text in {"tests/unit/y_test.cpp": "// The same random seed twice: byte for byte.\n",
                          "tests/sim/z_test.cpp": "  o.seed = seed;\n  for (std::uint64_t seed : {1u, 2u}) run(seed);\n",
                          "docs/other.md": "The original firmware's gain is 3 (docs/sources.md).\n"}.items():
            path = os.path.join(tmp, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as fh:
                fh.write(text)
            found = [p for p in check(tmp) if p.startswith(rel)]
            if found:
                failures.append(f"{rel}: not a violation, reported: {found}")
            os.remove(path)
    return failures


def main(argv):
    if len(argv) >= 2 and argv[1] == "dot":
        sys.stdout.write(dot())
        return 0
    if len(argv) == 3 and argv[1] in ("check", "dot-check"):
        problems = check(argv[2]) if argv[1] == "check" else dot_check(argv[2])
    elif len(argv) == 2 and argv[1] == "self-test":
        problems = self_test()
    else:
        sys.stderr.write(__doc__)
        return 2
    for p in problems:
        print(p)
    print(f"{argv[1]}: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
