#!/usr/bin/env python3
"""venus/install.sh against a fake GX root (docs/integrations.md "Victron GX"):
install, install again, a firmware update that wipes everything outside
/data and then the boot's /data/rc.local, uninstall. The owner's own
rc.local lines are kept throughout.

usage: gx_install_test.py
"""
import os
import shutil
import stat
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gx_bus import PYTHON, ROOT  # noqa: E402
from harness import Checks  # noqa: E402

INSTALL = os.path.join(ROOT, "venus", "install.sh")
URL = "http://192.168.1.20:8080"


def run(root, *args, script=INSTALL):
    r = subprocess.run(["sh", script, "--root", root] + list(args), capture_output=True, text=True, timeout=60,
                       env=dict(os.environ, PYTHON=PYTHON))
    print(f"$ install.sh {' '.join(args)} -> {r.returncode}\n{r.stdout}{r.stderr}", end="")
    return r


def boot_lines(root):
    with open(os.path.join(root, "data", "rc.local")) as f:
        return f.read().splitlines()


def firmware_update(root):
    """Everything outside /data is replaced: /service, /opt, the rest."""
    for name in os.listdir(root):
        if name != "data":
            shutil.rmtree(os.path.join(root, name))
    os.makedirs(os.path.join(root, "opt", "victronenergy"))
    os.makedirs(os.path.join(root, "service"))


def main():
    c = Checks()
    outside = tempfile.mkdtemp(prefix="xr-gx-install-")
    root = os.path.join(outside, "gx")
    app = os.path.join(root, "data", "xregulator")
    link = os.path.join(root, "service", "dbus-xregulator")
    try:
        os.makedirs(os.path.join(root, "data"))
        os.makedirs(os.path.join(root, "service"))
        os.makedirs(os.path.join(root, "opt", "victronenergy"))
        with open(os.path.join(root, "data", "rc.local"), "w") as f:
            f.write("#!/bin/sh\necho owner-line\n")
        token = os.path.join(outside, "token-from-pairing")
        with open(token, "w") as f:
            f.write("paired-device-token\n")

        c.check(run(root, "install", "--token-file", token).returncode != 0, "install without --xregulator fails")
        c.check(run(root, "install", "--xregulator", "ftp://x", "--token-file", token).returncode != 0,
                "install with a bad URL fails")
        c.check(not os.path.exists(app), "a refused install leaves nothing")

        r = run(root, "install", "--xregulator", URL, "--token-file", token)
        c.check(r.returncode == 0, "install succeeds")
        for f in ("dbus-xregulator", "xr_busitem.py", "xr_regulator.py", "xr_settings.py", "install.sh",
                  "service/run", "service/log/run", "xregulator.conf", "token"):
            c.check(os.path.exists(os.path.join(app, f)), f"installed /data/xregulator/{f}")
        c.check(stat.S_IMODE(os.stat(os.path.join(app, "token")).st_mode) == 0o600, "the token file is 0600")
        c.check(os.path.islink(link) and os.readlink(link) == os.path.join(app, "service"),
                "/service/dbus-xregulator links to the service folder")
        with open(os.path.join(app, "service", "run")) as f:
            run_script = f.read()
        c.check("--token-file" in run_script and os.path.join(app, "dbus-xregulator") in run_script,
                "the run script starts the installed driver")
        with open(os.path.join(app, "xregulator.conf")) as f:
            conf = f.read()
        c.check(f"XREGULATOR_URL={URL}" in conf and "XREGULATOR_ID=192_168_1_20" in conf,
                "the configuration holds the URL and the id from the host")
        r = subprocess.run([PYTHON, os.path.join(app, "dbus-xregulator"), "--help"], capture_output=True, text=True)
        c.check(r.returncode == 0 and "--xregulator" in r.stdout, "the installed copy runs (imports its modules)")
        lines = boot_lines(root)
        c.check(lines[:2] == ["#!/bin/sh", "echo owner-line"], "the owner's rc.local lines are kept")
        c.check(sum("xregulator GX driver" in x for x in lines) == 1, "one boot line")

        c.check(run(root, "install", "--xregulator", URL, "--token-file", token, "--id", "saloon").returncode == 0,
                "install again (an update) succeeds")
        c.check(sum("xregulator GX driver" in x for x in boot_lines(root)) == 1, "still one boot line")
        with open(os.path.join(app, "xregulator.conf")) as f:
            c.check("XREGULATOR_ID=saloon" in f.read(), "the new id is kept")

        firmware_update(root)
        c.check(not os.path.lexists(link), "the firmware update took the service link")
        r = subprocess.run(["sh", os.path.join(root, "data", "rc.local")], capture_output=True, text=True,
                           timeout=60)
        c.check(r.returncode == 0, f"the boot's rc.local runs ({r.stderr.strip()})")
        c.check(os.path.islink(link) and os.path.isdir(link), "after the boot the service is linked again")
        c.check(os.path.exists(os.path.join(app, "token")), "the token survived the update")
        r = run(root, "status")
        c.check("service: " in r.stdout and "not linked" not in r.stdout, "status says linked")

        c.check(run(root, "uninstall").returncode == 0, "uninstall succeeds")
        c.check(not os.path.exists(app), "uninstall removes /data/xregulator")
        c.check(not os.path.lexists(link), "uninstall removes the service link")
        c.check(boot_lines(root) == ["#!/bin/sh", "echo owner-line"],
                "uninstall drops only our rc.local line")
        c.check(run(root, "uninstall").returncode == 0, "uninstall twice is harmless")
    finally:
        shutil.rmtree(outside, ignore_errors=True)
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
