#!/usr/bin/env python3
"""The cruising-day judge on made-up runs: each criterion passes a run that
meets it and fails one that breaks it by a little."""
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bms_fit as B  # noqa: E402
import criteria as C  # noqa: E402


def make_run(n, dt=1.0, **cols):
    r = C.Run()
    r.t = [i * dt for i in range(n)]
    defaults = dict(mode="MODE_NORMAL_AUTO_PID", stage="ABSORPTION", reason="NONE", v=14.2, target_v=14.2,
                    bcur=10.0, alt_a=20.0, alt_temp_f=100.0, duty=30.0, field_on=1, setpoint_a=20.0,
                    target_a=50.0, soc=90.0)
    for k, d in defaults.items():
        v = cols.get(k, d)
        setattr(r, k, list(v) if isinstance(v, list) else [v] * n)
    return r


class Trips(unittest.TestCase):
    def test_counts_entries_not_rows(self):
        modes = ["MODE_NORMAL_AUTO_PID"] * 3 + ["MODE_WARNING_RAMP_AND_LOCKOUT", "MODE_LOCKOUT_RAMP"] + \
                ["MODE_NORMAL_AUTO_PID"] * 2 + ["MODE_CRITICAL_RAMP"] + ["MODE_NORMAL_AUTO_PID"] * 2
        r = make_run(len(modes), mode=modes)
        self.assertEqual(C.count_trips(r), 2)
        self.assertEqual(C.count_trips(r, before_s=7.0), 1)  # the second trip is at t = 7

    def test_none(self):
        self.assertEqual(C.count_trips(make_run(10)), 0)


class BeltSlips(unittest.TestCase):
    def test_counts_events_during_the_run_only(self):
        r = make_run(5)
        r.belt_slips = [2.0, 2.0, 3.0, 3.0, float("nan")]  # two from earlier runs, one now
        self.assertEqual(C.belt_slips(r), 1)

    def test_none_or_no_column(self):
        r = make_run(3)
        r.belt_slips = [0.0, 0.0, 0.0]
        self.assertEqual(C.belt_slips(r), 0)
        r.belt_slips = [float("nan")] * 3
        self.assertEqual(C.belt_slips(r), 0)


class Regulation(unittest.TestCase):
    def test_median_only_while_the_voltage_loop_holds(self):
        v = [14.2 + 0.019] * 10 + [13.0] * 10
        setpoint = [20.0] * 10 + [50.0] * 10  # second half: current-capped, not judged
        r = make_run(20, v=v, setpoint_a=setpoint)
        med = C.regulation_error_mv(r, [True] * 20)
        self.assertAlmostEqual(med, 19.0, places=3)
        r.v = [14.2 + 0.021] * 10 + [13.0] * 10
        self.assertGreater(C.regulation_error_mv(r, [True] * 20), 20.0)

    def test_resting_field_is_not_judged(self):
        # A full bank resting above its target with the field off is not the
        # voltage loop failing to hold it; the same rows with the field on are.
        r = make_run(20, v=14.5, setpoint_a=0.0, field_on=[0] * 20)
        self.assertIsNone(C.regulation_error_mv(r, [True] * 20))
        r.field_on = [1] * 20
        self.assertAlmostEqual(C.regulation_error_mv(r, [True] * 20), 300.0, places=3)

    def test_settling_after_stage_change_and_event(self):
        stages = ["BULK"] * 5 + ["ABSORPTION"] * 15
        r = make_run(20, stage=stages)
        m = C.settled_mask(r, settle_s=3.0, event_times=[12.0])
        self.assertEqual(m[5:9], [False, False, False, True])  # stage change at t = 5
        self.assertEqual(m[12:16], [False, False, False, True])  # event at t = 12


class FloatCreep(unittest.TestCase):
    def test_window_mean(self):
        r = make_run(1300, stage="FLOAT", v=13.55, target_v=13.5)
        self.assertAlmostEqual(C.float_creep_mv(r, 13.5), 50.0, places=3)
        r.v = [13.5] * 600 + [13.56] * 700  # the last 600 s sit 60 mV high
        self.assertAlmostEqual(C.float_creep_mv(r, 13.5), 60.0, places=3)

    def test_windows_with_the_field_resting_throughout_are_not_judged(self):
        r = make_run(1300, stage="FLOAT", v=13.9, target_v=13.5, field_on=0)
        self.assertIsNone(C.float_creep_mv(r, 13.5))
        r.field_on = [0] * 1050 + [1] * 250  # on for under half of every window
        self.assertIsNone(C.float_creep_mv(r, 13.5))
        r.field_on = [0] * 700 + [1] * 600  # the last window: on for half of it
        self.assertAlmostEqual(C.float_creep_mv(r, 13.5), 400.0, places=3)

    def test_short_float_is_not_judged(self):
        self.assertIsNone(C.float_creep_mv(make_run(100, stage="FLOAT", v=14.0), 13.5))


class ThermalUtilisation(unittest.TestCase):
    def test_share_of_the_allowed_rise_over_the_last_window(self):
        temps = [150.0] * 100 + [197.0] * 900  # 140 ambient, 200 limit: 57 of 60 degF
        r = make_run(1000, alt_temp_f=temps)
        self.assertAlmostEqual(C.thermal_utilisation(r, 140.0, 200.0, window_s=899.0), 0.95, places=6)
        r.alt_temp_f = [196.9] * 1000
        self.assertLess(C.thermal_utilisation(r, 140.0, 200.0, window_s=899.0), 0.95)


class AbsorptionExit(unittest.TestCase):
    def run_exit(self, bcur, v=14.2, n_abs=100):
        stages = ["BULK"] * 10 + ["ABSORPTION"] * n_abs + ["FLOAT"] * 10
        return C.absorption_exits(make_run(len(stages), stage=stages, bcur=bcur, v=v), tail_a=4.0, timeout_s=3600)

    def test_tail(self):
        self.assertEqual(self.run_exit(bcur=4.0)[0][1], "tail")

    def test_discharging_bank_is_early(self):
        self.assertEqual(self.run_exit(bcur=-39.0)[0][1], "early")

    def test_small_discharge_at_the_target_is_a_tail(self):
        # At the RPM duty floor a full bank can discharge a little into the
        # house load while the voltage stays at the target.
        self.assertEqual(self.run_exit(bcur=-3.9)[0][1], "tail")
        self.assertEqual(self.run_exit(bcur=-4.1)[0][1], "early")

    def test_not_at_voltage_is_early(self):
        self.assertEqual(self.run_exit(bcur=3.0, v=14.0)[0][1], "early")

    def test_resting_field_above_target_is_a_tail(self):
        stages = ["BULK"] * 10 + ["ABSORPTION"] * 100 + ["FLOAT"] * 10
        r = make_run(len(stages), stage=stages, bcur=-5.0, v=14.25, field_on=0)
        self.assertEqual(C.absorption_exits(r, tail_a=4.0, timeout_s=3600)[0][1], "tail")
        r.v = [14.14] * len(stages)  # resting but sagging under the target: not a tail
        self.assertEqual(C.absorption_exits(r, tail_a=4.0, timeout_s=3600)[0][1], "early")

    def test_timeout(self):
        self.assertEqual(self.run_exit(bcur=-39.0, n_abs=3600)[0][1], "timeout")

    def test_a_lifepo4_rest_after_absorption_is_judged_too(self):
        stages = ["BULK"] * 10 + ["ABSORPTION"] * 100 + ["IDLE"] * 10
        r = make_run(len(stages), stage=stages, bcur=4.0, v=14.2)
        self.assertEqual(C.absorption_exits(r, tail_a=4.0, timeout_s=3600)[0][1], "tail")
        r.bcur = [-39.0] * len(stages)
        self.assertEqual(C.absorption_exits(r, tail_a=4.0, timeout_s=3600)[0][1], "early")


class LoadDump(unittest.TestCase):
    def test_peak_and_recovery(self):
        v = [14.2] * 100 + [14.2 + 0.240, 14.2 + 0.1, 14.21] + [14.2] * 97
        r = make_run(200, dt=0.5, v=v)  # event at 50 s, peak at 50 s, back at 51 s
        peak, back = C.load_dump(r, 50.0)
        self.assertAlmostEqual(peak, 240.0, places=3)
        self.assertAlmostEqual(back, 1.0, places=6)

    def test_never_back(self):
        r = make_run(200, dt=0.5, v=[14.2] * 100 + [14.5] * 100)
        self.assertEqual(C.load_dump(r, 50.0)[1], None)


class FieldOff(unittest.TestCase):
    def test_delay(self):
        r = make_run(10, dt=0.1, field_on=[1] * 7 + [0] * 3)
        self.assertAlmostEqual(C.field_off_after(r, 0.5), 0.2, places=6)
        self.assertIsNone(C.field_off_after(make_run(10, dt=0.1), 0.5))



class HeatSoak(unittest.TestCase):
    def test_engine_stopped_rows_do_not_count(self):
        temps = [140.0] * 5 + [153.7] * 5 + [151.0] * 5
        reasons = ["NONE"] * 5 + ["REASON_RPM_LOW"] * 3 + ["REASON_TEMP_SOAK"] * 2 + ["NONE"] * 5
        r = make_run(15, alt_temp_f=temps, reason=reasons)
        self.assertEqual(C.hottest_while_running(r), 151.0)  # 151 > limit + 1 would still fail

    def test_a_hot_running_row_counts(self):
        temps = [140.0] * 5 + [153.7] * 5
        reasons = ["REASON_RPM_LOW"] * 5 + ["REASON_LOCKOUT"] * 5
        self.assertEqual(C.hottest_while_running(make_run(10, alt_temp_f=temps, reason=reasons)), 153.7)

    def test_resumed_after(self):
        on = [1] * 3 + [0] * 4 + [1] * 3
        modes = ["MODE_NORMAL_AUTO_PID"] * 3 + ["MODE_DISABLED_RAMP"] * 4 + ["MODE_NORMAL_AUTO_PID"] * 3
        r = make_run(10, field_on=on, mode=modes)
        self.assertEqual(C.resumed_after(r, 3.0), 4.0)
        self.assertIsNone(C.resumed_after(make_run(10, field_on=0), 3.0))

class BmsFit(unittest.TestCase):
    def fit_run(self, n=100, **cols):
        r = make_run(n)
        r.alarm = cols.get("alarm", [0] * n)
        r.bms_mismatch = cols.get("bms_mismatch", ["NONE"] * n)
        r.bms_state = cols.get("bms_state", ["OK"] * n)
        r.charge_held_by = cols.get("charge_held_by", ["NONE"] * n)
        r.charge_held_min = cols.get("charge_held_min", [0.0] * n)
        return r

    def test_mismatch_alarm_within_the_minute(self):
        crit = {"mismatch_within_s": 60, "mismatch_kind": "CVL_CLASS"}
        at60 = self.fit_run(bms_mismatch=["NONE"] * 60 + ["CVL_CLASS"] * 40, alarm=[0] * 60 + [1] * 40)
        v = C.Verdict()
        B.judge_bms_fit(at60, crit, v, None)
        self.assertTrue(v.passed, v.failures)
        at61 = self.fit_run(bms_mismatch=["NONE"] * 61 + ["CVL_CLASS"] * 39, alarm=[0] * 61 + [1] * 39)
        v = C.Verdict()
        B.judge_bms_fit(at61, crit, v, None)
        self.assertFalse(v.passed)
        silent = self.fit_run(bms_mismatch=["CVL_CLASS"] * 100)  # named, but no alarm
        v = C.Verdict()
        B.judge_bms_fit(silent, crit, v, None)
        self.assertFalse(v.passed)

    def test_a_fitting_bms_never_warns(self):
        v = C.Verdict()
        B.judge_bms_fit(self.fit_run(), {"bms_fits": True}, v, None)
        self.assertTrue(v.passed, v.failures)
        v = C.Verdict()
        B.judge_bms_fit(self.fit_run(bms_state=["OK"] * 99 + ["WARNING"]), {"bms_fits": True}, v, None)
        self.assertFalse(v.passed)

    def test_log_lines_about_the_bms(self):
        import tempfile
        with tempfile.TemporaryDirectory() as tmp:
            log = Path(tmp) / "run.log"
            log.write_text("x BMS one\ny bms two\nz other\n")
            v = C.Verdict()
            B.judge_bms_fit(self.fit_run(), {"max_bms_lines": 2}, v, log)
            self.assertTrue(v.passed, v.failures)
            v = C.Verdict()
            B.judge_bms_fit(self.fit_run(), {"max_bms_lines": 1}, v, log)
            self.assertFalse(v.passed)


if __name__ == "__main__":
    unittest.main()
