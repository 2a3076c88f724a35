#!/usr/bin/env python3
"""Victron GX over MQTT against Debian's real mosquitto (docs/integrations.md).

  victron_gx_test.py XREGULATORD

Venus-style topics (N/<portalId>/battery/<instance>/..., JSON {"value": ...})
are played into the broker; the daemon must subscribe, write the keepalive
Venus requires, take the good values, refuse and count bad ones (a string, a
bare NaN, absurd limits, not JSON) without letting them replace a good value,
take an empty payload as Venus's "the battery is gone" (unknown, not refused),
send read requests (Venus publishes only on change), mark the limits stale
after BmsStaleS of silence (and fresh again after), and ride out the broker
being killed without a control overrun. The regulator's following of the
limits is victron_follow_test.py."""
import sys
import time

from harness import Checks, Harness, wait_until

PORTAL = "c0619ab1cafe"
BASE = f"N/{PORTAL}/battery/512/"


def values(h):
    return h.integration("victron").get("values", {})


def main():
    c = Checks()
    h = Harness(sys.argv[1])
    try:
        h.start_broker()
        keepalive = h.sub_start(f"R/{PORTAL}/#", fresh_only=False)
        h.start_daemon(f"""[can]
BmsStaleS = 3.0

[integrations.victron]
enabled = true
host = "127.0.0.1"
port = {h.broker_port}
portal_id = "{PORTAL}"
battery_instance = 512
""")
        wait_until("victron connected", lambda: h.integration("victron")["connected"], 20)
        h.wait_sim(1.5)  # a poll or two on the daemon's clock
        got = h.sub_collect(keepalive)
        c.check(any(t == f"R/{PORTAL}/keepalive" for t, _ in got), f"keepalive written on connect: {got}")
        c.check(any(t == f"R/{PORTAL}/battery/512/Info/MaxChargeCurrent" for t, _ in got),
                f"read requests for the limits: {got}")

        good = {"Info/MaxChargeVoltage": 14.2, "Info/MaxChargeCurrent": 50.0, "Soc": 81.5,
                "Dc/0/Temperature": 22.5, "Io/AllowToCharge": 1}
        for path, v in good.items():
            h.pub(BASE + path, '{"value": %s}' % v)
        wait_until("the limits to arrive",
                   lambda: values(h).get("bms_ccl_a") == 50.0 and values(h).get("allow_to_charge") == 1, 10)
        v = values(h)
        c.check(v.get("bms_cvl_v") == 14.2, f"MaxChargeVoltage {v.get('bms_cvl_v')}")
        c.check(v.get("bms_soc_pct") == 81.5, f"Soc {v.get('bms_soc_pct')}")
        c.check(v.get("battery_temp_c") == 22.5, f"Temperature {v.get('battery_temp_c')}")
        c.check(v.get("allow_to_charge") == 1, f"AllowToCharge {v.get('allow_to_charge')}")
        c.check(v.get("stale") == 0, "fresh")

        # Bad input: refused, counted, the good value stays.
        refused0 = h.integration("victron")["values_refused"]
        bad = [("Info/MaxChargeCurrent", '{"value": "12"}'),   # a string where a number belongs
               ("Info/MaxChargeCurrent", '{"value": NaN}'),    # NaN (not even JSON)
               ("Info/MaxChargeCurrent", '{"value": 50000}'),  # absurd
               ("Info/MaxChargeVoltage", '{"value": 400}'),    # absurd
               ("Io/AllowToCharge", '{"value": 0.5}'),         # not a flag
               ("Soc", "eighty")]                              # not JSON at all
        for path, payload in bad:
            h.pub(BASE + path, payload)
        wait_until("every bad value refused",
                   lambda: h.integration("victron")["values_refused"] == refused0 + len(bad), 10)
        v = values(h)
        c.check(v.get("bms_ccl_a") == 50.0, f"bad currents never replace the good one: {v.get('bms_ccl_a')}")
        c.check(v.get("bms_cvl_v") == 14.2, f"bad voltage never replaces the good one: {v.get('bms_cvl_v')}")
        c.check(v.get("allow_to_charge") == 1, "bad flag never replaces the good one")
        c.check(v.get("bms_soc_pct") == 81.5, "bad SoC never replaces the good one")
        c.check("victron: refused a value" in h.log_text(), "refusal logged")

        # Venus's null: the battery has no such value now.
        h.pub(BASE + "Dc/0/Temperature", '{"value": null}')
        wait_until("null temperature", lambda: values(h).get("battery_temp_c", 0) is None, 10)

        # Venus's empty payload: the battery service left the GX. Unknown,
        # not refused.
        refused1 = h.integration("victron")["values_refused"]
        h.pub(BASE + "Info/MaxChargeCurrent", "")
        wait_until("the gone battery's CCL unknown", lambda: values(h).get("bms_ccl_a", 0) is None, 10)
        c.check(h.integration("victron")["values_refused"] == refused1, "an empty payload is not a refusal")
        c.check("left the GX" in h.log_text(), "the vanished battery is logged")

        # Silence: stale after BmsStaleS, fresh again with the next value.
        wait_until("stale after 3 s of silence", lambda: values(h).get("stale") == 1, 15)
        c.check("stale (REASON_BMS_STALE)" in h.log_text(), "staleness logged")
        h.pub(BASE + "Info/MaxChargeCurrent", '{"value": 40}')
        wait_until("fresh again", lambda: values(h).get("stale") == 0 and values(h).get("bms_ccl_a") == 40, 10)

        # The broker dies mid-run and comes back: resubscribed, no overrun.
        overruns0 = h.overruns()
        h.kill_broker()
        wait_until("victron to notice", lambda: not h.integration("victron")["connected"], 20)
        c.check(h.daemon.poll() is None, "daemon alive with the GX gone")
        h.start_broker(port=h.broker_port)
        wait_until("victron to reconnect", lambda: h.integration("victron")["connected"], 40)
        time.sleep(0.5)
        h.pub(BASE + "Info/MaxChargeCurrent", '{"value": 35}')
        wait_until("values after the reconnect", lambda: values(h).get("bms_ccl_a") == 35, 10)
        c.check(h.integration("victron")["outages"] == 1, "one outage")
        c.check(h.log_text().count("retrying with backoff") == 1, "the dead GX logged once, not per attempt")
        c.check(h.overruns() == overruns0, f"no control overrun ({overruns0} -> {h.overruns()})")
    finally:
        h.stop()
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
