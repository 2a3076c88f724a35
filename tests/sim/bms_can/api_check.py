#!/usr/bin/env python3
"""The CAN side through the web API (docs/integrations.md), the daemon in --sim:

  api_check.py XREGULATORD

A REC BMS on the simulated BMS bus and our node on the simulated NMEA 2000
bus (tests/sim/bms_can/can_api.toml). Every time is the simulation's t_s
from /api/status, never the wall clock.

  - /api/system "bms": protocol rec, talking, the BMS's CVL / CCL / SoC,
    the age of its limits, no bad frames; "n2k": claimed at address 35,
    frames sent;
  - a CCL of 6 000 A for 20 s (about 40 bad frames): counted in
    /api/system, and ONE BmsBadFrames event in /api/events (rate-limited to
    one per 30 s), naming 0x351 and the reason; the limits shown are the
    last good ones, never 6 000 A;
  - the BMS silent: "silent" within 5 s + 1 s, its last values kept and
    their age growing (never invented)."""
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "integrations"))
from harness import Checks, Harness, wait_until  # noqa: E402

SPEED = 5
HERE = os.path.dirname(os.path.abspath(__file__))


def sim_t(h):
    s = h.status()
    return s["t_s"] if s and "t_s" in s else -1.0


def wait_sim(h, t):
    wait_until(f"simulated t = {t} s", lambda: sim_t(h) >= t, timeout=120, step=0.05)


def system(h):
    return json.loads(h.get("/api/system"))


def bad_frame_events(h):
    evs = json.loads(h.get("/api/events?limit=1000"))["events"]
    return [e for e in evs if e["code"] == "BmsBadFrames"]


def main():
    daemon = sys.argv[1]
    c = Checks()
    h = Harness(daemon)
    try:
        h.start_daemon('[can]\nn2k_interface = "can1"\n', speed=SPEED,
                       extra_args=["--scenario", os.path.join(HERE, "can_api.toml")])
        wait_sim(h, 10)
        s = system(h)
        bms, n2k = s.get("bms"), s.get("n2k")
        c.check(bms is not None and n2k is not None, f"/api/system has bms and n2k: {s.keys()}")
        c.check(bms["protocol"] == "rec", f"bms.protocol {bms['protocol']}")
        c.check(bms["state"] == "talking", f"bms.state {bms['state']} while the BMS talks")
        c.check(bms["cvl_v"] is not None and abs(bms["cvl_v"] - 14.2) < 0.01, f"bms.cvl_v {bms['cvl_v']}")
        c.check(bms["ccl_a"] is not None and 0 < bms["ccl_a"] <= 100, f"bms.ccl_a {bms['ccl_a']}")
        c.check(bms["soc_pct"] is not None and 55 < bms["soc_pct"] < 65, f"bms.soc_pct {bms['soc_pct']}")
        c.check(bms["cell_max_v"] is not None and 3.0 < bms["cell_max_v"] < 3.7, f"bms.cell_max_v {bms['cell_max_v']}")
        c.check(bms["age_s"] is not None and 0 <= bms["age_s"] < 1.5, f"bms.age_s {bms['age_s']}")
        c.check(bms["bad_frames"] == 0, f"bms.bad_frames {bms['bad_frames']} before any bad frame")
        c.check(n2k["state"] == "claimed" and n2k["claimed"] is True, f"n2k {n2k}")
        c.check(n2k["address"] == 35, f"n2k.address {n2k['address']}")
        c.check(n2k["tx_frames"] > 10, f"n2k.tx_frames {n2k['tx_frames']}")
        c.check(not bad_frame_events(h), "no BmsBadFrames event before any bad frame")

        wait_sim(h, 45)  # 6 000 A from 20 to 40 s, good again since
        time.sleep(0.5)  # the event pump delivers within 20 ms
        s = system(h)
        bms = s["bms"]
        c.check(bms["bad_frames"] >= 30, f"bms.bad_frames {bms['bad_frames']} after 20 s of 6 000 A")
        c.check(bms["ccl_a"] is not None and bms["ccl_a"] <= 2000, f"bms.ccl_a {bms['ccl_a']}: a bad CCL shown")
        c.check(bms["state"] == "talking", f"bms.state {bms['state']}: good frames (0x355, 0x356) kept coming")
        evs = bad_frame_events(h)
        c.check(len(evs) == 1, f"{len(evs)} BmsBadFrames events in 20 s of bad frames: want one (30 s rate limit)")
        if evs:
            e = evs[0]
            c.check("0x351" in e["text"] and "CCL out of range" in e["text"], f"event text: {e['text']}")
            c.check(e["level"] == "warning", f"event level {e['level']}")

        wait_sim(h, 67)  # silent from 60 s
        bms = system(h)["bms"]
        c.check(bms["state"] == "silent", f"bms.state {bms['state']} 7 s after the BMS fell silent")
        c.check(bms["cvl_v"] is not None and abs(bms["cvl_v"] - 14.2) < 0.01, "the last CVL is kept while silent")
        c.check(bms["age_s"] is not None and bms["age_s"] >= 6, f"bms.age_s {bms['age_s']} while silent")
        c.check(h.status().get("bms_state") == "STALE", "the control law's bms_state is STALE meanwhile")
    finally:
        h.stop()
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
