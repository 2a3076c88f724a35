#!/usr/bin/env python3
"""A local Open-Meteo-compatible forecast server for --sim runs
(docs/simulator.md, scenarios/weather-gps.toml): it answers every GET with
one recorded daily forecast, so a scenario's [weather] url can point here.

  tools/forecast_server.py [--port 8099] tests/integrations/weather/sunny.json

It prints each request's query (the position the daemon asked for)."""
import argparse
import http.server


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("answer", help="a recorded forecast (JSON)")
    ap.add_argument("--port", type=int, default=8099)
    args = ap.parse_args()
    with open(args.answer, "rb") as f:
        body = f.read()

    class Handler(http.server.BaseHTTPRequestHandler):
        def do_GET(self):
            print(self.path, flush=True)
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
