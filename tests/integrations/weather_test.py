#!/usr/bin/env python3
"""Weather mode from a forecast (docs/integrations.md "Weather"): the daemon
in --sim reads recorded Open-Meteo answers from a local HTTP server.

  weather_test.py XREGULATORD [refresh|floor|broken ...]   (all by default)

  The daemon runs at --speed SPEED: its refreshes, retries and request
  timeout are simulated time (docs/architecture.md "One clock"), so a
  one-minute refresh passes in a few seconds.

  - a sunny forecast puts the regulator in MODE_DISABLED_RAMP with
    REASON_WEATHER_MODE; a cloudy one, served at the next refresh (1 min),
    brings charging back; a mixed one (1 sunny day of 3) charges;
  - below WeatherModeMinSoC it charges in sunshine, and rests just above it;
  - a broken server (500, no answer at all, bad JSON, a wrong shape, a 10 MB
    body) leaves charging untouched, says why once with the next try, and the
    daemon keeps running;
  - scenarios/weather-gps.toml: with no position in the file, the forecast is
    asked for the position a simulated GNSS sends on NMEA 2000 (129029),
    decoded by the daemon, and the dashboard's source says so."""
import datetime
import http.server
import json
import os
import sys
import threading
import time
import urllib.parse
import urllib.request

from harness import Checks, Harness, wait_until

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
TOKEN = "weather-test-token-0123456789abcdef"
WEATHER = "REASON_WEATHER_MODE"
SPEED = 20  # simulated seconds per second: a 1 min refresh in 3 s


def recorded(name, path="", start=None, shift_deg=0.0):
    """A recorded forecast, made today's (or from `start`) for the place the
    request asked (moved by shift_deg): the daemon refuses another day's or
    another place's forecast."""
    with open(os.path.join(HERE, "weather", name + ".json"), "rb") as f:
        answer = json.loads(f.read())
    query = urllib.parse.parse_qs(urllib.parse.urlsplit(path).query)
    if "latitude" in query and "longitude" in query:
        answer["latitude"] = float(query["latitude"][0]) + shift_deg
        answer["longitude"] = float(query["longitude"][0])
    first = start or datetime.datetime.now(datetime.timezone.utc).date()
    answer["daily"]["time"] = [(first + datetime.timedelta(days=i)).isoformat()
                               for i in range(len(answer["daily"]["time"]))]
    return json.dumps(answer).encode()


class Server:
    """Serves what `self.answer` says: a recorded forecast or a failure."""

    def __init__(self):
        self.answer = "sunny"
        self.requests = []
        outer = self

        class Handler(http.server.BaseHTTPRequestHandler):
            def do_GET(self):
                outer.requests.append(self.path)
                a = outer.answer
                if a == "500":
                    return self._send(500, b"oops")
                if a == "timeout":
                    # No answer: hold the connection until the client gives
                    # up (its 10 s of simulated time) and closes it.
                    self.connection.settimeout(60)
                    try:
                        self.rfile.read(1)
                    except OSError:
                        pass
                    return None
                if a == "badjson":
                    return self._send(200, b'{"daily": {"time": [')
                if a == "shape":
                    return self._send(200, b'{"hourly": {"uv_index": [9, 9, 9]}}')
                if a == "huge":
                    return self._send(200, b'{"pad":"' + b"x" * (10 * 1024 * 1024) + b'"}')
                if a == "olddates":  # a cached answer: sunny, but for 1999
                    return self._send(200, recorded("sunny", self.path, start=datetime.date(1999, 7, 5)))
                if a == "elsewhere":  # sunny, but 10 degrees of latitude away
                    return self._send(200, recorded("sunny", self.path, shift_deg=10.0))
                return self._send(200, recorded(a, self.path))

            def _send(self, code, body):
                try:
                    self.send_response(code)
                    self.send_header("Content-Type", "application/json")
                    self.send_header("Content-Length", str(len(body)))
                    self.end_headers()
                    self.wfile.write(body)
                except OSError:
                    pass  # the client gave up (the 10 MB body): expected

            def log_message(self, *args):
                pass

        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.port = self.httpd.server_address[1]
        threading.Thread(target=self.httpd.serve_forever, daemon=True).start()


def config(port, min_soc=50):
    return f"""[web]
token = "{TOKEN}"

[modes]
weatherModeEnabled = true
UVThresholdHigh = 6.0
WeatherModeMinSoC = {min_soc}

[integrations.weather]
enabled = true
url = "http://127.0.0.1:{port}/v1/forecast"
latitude = 43.3
longitude = 5.4
refresh_min = 1
"""


def command(h, body):
    req = urllib.request.Request(f"http://127.0.0.1:{h.http_port}/api/commands", data=json.dumps(body).encode(),
                                 headers={"Authorization": "Bearer " + TOKEN, "Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=5) as r:
        return r.status


def reason(h):
    return h.status()["reason"]


def sunny_then_cloudy(c, srv, daemon):
    h = Harness(daemon)
    try:
        srv.answer = "sunny"
        h.start_daemon(config(srv.port), speed=SPEED)
        command(h, {"command": "set_soc", "soc_pct": 80})
        wait_until("weather mode from the sunny forecast", lambda: reason(h) == WEATHER, 20)
        st = h.status()
        c.check(st["mode"] == "MODE_DISABLED_RAMP", f"sunny: mode {st['mode']}")
        c.check("daily=uv_index_max,shortwave_radiation_sum" in srv.requests[-1] and "forecast_days=3" in
                srv.requests[-1] and "latitude=43.3" in srv.requests[-1], f"request {srv.requests[-1]}")
        w = h.integration("weather")
        c.check(w["values"]["active"] == 1 and w["values"]["sunny_days"] == 3, f"sunny: values {w['values']}")
        c.check(abs(w["values"]["uv_day2"] - 8.9) < 1e-9, "the dashboard sees day 2's UV index")
        srv.answer = "cloudy"
        wait_until("the cloudy forecast read (one refresh)",
                   lambda: h.integration("weather")["values"]["sunny_days"] == 0, 15)
        wait_until("charging again after the cloudy forecast", lambda: reason(h) != WEATHER, 5)
        srv.answer = "mixed"
        n = len(srv.requests)
        wait_until("the mixed forecast", lambda: len(srv.requests) > n, 15)
        time.sleep(0.5)
        c.check(reason(h) != WEATHER, "mixed (1 sunny day of 3, one null): charging")
        c.check(h.integration("weather")["values"]["sunny_days"] == 1, "mixed: one sunny day")
        c.check(weather_events(h) == [], "a server that answers: no weather event")
    finally:
        h.stop()


def soc_floor(c, srv, daemon):
    h = Harness(daemon)
    try:
        srv.answer = "sunny"
        h.start_daemon(config(srv.port, min_soc=50), speed=SPEED)
        command(h, {"command": "set_soc", "soc_pct": 49.5})
        wait_until("the forecast read", lambda: h.integration("weather")["values"].get("active") == 1, 20)
        time.sleep(1)
        c.check(reason(h) != WEATHER, f"SoC 49.5 % < 50 %: charging in sunshine ({reason(h)})")
        # Just above the floor: the house load discharges the sim's battery
        # from the moment the SoC is set (the exact threshold is
        # Regulator.WeatherModeRestsTheAlternatorAtWeatherModeMinSoC).
        command(h, {"command": "set_soc", "soc_pct": 52})
        wait_until("weather mode above the floor", lambda: reason(h) == WEATHER, 10)
        command(h, {"command": "set_soc", "soc_pct": 30})
        wait_until("charging again below the floor", lambda: reason(h) != WEATHER, 10)
        c.check(h.status()["mode"] != "MODE_DISABLED_RAMP", "below the floor: not ramped off")
    finally:
        h.stop()


def weather_events(h):
    ev = json.loads(h.get("/api/events?limit=200"))["events"]
    return [e for e in ev if e["code"] in ("WeatherForecastMissing", "WeatherForecastBack")]


def broken(c, srv, daemon, answer, why, event_why):
    h = Harness(daemon)
    try:
        srv.answer = answer
        h.start_daemon(config(srv.port), speed=SPEED)
        command(h, {"command": "set_soc", "soc_pct": 80})
        wait_until(f"{answer}: the failure reported",
                   lambda: why in (h.integration("weather")["last_error"] or ""), 30)
        time.sleep(0.5)
        c.check(reason(h) != WEATHER, f"{answer}: charging untouched ({reason(h)})")
        c.check(h.daemon.poll() is None, f"{answer}: the daemon runs")
        lines = [l for l in h.log_text().splitlines() if "weather:" in l and "next try in" in l]
        c.check(len(lines) == 1, f"{answer}: one log line says why with the next try, got {len(lines)}")
        ev = weather_events(h)
        c.check(len(ev) == 1 and ev[0]["code"] == "WeatherForecastMissing" and event_why in ev[0]["text"] and
                "next try in" in ev[0]["text"], f"{answer}: one event says why with the next try: {ev}")
    finally:
        h.stop()


def position_from_nmea2000(c, srv, daemon):
    h = Harness(daemon)
    try:
        srv.answer = "sunny"
        with open(os.path.join(ROOT, "scenarios", "weather-gps.toml")) as f:
            text = f.read().replace("127.0.0.1:8099", f"127.0.0.1:{srv.port}")
        scenario = os.path.join(h.dir, "weather-gps.toml")
        with open(scenario, "w") as f:
            f.write(text)
        n = len(srv.requests)
        h.start_daemon(f"""[web]
token = "{TOKEN}"

[modes]
weatherModeEnabled = true
UVThresholdHigh = 6.0

[can]
n2k_interface = "can1"
""", extra_args=["--scenario", scenario], speed=SPEED)
        command(h, {"command": "set_soc", "soc_pct": 80})
        wait_until("a forecast asked for the GPS's position",
                   lambda: any("latitude=-33.8568&longitude=151.2153" in r for r in srv.requests[n:]), 30)
        c.check(not any("latitude=0.0000" in r for r in srv.requests[n:]), "never asked for (0, 0)")
        w = h.integration("weather")
        c.check(w.get("texts", {}).get("position_source") == "nmea2000",
                f"the source shown is NMEA 2000 ({w.get('texts')})")
        c.check(abs(w["values"]["latitude"] + 33.8568) < 1e-6 and abs(w["values"]["longitude"] - 151.2153) < 1e-6,
                f"the position shown is the GPS's ({w['values']['latitude']}, {w['values']['longitude']})")
        wait_until("weather mode on the GPS position's sunny forecast", lambda: reason(h) == WEATHER, 20)
        c.check(weather_events(h) == [], "the GPS was heard before any 'no position' was said")
    finally:
        h.stop()


PARTS = {
    # A sunny forecast, then a cloudy and a mixed one at the next refreshes.
    "refresh": lambda c, srv, d: sunny_then_cloudy(c, srv, d),
    # The SoC floor, and the position from the boat's GPS on NMEA 2000.
    "floor": lambda c, srv, d: (soc_floor(c, srv, d), position_from_nmea2000(c, srv, d)),
    # A broken server, five ways.
    "broken": lambda c, srv, d: [broken(c, srv, d, answer, why, ev) for answer, why, ev in [
        ("500", "HTTP 500", "server answered HTTP 500"), ("badjson", "not JSON", "not a forecast"),
        ("shape", "no daily object", "not a forecast"), ("huge", "body limit", "not a forecast"),
        ("timeout", "timeout", "no answer from the server"),
        ("olddates", "not for today", "not a forecast"), ("elsewhere", "another place", "not a forecast")]],
}


def main():
    daemon = sys.argv[1]
    parts = sys.argv[2:] or list(PARTS)
    c = Checks()
    srv = Server()
    for p in parts:
        PARTS[p](c, srv, daemon)
    srv.httpd.shutdown()
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
