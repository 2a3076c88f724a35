"""The soak test's load (docs/security.md): 20 dashboards on WebSockets, 5 API
requests a second, a dashboard write every 30 s; each counts what it did
and every failure in a shared Counters. Python standard library only."""
import base64
import http.client
import json
import os
import socket
import struct
import threading
import time

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
