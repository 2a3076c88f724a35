"""A Venus OS battery service as the GX's broker shows it (dbus-flashmq),
played into a real mosquitto with the mosquitto_sub/mosquitto_pub CLIs:

  - N/<portal>/battery/<instance>/<path> with {"value": ...}, published when
    a value changes (set()), never retained;
  - a read request R/<portal>/battery/<instance>/<path> republishes that
    value; a keepalive R/<portal>/keepalive without "suppress-republish"
    republishes them all;
  - raw() publishes any payload (bad values, Venus's empty "device gone").

stop() makes the GX silent (the broker stays up). Every process is started
through the Harness, so it is stopped by its pid whatever happens."""
import json
import subprocess
import threading
import time


class FakeVenus:
    def __init__(self, h, portal, instance, values):
        self.h = h
        self.portal = portal
        self.base = f"N/{portal}/battery/{instance}/"
        self.read_prefix = f"R/{portal}/battery/{instance}/"
        self.values = dict(values)  # path -> Python value (json-encoded when sent)
        self.reads = 0
        self.lock = threading.Lock()
        port = str(h.broker_port)
        self.sub = subprocess.Popen(["mosquitto_sub", "-h", "127.0.0.1", "-p", port, "-t", f"R/{portal}/#", "-v"],
                                    stdout=subprocess.PIPE, text=True, bufsize=1)
        h.procs.append(self.sub)
        # One long-lived publisher per topic (-l: a message per stdin line).
        self.pubs = {}
        for path in self.values:
            p = subprocess.Popen(["mosquitto_pub", "-h", "127.0.0.1", "-p", port, "-t", self.base + path, "-l"],
                                 stdin=subprocess.PIPE, text=True, bufsize=1)
            h.procs.append(p)
            self.pubs[path] = p
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()
        time.sleep(0.5)  # subscribed and connected before anyone asks

    def _serve(self):
        for line in self.sub.stdout:
            topic, _, payload = line.rstrip("\n").partition(" ")
            if topic == f"R/{self.portal}/keepalive":
                if "suppress-republish" not in payload:
                    for path in list(self.values):
                        self._send(path)
            elif topic.startswith(self.read_prefix):
                path = topic[len(self.read_prefix):]
                if path in self.values:
                    with self.lock:
                        self.reads += 1
                    self._send(path)

    def _send(self, path):
        self.raw(path, json.dumps({"value": self.values[path]}))

    def raw(self, path, payload):
        """Any payload on N/.../path; an empty one is sent with mosquitto_pub
        -n (Venus's "the device is gone")."""
        with self.lock:
            if payload == "":
                subprocess.run(["mosquitto_pub", "-h", "127.0.0.1", "-p", str(self.h.broker_port),
                                "-t", self.base + path, "-n"], check=True, timeout=10)
                return
            p = self.pubs[path]
            try:
                p.stdin.write(payload + "\n")
                p.stdin.flush()
            except (BrokenPipeError, ValueError):
                pass  # the broker went away and its publisher with it

    def set(self, path, value):
        """A value changes on the GX: Venus publishes it at once."""
        self.values[path] = value
        self._send(path)

    def read_count(self):
        with self.lock:
            return self.reads

    def stop(self):
        for p in [self.sub] + list(self.pubs.values()):
            if p.poll() is None:
                p.terminate()
                p.wait(timeout=10)
        self.thread.join(timeout=10)
