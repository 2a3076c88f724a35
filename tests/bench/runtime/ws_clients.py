#!/usr/bin/env python3
"""N minimal WebSocket clients on /ws for the control-loop benchmark: each
does the RFC 6455 handshake and reads frames until killed, counting them."""
import base64, os, socket, sys, threading, time

host, port, n, seconds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
counts = [0] * n

def client(i):
    try:
        s = socket.create_connection((host, port), timeout=5)
        key = base64.b64encode(os.urandom(16)).decode()
        s.sendall((f"GET /ws HTTP/1.1\r\nHost: {host}:{port}\r\nUpgrade: websocket\r\n"
                   f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                   f"Sec-WebSocket-Version: 13\r\nOrigin: http://{host}:{port}\r\n\r\n").encode())
        buf = b""
        while b"\r\n\r\n" not in buf:
            buf += s.recv(4096)
        if b" 101 " not in buf.split(b"\r\n")[0]:
            print(f"client {i}: handshake refused: {buf.splitlines()[0]!r}", file=sys.stderr)
            return
        s.settimeout(2)
        end = time.time() + seconds
        while time.time() < end:
            try:
                data = s.recv(65536)
            except socket.timeout:
                continue
            if not data:
                break
            counts[i] += data.count(b'"t_s"')
    except OSError as e:
        print(f"client {i}: {e}", file=sys.stderr)

threads = [threading.Thread(target=client, args=(i,), daemon=True) for i in range(n)]
for t in threads:
    t.start()
for t in threads:
    t.join(seconds + 10)
print(f"ws_clients={n} snapshots_received={sum(counts)} min_per_client={min(counts)}")
