#!/usr/bin/env python3
"""The GX driver's status mapping (venus/xr_regulator.py) on its own: our
modes, stages and reasons as Victron's /State and /ErrorCode, the owner
model's limits as external control, and answers that are not a status.

usage: gx_mapping_test.py
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "venus"))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "integrations"))

import xr_regulator as m  # noqa: E402
from harness import Checks  # noqa: E402

BASE = {"battery_v": 14.0, "alt_a": 50.0, "temp_f": 212.0, "duty_pct": 60.0, "rpm": 4000,
        "mode": "MODE_NORMAL_AUTO_PID", "stage": "BULK", "reason": "NONE", "field_enable": True,
        "bms_state": "OFF"}


def st(**kw):
    return dict(BASE, **kw)


def main():
    c = Checks()
    for stage, want in (("BULK", 3), ("ABSORPTION", 4), ("FLOAT", 5), ("IDLE", 0)):
        c.check(m.victron_state(st(stage=stage)) == want, f"stage {stage} is /State {want}")
    c.check(m.victron_state(st(field_enable=False, mode="MODE_DISABLED_RAMP", reason="REASON_RPM_LOW")) == 0,
            "engine stopped: off, not fault")
    c.check(m.error_code(st(reason="REASON_RPM_LOW")) == 0, "engine stopped: no error")
    c.check(m.victron_state(st(field_enable=False, mode="MODE_CRITICAL_RAMP", reason="REASON_INA_OVERVOLTAGE")) == 2,
            "a critical mode is a fault")
    c.check(m.victron_state(st(field_enable=False, mode="MODE_LOCKOUT_RAMP", reason="REASON_LOCKOUT")) == 2,
            "lockout is a fault")
    c.check(m.victron_state(st(field_enable=False, mode="MODE_DISABLED_RAMP", reason="REASON_BATTERY_COLD")) == 2,
            "a protection that disables the field is a fault")
    table = {"REASON_INA_OVERVOLTAGE": 2, "REASON_HARD_OVERCURRENT": 18, "REASON_TEMP_CRITICAL": 17,
             "REASON_TEMP_STALE": 23, "REASON_CURRENT_STALE": 21, "REASON_BMS_STALE": 67,
             "REASON_BATTERY_HOT": 1, "REASON_BATTERY_COLD": 14, "REASON_VOLTAGE_IMPLAUSIBLE": 8,
             "REASON_SYS_OFF": 0, "REASON_WEATHER_MODE": 0, "NONE": 0, "SOMETHING_NEW": 0}
    for reason, code in table.items():
        c.check(m.error_code(st(reason=reason)) == code, f"{reason} is /ErrorCode {code}")
    # External control: the owner model when present, bms_state otherwise.
    c.check(m.victron_state(st(bms_state="OK")) == 252, "a followed BMS without owner: external control")
    c.check(m.victron_state(st(bms_state="OK", owner={"limits": []})) == 3, "owner with no acting limit: bulk")
    c.check(m.victron_state(st(owner={"limits": [{"what": "DVCC", "amps": 20, "why": "the GX"}]})) == 252,
            "owner naming DVCC: external control")
    c.check(m.victron_state(st(owner={"limits": [{"what": "BMS CCL", "amps": 40, "why": "x"}]})) == 252,
            "owner naming the BMS: external control")
    c.check(m.victron_state(st(bms_state="OK", owner={"limits": [{"what": "thermal derate", "amps": 30}]})) == 3,
            "owner naming only our own limit: bulk")
    v = m.values_from_status(st())
    c.check(v["/Dc/0/Power"] == 700.0, "/Dc/0/Power = V x I")
    c.check(v["/Alternator/Temperature"] == 100.0, "212 F is 100 C")
    c.check("/Dc/0/Temperature" not in v, "never /Dc/0/Temperature")
    c.check(v["/Mode"] == 1, "/Mode 1 on")
    c.check(m.values_from_status(st(mode="MODE_DISABLED_RAMP", reason="REASON_SYS_OFF"))["/Mode"] == 4,
            "the owner's off is /Mode 4")
    c.check(m.values_from_status(st(temp_f=None, rpm="fast"))["/Speed"] is None, "a non-number is invalid")
    c.check(m.values_from_status(st(rpm=1e300))["/Speed"] is None, "an absurd number is invalid")
    for bad in ([1, 2], "text", None, {"battery_v": "14"}, {"alt_a": 3}, st(battery_v=float("nan"))):
        try:
            m.values_from_status(bad)
            c.check(False, f"{bad!r} is not a status")
        except ValueError:
            c.check(True, "")
    return c.done()


if __name__ == "__main__":
    sys.exit(main())
