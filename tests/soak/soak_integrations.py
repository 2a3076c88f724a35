"""The integrations that exist, for the soak test ("... and the
integrations that exist"), started with the integration tests' own helpers
(tests/integrations/harness.py, signalk_test.py):

  - Debian's mosquitto broker, with the daemon's Home Assistant MQTT
    publisher on it and a subscriber recording every state document;
  - a real signalk-server (npm, pinned in tests/integrations/signalk/) the
    daemon streams deltas to;
  - the simulated CAN buses of --sim: the BMS (day.toml's [bms]) and the
    NMEA 2000 bus with its engine ECU ([can] n2k_interface, [engine] ecu).

At the end each must still be connected, with no outage, and have moved
messages; anything else is counted as an error."""
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "integrations"))

from harness import Harness  # noqa: E402
from signalk_test import SignalK  # noqa: E402

NODE_ID = "soak"


class Integrations:
    def __init__(self, daemon, node, signalk_server):
        self.h = Harness(daemon)  # its temporary directory and its process list
        self.node, self.signalk_server = node, signalk_server
        self.sk = None
        self.sub = None
        self.sub_path = os.path.join(self.h.dir, "ha-state.txt")

    def start(self):
        if not shutil.which("mosquitto"):  # Debian installs the broker in /usr/sbin
            os.environ["PATH"] += os.pathsep + "/usr/sbin"
        self.h.start_broker()
        out = open(self.sub_path, "w")
        self.sub = subprocess.Popen(["mosquitto_sub", "-h", "127.0.0.1", "-p", str(self.h.broker_port), "-t",
                                     f"xregulator/{NODE_ID}/state", "-R"], stdout=out, stderr=subprocess.STDOUT)
        self.h.procs.append(self.sub)
        if self.signalk_server:
            self.sk = SignalK(self.h, self.node, self.signalk_server, secured=False)
            self.sk.start()

    def config(self):
        """The daemon's configuration text for them."""
        text = (f'[integrations.mqtt]\nenabled = true\nhost = "127.0.0.1"\nport = {self.h.broker_port}\n'
                f'node_id = "{NODE_ID}"\nstate_rate_hz = 1.0\n\n'
                # Any name: --sim puts the NMEA 2000 bus on a simulated segment.
                '[can]\nn2k_interface = "can1"\n\n')
        if self.sk:
            text += (f'[integrations.signalk]\nenabled = true\n'
                     f'url = "ws://127.0.0.1:{self.sk.port}/signalk/v1/stream?subscribe=none"\n'
                     'rate_hz = 1.0\nalternator_id = "main"\nbattery_id = "house"\n\n')
        return text

    def check(self, system, status, counters):
        """At the end, from the daemon's /api/system and /api/status (dicts)
        and the broker and server themselves."""
        names = ["mqtt"] + (["signalk"] if self.sk else [])
        found = {i["name"]: i for i in system.get("integrations", [])}
        report = {}
        for name in names:
            i = found.get(name)
            if i is None:
                counters.add("errors.integration", example=f"/api/system lists no '{name}'")
                continue
            report[name] = {k: i.get(k) for k in ("connected", "messages_sent", "outages", "last_error")}
            if not i.get("connected"):
                counters.add("errors.integration", example=f"{name} not connected: {i.get('last_error')}")
            if i.get("outages", 0) > 0:
                counters.add("errors.integration", i["outages"], example=f"{name}: {i['outages']} outages")
            if i.get("messages_sent", 0) == 0:
                counters.add("errors.integration", example=f"{name} sent nothing")
        with open(self.sub_path) as f:
            docs = [ln for ln in f if ln.startswith("{")]
        report["ha_state_documents"] = len(docs)
        if not docs:
            counters.add("errors.integration", example="no Home Assistant state document reached the broker")
        else:
            try:
                json.loads(docs[-1])
            except ValueError as e:
                counters.add("errors.integration", example=f"the last HA state document: {e}")
        # The simulated BMS on CAN: its limits reach the regulator (day.toml's
        # cvl_v 14.2) and it is not stale.
        report["bms_state"], report["bms_cvl_v"] = status.get("bms_state"), status.get("bms_cvl_v")
        if report["bms_state"] not in ("OK", "WARNING") or abs((report["bms_cvl_v"] or 0) - 14.2) > 0.05:
            counters.add("errors.integration", example=f"BMS on CAN: state {report['bms_state']}, "
                                                       f"CVL {report['bms_cvl_v']}")
        if self.sk:
            alt = self.sk.alternator() or {}
            report["signalk_alternator_voltage"] = alt.get("voltage", {}).get("value")
            if report["signalk_alternator_voltage"] is None:
                counters.add("errors.integration", example="signalk-server holds no alternator voltage")
        return report

    def rss_kb(self):
        """The helpers' own memory (not the daemon's): for the report."""
        out = {}
        for name, p in (("mosquitto", self.h.broker), ("signalk-server", self.sk.proc if self.sk else None)):
            if p and p.poll() is None:
                with open(f"/proc/{p.pid}/status") as f:
                    out[name] = next(int(ln.split()[1]) for ln in f if ln.startswith("VmRSS:"))
        return out

    def stop(self):
        self.h.stop()


def signalk_default():
    """The pinned signalk-server of `make deps`, when it is installed."""
    path = os.path.join(HERE, "..", "integrations", "signalk", "node_modules", "signalk-server", "bin",
                        "signalk-server")
    return os.path.realpath(path) if os.path.exists(path) else ""


