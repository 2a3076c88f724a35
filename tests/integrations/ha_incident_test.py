#!/usr/bin/env python3
"""An incident in Home Assistant through Debian's real mosquitto
(docs/integrations.md "Alarms that reach the owner"): xregulatord --sim with
[integrations.mqtt], one simulated thermal fault (the alternator's sensor
reads 170 F from 12 s to 18 s of simulated time), at --speed SPEED: every
wait is for a message, an event or the daemon's clock.

  ha_incident_test.py XREGULATORD

The discovery configs of the Incident binary sensor (device class problem,
its words as attributes) and the Incident event entity; the binary sensor's
state turns ON with the fault's title and what to do, and OFF once it is
over; the event entity fires exactly one start and one end, with the same
incident id."""
import json
import os
import sys

from harness import Checks, Harness, wait_until
from notify_test import FAULT

NODE = "boat1"
SPEED = 5  # the fault, the settle and the state period are simulated time
FAULT_AT_S = 12


def incident_runs(docs):
    """The binary sensor's state as runs: OFF, ON, OFF is one incident."""
    seq = [d["incident"] for d in docs]
    return [v for i, v in enumerate(seq) if i == 0 or seq[i - 1] != v]


def main():
    c = Checks()
    h = Harness(sys.argv[1])
    try:
        h.start_broker()
        # Listening before the daemon starts: every document from its first.
        states = h.sub_start(f"xregulator/{NODE}/state")
        events = h.sub_start(f"xregulator/{NODE}/incident")
        scenario = os.path.join(h.dir, "fault.toml")
        with open(scenario, "w") as f:
            # Later than the push test's fault: the bridge is connected first.
            f.write(FAULT.replace("at_s = 4", f"at_s = {FAULT_AT_S}").replace("at_s = 10", f"at_s = {FAULT_AT_S + 6}"))
        h.start_daemon(f"""[integrations.mqtt]
enabled = true
host = "127.0.0.1"
port = {h.broker_port}
node_id = "{NODE}"
""", ["--scenario", scenario], speed=SPEED)
        wait_until("mqtt connected", lambda: h.integration("mqtt")["connected"], 20)
        t_connected = h.status()["t_s"]
        c.check(t_connected < FAULT_AT_S, f"connected at {t_connected:.1f} s, before the fault (simulated time)")
        # The discovery documents follow the connection (later on a loaded machine): wait for both.
        topic = f"homeassistant/+/xregulator_{NODE}/incident/config"
        wait_until("the incident discovery documents",
                   lambda: len(dict(h.sub(topic, 2, timeout=2, retained_only=True))) == 2, 20)
        configs = dict(h.sub(topic, 2, timeout=10, retained_only=True))
        sensor = json.loads(configs.get(f"homeassistant/binary_sensor/xregulator_{NODE}/incident/config", "{}"))
        c.check(sensor.get("device_class") == "problem" and sensor.get("payload_on") == "ON",
                f"the Incident binary sensor: {sensor}")
        c.check(sensor.get("json_attributes_topic") == f"xregulator/{NODE}/state", "its words are attributes")
        event = json.loads(configs.get(f"homeassistant/event/xregulator_{NODE}/incident/config", "{}"))
        c.check(event.get("event_types") == ["start", "end"] and event.get("state_topic") == f"xregulator/{NODE}/incident",
                f"the Incident event entity: {event}")
        wait_until("the fault to come and go", lambda: any(
            e["code"] == "ProtectionClear" and e["reason"] == "REASON_TEMP_CRITICAL"
            for e in json.loads(h.get("/api/events?limit=200"))["events"]), 60)
        # The end comes after the settle (5 s of simulated time), with its state document.
        wait_until("the end fired", lambda: any('"end"' in p for _, p in h.sub_seen(events)), 30)
        wait_until("the state OFF again after the end",
                   lambda: incident_runs([json.loads(p) for _, p in h.sub_seen(states)])[-1:] == ["OFF"] and
                   "ON" in incident_runs([json.loads(p) for _, p in h.sub_seen(states)]), 30)
        h.wait_sim(2)  # a second start or end would come within the tracker's next polls
        docs = [json.loads(p) for _, p in h.sub_collect(states)]
        runs = incident_runs(docs)
        # OFF, then ON for the fault, then OFF: one run of ON.
        c.check(runs == ["OFF", "ON", "OFF"], f"the binary sensor turns on and off once: {runs}")
        on = [d for d in docs if d["incident"] == "ON"]
        if on:
            detail = on[0]["incident_detail"]
            c.check(detail.get("title") == "Alternator far too hot", f"ON with the title: {detail}")
            c.check(detail.get("what_to_do", "").startswith("Let it cool"), f"and what to do: {detail}")
        c.check(docs and docs[-1]["incident_detail"] == {}, "OFF carries no stale words")
        fired = [json.loads(p) for _, p in h.sub_collect(events)]
        c.check([e["event_type"] for e in fired] == ["start", "end"], f"one start and one end fire: {fired}")
        if len(fired) == 2:
            c.check(fired[0]["incident_id"] == fired[1]["incident_id"], "one incident id")
            c.check(fired[1]["title"] == "Alternator far too hot" and "Over after" in fired[1]["what_happened"],
                    f"the end names the worst reason and how long: {fired[1]}")
    finally:
        h.stop()
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
