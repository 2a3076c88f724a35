"""The regulator side of dbus-xregulator: xregulatord's HTTP API read on a
worker thread, and its status turned into the values of a Victron
alternator service (Victron's charger state and error numbers).

The worker never touches D-Bus: it hands each result to the GLib main loop
with GLib.idle_add. Anything the regulator answers that is not a status
(a closed socket, a timeout, HTML, JSON without numbers) is an error, and
errors only ever make the service go invalid: they never end the driver.
"""
import json
import math
import queue
import threading
import time
import urllib.error
import urllib.request

# Victron's charger states (/State), the numbers VE.Direct chargers and
# the GX use: 0 off, 2 fault, 3 bulk, 4 absorption, 5 float, 252 external
# control (a BMS or DVCC decides the charge).
STATE_OFF, STATE_FAULT, STATE_BULK, STATE_ABSORPTION, STATE_FLOAT = 0, 2, 3, 4, 5
STATE_EXTERNAL = 252

# Our protection reasons as Victron charger error codes (/ErrorCode), the
# VE.Direct charger error list the GX shows as text: 1 battery temperature
# too high, 2 battery voltage too high, 8 battery voltage sense
# disconnected, 14 battery temperature too low, 17 charger temperature too
# high, 18 charger over current, 21 current sensor issue, 23 internal
# temperature sensor disconnected, 67 BMS connection lost. Reasons that are
# normal operation (engine off, idle stage, owner's off) are 0: no error.
# The table is documented in docs/integrations.md "Victron GX".
ERROR_CODES = {
    "REASON_BATTERY_HOT": 1,
    "REASON_INA_OVERVOLTAGE": 2,
    "REASON_VOLTAGE_DISAGREE_WARNING": 8,
    "REASON_VOLTAGE_DISAGREE_CRITICAL": 8,
    "REASON_VOLTAGE_IMPLAUSIBLE": 8,
    "REASON_BANK_MISMATCH": 8,
    "REASON_BATTERY_COLD": 14,
    "REASON_TEMP_CRITICAL": 17,
    "REASON_TEMP_WARNING": 17,
    "REASON_TEMP_SUSTAINED": 17,
    "REASON_ALT_HARD_SHUTDOWN": 17,
    "REASON_TEMP_SOAK": 17,
    "REASON_HARD_OVERCURRENT": 18,
    "REASON_CURRENT_STALE": 21,
    "REASON_TEMP_STALE": 23,
    "REASON_BMS_STALE": 67,
}
# Modes in which the regulator has taken the field away for a fault.
FAULT_MODES = ("MODE_CRITICAL_RAMP", "MODE_WARNING_RAMP_AND_LOCKOUT", "MODE_LOCKOUT_RAMP")
STAGE_STATES = {"BULK": STATE_BULK, "ABSORPTION": STATE_ABSORPTION, "FLOAT": STATE_FLOAT}


def number(status, key):
    """A finite number of a sane size from the status, or None (a value no
    regulator can have is no value, never an overflow on the bus)."""
    v = status.get(key)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or abs(v) > 1e6:
        return None
    return float(v)


def error_code(status):
    return ERROR_CODES.get(status.get("reason"), 0)


def externally_limited(status):
    """A BMS or DVCC decides the charge now. The owner model's limits (the
    limits acting now) when the status has them; else any BMS source that is
    followed (bms_state not OFF), as a Victron charger under DVCC shows
    "external control" whether or not the limit binds at the moment."""
    owner = status.get("owner")
    if isinstance(owner, dict) and isinstance(owner.get("limits"), list):
        for lim in owner["limits"]:
            what = str(lim.get("what", "")) if isinstance(lim, dict) else ""
            if "BMS" in what.upper() or "DVCC" in what.upper():
                return True
        return False
    return status.get("bms_state") not in (None, "OFF")


def victron_state(status):
    mode = status.get("mode")
    if mode in FAULT_MODES or (mode == "MODE_DISABLED_RAMP" and error_code(status)):
        return STATE_FAULT
    if not status.get("field_enable") or status.get("stage") == "IDLE":
        return STATE_OFF
    if externally_limited(status):
        return STATE_EXTERNAL
    return STAGE_STATES.get(status.get("stage"), STATE_OFF)


def values_from_status(status):
    """The service's values (path -> value) for one status; None = invalid.
    Raises ValueError when the answer is not a status at all."""
    if not isinstance(status, dict):
        raise ValueError("the status is not a JSON object")
    v, i = number(status, "battery_v"), number(status, "alt_a")
    if v is None or i is None:
        raise ValueError("the status has no battery_v and alt_a numbers")
    temp_f = number(status, "temp_f")
    duty = number(status, "duty_pct")
    rpm = number(status, "rpm")
    off = str(status.get("mode", "")) == "MODE_DISABLED_RAMP" and status.get("reason") == "REASON_SYS_OFF"
    return {
        "/Dc/0/Voltage": round(v, 3),
        "/Dc/0/Current": round(i, 2),
        # The GX sums alternators' /Dc/0/Power (no V x I of its own).
        "/Dc/0/Power": round(v * i, 1),
        # The alternator's own temperature, never at /Dc/0/Temperature: the
        # GX could take that for the battery's (docs/integrations.md).
        "/Alternator/Temperature": None if temp_f is None else round((temp_f - 32.0) / 1.8, 1),
        "/FieldDrive": None if duty is None else round(duty, 1),
        "/Speed": None if rpm is None else int(round(rpm)),
        "/State": victron_state(status),
        "/ErrorCode": error_code(status),
        "/Mode": 4 if off else 1,  # Victron: 1 on, 4 off
    }


class RegulatorLink(threading.Thread):
    """Polls GET /api/status every `period` seconds and posts the GX's DVCC
    limits (POST /api/dvcc) as they arrive. on_status(status) and
    on_error(text) run on the GLib main loop (through `post`)."""

    def __init__(self, base_url, token_file, post, on_status, on_error, on_dvcc_answer, period=0.5, timeout=2.0):
        super().__init__(daemon=True, name="xregulator-link")
        self.base = base_url.rstrip("/")
        self.token_file = token_file
        self.post = post
        self.on_status = on_status
        self.on_error = on_error
        self.on_dvcc_answer = on_dvcc_answer
        self.period = period
        self.timeout = timeout
        self.dvcc = queue.Queue()
        self.stopping = threading.Event()
        self.wake = threading.Event()
        self.versions = {}

    def token(self):
        try:
            with open(self.token_file) as f:
                return f.read().strip()
        except OSError:
            return ""

    def request(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base + path, data=data, method=method)
        tok = self.token()
        if tok:
            req.add_header("Authorization", "Bearer " + tok)
        if data is not None:
            req.add_header("Content-Type", "application/json")
        try:
            with urllib.request.urlopen(req, timeout=self.timeout) as r:
                return r.status, json.loads(r.read(1 << 20).decode())
        except urllib.error.HTTPError as e:
            try:
                return e.code, json.loads(e.read(1 << 16).decode())
            except ValueError:
                return e.code, {}

    def send_dvcc(self):
        latest = None
        while True:
            try:
                latest = self.dvcc.get_nowait()
            except queue.Empty:
                break
        if latest is None:
            return
        try:
            code, body = self.request("POST", "/api/dvcc", latest)
            msg = (body.get("message") or body.get("error") or "") if isinstance(body, dict) else ""
            self.post(self.on_dvcc_answer, code == 200, f"{code} {msg}".strip())
        except Exception as e:  # noqa: BLE001 - every failure is an answer
            self.post(self.on_dvcc_answer, False, f"{type(e).__name__}: {e}")

    def poll_once(self, with_versions):
        try:
            if with_versions:
                code, system = self.request("GET", "/api/system")
                if code == 200 and isinstance(system, dict) and isinstance(system.get("versions"), dict):
                    self.versions = {str(k): str(v) for k, v in system["versions"].items()}
            code, status = self.request("GET", "/api/status")
            if code != 200:
                raise ValueError(f"GET /api/status answered {code}")
            values = values_from_status(status)
            self.post(self.on_status, values, dict(self.versions))
        except Exception as e:  # noqa: BLE001 - garbage or a dead socket is one error
            self.post(self.on_error, f"{type(e).__name__}: {e}")

    def run(self):
        n = 0
        while not self.stopping.is_set():
            start = time.monotonic()
            self.send_dvcc()
            self.poll_once(with_versions=(n % 60 == 0 or not self.versions))
            n += 1
            # A DVCC write wakes the loop at once; otherwise one poll a period.
            self.wake.wait(max(0.0, self.period - (time.monotonic() - start)))
            self.wake.clear()

    def send_limits(self, limits):
        """Main loop: queue the GX's newest DVCC limits for the worker."""
        self.dvcc.put(limits)
        self.wake.set()

    def stop(self):
        self.stopping.set()
        self.wake.set()
