#!/usr/bin/env python3
"""The Victron GX follow test (docs/integrations.md): the regulator follows a battery's
limits read from a GX over MQTT.

  victron_follow_test.py XREGULATORD SCENARIO

Debian's mosquitto on a free port; a Venus-style battery service played into
it (fake_venus.py: publishes on change, answers read requests and keepalives,
like dbus-flashmq); xregulatord --sim --speed 5 charging a half-empty LFP bank
in bulk on an alternator that could push far more than the limit. Every time
check is on simulated time, from the telemetry CSV (t_s), never on the wall
clock:

  - a MaxChargeCurrent is followed: battery current <= limit + 2 A from 2 s
    after the control law received it (the row where bms_ccl_a changes), and
    a lowered limit likewise;
  - a string, NaN, 6000 A, -5 A and a payload that is not JSON are refused
    and counted (/api/system and /metrics) and never change the limit;
  - AllowToCharge 0 turns the field off (REASON_BMS_DISABLED);
  - a GX that goes silent is stale after BmsStaleS: from BmsStaleS + 1 s the
    battery current is under BmsFallbackCapA + 2 A and the reason is
    REASON_BMS_STALE; it is followed again when the GX answers;
  - mosquitto killed mid-run: no crash, no control overrun, the fallback
    holds, and the limits are followed again when the broker is back."""
import csv
import math
import os
import sys

from fake_venus import FakeVenus
from harness import Checks, Harness, wait_until

PORTAL = "c0619ab1cafe"
CCL = "Info/MaxChargeCurrent"
SPEED = 5            # simulated seconds per wall second (the control period stays 20 ms of wall time)
STALE_S = 6.0        # BmsStaleS
FALLBACK_A = 10.0    # BmsFallbackCapA
MARGIN_A = 2.0       # "battery current <= MaxChargeCurrent + 2 A ..."
FOLLOW_S = 2.0       # "... within 2 s of the limit"


def gx_values(ccl):
    return {"Info/MaxChargeVoltage": 14.4, CCL: ccl, "Soc": 30.0, "Dc/0/Temperature": 20.0,
            "Io/AllowToCharge": 1}


def num(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["t"] = num(r["t_s"])
        r["bcur"] = num(r["bcur_a"])
        r["ccl"] = num(r["bms_ccl_a"])
    return rows


def between(rows, t0, t1):
    return [r for r in rows if t0 <= r["t"] < t1]


def peak(rows):
    """The highest battery current; an unknown one (NaN) counts as infinite,
    so a row without a reading can never pass for one under a limit."""
    return max((math.inf if math.isnan(r["bcur"]) else r["bcur"] for r in rows), default=math.nan)


def main():
    daemon, scenario = sys.argv[1], sys.argv[2]
    c = Checks()
    h = Harness(daemon)
    venus = None
    csv_path = os.path.join(h.dir, "telemetry.csv")
    marks = {}
    try:
        h.start_broker()
        venus = FakeVenus(h, PORTAL, 512, gx_values(300.0))  # 300 A: no cap at first
        h.start_daemon(f"""[can]
BmsLimitsEnabled = true
BmsStaleS = {STALE_S}
BmsFallbackCapA = {FALLBACK_A}

[integrations.victron]
enabled = true
host = "127.0.0.1"
port = {h.broker_port}
portal_id = "{PORTAL}"
battery_instance = 512
""", extra_args=["--scenario", scenario, "--telemetry-csv", csv_path], speed=SPEED)

        def st():
            return h.status()

        def t_now():
            return st()["t_s"]

        # Bulk with the GX's 300 A: the alternator gives what it can.
        wait_until("limits followed and charging hard",
                   lambda: st()["bms_state"] == "OK" and (st()["bcur_a"] or 0) > 80, 90)
        c.check(venus.read_count() > 0, "the daemon sends read requests (Venus publishes only on change)")

        for limit in (40.0, 20.0):
            marks[limit] = t_now()
            venus.set(CCL, limit)
            wait_until(f"the control law to get {limit} A", lambda: st()["bms_ccl_a"] == limit, 20)
            h.wait_sim(6)  # 6 s under this limit
        marks["bad"] = t_now()

        # Bad values: refused, counted, never the limit.
        refused0 = h.integration("victron")["values_refused"]
        metric = 'xregulator_integration_values_refused_total{integration="victron"}'
        metric0 = h.metrics().get(metric)
        bad = ['{"value": "12"}', '{"value": NaN}', '{"value": 6000}', '{"value": -5}', "forty"]
        for payload in bad:
            venus.raw(CCL, payload)
        wait_until("every bad value refused",
                   lambda: h.integration("victron")["values_refused"] == refused0 + len(bad), 10)
        c.check(h.metrics().get(metric) == (metric0 or 0) + len(bad),
                f"/metrics counts them: {metric0} -> {h.metrics().get(metric)}")
        h.wait_sim(1)
        marks["bad_end"] = t_now()
        c.check(st()["bms_ccl_a"] == 20.0, f"the limit is still 20 A: {st()['bms_ccl_a']}")

        # The BMS says no: field off (the digital BMS input's path).
        venus.set("Io/AllowToCharge", 0)
        wait_until("charge disabled", lambda: st()["reason"] == "REASON_BMS_DISABLED" and not st()["field_enable"],
                   20)
        venus.set("Io/AllowToCharge", 1)
        wait_until("charging again", lambda: st()["field_enable"] and st()["bms_state"] == "OK", 20)
        h.wait_sim(2)

        # The GX goes silent (the broker stays up): between these two marks
        # its last answer left.
        marks["silent"] = t_now()
        venus.stop()
        marks["silent_done"] = t_now()
        wait_until("stale", lambda: st()["bms_state"] == "STALE", 30)
        h.wait_sim(STALE_S + 4)
        c.check(st()["reason"] == "REASON_BMS_STALE", f"reason {st()['reason']}")
        c.check("victron: no battery limits" in h.log_text(), "the silence is logged")
        # Marked before the GX is back: its first answer may come within the
        # fake's start-up (the daemon polls every simulated second).
        marks["back"] = t_now()
        venus = FakeVenus(h, PORTAL, 512, gx_values(20.0))
        wait_until("followed again", lambda: st()["bms_state"] == "OK", 30)
        h.wait_sim(2)

        # The broker dies mid-run and comes back.
        overruns0 = h.overruns()
        h.kill_broker()
        venus.stop()
        marks["broker_dead"] = t_now()
        wait_until("victron to notice", lambda: not h.integration("victron")["connected"], 30)
        wait_until("stale while the GX is unreachable", lambda: st()["bms_state"] == "STALE", 30)
        # Dead for a while past BmsStaleS + 1 s, so the fallback is seen held.
        wait_until("3 s of fallback", lambda: t_now() >= marks["broker_dead"] + STALE_S + 4.0, 30)
        c.check(h.daemon.poll() is None, "daemon alive with the broker gone")
        h.start_broker(port=h.broker_port)
        venus = FakeVenus(h, PORTAL, 512, gx_values(20.0))
        wait_until("victron to reconnect", lambda: h.integration("victron")["connected"], 60)
        wait_until("followed after the reconnect", lambda: st()["bms_state"] == "OK", 30)
        marks["end"] = t_now()
        c.check(h.overruns() == overruns0, f"no control overrun ({overruns0} -> {h.overruns()})")
        c.check(h.log_text().count("retrying with backoff") == 1, "the dead broker logged once")
    finally:
        if venus:
            venus.stop()
        h.stop_daemon()
        rows = read_csv(csv_path) if os.path.exists(csv_path) else []
        h.stop()
    if not marks.get("end"):
        print("FAIL: the run did not finish; no CSV checks")
        return 1

    # ---- on simulated time, from the CSV ----
    c.check(len(rows) > 100, f"{len(rows)} telemetry rows")
    hard = max(r["bcur"] for r in between(rows, 0, marks[40.0]) if not math.isnan(r["bcur"]))
    c.check(hard > 1.5 * 40.0, f"uncapped bulk charges hard: {hard:.1f} A")
    print(f"MEASURED: uncapped bulk {hard:.1f} A into the battery")
    ends = {40.0: marks[20.0], 20.0: marks["bad"]}
    for limit in (40.0, 20.0):
        got = [r for r in between(rows, marks[limit], ends[limit] + 10) if r["ccl"] == limit]
        if not got:
            c.check(False, f"no row with bms_ccl_a = {limit}")
            continue
        t_got = got[0]["t"]
        # The phase lasts until the next limit reaches the law.
        nxt = [r for r in rows if r["t"] > t_got and r["ccl"] != limit]
        t_end = nxt[0]["t"] if nxt else marks["bad"]
        before = between(rows, t_got - 1.0, t_got)
        c.check(peak(before) > limit + MARGIN_A, f"{limit} A is a real cut (before it: {peak(before):.1f} A)")
        under = between(rows, t_got + FOLLOW_S, t_end)
        worst = peak(under)
        c.check(len(under) >= 20 and worst <= limit + MARGIN_A,
                f"{limit} A followed from {FOLLOW_S} s on: worst {worst:.2f} A over {len(under)} rows")
        settle = next((r["t"] - t_got for r in between(rows, t_got, t_end)
                       if peak(between(rows, r["t"], t_end)) <= limit + MARGIN_A), math.nan)
        print(f"MEASURED: {limit:.0f} A limit met {settle:.2f} s (simulated) after the law received it")

    bad_rows = between(rows, marks["bad"], marks["bad_end"])
    c.check(bad_rows and all(r["ccl"] == 20.0 for r in bad_rows),
            "bad values never change the limit the law follows")
    c.check(bad_rows and peak(bad_rows) <= 20.0 + MARGIN_A, "nor the current")

    stale_rows = [r for r in between(rows, marks["silent"], marks["back"]) if r["bms_state"] == "STALE"]
    c.check(bool(stale_rows), "STALE rows after the silence")
    if stale_rows:
        t_stale = stale_rows[0]["t"] - marks["silent"]
        quiet = marks["silent_done"] - marks["silent"]
        print(f"MEASURED: stale {t_stale:.2f} s (simulated) after the GX went silent (BmsStaleS {STALE_S}, "
              f"stopping it took {quiet:.2f} s)")
        # The last answer came at most one poll (1 s, simulated) before the
        # silence began, and at the latest as it ended, read within the MQTT
        # link's 50 ms poll (at the simulation's speed) and a control tick.
        late = 0.2 + 0.05 * SPEED
        c.check(STALE_S - 1.0 - 0.5 <= t_stale <= quiet + STALE_S + late,
                f"stale after BmsStaleS of silence: {t_stale:.2f} s")
        held = between(rows, marks["silent_done"] + STALE_S + 1.0, marks["back"])
        c.check(len(held) >= 10 and all(r["bms_state"] == "STALE" and r["reason"] == "REASON_BMS_STALE"
                                        for r in held), "REASON_BMS_STALE while silent")
        worst = peak(held) if held else math.inf
        c.check(worst <= FALLBACK_A + MARGIN_A,
                f"fallback cap {FALLBACK_A} A from BmsStaleS + 1 s: worst {worst:.2f} A")
    dead = between(rows, marks["broker_dead"] + STALE_S + 1.0, marks["end"])
    dead_stale = [r for r in dead if r["bms_state"] == "STALE"]
    c.check(len(dead_stale) >= 10 and peak(dead_stale) <= FALLBACK_A + MARGIN_A,
            f"the fallback holds while the broker is dead: {len(dead_stale)} rows, worst {peak(dead_stale):.2f} A")
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
