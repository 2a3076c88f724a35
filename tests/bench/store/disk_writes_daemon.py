#!/usr/bin/env python3
"""What the running daemon writes to its disk per hour (docs/performance.md
"Storage writes"): xregulatord in --sim at --speed S on a state database that
already holds a year of history (xr_history_fill: the 1 s chart window full,
a year of minutes, hours and days), in three conditions:

  cruising     the engine running, the bank charging (bulk, absorption, float)
  anchor       the engine off, the field off, a house load
  fault_storm  cruising while a sensor fault comes and goes every 15 s

After a warm-up (the start's own backup and first flushes) it reads
/proc/<pid>/io write_bytes (what the daemon sent to the block layer: the SD
card's wear) at two simulated times, from the telemetry CSV the daemon writes
to a pipe, and scales the difference to a simulated hour. The daily verified
backup (not inside an hour's window) is added as its size / 24. The journal:
the bytes the daemon logged per simulated hour (stdout, which systemd sends
to journald). Exits 1 when steady running (cruising or anchor) with the
daily backup's share writes 1 MB/h or more.

  disk_writes_daemon.py BUILD_DIR OUT_DIR [--speed S] [--hours H]

Why a paced speed and not max: the daemon's store is fed once a wall second
(StoreService::housekeeping), so at --speed S it sees one sample per S
simulated seconds. Up to S = 60 every minute still gets its 1 s history row
(a minute's row has its 60 slots whatever number is filled), so the rows and
pages written per simulated hour are those of real time; the summaries and
trends integrate the same hours; the ledger checkpoints and history flushes
keep their simulated intervals.
"""
import argparse
import json
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import threading
import time

LIMIT_PER_H = 1_000_000


def proc_io(pid):
    out = {}
    with open(f"/proc/{pid}/io") as f:
        for line in f:
            k, v = line.split(":")
            out[k.strip()] = int(v)
    return out


def scenario(kind, seconds):
    engine = "rpm = 0" if kind == "anchor" else "rpm = 1700"
    text = [f'name = "disk writes: {kind}"', f"duration_s = {seconds}", "seed = 7",
            "[battery]", 'chemistry = "agm"', "capacity_ah = 400", "soc_pct = 55",
            "[engine]", engine, "[loads]", "house_a = 6"]
    if kind == "fault_storm":
        # The battery monitor drops off the bus and comes back every 15 s:
        # a fault event and its recovery each time, for as long as it runs.
        for t in range(120, seconds, 30):
            text += ["[[events]]", f"at_s = {t}", 'fault = "ina228_nack"',
                     "[[events]]", f"at_s = {t + 15}", 'clear = "ina228_nack"']
    return "\n".join(text) + "\n"


class Telemetry(threading.Thread):
    """Reads the daemon's telemetry CSV from a FIFO: the latest simulated time."""

    def __init__(self, fifo):
        super().__init__(daemon=True)
        self.fifo, self.t, self.col = fifo, -1.0, None

    def run(self):
        with open(self.fifo) as f:
            for line in f:
                cells = line.rstrip("\n").split(",")
                if self.col is None:
                    names = [c.strip() for c in cells]
                    self.col = next(i for i, n in enumerate(names) if n in ("t_s", "t", "time_s"))
                    continue
                try:
                    self.t = float(cells[self.col])
                except (ValueError, IndexError):
                    pass


def measure(build, base_db, kind, speed, hours, work, warm):
    d = tempfile.mkdtemp(prefix=f"xr-disk-{kind}-", dir=work)
    db = os.path.join(d, "state.db")
    for suffix in ("", ".bak"):
        if os.path.exists(base_db + suffix):
            shutil.copy2(base_db + suffix, db + suffix)
    total = warm + int(hours * 3600) + 120
    scen = os.path.join(d, "scenario.toml")
    with open(scen, "w") as f:
        f.write(scenario(kind, total))
    # The bench's own telemetry pipe lives in memory: on the disk, each write
    # to it updated the FIFO's inode times, and the writeback every second
    # charged the daemon ~450 KB/h that a daemon in service (no pipe on the
    # card) never writes (docs/performance.md "Storage writes").
    fifo_dir = tempfile.mkdtemp(prefix="xr-disk-fifo-", dir="/dev/shm" if os.path.isdir("/dev/shm") else d)
    fifo = os.path.join(fifo_dir, "telemetry.fifo")
    os.mkfifo(fifo)
    log = open(os.path.join(d, "daemon.log"), "w+")
    cmd = [os.path.join(build, "daemon/app/xregulatord"), "--sim", "--speed", str(speed), "--scenario", scen,
           "--state-db", db, "--duration", str(total), "--telemetry-csv", fifo, "--telemetry-rate", "1"]
    p = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)
    tel = Telemetry(fifo)
    tel.start()
    start_io = end_io = None
    t0 = t1 = None
    log_at_start = 0
    deadline = time.monotonic() + total / speed * 3 + 120
    last_sync = time.monotonic()
    while p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.1)
        # The kernel writes a dirty page back once it is ~30 s old: a page the
        # daemon writes again before that reaches the disk once. A paced run
        # would write it again within 30 s of WALL time and be counted once,
        # so the bench writes back every 30 simulated seconds itself.
        if time.monotonic() - last_sync >= 30.0 / speed:
            os.sync()
            last_sync = time.monotonic()
        t = tel.t
        if start_io is None and t >= warm:
            start_io, t0, log_at_start = proc_io(p.pid), t, os.path.getsize(log.name)
        elif start_io is not None and t >= warm + hours * 3600:
            end_io, t1 = proc_io(p.pid), t
            log_at_end = os.path.getsize(log.name)
            break
    p.send_signal(signal.SIGTERM)
    p.wait(timeout=120)
    if end_io is None:
        raise SystemExit(f"{kind}: the daemon stopped before the measurement ended (see {log.name})")
    per_h = 3600.0 / (t1 - t0)
    bak = os.path.getsize(db + ".bak") if os.path.exists(db + ".bak") else 0
    with sqlite3.connect(db) as c:
        events = c.execute("SELECT count(*) FROM events WHERE t_ms >= (SELECT max(t_ms) FROM events) - ?",
                           (int((t1 - t0) * 1000),)).fetchone()[0]
    r = {
        "condition": kind,
        "simulated_s": round(t1 - t0),
        "write_bytes_per_h": round((end_io["write_bytes"] - start_io["write_bytes"]) * per_h),
        "wchar_per_h": round((end_io["wchar"] - start_io["wchar"]) * per_h),
        "backup_bytes": bak,
        "backup_share_per_h": round(bak / 24),
        "db_bytes": os.path.getsize(db),
        "journal_bytes_per_h": round((log_at_end - log_at_start) * per_h),
        "event_rows_in_window": events,
    }
    r["with_backup_per_h"] = r["write_bytes_per_h"] + r["backup_share_per_h"]
    if os.environ.get("XR_DISK_KEEP"):
        shutil.copy2(db, os.path.join(os.environ["XR_DISK_KEEP"], f"{kind}.db"))
        shutil.copy2(log.name, os.path.join(os.environ["XR_DISK_KEEP"], f"{kind}.log"))
    shutil.rmtree(d, ignore_errors=True)
    shutil.rmtree(fifo_dir, ignore_errors=True)
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("out")
    ap.add_argument("--speed", type=float, default=30.0)
    ap.add_argument("--hours", type=float, default=2.0)
    ap.add_argument("--days", type=int, default=365, help="history filled before (days)")
    ap.add_argument("--only", default="", help="one condition")
    ap.add_argument("--warm", type=int, default=900,
                    help="simulated seconds before the window (the start's backup, the first flushes)")
    a = ap.parse_args()
    if a.speed > 60:
        raise SystemExit("--speed above 60 leaves minutes without a history row: not the real write pattern")
    os.makedirs(a.out, exist_ok=True)
    # /var/tmp: a disk (write_bytes counts nothing on a tmpfs).
    work = tempfile.mkdtemp(prefix="xr-disk-writes-", dir="/var/tmp")
    try:
        base = os.path.join(work, "filled.db")
        subprocess.run([os.path.join(a.build, "daemon/app/xr_history_fill"), "--state-db", base, "--days",
                        str(a.days), "--fine-days", "2"], check=True, stdout=subprocess.DEVNULL)
        kinds = [a.only] if a.only else ["cruising", "anchor", "fault_storm"]
        results = [measure(a.build, base, k, a.speed, a.hours, work, a.warm) for k in kinds]
    finally:
        shutil.rmtree(work, ignore_errors=True)
    over = False
    print(f"{'condition':<12} {'write_bytes/h':>14} {'+ backup/24':>12} {'= per h':>10} {'journal/h':>10} events")
    for r in results:
        print(f"{r['condition']:<12} {r['write_bytes_per_h']:>14,} {r['backup_share_per_h']:>12,} "
              f"{r['with_backup_per_h']:>10,} {r['journal_bytes_per_h']:>10,} {r['event_rows_in_window']}")
        if r["condition"] != "fault_storm" and r["with_backup_per_h"] >= LIMIT_PER_H:
            print(f"disk writes: {r['condition']} writes {r['with_backup_per_h']:,} B/h with the daily backup: "
                  f"over the 1 MB/h of docs/performance.md", file=sys.stderr)
            over = True
    with open(os.path.join(a.out, "disk-writes.json"), "w") as f:
        json.dump({"speed": a.speed, "hours": a.hours, "results": results}, f, indent=1)
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
