#!/usr/bin/env python3
"""Signal K deltas against a real signalk-server from the npm registry
(docs/integrations.md), pinned in tests/integrations/signalk/package.json (`make deps`).

  signalk_test.py XREGULATORD NODE SIGNALK_SERVER_BIN plain|secured

The server runs on a free local port with a temporary config directory. The
daemon (--sim) pushes deltas; the values are read back through the server's
REST API (/signalk/v1/api/vessels/self/electrical/...) and checked against
the daemon's /api/status in their SI units, with the meta units.
secured: the server needs a token; the daemon makes an access request, the
test approves it as the admin, the daemon connects with the token and keeps
it in the state database. Both: the server killed mid-run, no control
overrun, reconnect when it is back.
plain: a navigation.position published to the server by another client
reaches the daemon's subscription, and the weather forecast is asked for it
(docs/integrations.md "Where the forecast is asked for").
The daemon runs at --speed SPEED: its backoff, delta period and position
checks are simulated time (docs/architecture.md "One clock")."""
import json
import os
import signal
import subprocess
import sys
import urllib.request

from harness import Checks, Harness, free_port, wait_until
from weather_test import Server as ForecastServer

ADMIN = ("admin", "admin-pass-1234")
SPEED = 5


class SignalK:
    def __init__(self, h, node, server_bin, secured):
        self.h, self.node, self.bin, self.secured = h, node, server_bin, secured
        self.port = free_port()
        self.dir = os.path.join(h.dir, "signalk")
        os.makedirs(self.dir, exist_ok=True)
        settings = {"interfaces": {"tcp": False, "nmea-tcp": False, "appstore": False, "plugins": False,
                                   "webapps": False, "wasm": False, "mfd_webapp": False, "playground": False,
                                   "logfiles": False},
                    "pipedProviders": [], "mdns": False}
        if secured:
            settings["security"] = {"strategy": "./tokensecurity"}
        with open(os.path.join(self.dir, "settings.json"), "w") as f:
            json.dump(settings, f)
        if secured:
            # Guests may read (the default), only a token may write. A fixed
            # secret key: tokens stay valid when the server is restarted.
            modules = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(server_bin))))
            bcrypt = os.path.join(modules, "bcryptjs")
            hashed = subprocess.run([node, "-e", f"console.log(require({json.dumps(bcrypt)}).hashSync("
                                     f"{json.dumps(ADMIN[1])}, 8))"], capture_output=True, text=True,
                                    check=True).stdout.strip()
            with open(os.path.join(self.dir, "security.json"), "w") as f:
                json.dump({"allow_readonly": True, "expiration": "1d", "secretKey": "ab" * 64,
                           "users": [{"username": ADMIN[0], "type": "admin", "password": hashed}],
                           "devices": [], "acls": [], "immutableConfig": False,
                           "allowDeviceAccessRequests": True, "allowNewUserRegistration": False}, f)
        self.proc = None

    def start(self):
        env = dict(os.environ, PORT=str(self.port), SIGNALK_NODE_CONFIG_DIR=self.dir)
        log = open(os.path.join(self.h.dir, "signalk.log"), "a")
        self.proc = subprocess.Popen([self.node, self.bin], env=env, stdout=log, stderr=log)
        self.h.procs.append(self.proc)
        wait_until("signalk-server to answer", lambda: self.http("GET", "/signalk") is not None, 120, 0.5)

    def kill(self):
        self.proc.send_signal(signal.SIGKILL)
        self.proc.wait()

    def http(self, method, path, body=None, token=None):
        req = urllib.request.Request(f"http://127.0.0.1:{self.port}{path}", method=method,
                                     data=json.dumps(body).encode() if body is not None else None)
        req.add_header("Content-Type", "application/json")
        if token:
            req.add_header("Authorization", "Bearer " + token)
        try:
            with urllib.request.urlopen(req, timeout=5) as r:
                text = r.read().decode()
        except Exception:
            return None
        try:
            return json.loads(text)
        except ValueError:
            return text  # e.g. "Request updated"

    def alternator(self):
        return self.http("GET", "/signalk/v1/api/vessels/self/electrical/alternators/main")

    def battery(self):
        return self.http("GET", "/signalk/v1/api/vessels/self/electrical/batteries/house")

    def publish_position(self, latitude, longitude):
        """A delta from another client (a GPS plugin would do the same)."""
        modules = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(self.bin))))
        delta = {"context": "vessels.self", "updates": [{"values": [
            {"path": "navigation.position", "value": {"latitude": latitude, "longitude": longitude}}]}]}
        script = (f"const W = require({json.dumps(os.path.join(modules, 'ws'))});"
                  f"const w = new W('ws://127.0.0.1:{self.port}/signalk/v1/stream?subscribe=none');"
                  f"w.on('open', () => {{ w.send({json.dumps(json.dumps(delta))});"
                  f" setTimeout(() => process.exit(0), 500); }});"
                  f"w.on('error', (e) => {{ console.error(e.message); process.exit(1); }});")
        return subprocess.run([self.node, "-e", script], timeout=20).returncode == 0

    def admin_token(self):
        r = self.http("POST", "/signalk/v1/auth/login", {"username": ADMIN[0], "password": ADMIN[1]})
        return r["token"]


ALTERNATOR_KEYS = ["voltage", "current", "temperature", "revolutions", "fieldDrive", "chargingMode",
                   "setpointVoltage", "setpointCurrent", "weatherMode", "runTime", "insulationLifeUsed", "beltSlips"]


def has_values(d, keys):
    return d and all(d.get(k, {}).get("value") is not None for k in keys)


def check_values(c, sk, h):
    # Wait for every path to hold a value: the daemon sends none it does not
    # have (a sensor not read yet in the first second is left out, never
    # sent as NaN), so the first deltas can carry only some of them.
    alt = wait_until("alternator values on the server",
                     lambda: (a := sk.alternator()) and has_values(a, ALTERNATOR_KEYS) and a, 60)
    bat = wait_until("battery values on the server",
                     lambda: (b := sk.battery()) and has_values(b, ["voltage"]) and b, 30)
    st = h.status()
    for key in ALTERNATOR_KEYS:
        c.check(key in alt, f"electrical.alternators.main.{key} on the server")
    units = {"voltage": "V", "current": "A", "temperature": "K", "revolutions": "Hz", "fieldDrive": "ratio",
             "setpointVoltage": "V", "setpointCurrent": "A", "runTime": "s", "insulationLifeUsed": "ratio"}
    for key, unit in units.items():
        got = alt.get(key, {}).get("meta", {}).get("units")
        c.check(got == unit, f"alternators.main.{key} meta units {got!r} == {unit!r}")
    v = lambda d, k: d.get(k, {}).get("value")
    c.check(abs(v(alt, "voltage") - st["battery_v"]) < 0.5, f"voltage {v(alt, 'voltage')} ~ {st['battery_v']} V")
    temp_k = (st["temp_f"] - 32) * 5 / 9 + 273.15
    c.check(abs(v(alt, "temperature") - temp_k) < 3.0, f"temperature {v(alt, 'temperature')} K ~ {temp_k:.1f} K")
    c.check(200 < v(alt, "temperature") < 450, "temperature is in kelvin")
    c.check(abs(v(alt, "revolutions") - st["rpm"] / 60) < 5.0, f"revolutions {v(alt, 'revolutions')} Hz ~ rpm/60")
    c.check(0.0 <= v(alt, "fieldDrive") <= 1.0, f"fieldDrive {v(alt, 'fieldDrive')} is a ratio 0-1")
    c.check(v(alt, "chargingMode") in ("bulk", "acceptance", "float", "other"),
            f"chargingMode {v(alt, 'chargingMode')!r} in the spec's words")
    # A fresh daemon does not know the SoC (docs/batteries.md "State of charge
    # at first start"): the path is not published then, never a guessed number.
    soc = bat.get("capacity", {}).get("stateOfCharge", {}).get("value")
    if st["soc_pct"] is None:
        c.check(soc is None, f"an unknown SoC is not published as a number (stateOfCharge {soc})")
    else:
        c.check(soc is not None and 0.0 <= soc <= 1.0 and abs(soc - st["soc_pct"] / 100) < 0.05,
                f"stateOfCharge {soc} ratio ~ {st['soc_pct']} %")
    c.check(abs(v(bat, "voltage") - st["battery_v"]) < 0.5, "battery voltage")


def position_from_signalk(c, sk, h, forecast):
    n = len(forecast.requests)
    c.check(sk.publish_position(60.15, 24.95), "a navigation.position published to the server")
    wait_until("a forecast asked for the Signal K position",
               lambda: any("latitude=60.1500&longitude=24.9500" in r for r in forecast.requests[n:]), 40)
    w = h.integration("weather")
    c.check(w.get("texts", {}).get("position_source") == "signalk", f"the source shown is Signal K ({w.get('texts')})")
    c.check(abs(w["values"]["latitude"] - 60.15) < 1e-9, f"the position shown is Signal K's ({w['values']})")


def main():
    daemon, node, server_bin, variant = sys.argv[1:5]
    secured = variant == "secured"
    c = Checks()
    h = Harness(daemon)
    forecast = ForecastServer()
    # plain: the weather forecast is on, with a position in the file that
    # the boat's (from Signal K) must replace.
    weather = "" if secured else f"""
[integrations.weather]
enabled = true
url = "http://127.0.0.1:{forecast.port}/v1/forecast"
latitude = 43.3
longitude = 5.4
refresh_min = 60
"""
    try:
        sk = SignalK(h, node, server_bin, secured)
        sk.start()
        h.start_daemon(weather + f"""[integrations.signalk]
enabled = true
url = "ws://127.0.0.1:{sk.port}/signalk/v1/stream?subscribe=none"
rate_hz = 2.0
alternator_id = "main"
battery_id = "house"
""", speed=SPEED)
        if secured:
            # The daemon asks for access; the admin approves it.
            admin = sk.admin_token()
            reqs = wait_until("the daemon's access request",
                              lambda: [r for r in (sk.http("GET", "/skServer/security/access/requests", token=admin)
                                                   or []) if "xregulator" in json.dumps(r)], 60)
            ident = reqs[0].get("accessIdentifier") or reqs[0].get("identifier")
            c.check("access requested" in h.log_text(), "the access request is in the journal")
            c.check(sk.alternator() is None or "voltage" not in (sk.alternator() or {}),
                    "nothing is written before approval")
            r = sk.http("PUT", f"/skServer/security/access/requests/{ident}/approved",
                        {"permissions": "readwrite", "expiration": "1d"}, token=admin)
            c.check(r is not None, "approval accepted by the server")
        wait_until("signalk connected", lambda: h.integration("signalk")["connected"], 90)
        check_values(c, sk, h)
        if not secured:
            position_from_signalk(c, sk, h, forecast)
        if secured:
            c.check("token kept in the state database" in h.log_text(), "token stored")
            out = subprocess.run(["sqlite3", os.path.join(h.dir, "state.db"),
                                  "SELECT length(value) FROM kv WHERE key='signalk_token'"],
                                 capture_output=True, text=True)
            c.check(out.stdout.strip().isdigit() and int(out.stdout.strip()) > 20,
                    f"the token is in the state database ({out.stdout.strip()!r})")

        # Kill the server mid-run; the loop keeps its timing; reconnect when back.
        overruns0, ticks0 = h.overruns(), h.status()["loop"]["ticks"]
        sk.kill()
        wait_until("signalk to notice", lambda: not h.integration("signalk")["connected"], 30)
        h.wait_sim(5)  # several reconnect attempts (backoff 1 s, 2 s: simulated time)
        c.check(h.daemon.poll() is None, "daemon alive with the server dead")
        c.check(h.status()["loop"]["ticks"] > ticks0, "control loop ticks on")
        c.check(h.integration("signalk")["last_error"] != "", "last_error while down")
        sk.start()
        wait_until("signalk to reconnect", lambda: h.integration("signalk")["connected"], 120)
        check_values(c, sk, h)  # meta again on the new connection: units are back
        c.check(h.integration("signalk")["outages"] == 1, f"one outage ({h.integration('signalk')['outages']})")
        c.check(h.log_text().count("retrying with backoff") == 1, "the dead server logged once")
        c.check(h.overruns() == overruns0, f"no control overrun ({overruns0} -> {h.overruns()})")
        if secured:
            c.check(h.log_text().count("access requested") == 1, "the stored token is reused, no second request")
    finally:
        h.stop()
        forecast.httpd.shutdown()
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
