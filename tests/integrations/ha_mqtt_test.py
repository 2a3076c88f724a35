#!/usr/bin/env python3
"""Home Assistant MQTT discovery against Debian's real mosquitto (docs/integrations.md).

  ha_mqtt_test.py XREGULATORD

Part A, anonymous broker, commands off: every retained discovery topic and
the fields Home Assistant requires in it; the state document updating; the
broker killed mid-run (no control overrun, one log line for the outage,
reconnect and re-announce when it is back); a re-announce after
homeassistant/status "online"; a command topic that is ignored because
commands are off; the last will "offline" when the daemon is killed -9.
Part B, broker with a password, commands on: the select and button configs,
off and auto through the select, limp home through the button, a bad payload
refused and counted, and "offline" said by a clean stop.

The daemon runs at --speed SPEED: its state period and reconnect backoff are
simulated time (docs/architecture.md "One clock")."""
import json
import sys
import time

from harness import Checks, Harness, wait_until

NODE = "boat1"
SENSORS = {"battery_voltage": "V", "battery_current": "A", "alternator_current": "A",
           "alternator_temperature": "°C", "soc": "%", "field_duty": "%", "power": "W", "stage": None,
           "mode": None, "charged_energy": "kWh", "capacity_measured": "Ah", "battery_resistance": "mΩ",
           "alternator_run_hours": "h", "alternator_life_used": "%", "belt_slips": None,
           "charging_state": None, "limited_by": None}
BINARY = ["field", "alarm", "weather_mode", "incident"]
SPEED = 5


def config_topic(component, obj):
    return f"homeassistant/{component}/xregulator_{NODE}/{obj}/config"


def expected_topics(commands):
    t = {config_topic("sensor", s) for s in SENSORS} | {config_topic("binary_sensor", b) for b in BINARY}
    t.add(config_topic("event", "incident"))  # an incident's start and end (docs/integrations.md)
    if commands:
        t |= {config_topic("select", "regulator_mode"), config_topic("button", "limp_home")}
    return t


def check_config(c, topic, payload):
    """The fields Home Assistant's MQTT discovery requires or we promise."""
    try:
        doc = json.loads(payload)
    except ValueError:
        c.check(False, f"{topic}: payload is not JSON: {payload[:80]}")
        return
    component, obj = topic.split("/")[1], topic.split("/")[3]
    c.check(doc.get("unique_id") == f"xregulator_{NODE}_{obj}", f"{topic}: unique_id {doc.get('unique_id')}")
    c.check(isinstance(doc.get("name"), str) and doc["name"], f"{topic}: name")
    dev = doc.get("device", {})
    c.check(dev.get("identifiers") == [f"xregulator_{NODE}"], f"{topic}: device.identifiers {dev}")
    c.check(dev.get("name") == f"xregulator {NODE}", f"{topic}: one device block (name)")
    c.check(doc.get("availability_topic") == f"xregulator/{NODE}/availability", f"{topic}: availability_topic")
    if component in ("sensor", "binary_sensor"):
        c.check(doc.get("state_topic") == f"xregulator/{NODE}/state", f"{topic}: state_topic")
        c.check(doc.get("value_template") == "{{ value_json.%s }}" % obj, f"{topic}: value_template")
    if component == "sensor":
        unit = SENSORS[obj]
        c.check(doc.get("unit_of_measurement") == unit, f"{topic}: unit {doc.get('unit_of_measurement')} != {unit}")
    if component == "binary_sensor":
        c.check(doc.get("payload_on") == "ON" and doc.get("payload_off") == "OFF", f"{topic}: payloads")
    if component == "select":
        c.check(doc.get("command_topic") == f"xregulator/{NODE}/set/mode", f"{topic}: command_topic")
        c.check(doc.get("options") == ["off", "auto"], f"{topic}: options")
    if component == "button":
        c.check(doc.get("command_topic") == f"xregulator/{NODE}/set/limp_home", f"{topic}: command_topic")


def check_discovery(c, h, commands):
    # "connected" can be seen before the broker has stored every retained
    # config; a subscriber that comes first gets them live and
    # --retained-only stops at the first. Read again until they are stored.
    for _ in range(10):
        # As many as expected: mosquitto_sub returns when it has them all.
        msgs = h.sub("homeassistant/#", len(expected_topics(commands)), timeout=2, retained_only=True)
        topics = {t for t, _ in msgs}
        if topics == expected_topics(commands):
            break
        time.sleep(1)
    c.check(topics == expected_topics(commands),
            f"discovery topics: missing {expected_topics(commands) - topics}, extra {topics - expected_topics(commands)}")
    for t, p in msgs:
        check_config(c, t, p)


def states(h, n):
    out = []
    for _, p in h.sub(f"xregulator/{NODE}/state", n, timeout=15):
        out.append(json.loads(p))
    return out


def part_a(c, daemon):
    h = Harness(daemon)
    try:
        h.start_broker()
        h.start_daemon(f"""[integrations.mqtt]
enabled = true
host = "127.0.0.1"
port = {h.broker_port}
node_id = "{NODE}"
""", speed=SPEED)
        wait_until("mqtt connected", lambda: h.integration("mqtt")["connected"], 20)
        check_discovery(c, h, commands=False)
        avail = h.sub(f"xregulator/{NODE}/availability", 1, timeout=5, retained_only=True)
        c.check(avail == [(f"xregulator/{NODE}/availability", "online")], f"availability retained online: {avail}")

        docs = states(h, 3)
        c.check(len(docs) == 3, f"three state documents arrive ({len(docs)})")
        for d in docs:
            for key in list(SENSORS) + BINARY + ["regulator_mode"]:
                c.check(key in d, f"state has {key}")
            # null ("unknown" in Home Assistant) in the first second, before the
            # regulator's first battery reading; never a made-up 0 V.
            v = d.get("battery_voltage")
            c.check(v is None or 10.0 < v < 16.0, f"battery_voltage plausible: {v}")
            c.check(d.get("field") in ("ON", "OFF"), "field is ON or OFF")
            c.check(d.get("regulator_mode") == "auto", "regulator_mode auto")
        st = h.status()
        c.check(abs(docs[-1]["battery_voltage"] - st["battery_v"]) < 0.5,
                f"state battery_voltage {docs[-1]['battery_voltage']} matches /api/status {st['battery_v']}")
        metrics = h.get("/metrics")
        c.check('xregulator_integration_connected{integration="mqtt"} 1' in metrics, "/metrics: mqtt connected")
        c.check('xregulator_integration_messages_sent_total{integration="mqtt"}' in metrics, "/metrics: messages sent")

        # Commands are off: a command topic changes nothing.
        h.pub(f"xregulator/{NODE}/set/mode", "off")
        h.wait_sim(5)
        c.check(states(h, 1)[0]["regulator_mode"] == "auto", "commands off: 'off' ignored")
        c.check("from Home Assistant" not in h.log_text(), "commands off: no command logged")

        # Re-announce when Home Assistant comes back online.
        listener = h.sub_start("homeassistant/+/+/+/config")
        h.pub("homeassistant/status", "online")
        time.sleep(1)
        fresh = {t for t, _ in h.sub_collect(listener)}
        c.check(fresh == expected_topics(False), f"re-announce after online: {len(fresh)} configs")

        # The broker dies mid-run and comes back.
        overruns0, ticks0 = h.overruns(), h.status()["loop"]["ticks"]
        h.kill_broker()
        wait_until("mqtt to notice the dead broker", lambda: not h.integration("mqtt")["connected"], 20)
        h.wait_sim(4)  # several reconnect attempts (backoff 1 s, 2 s: simulated time)
        i = h.integration("mqtt")
        c.check(i["last_error"] != "", f"last_error while down: {i['last_error']!r}")
        c.check(h.daemon.poll() is None, "daemon alive with the broker dead")
        c.check(h.status()["loop"]["ticks"] > ticks0, "control loop ticks on with the broker dead")
        h.start_broker(port=h.broker_port)
        wait_until("mqtt to reconnect", lambda: h.integration("mqtt")["connected"], 40)
        i = h.integration("mqtt")
        c.check(i["outages"] == 1, f"one outage counted ({i['outages']})")
        c.check(h.log_text().count("mqtt: ") >= 2, "outage and recovery logged")
        c.check(h.log_text().count("retrying with backoff") == 1, "the dead broker logged once, not per attempt")
        c.check("mqtt: connected again after" in h.log_text(), "recovery logged")
        check_discovery(c, h, commands=False)  # the new broker has no retained configs of its own
        c.check(h.overruns() == overruns0, f"no control overrun across the outage ({overruns0} -> {h.overruns()})")

        # kill -9: the broker publishes the last will.
        listener = h.sub_start(f"xregulator/{NODE}/availability")
        h.daemon.kill()
        h.daemon.wait()
        time.sleep(1)
        got = h.sub_collect(listener)
        c.check((f"xregulator/{NODE}/availability", "offline") in got, f"LWT offline after kill -9: {got}")
    finally:
        h.stop()


def part_b(c, daemon):
    h = Harness(daemon)
    try:
        h.start_broker(users={"ha": "s3cret-pass"})
        h.start_daemon(f"""[integrations.mqtt]
enabled = true
host = "127.0.0.1"
port = {h.broker_port}
node_id = "{NODE}"
username = "ha"
password = "s3cret-pass"
commands_enabled = true
""", speed=SPEED)
        wait_until("mqtt connected with credentials", lambda: h.integration("mqtt")["connected"], 20)
        check_discovery(c, h, commands=True)
        h.pub(f"xregulator/{NODE}/set/mode", "off")
        wait_until("regulator off through the select", lambda: states(h, 1)[0]["regulator_mode"] == "off", 15)
        c.check("command 'off' from Home Assistant" in h.log_text(), "the command is logged with its source")
        h.pub(f"xregulator/{NODE}/set/mode", "auto")
        wait_until("regulator auto through the select", lambda: states(h, 1)[0]["regulator_mode"] == "auto", 15)
        h.pub(f"xregulator/{NODE}/set/limp_home", "PRESS")
        wait_until("limp home through the button", lambda: states(h, 1)[0]["mode"] == "MODE_LIMP_HOME", 15)
        c.check("command 'limp_home' from Home Assistant" in h.log_text(), "limp home logged")
        refused0 = h.integration("mqtt")["values_refused"]
        h.pub(f"xregulator/{NODE}/set/mode", "explode")
        wait_until("bad command payload counted", lambda: h.integration("mqtt")["values_refused"] == refused0 + 1, 10)
        c.check(states(h, 1)[0]["mode"] == "MODE_LIMP_HOME", "a bad payload changes nothing")
        # A clean stop says offline itself.
        h.daemon.terminate()
        h.daemon.wait(timeout=20)
        avail = h.sub(f"xregulator/{NODE}/availability", 1, timeout=5, retained_only=True)
        c.check(avail == [(f"xregulator/{NODE}/availability", "offline")], f"offline after a clean stop: {avail}")
    finally:
        h.stop()


def main():
    c = Checks()
    part_a(c, sys.argv[1])
    part_b(c, sys.argv[1])
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
