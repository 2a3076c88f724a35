#!/usr/bin/env python3
"""The soak test of issue 26 (`make soak`): xregulatord --sim at --speed 20
for a simulated day (tests/soak/day.toml) against 20 WebSocket clients, 5 API
requests a second and dashboard writes, reporting as numbers:

  - RSS growth after warm-up (VmRSS of the daemon, median of the samples
    around the end of warm-up against the median of the last samples);
  - control-loop overruns: all of them, and those attributable to the
    daemon (the tick itself took longer than its period: "(N own)" in the
    daemon's "control loop:" journal line, the last of which is written at
    the stop; the rest are late wake-ups of a loaded machine);
  - the state database's size (database + WAL + the verified backup);
  - errors: failed or refused requests, WebSocket clients dropped, writes
    not applied, error lines in the daemon's log, an exit that is not clean
    or does not leave the field LOW.

Exit status 1 when RSS growth >= 1 MB, own overruns > 0 or errors > 0
(--smoke: errors only; a minute says nothing about memory growth).
Python standard library only. Each WebSocket client connects from its own
loopback address (127.0.0.2 ...), as phones would from their own addresses.
"""
import argparse
import base64
import http.client
import json
import os
import re
import signal
import socket
import statistics
import struct
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOKEN = "soak-test-token-0123456789abcdef"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Counters:
    def __init__(self):
        self.lock = threading.Lock()
        self.values = {}
        self.examples = []

    def add(self, key, n=1, example=None):
        with self.lock:
            self.values[key] = self.values.get(key, 0) + n
            if example and len(self.examples) < 20:
                self.examples.append(f"{key}: {example}")

    def get(self, key):
        with self.lock:
            return self.values.get(key, 0)


def recv_exact(sock, n):
    buf = b""
    while len(buf) < n:
        chunk = sock.recv(n - len(buf))
        if not chunk:
            raise ConnectionError("closed by the server")
        buf += chunk
    return buf


def ws_client(index, port, stop, counters):
    """A dashboard's live view: connects, reads every frame, answers pings."""
    source = f"127.0.0.{2 + index}"
    while not stop.is_set():
        sock = None
        try:
            sock = socket.create_connection(("127.0.0.1", port), timeout=15, source_address=(source, 0))
            key = base64.b64encode(os.urandom(16)).decode()
            sock.sendall((f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n"
                          f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                          "Sec-WebSocket-Version: 13\r\n\r\n").encode())
            head = b""
            while b"\r\n\r\n" not in head:
                chunk = sock.recv(4096)
                if not chunk:
                    raise ConnectionError("closed during the handshake")
                head += chunk
            status = head.split(b"\r\n", 1)[0].decode(errors="replace")
            if " 101 " not in status:
                raise ConnectionError(f"handshake answered {status!r}")
            rest = head.split(b"\r\n\r\n", 1)[1]
            counters.add("ws_connects")
            pending = rest
            while not stop.is_set():
                def take(n):
                    nonlocal pending
                    if len(pending) >= n:
                        out, pending = pending[:n], pending[n:]
                        return out
                    out = pending + recv_exact(sock, n - len(pending))
                    pending = b""
                    return out
                b0, b1 = take(2)
                opcode, length = b0 & 0x0F, b1 & 0x7F
                if length == 126:
                    length = struct.unpack(">H", take(2))[0]
                elif length == 127:
                    length = struct.unpack(">Q", take(8))[0]
                payload = take(length)
                if opcode in (1, 2):
                    counters.add("ws_frames")
                    counters.add("ws_bytes", len(payload))
                elif opcode == 9:  # ping: a masked pong with the same payload
                    mask = os.urandom(4)
                    masked = bytes(c ^ mask[i % 4] for i, c in enumerate(payload))
                    sock.sendall(bytes([0x8A, 0x80 | len(payload)]) + mask + masked)
                elif opcode == 8:
                    raise ConnectionError("closed by the server (close frame)")
        except (OSError, ConnectionError, ValueError) as e:
            if not stop.is_set():
                counters.add("errors.ws_dropped", example=f"client {index}: {e}")
                time.sleep(1)
        finally:
            if sock:
                sock.close()


def request(port, method, path, body=None, token=None, source="127.0.0.200"):
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=15, source_address=(source, 0))
    try:
        headers = {}
        if body is not None:
            headers["Content-Type"] = "application/json"
        if token:
            headers["Authorization"] = "Bearer " + token
        conn.request(method, path, body=body, headers=headers)
        res = conn.getresponse()
        return res.status, res.read()
    finally:
        conn.close()


def api_traffic(port, rate, with_www, stop, counters):
    """rate requests a second over the read API, as dashboards and scripts do."""
    now = time.time()
    paths = ["/api/status", "/api/params", "/api/system", "/api/events?limit=50", "/metrics", "/healthz",
             f"/api/history?series=ibv_v&from={now - 3600:.0f}&to={now + 86400:.0f}&step=60"]
    if with_www:
        paths.append("/")
    i = 0
    next_t = time.monotonic()
    while not stop.is_set():
        path = paths[i % len(paths)]
        i += 1
        try:
            status, body = request(port, "GET", path)
            counters.add("api_requests")
            if status != 200:
                counters.add("errors.api", example=f"{path}: HTTP {status} {body[:120]!r}")
        except OSError as e:
            counters.add("errors.api", example=f"{path}: {e}")
        next_t += 1.0 / rate
        stop.wait(max(0.0, next_t - time.monotonic()))


def dashboard_writes(port, period_s, stop, counters):
    """The owner changing a setting from the dashboard, every period_s."""
    values = [95.0, 96.0]
    i = 0
    while not stop.wait(period_s):
        v = values[i % 2]
        i += 1
        try:
            status, body = request(port, "PATCH", "/api/params", json.dumps({"MaxDuty": v}), TOKEN,
                                   source="127.0.0.201")
            counters.add("writes")
            if status != 200:
                counters.add("errors.write", example=f"PATCH MaxDuty={v}: HTTP {status} {body[:200]!r}")
                continue
            _, params = request(port, "GET", "/api/params")
            got = next(p["value"] for p in json.loads(params)["params"] if p["name"] == "MaxDuty")
            if abs(got - v) > 1e-9:
                counters.add("errors.write", example=f"MaxDuty is {got} after PATCH {v}")
        except (OSError, ValueError, StopIteration) as e:
            counters.add("errors.write", example=f"PATCH: {e}")


def rss_kb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def store_bytes(db):
    total = 0
    for suffix in ("", "-wal", "-shm", ".bak"):
        try:
            total += os.path.getsize(db + suffix)
        except OSError:
            pass
    return total


def loop_stats(port):
    status, body = request(port, "GET", "/api/system", source="127.0.0.202")
    if status != 200:
        raise OSError(f"/api/system: HTTP {status}")
    return json.loads(body).get("loop", {})


LOOP_LINE = re.compile(r"control loop: (\d+) ticks, (\d+) overruns \((\d+) own\)")


def last_loop_line(log_path):
    """(ticks, overruns, own) of the daemon's last "control loop:" line."""
    last = None
    with open(log_path, errors="replace") as f:
        for line in f:
            m = LOOP_LINE.search(line)
            if m:
                last = tuple(int(x) for x in m.groups())
    return last


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--daemon", required=True, help="the xregulatord binary")
    ap.add_argument("--duration-s", type=float, default=72 * 60, help="wall seconds (72 min = 24 h at speed 20)")
    ap.add_argument("--warmup-s", type=float, default=300, help="wall seconds before the RSS baseline")
    ap.add_argument("--speed", default="20")
    ap.add_argument("--clients", type=int, default=20)
    ap.add_argument("--rate", type=float, default=5.0, help="API requests a second")
    ap.add_argument("--write-period-s", type=float, default=30.0, help="one dashboard write this often")
    ap.add_argument("--scenario", default=os.path.join(HERE, "day.toml"))
    ap.add_argument("--www", default="", help="dashboard assets (www_root), to serve / as well")
    ap.add_argument("--sample-s", type=float, default=10.0)
    ap.add_argument("--out", default="", help="directory for the report (default: a temporary one)")
    ap.add_argument("--smoke", action="store_true", help="judge errors only (a short run of the script)")
    a = ap.parse_args()

    out = a.out or tempfile.mkdtemp(prefix="xr-soak-")
    os.makedirs(out, exist_ok=True)
    port = free_port()
    db = os.path.join(out, "state.db")
    for suffix in ("", "-wal", "-shm", ".bak"):
        if os.path.exists(db + suffix):
            os.remove(db + suffix)
    cfg = os.path.join(out, "xregulator.toml")
    with open(cfg, "w") as f:
        f.write(f'[web]\ntoken = "{TOKEN}"\n')
        if a.www:
            f.write(f'www_root = "{a.www}"\n')
        # As in the browser tests: at speed 20 a simulator thread starved by a
        # loaded machine misses 25 ms of wall time = 500 ms of samples and the
        # real CURRENT_STALE protection trips; that is the protection working
        # on a late simulation, not what the soak measures.
        f.write("[sensor_health]\nCurrentStaleMs = 3000\n")
    os.chmod(cfg, 0o600)
    outputs = os.path.join(out, "sim-outputs")
    log_path = os.path.join(out, "daemon.log")
    log = open(log_path, "w")
    argv = [a.daemon, "--sim", "--speed", a.speed, "--scenario", a.scenario, "--config", cfg, "--state-db", db,
            "--http", f"127.0.0.1:{port}", "--sim-outputs", outputs]
    proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT)
    counters = Counters()
    deadline = time.monotonic() + 30
    while True:
        if proc.poll() is not None:
            print(f"soak: the daemon exited at start ({proc.returncode}); see {log_path}", file=sys.stderr)
            return 1
        try:
            if request(port, "GET", "/healthz")[0] == 200:
                break
        except OSError:
            pass
        if time.monotonic() > deadline:
            proc.kill()
            print("soak: the daemon did not answer within 30 s", file=sys.stderr)
            return 1
        time.sleep(0.2)

    stop = threading.Event()
    threads = [threading.Thread(target=ws_client, args=(i, port, stop, counters), daemon=True)
               for i in range(a.clients)]
    threads.append(threading.Thread(target=api_traffic, args=(port, a.rate, bool(a.www), stop, counters), daemon=True))
    threads.append(threading.Thread(target=dashboard_writes, args=(port, a.write_period_s, stop, counters),
                                    daemon=True))
    for t in threads:
        t.start()

    t0 = time.monotonic()
    samples = []  # (t, rss_kb, store_bytes, overruns, ticks)
    timeline = open(os.path.join(out, "timeline.csv"), "w")
    timeline.write("t_s,rss_kb,store_bytes,overruns,ticks,ws_frames,api_requests,errors\n")
    early_exit = None
    while time.monotonic() - t0 < a.duration_s:
        stop.wait(min(a.sample_s, max(0.0, a.duration_s - (time.monotonic() - t0))))
        if proc.poll() is not None:
            early_exit = proc.returncode
            break
        try:
            loop = loop_stats(port)
        except (OSError, ValueError) as e:
            counters.add("errors.api", example=f"/api/system: {e}")
            continue
        s = (time.monotonic() - t0, rss_kb(proc.pid), store_bytes(db), loop.get("overruns", 0),
             loop.get("ticks", 0))
        samples.append(s)
        errors = sum(v for k, v in counters.values.items() if k.startswith("errors."))
        timeline.write(",".join(str(round(x, 1)) for x in s) +
                       f",{counters.get('ws_frames')},{counters.get('api_requests')},{errors}\n")
        timeline.flush()

    stop.set()
    if early_exit is None:
        proc.send_signal(signal.SIGTERM)
        try:
            rc = proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            rc = "killed after 30 s"
    else:
        rc = early_exit
        counters.add("errors.daemon_exit", example=f"the daemon ended early with {rc}")
    log.close()
    if rc != 0:
        counters.add("errors.daemon_exit", example=f"exit status {rc}")
    try:
        final = open(outputs).read()
        if "enable=0" not in final:
            counters.add("errors.field_left_on", example=final.strip())
    except OSError as e:
        counters.add("errors.field_left_on", example=f"no --sim-outputs file: {e}")
    # The daemon's stderr lines: "<date> <time> <level> <text>". The
    # regulator's own events ("[event=...]", e.g. a protection trip) are
    # counted apart: they are the control working, not the software failing.
    error_lines, trips = [], 0
    for ln in open(log_path, errors="replace"):
        if re.match(r"\S+ \S+ (error|critical) ", ln):
            if "[event=" in ln:
                trips += 1
            else:
                error_lines.append(ln)
    if error_lines:
        counters.add("errors.daemon_log", len(error_lines), example=error_lines[0].strip())
    if counters.get("ws_frames") == 0:
        counters.add("errors.ws_silent", example="no WebSocket frame arrived")
    if counters.get("writes") == 0:
        counters.add("errors.no_writes", example="no dashboard write was made (run too short?)")

    after = [s for s in samples if s[0] >= a.warmup_s]
    if len(after) >= 2:
        n = max(1, min(3, len(after) // 4))
        rss_warm = statistics.median(s[1] for s in after[:n])
        rss_end = statistics.median(s[1] for s in after[-n:])
        growth_kb = rss_end - rss_warm
        rss_max = max(s[1] for s in after)
    else:
        rss_warm = rss_end = growth_kb = rss_max = float("nan")
    last = samples[-1] if samples else (0, 0, 0, 0, 0)
    final_loop = last_loop_line(log_path)
    if final_loop is None:
        counters.add("errors.no_loop_line", example="no 'control loop:' line with own overruns in the log")
        final_loop = (last[4], last[3], 0)
    errors = {k: v for k, v in counters.values.items() if k.startswith("errors.")}
    report = {
        "duration_s": round(samples[-1][0], 1) if samples else 0,
        "speed": a.speed,
        "simulated_h": round(final_loop[0] / 400 / 3600, 2),
        "clients": a.clients,
        "api_rate_per_s": a.rate,
        "api_requests": counters.get("api_requests"),
        "writes": counters.get("writes"),
        "ws_frames": counters.get("ws_frames"),
        "ws_connects": counters.get("ws_connects"),
        "rss_kb_at_warmup": rss_warm,
        "rss_kb_end": rss_end,
        "rss_kb_max_after_warmup": rss_max,
        "rss_growth_kb": growth_kb,
        "overruns": final_loop[1],
        "overruns_own": final_loop[2],
        "ticks": final_loop[0],
        "store_bytes_end": last[2],
        "critical_events": trips,
        "errors": sum(errors.values()),
        "error_kinds": errors,
        "error_examples": counters.examples,
        "exit": rc,
        "out": out,
    }
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
    print(json.dumps(report, indent=2))
    failures = []
    if report["errors"] > 0:
        failures.append(f"{report['errors']} errors")
    if not a.smoke:
        if not growth_kb < 1024:
            failures.append(f"RSS grew {growth_kb} kB after warm-up (limit < 1024 kB)")
        if report["overruns_own"] > 0:
            failures.append(f"{report['overruns_own']} overruns attributable to the daemon")
    print("soak: " + ("FAIL: " + "; ".join(failures) if failures else "PASS"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
