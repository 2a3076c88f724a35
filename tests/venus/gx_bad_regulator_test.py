#!/usr/bin/env python3
"""The GX driver against a regulator that answers garbage or closes the
socket (docs/integrations.md "Victron GX"): the service stays on the bus
with /Connected 0, the driver never crashes, each kind of failure is logged
once, and a good answer brings /Connected 1 back by itself. Also: without
localsettings the driver uses the default instance, and DVCC writes while
the regulator is away are refused. No xregulatord here: a small HTTP server
in this process plays the regulator.

usage: gx_bad_regulator_test.py
"""
import http.server
import json
import os
import shutil
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gx_bus import Bus, wait_until  # noqa: E402
from harness import Checks  # noqa: E402

SERVICE = "com.victronenergy.alternator.xregulator_bad"
GOOD = {"battery_v": 13.6, "alt_a": 30.0, "temp_f": 140.0, "duty_pct": 40.0, "rpm": 2500,
        "mode": "MODE_NORMAL_AUTO_PID", "stage": "ABSORPTION", "reason": "NONE", "field_enable": True,
        "bms_state": "OFF"}
MODE = {"now": "html"}


class Regulator(http.server.BaseHTTPRequestHandler):
    def log_message(self, *args):
        pass

    def do_GET(self):
        mode = MODE["now"]
        if mode == "close":
            self.close_connection = True
            return  # no answer at all: the client sees the socket closed
        if mode == "html":
            body, ctype = b"<html><body>garbage</body></html>", "text/html"
        elif mode == "strings":
            body, ctype = json.dumps(dict(GOOD, battery_v="13.6")).encode(), "application/json"
        elif mode == "array":
            body, ctype = b"[1, 2, 3]", "application/json"
        elif mode == "fault":
            body = json.dumps(dict(GOOD, mode="MODE_CRITICAL_RAMP", reason="REASON_TEMP_CRITICAL",
                                   field_enable=False, duty_pct=0)).encode()
            ctype = "application/json"
        else:
            body, ctype = json.dumps(GOOD if self.path == "/api/status" else {"versions": {}}).encode(), \
                "application/json"
        self.send_response(200)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)


def main():
    c = Checks()
    work = tempfile.mkdtemp(prefix="xr-gx-bad-")
    procs = []
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Regulator)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        bus = Bus(work, procs)  # no localsettings on this bus
        token = os.path.join(work, "token")
        with open(token, "w") as f:
            f.write("some-token\n")
        log_path = os.path.join(work, "driver-bad.log")
        driver = bus.start_driver(f"http://127.0.0.1:{server.server_address[1]}", token, "bad",
                                  ["--instance", "3", "--settings-wait-s", "2"])
        # The driver waits for localsettings (2 s here) before it registers.
        wait_until("the service on the bus", lambda: SERVICE in bus.names(), 20, 0.2)
        c.check(bus.get(SERVICE, "/DeviceInstance") == 3, "without localsettings: the default instance")
        for mode in ("html", "strings", "array", "close"):
            MODE["now"] = mode
            time.sleep(2.0)
            c.check(bus.get(SERVICE, "/Connected") == 0, f"{mode}: /Connected 0")
            c.check(bus.get(SERVICE, "/Dc/0/Voltage") is None, f"{mode}: /Dc/0/Voltage invalid")
            c.check(driver.poll() is None, f"{mode}: the driver runs on")
        c.check(bus.set(SERVICE, "/Link/ChargeCurrent", "double:20") != 0,
                "a DVCC write with no regulator is refused")
        MODE["now"] = "good"
        wait_until("/Connected 1 on a good answer", lambda: bus.get(SERVICE, "/Connected") == 1, 10)
        c.check(bus.get(SERVICE, "/State") == 4, "/State 4 (absorption)")
        c.check(bus.get(SERVICE, "/Dc/0/Power") == 408.0, "/Dc/0/Power 13.6 V x 30 A")
        MODE["now"] = "fault"
        wait_until("/State 2 on a fault", lambda: bus.get(SERVICE, "/State") == 2, 10)
        c.check(bus.get(SERVICE, "/ErrorCode") == 17, "REASON_TEMP_CRITICAL is error 17 (charger too hot)")
        MODE["now"] = "close"
        start = time.monotonic()
        wait_until("/Connected 0 after the socket closes", lambda: bus.get(SERVICE, "/Connected") == 0, 10, 0.1)
        c.check(time.monotonic() - start <= 5.0, "/Connected 0 within 5 s")
        with open(log_path) as f:
            log = f.read()
        c.check(log.count(": RemoteDisconnected") == 2, "each spell of closed sockets logged once (two spells)")
        c.check("Traceback" not in log, "no traceback in the driver's log")
        c.check(driver.poll() is None, "the driver never stopped")
        print(log[-2500:])
    except AssertionError as e:
        c.check(False, str(e))
    finally:
        server.shutdown()
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
                p.wait(timeout=10)
        shutil.rmtree(work, ignore_errors=True)
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
