#!/usr/bin/env python3
"""The GX driver on a real D-Bus against xregulatord --sim
(docs/integrations.md "Victron GX"): a private dbus-daemon as the GX's
system bus, the localsettings stand-in, the daemon and venus/dbus-xregulator.

  - the device instance is the one localsettings holds (pre-set to 7)
  - Introspect lists every mandatory and DC path, and no /Dc/0/Temperature
  - every path read with dbus-send agrees with /api/status and /api/system;
    /Dc/0/Power = V x I within 1 %; values change at least once a second
  - DVCC: /Link/ChargeCurrent = 20 (rewritten each second, as the GX does)
    brings the battery current down to 20 A; when the writes stop the
    limits go stale (REASON_BMS_STALE after BmsStaleS)
  - bad DVCC writes (NaN, a string, negative, huge) are refused by the driver
    and by the daemon, each kind logged once
  - the daemon killed: /Connected 0 and values invalid within 5 s; restarted
    on the same port: values back by themselves

usage: gx_driver_test.py XREGULATORD SCENARIO (gx_dvcc.toml)
"""
import json
import os
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gx_bus import Bus, wait_until  # noqa: E402
from harness import Checks, Harness, free_port  # noqa: E402

TOKEN = "gx-driver-test-token-0123456789abcdef"
SERVICE = "com.victronenergy.alternator.xregulator_test"
MANDATORY = ["/Mgmt/ProcessName", "/Mgmt/ProcessVersion", "/Mgmt/Connection", "/DeviceInstance", "/ProductId",
             "/ProductName", "/FirmwareVersion", "/HardwareVersion", "/Connected"]
DC = ["/Dc/0/Voltage", "/Dc/0/Current", "/Dc/0/Power"]
CONFIG = f'[web]\ntoken = "{TOKEN}"\n'


def start_daemon(h, port):
    """xregulatord --sim on `port` (the same one again after a kill)."""
    h.http_port = port
    conf = os.path.join(h.dir, "xregulator.toml")
    with open(conf, "w") as f:
        f.write("[runtime]\ncontrol_period_us = 20000\n\n" + CONFIG)
    h.daemon_log = os.path.join(h.dir, "daemon.log")
    log = open(h.daemon_log, "a")
    h.daemon = subprocess.Popen([h.daemon_bin, "--sim", "--speed", "1", "--config", conf, "--http",
                                 f"127.0.0.1:{port}", "--state-db", os.path.join(h.dir, "state.db"),
                                 "--scenario", h.scenario],
                                stdout=log, stderr=log)
    h.procs.append(h.daemon)
    wait_until("the daemon's first telemetry", lambda: h.status() is not None, 30)


def post_dvcc(h, body, token=TOKEN):
    data = body if isinstance(body, bytes) else json.dumps(body).encode()
    req = urllib.request.Request(f"http://127.0.0.1:{h.http_port}/api/dvcc", data=data, method="POST",
                                 headers={"Content-Type": "application/json"})
    if token:
        req.add_header("Authorization", "Bearer " + token)
    try:
        with urllib.request.urlopen(req, timeout=5) as r:
            return r.status
    except urllib.error.HTTPError as e:
        return e.code


def check_paths(c, bus, h):
    paths = bus.introspect_paths(SERVICE)
    for p in MANDATORY + DC + ["/Alternator/Temperature", "/State", "/ErrorCode", "/Link/ChargeVoltage",
                               "/Link/ChargeCurrent"]:
        c.check(p in paths, f"Introspect lists {p} (found {len(paths)} paths)")
    c.check("/Dc/0/Temperature" not in paths, "no /Dc/0/Temperature: the GX must not take it for the battery's")
    c.check(bus.get(SERVICE, "/DeviceInstance") == 7, "the device instance is localsettings' (alternator:7)")
    c.check(bus.get(SERVICE, "/ProductName") == "xregulator alternator regulator", "/ProductName")
    c.check(bus.get(SERVICE, "/ProductId") == 0xFFFF, "/ProductId 0xFFFF")
    c.check(bus.get(SERVICE, "/Mgmt/ProcessName") == "dbus-xregulator", "/Mgmt/ProcessName")
    c.check(bus.get(SERVICE, "/Connected") == 1, "/Connected 1")
    versions = json.loads(h.get("/api/system"))["versions"]
    c.check(bus.get(SERVICE, "/FirmwareVersion") == versions["xregulatord"], "/FirmwareVersion is the daemon's")
    c.check(bus.get(SERVICE, "/HardwareVersion") == "sim", "/HardwareVersion says sim")
    # Each path read on its own, then compared with the status read next to it.
    got = {p: bus.get(SERVICE, p) for p in ["/Dc/0/Voltage", "/Dc/0/Current", "/Alternator/Temperature",
                                            "/FieldDrive", "/Speed", "/State", "/ErrorCode"]}
    st = h.status()
    print("status:", {k: st.get(k) for k in ("battery_v", "alt_a", "bcur_a", "temp_f", "duty_pct", "rpm", "mode",
                                             "stage", "reason", "bms_state")}, "dbus:", got)
    c.check(abs(got["/Dc/0/Voltage"] - st["battery_v"]) < 0.15, "/Dc/0/Voltage = battery_v")
    c.check(abs(got["/Dc/0/Current"] - st["alt_a"]) < max(3.0, 0.1 * abs(st["alt_a"])), "/Dc/0/Current = alt_a")
    c.check(abs(got["/Alternator/Temperature"] - (st["temp_f"] - 32) / 1.8) < 1.0, "/Alternator/Temperature in C")
    c.check(abs(got["/FieldDrive"] - st["duty_pct"]) < 10.0, "/FieldDrive = duty_pct")
    c.check(abs(got["/Speed"] - st["rpm"]) < 100, "/Speed = rpm")
    want_state = {"BULK": 3, "ABSORPTION": 4, "FLOAT": 5}.get(st["stage"], 0) if st["field_enable"] else 0
    c.check(got["/State"] == want_state, f"/State {got['/State']} for stage {st['stage']}")
    c.check(got["/ErrorCode"] == 0, "/ErrorCode 0 with no fault")
    # One GetItems: V, I and P of the same moment.
    items = bus.items(SERVICE)
    v, i, p = items["/Dc/0/Voltage"], items["/Dc/0/Current"], items["/Dc/0/Power"]
    c.check(abs(p - v * i) <= 0.01 * abs(v * i) + 0.05, f"/Dc/0/Power {p} = V x I {v * i:.1f} within 1 %")
    c.check(set(MANDATORY + DC) <= set(items), "GetItems carries every mandatory and DC path")


def count_updates(bus, seconds):
    """ItemsChanged signals of the service seen by dbus-monitor."""
    try:
        r = subprocess.run(["dbus-monitor", "--address", bus.address,
                            "type='signal',interface='com.victronenergy.BusItem',member='ItemsChanged'"],
                           capture_output=True, text=True, timeout=seconds)
        out = r.stdout
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
    return out.count("member=ItemsChanged")


def check_dvcc(c, bus, h, driver_log):
    try:
        wait_until("bulk above 25 A", lambda: (h.status()["bcur_a"] or 0) > 25, 40, 0.5)
    except AssertionError:
        pass
    st = h.status()
    c.check(st["bcur_a"] > 25, f"before DVCC the battery takes more than 20 A ({st['bcur_a']} A)")
    held = 0
    end = time.monotonic() + 45
    while time.monotonic() < end and held < 3:
        c_ok = bus.set(SERVICE, "/Link/ChargeCurrent", "double:20") == 0
        last_write = time.monotonic()
        time.sleep(1.0)
        st = h.status()
        following = c_ok and st["bms_state"] == "OK" and st["bms_ccl_a"] == 20
        held = held + 1 if following and 15.0 <= st["bcur_a"] <= 20.5 else 0
    print("under DVCC:", {k: st[k] for k in ("bcur_a", "alt_a", "bms_state", "bms_ccl_a")})
    c.check(held >= 3, "DVCC ChargeCurrent 20 A: the battery current falls to 20 A and stays")
    c.check(bus.get(SERVICE, "/Link/ChargeCurrent") == 20.0, "/Link/ChargeCurrent reads 20")
    c.check(bus.get(SERVICE, "/State") == 252, "/State 252 (external control) while DVCC limits it")

    for bad in ("double:nan", "string:abc", "double:-5", "double:1e9", "double:nan"):
        c.check(bus.set(SERVICE, "/Link/ChargeCurrent", bad) != 0, f"the driver refuses ChargeCurrent {bad}")
    c.check(bus.set(SERVICE, "/Link/ChargeVoltage", "double:500") != 0, "the driver refuses ChargeVoltage 500")
    c.check(bus.get(SERVICE, "/Link/ChargeCurrent") == 20.0, "a refused write leaves 20")
    with open(driver_log) as f:
        log = f.read()
    c.check(log.count("not a finite number") == 1, "the driver logs NaN once (written twice)")
    c.check("not a number (str)" in log, "the driver logs the string")
    for body in ({"charge_current_a": -5}, {"charge_current_a": -5}, {"charge_current_a": "abc"},
                 {"charge_voltage_v": 1e9}, b'{"charge_current_a": NaN}', {}, {"x": 1}):
        c.check(post_dvcc(h, body) == 400, f"the daemon refuses {body!r} (400)")
    c.check(post_dvcc(h, {"charge_current_a": 20}, token=None) == 401, "no token: 401")
    daemon_log = h.log_text()
    c.check(daemon_log.count("ChargeCurrent outside 0 to 2000 A") == 1, "the daemon logs the negative once")
    c.check("must be a number or null" in daemon_log, "the daemon logs the string")
    c.check(h.status()["bms_ccl_a"] == 20, "the refusals left the limit at 20 A")

    # The GX stops writing: the limits go stale after BmsStaleS (5 s) from
    # its last good write (the refused ones above do not refresh them).
    wait_until("DVCC limits going stale", lambda: h.status()["bms_state"] == "STALE", 15, 0.1)
    took = time.monotonic() - last_write
    c.check(4.5 <= took <= 8.0, f"stale BmsStaleS after the last good write (took {took:.1f} s)")


def check_outage(c, bus, h, driver):
    port = h.http_port
    h.daemon.send_signal(signal.SIGKILL)
    h.daemon.wait()
    killed = time.monotonic()
    wait_until("/Connected 0", lambda: bus.get(SERVICE, "/Connected") == 0, 10, 0.1)
    took = time.monotonic() - killed
    c.check(took <= 5.0, f"/Connected 0 within 5 s of losing the regulator ({took:.1f} s)")
    c.check(bus.get(SERVICE, "/Dc/0/Voltage") is None, "/Dc/0/Voltage invalid")
    c.check(bus.text(SERVICE, "/Dc/0/Power") == "---", "/Dc/0/Power's text is ---")
    c.check(bus.get(SERVICE, "/DeviceInstance") == 7, "the identity paths stay")
    c.check(driver.poll() is None, "the driver runs on")
    start_daemon(h, port)
    wait_until("/Connected 1 again", lambda: bus.get(SERVICE, "/Connected") == 1, 20, 0.2)
    c.check(isinstance(bus.get(SERVICE, "/Dc/0/Voltage"), float), "values back by themselves")


def main():
    c = Checks()
    h = Harness(sys.argv[1])
    h.scenario = sys.argv[2]
    try:
        bus = Bus(h.dir, h.procs)
        bus.start_localsettings()
        # The owner chose instance 7 on the GX before: the driver must use it.
        path = "/Settings/Devices/xregulator_test/ClassAndVrmInstance"
        bus.send("com.victronenergy.settings", "/Settings", "com.victronenergy.Settings.AddSetting", "string:",
                 "string:Devices/xregulator_test/ClassAndVrmInstance", "variant:string:alternator:0", "string:s",
                 "variant:int32:0", "variant:int32:0")
        bus.send("com.victronenergy.settings", path, "com.victronenergy.BusItem.SetValue",
                 "variant:string:alternator:7")
        start_daemon(h, free_port())
        token_file = os.path.join(h.dir, "token")
        with open(token_file, "w") as f:
            f.write(TOKEN + "\n")
        driver = bus.start_driver(f"http://127.0.0.1:{h.http_port}", token_file, "test")
        wait_until("the service on the bus", lambda: SERVICE in bus.names(), 40)
        wait_until("/Connected 1", lambda: bus.get(SERVICE, "/Connected") == 1, 15)
        check_paths(c, bus, h)
        n = count_updates(bus, 4)
        c.check(n >= 4, f"values change at least once a second ({n} ItemsChanged in 4 s)")
        check_dvcc(c, bus, h, os.path.join(h.dir, "driver-test.log"))
        check_outage(c, bus, h, driver)
        c.check(driver.poll() is None, "the driver never stopped")
    except AssertionError as e:
        c.check(False, str(e))
    finally:
        for name in ("driver-test.log", "localsettings.log"):
            p = os.path.join(h.dir, name)
            if os.path.exists(p):
                print(f"---- {name}\n" + open(p).read()[-3000:])
        h.stop()
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
