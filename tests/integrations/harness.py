"""Shared pieces of the integration tests (docs/integrations.md): free ports, a real
mosquitto broker, the daemon in --sim with an [integrations] configuration,
and small HTTP and MQTT helpers. Every process started here is stopped by
the Harness, by its own pid."""
import json
import os
import shutil
import signal
import socket
import subprocess
import tempfile
import threading
import time
import urllib.request


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_until(what, predicate, timeout=30.0, step=0.1):
    """Polls predicate until it returns a true value; fails the test with
    `what` when it never does. Returns the value."""
    end = time.monotonic() + timeout
    while True:
        v = predicate()
        if v:
            return v
        if time.monotonic() > end:
            raise AssertionError("timed out waiting for " + what)
        time.sleep(step)


class Harness:
    def __init__(self, daemon):
        self.daemon_bin = daemon
        self.dir = tempfile.mkdtemp(prefix="xr-integrations-")
        self.procs = []
        self.daemon = None
        self.http_port = None
        self.broker = None
        self.broker_port = None

    # ---- mosquitto ----
    def start_broker(self, port=None, users=None, anonymous=False):
        """Debian's mosquitto on 127.0.0.1:port; users = {name: password}
        makes it refuse anonymous clients unless anonymous=True."""
        self.broker_port = port or self.broker_port or free_port()
        conf = os.path.join(self.dir, "mosquitto.conf")
        lines = [f"listener {self.broker_port} 127.0.0.1", "persistence false", "log_dest stderr",
                 "log_type error", "log_type warning"]
        if os.geteuid() == 0:
            # As root mosquitto would drop to its own user, which cannot read
            # this private temporary directory.
            lines.append("user root")
        if users:
            pw = os.path.join(self.dir, "passwd")
            open(pw, "w").close()
            for u, p in users.items():
                subprocess.run(["mosquitto_passwd", "-b", pw, u, p], check=True)
            lines += [f"allow_anonymous {'true' if anonymous else 'false'}", f"password_file {pw}"]
        else:
            lines += ["allow_anonymous true"]
        with open(conf, "w") as f:
            f.write("\n".join(lines) + "\n")
        log = open(os.path.join(self.dir, "mosquitto.log"), "a")
        self.broker = subprocess.Popen(["mosquitto", "-c", conf], stdout=log, stderr=log)
        self.procs.append(self.broker)
        wait_until("mosquitto to listen", self._broker_listening, 10)
        self.users = users or {}

    def _broker_listening(self):
        try:
            with socket.create_connection(("127.0.0.1", self.broker_port), timeout=0.5):
                return True
        except OSError:
            return False

    def kill_broker(self):
        self.broker.send_signal(signal.SIGKILL)
        self.broker.wait()

    def _auth(self):
        if not self.users:
            return []
        u, p = next(iter(self.users.items()))
        return ["-u", u, "-P", p]

    def sub(self, topic, count, timeout=20, retained_only=False, fresh_only=False):
        """mosquitto_sub: up to `count` messages as (topic, payload)."""
        args = ["mosquitto_sub", "-h", "127.0.0.1", "-p", str(self.broker_port), "-t", topic, "-v",
                "-C", str(count), "-W", str(timeout)] + self._auth()
        if retained_only:
            args.append("--retained-only")
        if fresh_only:
            args.append("-R")
        r = subprocess.run(args, capture_output=True, text=True, timeout=timeout + 5)
        out = []
        for line in r.stdout.splitlines():
            t, _, p = line.partition(" ")
            out.append((t, p))
        return out

    def sub_start(self, topic, fresh_only=True):
        """A background mosquitto_sub; read its messages with sub_collect."""
        args = ["mosquitto_sub", "-h", "127.0.0.1", "-p", str(self.broker_port), "-t", topic, "-v"] + self._auth()
        if fresh_only:
            args.append("-R")
        p = subprocess.Popen(args, stdout=subprocess.PIPE, text=True, bufsize=1)
        self.procs.append(p)
        p.got = []  # (topic, payload) as they arrive, for sub_seen

        def read():
            for line in p.stdout:
                p.got.append(tuple(line.rstrip("\n").partition(" ")[::2]))
        p.reader = threading.Thread(target=read, daemon=True)
        p.reader.start()
        time.sleep(0.5)  # subscribed before anything is published
        return p

    def sub_seen(self, p):
        """The messages a background mosquitto_sub has printed so far."""
        return list(p.got)

    def sub_collect(self, p):
        p.send_signal(signal.SIGTERM)
        p.wait(timeout=10)
        p.reader.join(timeout=10)
        return list(p.got)

    def pub(self, topic, payload, retain=False):
        args = ["mosquitto_pub", "-h", "127.0.0.1", "-p", str(self.broker_port), "-t", topic, "-m", payload]
        if retain:
            args.append("-r")
        subprocess.run(args + self._auth(), check=True, timeout=10)

    # ---- the daemon ----
    def start_daemon(self, integrations_toml, extra_args=(), speed=1):
        """xregulatord --sim --speed `speed` with this configuration text
        added to the default one. The integrations' refreshes, backoffs and
        timeouts run on the simulated clock, so a faster speed shortens the
        test. The control period is 20 ms of wall time (20 ms x speed
        simulated, at most the 100 ms the loader allows): the loop's own
        timing is not what these tests measure, and an overrun (a wake-up one
        wall period late) must mean the same thing at every speed on a busy
        build machine."""
        self.http_port = free_port()
        conf = os.path.join(self.dir, "xregulator.toml")
        with open(conf, "w") as f:
            f.write(f"[runtime]\ncontrol_period_us = {min(int(20000 * speed), 100000)}\n\n" + integrations_toml)
        self.daemon_log = os.path.join(self.dir, "daemon.log")
        log = open(self.daemon_log, "a")
        args = [self.daemon_bin, "--sim", "--speed", str(speed), "--config", conf,
                "--http", f"127.0.0.1:{self.http_port}", "--state-db", os.path.join(self.dir, "state.db")]
        self.daemon = subprocess.Popen(args + list(extra_args), stdout=log, stderr=log)
        self.procs.append(self.daemon)
        wait_until("the daemon's first telemetry", lambda: self.status() is not None, 30)

    def log_text(self):
        with open(self.daemon_log) as f:
            return f.read()

    def get(self, path):
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{self.http_port}{path}", timeout=5) as r:
                return r.read().decode()
        except Exception:
            return None

    def status(self):
        t = self.get("/api/status")
        return json.loads(t) if t else None

    def integration(self, name):
        sysinfo = json.loads(self.get("/api/system"))
        for i in sysinfo["integrations"]:
            if i["name"] == name:
                return i
        raise AssertionError(f"/api/system lists no integration '{name}'")

    def metrics(self):
        """GET /metrics as {"name{labels}": value}."""
        out = {}
        for line in (self.get("/metrics") or "").splitlines():
            if line and not line.startswith("#"):
                k, _, v = line.rpartition(" ")
                out[k] = float(v)
        return out

    def wait_sim(self, seconds, timeout=60):
        """Waits until `seconds` of the daemon's simulated time have passed
        (t_s in /api/status): a wait on the daemon's clock, not a sleep."""
        t0 = self.status()["t_s"]
        wait_until(f"{seconds} s of simulated time", lambda: self.status()["t_s"] >= t0 + seconds, timeout)

    def overruns(self):
        return self.status()["loop"]["overruns"]

    def stop_daemon(self):
        """SIGTERM and wait: the daemon's clean stop (CSV flushed)."""
        if self.daemon and self.daemon.poll() is None:
            self.daemon.send_signal(signal.SIGTERM)
            try:
                self.daemon.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.daemon.kill()
                self.daemon.wait()

    def stop(self):
        for p in reversed(self.procs):
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
                try:
                    p.wait(timeout=15)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        if os.environ.get("XR_KEEP_TEST_DIR"):
            print("kept", self.dir)
        else:
            shutil.rmtree(self.dir, ignore_errors=True)


class Checks:
    """Counts checks and failures so a test reports everything it found."""

    def __init__(self):
        self.failures = []
        self.count = 0

    def check(self, ok, what):
        self.count += 1
        if not ok:
            self.failures.append(what)
            print("FAIL:", what)

    def done(self):
        print(f"{self.count} checks, {len(self.failures)} failed")
        return 1 if self.failures else 0
