#!/usr/bin/env python3
"""The generic push (docs/integrations.md "Alarms that reach the owner"):
xregulatord --sim with [notify] url pointing at a local HTTP receiver (Python's
http.server), and one simulated thermal fault (the alternator's sensor reads
170 F from 4 s to 10 s of simulated time: a critical trip, a cut, the alarm,
the clears).

  notify_test.py XREGULATORD [up|down|failing|text ...]   (all by default)

  up:      the receiver answers 200: exactly one start and one end, in order,
           with the incident's words, the regulator's name and the token header;
  down:    nothing listens while the fault comes and goes; once the receiver is
           started, one start and one end arrive, in order;
  failing: the receiver answers 500 twice, then takes 2.5 s to answer (within
           timeout_s = 10), then once holds its answer until the sender gives
           up at timeout_s: every edge is accepted exactly once and a repeat
           carries the same Idempotency-Key; the control loop ticks on;
  text:    format = "text": a plain-text body with a Title header, as ntfy
           shows it; and a bad url or header is a configuration error (exit 78).

The daemon runs at --speed SPEED: the fault, the incident's settle, the
push's timeout_s and its backoff are simulated time (docs/architecture.md
"One clock"), and every wait is for a condition or for the daemon's clock."""
import http.server
import json
import os
import socket
import subprocess
import sys
import threading
import time

from harness import Checks, Harness, free_port, wait_until

FAULT = """name = "a thermal fault"
duration_s = 3600
seed = 3
[battery]
chemistry = "agm"
capacity_ah = 300
soc_pct = 50
[engine]
rpm = 1700
[config]
BatteryProfile = "agm"
[[events]]
at_s = 4
fault = "temp_value"
value = 170
[[events]]
at_s = 10
clear = "temp_value"
"""
SPEED = 5
SLOW = "slow"  # an answer after 2.5 s of simulated time: inside timeout_s = 10
HOLD = "hold"  # no answer until the sender gives up (timeout_s) and closes


class Receiver:
    """An HTTP receiver on 127.0.0.1:port; `plan` is what it does with each
    request in turn (200, 500, SLOW or HOLD before a 200), then 200."""

    def __init__(self, port, plan=()):
        self.port = port
        self.plan = list(plan)
        self.seen = []      # every request: (headers, body)
        self.accepted = []  # the ones answered 200
        outer = self

        class Handler(http.server.BaseHTTPRequestHandler):
            def do_POST(self):
                body = self.rfile.read(int(self.headers.get("Content-Length", 0)))
                outer.seen.append((dict(self.headers), body))
                step = outer.plan.pop(0) if outer.plan else 200
                if step == 500:
                    return self._send(500)
                if step == SLOW:
                    time.sleep(2.5 / SPEED)
                elif step == HOLD:
                    # Until the sender closes the connection: its timeout_s
                    # passed (simulated time). The answer then reaches no one.
                    self.connection.settimeout(60)
                    try:
                        self.rfile.read(1)
                    except OSError:
                        pass
                outer.accepted.append((dict(self.headers), body))
                return self._send(200)

            def _send(self, code):
                try:
                    self.send_response(code)
                    self.send_header("Content-Length", "2")
                    self.end_headers()
                    self.wfile.write(b"ok")
                except OSError:
                    pass  # the sender gave up waiting

            def log_message(self, *a):
                pass

        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", port), Handler)
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)
        self.thread.start()

    def stop(self):
        self.httpd.shutdown()
        self.httpd.server_close()

    def docs(self):
        return [json.loads(b) for _, b in self.accepted]


def notify_toml(port, extra=""):
    return (f'[notify]\nurl = "http://127.0.0.1:{port}/hooks/boat"\n'
            f'header = "Authorization: Bearer s3cret"\nname = "Blue Heron"\n{extra}\n')


def run_fault(h, port, extra=""):
    scenario = os.path.join(h.dir, "fault.toml")
    with open(scenario, "w") as f:
        f.write(FAULT)
    h.start_daemon(notify_toml(port, extra), ["--scenario", scenario], speed=SPEED)


def incident_over(h):
    events = json.loads(h.get("/api/events?limit=200") or '{"events": []}')["events"]
    return any(e["code"] == "ProtectionClear" and e["reason"] == "REASON_TEMP_CRITICAL" for e in events)


def check_pair(c, docs, what):
    c.check([d["event"] for d in docs] == ["start", "end"], f"{what}: one start then one end: {docs}")
    if len(docs) != 2:
        return
    start, end = docs
    c.check(start["incident_id"] == end["incident_id"], f"{what}: one incident id")
    c.check(start["title"] == "Alternator far too hot", f"{what}: title {start['title']}")
    c.check(start["what_to_do"].startswith("Let it cool"), f"{what}: what to do {start['what_to_do']}")
    c.check(start["regulator"] == "Blue Heron", f"{what}: the regulator's name")
    c.check(start["severity"] == "critical" and start["reason"] == "REASON_TEMP_CRITICAL", f"{what}: severity")
    c.check(start["end"] is None and isinstance(end["end"], str), f"{what}: end only at the end")
    c.check("cut the field at once" in end["what_happened"] and "Over after" in end["what_happened"],
            f"{what}: the end says what the regulator did: {end['what_happened']}")
    # 6 s of simulated fault, stamped on the simulated clock.
    c.check(4 <= end["duration_s"] <= 20, f"{what}: duration {end['duration_s']} s")


def part_up(c, daemon):
    h = Harness(daemon)
    port = free_port()
    r = Receiver(port)
    try:
        run_fault(h, port)
        wait_until("the start and the end", lambda: len(r.accepted) >= 2, 60)
        h.wait_sim(8)  # nothing more may come (a retry would, after 2 s)
        check_pair(c, r.docs(), "up")
        c.check(len(r.seen) == 2, f"up: exactly two requests, got {len(r.seen)}")
        headers = r.accepted[0][0]
        c.check(headers.get("Authorization") == "Bearer s3cret", "up: the configured header")
        c.check(headers.get("Content-Type") == "application/json", "up: JSON")
        c.check(headers.get("Idempotency-Key", "").endswith("-start"), "up: an idempotency key")
        st = h.integration("notify")
        c.check(st["messages_sent"] == 2 and st["connected"], f"up: /api/system {st}")
    finally:
        h.stop()
        r.stop()


def part_down(c, daemon):
    h = Harness(daemon)
    port = free_port()
    try:
        run_fault(h, port)
        wait_until("the fault to come and go", lambda: incident_over(h), 60)
        wait_until("a failed delivery", lambda: h.integration("notify")["outages"] >= 1, 30)
        wait_until("the end to be due too and wait", lambda: h.integration("notify")["values"]["queued"] == 2, 30)
        st = h.integration("notify")
        c.check(st["values"]["queued"] == 2, f"down: start and end wait: {st}")
        c.check("Connection refused" in st["last_error"] or "refused" in st["last_error"],
                f"down: last_error says why: {st['last_error']}")
        r = Receiver(port)
        try:
            wait_until("the start and the end after the receiver came back", lambda: len(r.accepted) >= 2, 60)
            h.wait_sim(8)  # nothing more may come (a retry would, after 2 s)
            check_pair(c, r.docs(), "down")
            c.check(len(r.seen) == 2, f"down: exactly two requests once back, got {len(r.seen)}")
            c.check(h.integration("notify")["values"]["queued"] == 0, "down: nothing left waiting")
        finally:
            r.stop()
        c.check(h.log_text().count("notify: incident") >= 2, "down: the journal says what was delivered")
    finally:
        h.stop()


def part_failing(c, daemon):
    h = Harness(daemon)
    port = free_port()
    # 500, 500, a slow answer (inside timeout_s), then one held past it.
    r = Receiver(port, [500, 500, SLOW, HOLD])
    try:
        run_fault(h, port, "timeout_s = 10")
        wait_until("both edges accepted", lambda: len({json.loads(b)["event"] for _, b in r.accepted}) == 2, 90)
        wait_until("nothing left waiting", lambda: h.integration("notify")["values"]["queued"] == 0, 30)
        h.wait_sim(8)  # nothing more may come (a retry would, after 2 s)
        docs = r.docs()
        events = [d["event"] for d in docs]
        keys = [hd.get("Idempotency-Key") for hd, _ in r.accepted]
        # The held answer reached the receiver but never us: that one edge may
        # arrive twice, with the same key; every other edge exactly once.
        c.check(events[0] == "start" and events.count("start") == 1, f"failing: one start first: {events}")
        c.check(1 <= events.count("end") <= 2, f"failing: the end accepted: {events}")
        ends = [k for k, d in zip(keys, docs) if d["event"] == "end"]
        c.check(len(set(ends)) == 1, f"failing: a repeated end has the same Idempotency-Key: {ends}")
        c.check(len(r.seen) >= 4, f"failing: the 500s were retried ({len(r.seen)} requests)")
        # The sender is on the integrations thread: the loop ticks on while it waits.
        # (loop.ticks is published as the loop's statistics are: wait for it to move.)
        ticks = h.status()["loop"]["ticks"]
        try:
            wait_until("the control loop to tick on", lambda: h.status()["loop"]["ticks"] > ticks, 10)
            c.check(True, "failing: the control loop ticks on")
        except AssertionError as e:
            c.check(False, f"failing: {e} (ticks {ticks})")
    finally:
        h.stop()
        r.stop()


def part_text(c, daemon):
    h = Harness(daemon)
    port = free_port()
    r = Receiver(port)
    try:
        run_fault(h, port, 'format = "text"')
        wait_until("the start and the end", lambda: len(r.accepted) >= 2, 60)
        (h1, b1), (h2, b2) = r.accepted[:2]
        c.check(h1.get("Content-Type", "").startswith("text/plain"), "text: text/plain")
        c.check(h1.get("Title") == "Blue Heron: Alternator far too hot", f"text: Title {h1.get('Title')}")
        c.check(h2.get("Title") == "Blue Heron: over: Alternator far too hot", f"text: Title {h2.get('Title')}")
        c.check(b1.decode().startswith("Alternator far too hot (Blue Heron)\n") and "What to do: Let it cool" in
                b1.decode(), f"text: the start's words: {b1!r}")
        c.check(b2.decode().startswith("Over: Alternator far too hot"), f"text: the end's words: {b2!r}")
    finally:
        h.stop()
        r.stop()
    # A URL or header the sender could not use stops the start, with the key and why.
    for toml, key in (('[notify]\nurl = "ftp://example.org/x"\n', "notify.url"),
                      ('[notify]\nurl = "http://:99/x"\n', "notify.url"),
                      ('[notify]\nurl = "http://127.0.0.1:8/x"\nheader = "Bearer only"\n', "notify.header"),
                      ('[notify]\nurl = "http://127.0.0.1:8/x"\nformat = "xml"\n', "notify.format")):
        conf = os.path.join(h.dir, "bad.toml")
        os.makedirs(h.dir, exist_ok=True)
        with open(conf, "w") as f:
            f.write(toml)
        p = subprocess.run([daemon, "--check-config", "--config", conf], capture_output=True, text=True, timeout=30)
        c.check(p.returncode == 78 and key in (p.stdout + p.stderr),
                f"text: {toml.strip()!r} refused with {key} (exit {p.returncode}: {(p.stdout + p.stderr)[-200:]})")


PARTS = {"up": part_up, "down": part_down, "failing": part_failing, "text": part_text}


def main():
    daemon = sys.argv[1]
    c = Checks()
    for name in sys.argv[2:] or PARTS:
        t0 = time.monotonic()
        PARTS[name](c, daemon)
        print(f"part {name}: {time.monotonic() - t0:.1f} s")
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
