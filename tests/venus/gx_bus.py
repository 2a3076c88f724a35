"""Pieces of the GX driver's tests: a private dbus-daemon standing in for a
GX's system bus, the localsettings stand-in, the driver, and reading paths
with dbus-send the way a person on a GX would with dbus-spy's help."""
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DRIVER = os.path.join(ROOT, "venus", "dbus-xregulator")
LOCALSETTINGS = os.path.join(HERE, "fake_localsettings.py")
# Debian's python3 carries python3-dbus and python3-gi (what Venus OS has);
# another python3 first on PATH may not.
PYTHON = "/usr/bin/python3"
sys.path.insert(0, os.path.join(ROOT, "tests", "integrations"))

from harness import wait_until  # noqa: E402,F401


class Bus:
    """A private dbus-daemon; its address goes to the children as
    DBUS_SYSTEM_BUS_ADDRESS, as a GX's system bus."""

    def __init__(self, workdir, procs):
        self.dir = workdir
        self.procs = procs
        sock = os.path.join(workdir, "bus")
        self.daemon = subprocess.Popen(["dbus-daemon", "--session", "--nofork", "--print-address=1",
                                        "--address=unix:path=" + sock], stdout=subprocess.PIPE, text=True)
        procs.append(self.daemon)
        self.address = self.daemon.stdout.readline().strip()
        if not self.address:
            raise AssertionError("dbus-daemon gave no address")
        self.env = dict(os.environ, DBUS_SYSTEM_BUS_ADDRESS=self.address)
        self.env.pop("DBUS_SESSION_BUS_ADDRESS", None)

    def start(self, args, log_name):
        log = open(os.path.join(self.dir, log_name), "a")
        p = subprocess.Popen(args, stdout=log, stderr=log, env=self.env)
        self.procs.append(p)
        return p

    def start_localsettings(self):
        p = self.start([PYTHON, LOCALSETTINGS], "localsettings.log")
        wait_until("localsettings on the bus", lambda: "com.victronenergy.settings" in self.names(), 15)
        return p

    def start_driver(self, url, token_file, dev_id, extra=()):
        return self.start([PYTHON, DRIVER, "--xregulator", url, "--token-file", token_file, "--id", dev_id] +
                          list(extra), f"driver-{dev_id}.log")

    def send(self, dest, path, member, *args, timeout=5):
        r = subprocess.run(["dbus-send", "--system", "--print-reply", f"--reply-timeout={timeout * 1000}",
                            f"--dest={dest}", path, member] + list(args),
                           capture_output=True, text=True, env=self.env, timeout=timeout + 5)
        if r.returncode != 0:
            raise AssertionError(f"dbus-send {path} {member}: {r.stderr.strip()}")
        return r.stdout

    def names(self):
        try:
            out = self.send("org.freedesktop.DBus", "/org/freedesktop/DBus", "org.freedesktop.DBus.ListNames")
        except AssertionError:
            return []
        return re.findall(r'string "([^"]+)"', out)

    def get(self, dest, path):
        """GetValue of one path: a float, an int, a str, or None (invalid)."""
        return parse_variant(self.send(dest, path, "com.victronenergy.BusItem.GetValue"))

    def text(self, dest, path):
        out = self.send(dest, path, "com.victronenergy.BusItem.GetText")
        m = re.search(r'string "(.*)"', out)
        return m.group(1) if m else None

    def set(self, dest, path, typed_value):
        """SetValue(variant:<typed_value>), e.g. 'double:20': the int answer."""
        out = self.send(dest, path, "com.victronenergy.BusItem.SetValue", "variant:" + typed_value)
        return int(re.search(r"int32 (-?\d+)", out).group(1))

    def items(self, dest):
        """GetItems on "/": {path: value}."""
        out = self.send(dest, "/", "com.victronenergy.BusItem.GetItems")
        items = {}
        for m in re.finditer(r'string "(/[^"]*)"\s*array \[\s*dict entry\(\s*string "Value"\s*variant\s+([^\n]*)', out):
            items[m.group(1)] = parse_value_line(m.group(2))
        return items

    def introspect_paths(self, dest, path="/"):
        """Every object path under `path`, found by Introspect as dbus-spy does."""
        out = self.send(dest, path, "org.freedesktop.DBus.Introspectable.Introspect")
        kids = re.findall(r'<node name="([^"]+)"/>', out)
        found = []
        if "com.victronenergy.BusItem" in out and 'name="GetText"' in out and path != "/" and not kids:
            found.append(path)
        for k in kids:
            found += self.introspect_paths(dest, (path.rstrip("/") + "/" + k))
        return found


def parse_value_line(line):
    line = line.strip()
    if line.startswith("array ["):
        return None
    kind, _, rest = line.partition(" ")
    rest = rest.strip()
    if kind == "double":
        return float(rest)
    if kind in ("int32", "int64", "uint32", "int16", "byte"):
        return int(rest)
    if kind == "string":
        return rest[1:-1] if rest.startswith('"') else rest
    return rest


def parse_variant(out):
    m = re.search(r"variant\s+([^\n]*)", out)
    if not m:
        raise AssertionError("no variant in: " + out)
    return parse_value_line(m.group(1))
