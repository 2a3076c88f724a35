#!/usr/bin/env python3
"""The soak test (`make soak`, docs/performance.md): xregulatord --sim at --speed 20
for a simulated day (tests/soak/day.toml) against 20 WebSocket clients, 5 API
requests a second, dashboard writes and the integrations that exist (a real
mosquitto with the Home Assistant publisher, a real signalk-server, the
simulated BMS and NMEA 2000 buses: soak_integrations.py), reporting as numbers:

  - RSS growth after warm-up (VmRSS of the daemon, median of the samples
    just after warm-up against the median of the last samples; anonymous
    and file-backed apart). Warm-up ends at a simulated time: the first
    engine start + 30 simulated minutes (--warmup-sim-s);
  - control-loop overruns: all of them, and those attributable to the
    daemon (the tick used a whole period of CPU time, CLOCK_THREAD_CPUTIME_ID:
    "(N own)" and "tick CPU p99/max" in the daemon's "control loop:" journal
    line, the last of which is written at the stop, and overruns_own in
    /api/system; the rest are late wake-ups and preemption on a loaded
    machine);
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
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time

from soak_integrations import Integrations, signalk_default
from soak_load import TOKEN, Counters, api_traffic, dashboard_writes, free_port, request, ws_client

HERE = os.path.dirname(os.path.abspath(__file__))
PERIOD_S = 0.0025  # [runtime] control_period_us: one tick is 2.5 ms of simulated time
# The RSS baseline is taken once the daemon has been through its first
# engine start (day.toml: 6 h) and 30 simulated minutes of charging: the
# state database's page cache and the history rings fill as writes start
# (docs/performance.md, "The RSS step").
WARMUP_SIM_S = 6 * 3600 + 30 * 60


def rss_kb(pid):
    """(VmRSS, RssAnon, RssFile + RssShmem) in kB: anonymous memory (heap,
    caches, rings) apart from mapped files (libraries, the WAL index)."""
    v = {}
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            k, _, rest = line.partition(":")
            if k in ("VmRSS", "RssAnon", "RssFile", "RssShmem"):
                v[k] = int(rest.split()[0])
    return v.get("VmRSS", 0), v.get("RssAnon", 0), v.get("RssFile", 0) + v.get("RssShmem", 0)


def store_bytes(db):
    total = 0
    for suffix in ("", "-wal", "-shm", ".bak"):
        try:
            total += os.path.getsize(db + suffix)
        except OSError:
            pass
    return total


def system(port):
    status, body = request(port, "GET", "/api/system", source="127.0.0.202")
    if status != 200:
        raise OSError(f"/api/system: HTTP {status}")
    return json.loads(body)


LOOP_LINE = re.compile(r"control loop: (\d+) ticks, (\d+) overruns \((\d+) own\), tick CPU p99/max (\d+)/(\d+) us")


def last_loop_line(log_path):
    """(ticks, overruns, own, tick CPU p99 us, max us) of the daemon's last
    "control loop:" line (the last one is written at the stop)."""
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
    ap.add_argument("--warmup-sim-s", type=float, default=WARMUP_SIM_S,
                    help="simulated seconds before the RSS baseline (default: the first engine start + 30 min)")
    ap.add_argument("--speed", default="20")
    ap.add_argument("--clients", type=int, default=20)
    ap.add_argument("--rate", type=float, default=5.0, help="API requests a second")
    ap.add_argument("--write-period-s", type=float, default=30.0, help="one dashboard write this often")
    ap.add_argument("--scenario", default=os.path.join(HERE, "day.toml"))
    ap.add_argument("--www", default="", help="dashboard assets (www_root), to serve / as well")
    ap.add_argument("--sample-s", type=float, default=10.0)
    ap.add_argument("--out", default="", help="directory for the report (default: a temporary one)")
    ap.add_argument("--no-integrations", action="store_true", help="without mosquitto and signalk-server")
    ap.add_argument("--node", default=shutil.which("node") or "", help="node, for signalk-server")
    ap.add_argument("--signalk-server", default=signalk_default(), help="signalk-server's bin (empty: none)")
    ap.add_argument("--smoke", action="store_true", help="judge errors only (a short run of the script)")
    a = ap.parse_args()

    out = a.out or tempfile.mkdtemp(prefix="xr-soak-")
    os.makedirs(out, exist_ok=True)
    port = free_port()
    db = os.path.join(out, "state.db")
    for suffix in ("", "-wal", "-shm", ".bak"):
        if os.path.exists(db + suffix):
            os.remove(db + suffix)
    counters = Counters()
    integ = None
    if not a.no_integrations:
        integ = Integrations(a.daemon, a.node, a.signalk_server if a.node else "")
        integ.start()
    try:
        return run(a, out, port, db, counters, integ)
    finally:
        if integ:
            integ.stop()


def run(a, out, port, db, counters, integ):
    cfg = os.path.join(out, "xregulator.toml")
    with open(cfg, "w") as f:
        f.write(f'[web]\ntoken = "{TOKEN}"\n')
        if a.www:
            f.write(f'www_root = "{a.www}"\n')
        # As in the browser tests: at speed 20 a simulator thread starved by a
        # loaded machine misses 25 ms of wall time = 500 ms of samples and the
        # real CURRENT_STALE protection trips; that is the protection working
        # on a late simulation, not what the soak measures.
        f.write("[sensor_health]\nCurrentStaleMs = 3000\n\n")
        if integ:
            f.write(integ.config())
    os.chmod(cfg, 0o600)
    outputs = os.path.join(out, "sim-outputs")
    log_path = os.path.join(out, "daemon.log")
    log = open(log_path, "w")
    argv = [a.daemon, "--sim", "--speed", a.speed, "--scenario", a.scenario, "--config", cfg, "--state-db", db,
            "--http", f"127.0.0.1:{port}", "--sim-outputs", outputs]
    proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT)
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
    samples = []  # Sample rows, as in timeline.csv
    timeline = open(os.path.join(out, "timeline.csv"), "w")
    timeline.write("t_s,sim_s,rss_kb,rss_anon_kb,rss_file_kb,store_bytes,overruns,overruns_own,ticks,"
                   "ws_frames,api_requests,errors\n")
    early_exit = None
    last_system = {}
    while time.monotonic() - t0 < a.duration_s:
        stop.wait(min(a.sample_s, max(0.0, a.duration_s - (time.monotonic() - t0))))
        if proc.poll() is not None:
            early_exit = proc.returncode
            break
        try:
            last_system = system(port)
        except (OSError, ValueError) as e:
            counters.add("errors.api", example=f"/api/system: {e}")
            continue
        loop = last_system.get("loop", {})
        ticks = loop.get("ticks", 0)
        s = (time.monotonic() - t0, ticks * PERIOD_S) + rss_kb(proc.pid) + (
            store_bytes(db), loop.get("overruns", 0), loop.get("overruns_own", 0), ticks)
        samples.append(s)
        errors = sum(v for k, v in counters.values.items() if k.startswith("errors."))
        timeline.write(",".join(str(round(x, 1)) for x in s) +
                       f",{counters.get('ws_frames')},{counters.get('api_requests')},{errors}\n")
        timeline.flush()

    stop.set()
    integrations = {}
    if integ:
        try:
            status = json.loads(request(port, "GET", "/api/status", source="127.0.0.202")[1])
        except (OSError, ValueError) as e:
            status = {}
            counters.add("errors.api", example=f"/api/status at the end: {e}")
        integrations = integ.check(last_system, status, counters)
    helpers_rss = integ.rss_kb() if integ else {}
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
    trips = count_log_errors(log_path, counters)
    if counters.get("ws_frames") == 0:
        counters.add("errors.ws_silent", example="no WebSocket frame arrived")
    if counters.get("writes") == 0:
        counters.add("errors.no_writes", example="no dashboard write was made (run too short?)")

    after = [s for s in samples if s[1] >= a.warmup_sim_s]
    rss = {}
    if len(after) >= 2:
        n = max(1, min(3, len(after) // 4))
        for i, name in ((2, "rss"), (3, "rss_anon"), (4, "rss_file")):
            rss[f"{name}_kb_at_warmup"] = statistics.median(s[i] for s in after[:n])
            rss[f"{name}_kb_end"] = statistics.median(s[i] for s in after[-n:])
            rss[f"{name}_growth_kb"] = rss[f"{name}_kb_end"] - rss[f"{name}_kb_at_warmup"]
        rss["rss_kb_max_after_warmup"] = max(s[2] for s in after)
        rss["warmup_wall_s"] = round(after[0][0], 1)
    growth_kb = rss.get("rss_growth_kb", float("nan"))
    last = samples[-1] if samples else (0,) * 9
    final_loop = last_loop_line(log_path)
    if final_loop is None:
        counters.add("errors.no_loop_line", example="no 'control loop:' line with own overruns in the log")
        final_loop = (last[8], last[6], last[7], 0, 0)
    api_loop = last_system.get("loop", {})
    errors = {k: v for k, v in counters.values.items() if k.startswith("errors.")}
    report = {
        "duration_s": round(samples[-1][0], 1) if samples else 0,
        "speed": a.speed,
        "simulated_h": round(final_loop[0] * PERIOD_S / 3600, 2),
        "warmup_sim_s": a.warmup_sim_s,
        "clients": a.clients,
        "api_rate_per_s": a.rate,
        "api_requests": counters.get("api_requests"),
        "writes": counters.get("writes"),
        "ws_frames": counters.get("ws_frames"),
        "ws_connects": counters.get("ws_connects"),
        **rss,
        "ticks": final_loop[0],
        "overruns": final_loop[1],
        "overruns_own": final_loop[2],
        "tick_cpu_p99_us": final_loop[3],
        "tick_cpu_max_us": final_loop[4],
        # The last /api/system sample before the stop: the same counters,
        # read the way a monitoring system would.
        "api_overruns_own": api_loop.get("overruns_own"),
        "api_tick_cpu_max_us": api_loop.get("tick_cpu_max_us"),
        "store_bytes_end": last[5],
        "integrations": integrations,
        "helpers_rss_kb": helpers_rss,
        "load_average": list(os.getloadavg()),
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
        own = max(report["overruns_own"], report["api_overruns_own"] or 0)
        if own > 0:
            failures.append(f"{own} overruns attributable to the daemon")
    print("soak: " + ("FAIL: " + "; ".join(failures) if failures else "PASS"))
    return 1 if failures else 0


def count_log_errors(log_path, counters):
    """The daemon's stderr lines: "<date> <time> <level> <text>". The
    regulator's own events ("[event=...]", e.g. a protection trip) are
    counted apart: they are the control working, not the software failing."""
    error_lines, trips = [], 0
    for ln in open(log_path, errors="replace"):
        if re.match(r"\S+ \S+ (error|critical) ", ln):
            if "[event=" in ln:
                trips += 1
            else:
                error_lines.append(ln)
    if error_lines:
        counters.add("errors.daemon_log", len(error_lines), example=error_lines[0].strip())
    return trips


if __name__ == "__main__":
    sys.exit(main())
