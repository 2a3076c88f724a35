#!/usr/bin/python3
"""unattended-upgrades and xregulator's origin (tests/update/run.sh).

With /etc/apt/apt.conf.d/52xregulator-unattended-upgrades as the package
installs it, unattended-upgrades' own origin matching (its functions, loaded
from /usr/bin/unattended-upgrade) must NOT allow the xregulator candidate from
our repository; with that file's one line turned on (ON_CONF) it must.
A full `unattended-upgrade --dry-run` takes minutes on a small machine; this
asks the same question of the same code in seconds.

    uu_origin.py ON_CONF
"""
import importlib.machinery
import importlib.util
import sys

import apt
import apt_pkg

loader = importlib.machinery.SourceFileLoader("unattended_upgrade", "/usr/bin/unattended-upgrade")
spec = importlib.util.spec_from_loader("unattended_upgrade", loader)
uu = importlib.util.module_from_spec(spec)
loader.exec_module(uu)

apt_pkg.init_config()
cand = apt.Cache()["xregulator"].candidate
ours = [o for o in cand.origins if o.origin == "xregulator"]
if not ours:
    sys.exit(f"FAIL: the xregulator candidate {cand.version} is not from origin xregulator")
off = any(uu.is_allowed_origin(o, uu.get_allowed_origins()) for o in ours)
apt_pkg.read_config_file(apt_pkg.config, sys.argv[1])
on = any(uu.is_allowed_origin(o, uu.get_allowed_origins()) for o in ours)
print(f"xregulator {cand.version} from origin xregulator: allowed as shipped: {off}; with the setting on: {on}")
sys.exit(0 if (not off and on) else 1)
