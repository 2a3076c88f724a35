#!/usr/bin/env python3
"""MQTT commands are actions, never states, from trusted clients only
(docs/security.md "MQTT commands"), against Debian's real mosquitto.

  mqtt_commands_test.py XREGULATORD

retained_command_is_not_replayed_at_start: a limp-home press stored
retained on the broker before the daemon starts is ignored, counted and
deleted from the broker; a live press still works; a retained press sent
while the daemon listens acts once and is deleted, so a restart does not
replay it.
commands_stay_off_when_the_broker_accepts_anonymous_clients: with a password
configured but a broker that also lets clients in without one, the daemon
says so, offers no command entities and ignores a command."""
import json
import sys
import time

from harness import Checks, Harness, wait_until

NODE = "boat1"
LIMP = f"xregulator/{NODE}/set/limp_home"
MODE = f"xregulator/{NODE}/set/mode"
CONF = """[integrations.mqtt]
enabled = true
host = "127.0.0.1"
port = {port}
node_id = "{node}"
username = "ha"
password = "s3cret-pass"
commands_enabled = true
"""
COMMANDS_ON = "commands from Home Assistant are on"
SPEED = 5  # the backoff and state period are simulated time


def state(h):
    msgs = h.sub(f"xregulator/{NODE}/state", 1, timeout=15)
    return json.loads(msgs[0][1])


def retained(h, topic):
    # A retained message comes with the subscription's answer: 1 s is ample.
    return h.sub(topic, 1, timeout=1, retained_only=True)


def retained_command_is_not_replayed_at_start(c, daemon):
    h = Harness(daemon)
    try:
        h.start_broker(users={"ha": "s3cret-pass"})
        h.pub(LIMP, "PRESS", retain=True)
        c.check(retained(h, LIMP) == [(LIMP, "PRESS")], "the broker holds the retained press before the start")
        h.start_daemon(CONF.format(port=h.broker_port, node=NODE), speed=SPEED)
        wait_until("commands on", lambda: COMMANDS_ON in h.log_text(), 20)
        wait_until("the retained press refused", lambda: h.integration("mqtt")["values_refused"] >= 1, 10)
        h.wait_sim(5)
        c.check(state(h)["mode"] != "MODE_LIMP_HOME", f"no limp home from a retained press: {state(h)['mode']}")
        c.check("command 'limp_home'" not in h.log_text(), "no limp-home command logged")
        c.check("retained command on" in h.log_text(), "the ignored retained command is logged")
        wait_until("the retained press deleted from the broker", lambda: retained(h, LIMP) == [], 10)

        # The same press, live, is an action: it works (the subscription is real).
        h.pub(MODE, "off")
        wait_until("off through a live command", lambda: state(h)["regulator_mode"] == "off", 15)
        h.pub(MODE, "auto")
        wait_until("auto again", lambda: state(h)["regulator_mode"] == "auto", 15)

        # Retained while the daemon listens: arrives live, acts once, then is deleted.
        h.pub(MODE, "off", retain=True)
        wait_until("off through the retained-while-listening command", lambda: state(h)["regulator_mode"] == "off", 15)
        wait_until("that retained copy deleted", lambda: retained(h, MODE) == [], 10)
        h.pub(MODE, "auto")
        wait_until("auto before the restart", lambda: state(h)["regulator_mode"] == "auto", 15)
        h.stop_daemon()
        h.start_daemon(CONF.format(port=h.broker_port, node=NODE), speed=SPEED)
        wait_until("commands on after the restart", lambda: COMMANDS_ON in h.log_text(), 20)
        h.wait_sim(5)
        c.check(state(h)["regulator_mode"] == "auto", "the restart replays no command")
    finally:
        h.stop()


def commands_stay_off_when_the_broker_accepts_anonymous_clients(c, daemon):
    h = Harness(daemon)
    try:
        h.start_broker(users={"ha": "s3cret-pass"}, anonymous=True)
        h.start_daemon(CONF.format(port=h.broker_port, node=NODE), speed=SPEED)
        wait_until("the anonymous broker reported",
                   lambda: "accepts clients without a user name" in h.log_text(), 20)
        c.check(COMMANDS_ON not in h.log_text(), "commands not switched on")
        # Discovery is published after the broker check; on a loaded machine
        # it can take seconds, so wait for it before judging what it holds.
        found = {}

        def discovery_published():
            # 20 sensors and binary sensors; 22 would be the two command entities too.
            found["configs"] = {t for t, _ in h.sub("homeassistant/#", 22, timeout=1, retained_only=True)}
            return bool(found["configs"])

        wait_until("the discovery configs published", discovery_published, 30)
        configs = found["configs"]
        c.check(configs and not any("/select/" in t or "/button/" in t for t in configs),
                f"no command entities announced ({len(configs)} configs)")
        h.pub(MODE, "off")
        h.pub(LIMP, "PRESS")
        h.wait_sim(10)
        s = state(h)
        c.check(s["regulator_mode"] == "auto" and s["mode"] != "MODE_LIMP_HOME",
                f"commands ignored: {s['regulator_mode']} {s['mode']}")
        c.check("from Home Assistant" not in h.log_text(), "no command logged")
    finally:
        h.stop()


def main():
    c = Checks()
    retained_command_is_not_replayed_at_start(c, sys.argv[1])
    commands_stay_off_when_the_broker_accepts_anonymous_clients(c, sys.argv[1])
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
