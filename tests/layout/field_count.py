#!/usr/bin/env python3
"""Owned parts, not hubs (docs/architecture.md "The parts of one tick").

Every class in the control core (daemon/control, daemon/protection,
daemon/battery) owns a small piece of state: no class holds more than
MAX_FIELDS member variables, and the values one regulator step hands from
stage to stage (Regulator::Tick) stay a handful. A class that grows past the
limit is a hub again: split it into parts that each own their state.

Counted: non-static data members declared directly in a `class` body, or in
a `struct` body that also declares a member function (a struct of plain data,
an input or output record, is a message, not a part). Nested types are
counted on their own.

  field_count.py check ROOT   exit 1 and name each class over its limit
  field_count.py list ROOT    every counted class with its count
  field_count.py self-test    the check catches a planted 21-field class
"""
import pathlib
import re
import sys
import tempfile

FOLDERS = ["daemon/control", "daemon/protection", "daemon/battery"]
MAX_FIELDS = 20
# The step's blackboard: values computed by one stage and read by a later one.
LIMITS = {"Tick": 8}

SKIP_WORDS = ("using", "typedef", "friend", "static", "enum", "template", "class", "struct",
              "static_assert", "union", "constexpr", "inline static")
HEAD_RE = re.compile(r"\b(class|struct)\s+(?:\[\[[^\]]*\]\]\s*)?([\w:]+)\s*(?:final\s*)?(?::[^;{]*)?\{")


def strip_comments_and_strings(text):
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text)
    return re.sub(r"'(?:\\.|[^'\\])'", "''", text)


def body_end(text, open_at):
    depth = 0
    for i in range(open_at, len(text)):
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return i
    return len(text)


def statements(body):
    """The declarations directly in a class body, each as its text up to ';' or a body's '}'."""
    out, cur, depth = [], [], 0
    for ch in body:
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0 and "(" in "".join(cur).split("=", 1)[0]:
                out.append("".join(cur) + "{}")  # an inline function body ends the declaration
                cur = []
                continue
        if ch == ";" and depth == 0:
            out.append("".join(cur))
            cur = []
            continue
        if depth == 0 or ch in "{}":
            cur.append(ch)
    return [re.sub(r"\b(public|private|protected)\s*:", "", s).strip() for s in out]


def without_templates(s):
    prev = None
    while prev != s:
        prev, s = s, re.sub(r"<[^<>]*>", "", s)
    return s


def classify(stmt):
    """'field', 'function' or None for one declaration."""
    if not stmt or stmt.startswith(SKIP_WORDS) or stmt.startswith("~"):
        return None
    head = without_templates(re.split(r"[={]", stmt, maxsplit=1)[0])
    if "(" in head or re.search(r"\boperator\b", head):
        return "function"
    return "field"


def classes_in(text):
    text = strip_comments_and_strings(text)
    for m in HEAD_RE.finditer(text):
        open_at = m.end() - 1
        body = text[open_at + 1:body_end(text, open_at)]
        kinds = [classify(s) for s in statements(body)]
        fields = sum(k == "field" for k in kinds)
        has_methods = any(k == "function" for k in kinds)
        if m.group(1) == "class" or has_methods or m.group(2).split("::")[-1] in LIMITS:
            yield m.group(2), fields


def counted(root):
    root = pathlib.Path(root)
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix in (".h", ".cpp"):
                rel = path.relative_to(root).as_posix()
                for name, fields in classes_in(path.read_text(encoding="utf-8")):
                    yield rel, name, fields, LIMITS.get(name.split("::")[-1], MAX_FIELDS)


def check(root):
    over = [(rel, name, n, limit) for rel, name, n, limit in counted(root) if n > limit]
    for rel, name, n, limit in over:
        print(f"{rel}: {name} holds {n} member variables (limit {limit}): split it into parts that own their state")
    print(f"field count: {len(over)} problem(s)")
    return 1 if over else 0


def list_all(root):
    for rel, name, n, limit in sorted(counted(root), key=lambda r: -r[2]):
        print(f"{n:4d} / {limit:2d}  {name:40s} {rel}")
    return 0


def self_test():
    fields = "\n".join(f"  double f{i}_ = 0.0;  // a note" for i in range(21))
    planted = ("class Hub {\n public:\n  void update(const In& in);\n  double value() const { return f0_; }\n"
               "  struct Nested { int a; };\n  static constexpr int kMax = 3;\n"
               f" private:\n{fields}\n  std::function<void(int)> cb_;\n}};\n")
    small = ("class Part {\n public:\n  explicit Part(const Params& p) : p_(p) {}\n  void update();\n"
             " private:\n  const Params& p_;\n  std::array<int, 4> a_{};\n};\n"
             "struct Inputs { " + " ".join(f"double i{i};" for i in range(30)) + " };\n")
    with tempfile.TemporaryDirectory() as d:
        root = pathlib.Path(d)
        (root / "daemon/control").mkdir(parents=True)
        (root / "daemon/control/small.h").write_text(small)
        if check(root) != 0:
            print("self-test: a small class or a plain input struct was refused")
            return 1
        (root / "daemon/control/hub.h").write_text(planted)
        counts = {name: n for _, name, n, _ in counted(root)}
        if counts.get("Hub") != 22 or counts.get("Part") != 2 or "Inputs" in counts:
            print(f"self-test: wrong counts {counts}")
            return 1
        if check(root) != 1:
            print("self-test: the planted 22-field class was not refused")
            return 1
    print("self-test: the check refuses a planted 22-field class and passes small parts")
    return 0


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else "check"
    if cmd == "self-test":
        sys.exit(self_test())
    root = sys.argv[2] if len(sys.argv) > 2 else "."
    sys.exit(list_all(root) if cmd == "list" else check(root))
