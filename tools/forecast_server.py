#!/usr/bin/env python3
"""A local Open-Meteo-compatible forecast server for --sim runs
(docs/simulator.md, scenarios/weather-gps.toml): it answers every GET with
one recorded daily forecast (its days made today's, its place the one
asked), so a scenario's [weather] url can point here.

  tools/forecast_server.py [--port 8099] tests/integrations/weather/sunny.json

It prints each request's query (the position the daemon asked for)."""
import argparse
import datetime
import http.server
import json
import urllib.parse


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("answer", help="a recorded forecast (JSON)")
    ap.add_argument("--port", type=int, default=8099)
    args = ap.parse_args()
    with open(args.answer, "rb") as f:
        recorded = json.loads(f.read())

    class Handler(http.server.BaseHTTPRequestHandler):
        def do_GET(self):
            print(self.path, flush=True)
            # Today's days for the place asked: the daemon refuses another
            # day's or another place's forecast.
            answer = dict(recorded)
            query = urllib.parse.parse_qs(urllib.parse.urlsplit(self.path).query)
            if "latitude" in query and "longitude" in query:
                answer["latitude"] = float(query["latitude"][0])
                answer["longitude"] = float(query["longitude"][0])
            today = datetime.datetime.now(datetime.timezone.utc).date()
            answer["daily"] = dict(recorded["daily"])
            answer["daily"]["time"] = [(today + datetime.timedelta(days=i)).isoformat()
                                       for i in range(len(recorded["daily"]["time"]))]
            body = json.dumps(answer).encode()
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, *a):
            pass

    http.server.ThreadingHTTPServer(("127.0.0.1", args.port), Handler).serve_forever()


if __name__ == "__main__":
    main()
