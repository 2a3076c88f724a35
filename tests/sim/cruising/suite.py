#!/usr/bin/env python3
"""The cruising-day suite (docs/deviations.md): run each scenarios/cruising/*.toml
through the real daemon (--sim --speed max), judge it by criteria.toml, print
one table and, unless --no-plot, write a PNG per scenario.

  suite.py --daemon build/daemon/app/xregulatord --out build/scenarios
  suite.py --daemon ... --out DIR --only 11-load-dump-absorption --no-plot

Exit status: 0 when every judged scenario passed, 1 when one failed (a
scenario with known_failure counts as failed in the table; with --only it
fails the run like any other), 2 on a usage or run error.
"""
from __future__ import annotations

import argparse
import concurrent.futures
import os
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bms_fit  # noqa: E402
import criteria as C  # noqa: E402
import passage  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
SCENARIOS = ROOT / "scenarios" / "cruising"


def flatten(table: dict, out: dict | None = None) -> dict:
    """Parameter names are unique across the config's sections."""
    out = {} if out is None else out
    for k, v in table.items():
        if isinstance(v, dict):
            flatten(v, out)
        else:
            out[k] = v
    return out


def effective_params(daemon: str, scenario: dict) -> dict:
    # Every parameter's default: --print-config of a file that names only the
    # battery type (the shipped file writes most keys commented out), as a
    # scenario's boat is set up (docs/configuration.md "Not set up"). No state
    # database is opened. The bank's keys go in too: a profile sets the tail
    # current, the absorption's timeout and the float voltage the judge uses,
    # scaled to the bank's capacity and cells (docs/batteries.md).
    config = scenario.get("config", {})
    bank = {"BatteryProfile": "custom"}
    bank.update({k: config[k] for k in ("BatteryProfile", "BatteryCapacity_Ah", "BatteryCells") if k in config})
    with tempfile.TemporaryDirectory() as tmp:
        empty = Path(tmp) / "empty.toml"
        empty.write_text("[battery]\n" + "".join(f"{k} = {v!r}\n".replace("'", '"') for k, v in bank.items()))
        text = subprocess.run([daemon, "--config", str(empty), "--state-db", str(Path(tmp) / "none.db"),
                               "--print-config"], check=True, capture_output=True, text=True).stdout
    params = flatten(tomllib.loads(text))
    params.update(scenario.get("config", {}))
    return params


def criteria_for(name: str, table: dict) -> dict:
    c = dict(table["defaults"])
    c.update(table.get(name, {}))
    return c


def run_daemon(daemon: str, toml_path: Path, csv_path: Path, rate_hz: float) -> None:
    cmd = [daemon, "--sim", "--scenario", str(toml_path), "--speed", "max",
           "--telemetry-csv", str(csv_path), "--telemetry-rate", str(rate_hz)]
    log = csv_path.with_suffix(".log")
    with open(log, "w") as f:
        rc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT).returncode
    if rc != 0:
        raise RuntimeError(f"{toml_path.name}: xregulatord exited {rc}, see {log}")


def judge(run: C.Run, crit: dict, params: dict, scenario: dict, log: Path | None = None) -> C.Verdict:
    v = C.Verdict()
    fault_at = crit.get("fault_at_s", float("inf"))
    trips = C.count_trips(run, before_s=fault_at)
    v.figures["trips"] = str(trips)
    if trips > crit["max_trips"]:
        v.failures.append(f"{trips} protection trips (max {crit['max_trips']})")

    slips = C.belt_slips(run)
    if slips:
        v.failures.append(f"{slips} BeltSlip event(s) on a belt that grips")

    limit = float(params["TemperatureLimitF"])
    hottest = C.hottest_while_running(run)
    v.figures["alt max F"] = f"{hottest:.1f}/{limit:.0f}"
    soak = max(run.alt_temp_f)
    if soak > hottest + 0.05:
        v.figures["soak max F"] = f"{soak:.1f}"
    if fault_at == float("inf") and hottest > limit + crit["temp_margin_f"]:
        v.failures.append(f"alternator reached {hottest:.1f} F, limit {limit:.0f} + {crit['temp_margin_f']}")

    if "thermal_utilisation_min" in crit:
        # Steady thermal utilisation, plant-neutral: the temperature rise the
        # last 15 min held, as a share of the rise the limit allows. Heating
        # grows at least linearly with current, so this share is a lower
        # bound of the share of the current that holds the limit.
        ambient = float(scenario["alternator"]["ambient_f"])
        util = C.thermal_utilisation(run, ambient, limit, window_s=900.0)
        v.figures["thermal util"] = f"{util * 100:.1f}%"
        if util < crit["thermal_utilisation_min"]:
            v.failures.append(f"thermal utilisation {util * 100:.1f} % (min {crit['thermal_utilisation_min'] * 100:.0f} %)")

    events = [e["at_s"] for e in scenario.get("events", [])]
    settled = C.settled_mask(run, crit["settle_s"], events)
    med = C.regulation_error_mv(run, settled)
    v.figures["reg mV"] = "-" if med is None else f"{med:.0f}"
    if med is not None and med > crit["regulation_median_mv"]:
        v.failures.append(f"median |V - target| {med:.0f} mV in absorption/float (max {crit['regulation_median_mv']})")

    creep = C.float_creep_mv(run, float(params["FloatVoltage"]))
    v.figures["float creep mV"] = "-" if creep is None else f"{creep:+.0f}"
    if creep is not None and creep > crit["float_creep_mv"]:
        v.failures.append(f"float crept {creep:.0f} mV above FloatVoltage (max {crit['float_creep_mv']})")
    if "min_float_s" in crit:
        in_float = sum(b - a for a, b, s in zip(run.t, run.t[1:], run.stage) if s == "FLOAT")
        v.figures["float s"] = f"{in_float:.0f}"
        if in_float < crit["min_float_s"]:
            v.failures.append(f"only {in_float:.0f} s in FLOAT (min {crit['min_float_s']})")

    if crit["tail_exit"]:
        exits = C.absorption_exits(run, float(params["TailCurrent_A"]), float(params["AbsorptionTimeoutMs"]) / 1000.0)
        v.figures["abs exits"] = ",".join(k for _, k in exits) or "-"
        for t, kind in exits:
            if kind == "early":
                v.failures.append(f"absorption ended at {t:.0f} s without a tail or its timeout")
        if crit.get("tail_exit_required") and not any(k == "tail" for _, k in exits):
            v.failures.append("no absorption ended on its tail current")

    if "load_dump_at_s" in crit:
        peak, back = C.load_dump(run, crit["load_dump_at_s"])
        v.figures["dump peak mV"] = f"{peak:+.0f}"
        if peak > crit["load_dump_peak_mv"]:
            v.failures.append(f"load dump peaked {peak:.0f} mV over target (max {crit['load_dump_peak_mv']})")
        if "load_dump_recover_s" in crit:
            v.figures["dump back s"] = "never" if back is None else f"{back:.1f}"
            if back is None or back > crit["load_dump_recover_s"]:
                v.failures.append(f"not back within 20 mV in {crit['load_dump_recover_s']} s after the load dump")

    if "field_off_within_s" in crit:
        off = C.field_off_after(run, fault_at)
        v.figures["field off s"] = "never" if off is None else f"{off:.2f}"
        if off is None or off > crit["field_off_within_s"]:
            v.failures.append(f"field not off within {crit['field_off_within_s']} s of the fault")

    if "resumes_after_s" in crit:
        back = C.resumed_after(run, crit["resumes_after_s"])
        v.figures["resume s"] = "never" if back is None else f"{back:.0f}"
        if back is None or back > crit["resume_within_s"]:
            v.failures.append(f"charging not resumed within {crit['resume_within_s']} s of {crit['resumes_after_s']} s")

    passage.judge_passage(run, crit, v)
    bms_fit.judge_bms_fit(run, crit, v, log)
    v.figures["end"] = f"{run.stage[-1]} {run.soc[-1]:.0f}%"
    if crit.get("known_failure"):
        v.failures.append("known failure: " + crit["known_failure"])
    return v


def run_one(daemon: str, toml_path: Path, out: Path, table: dict, plot: bool) -> tuple[str, C.Verdict, str]:
    name = toml_path.stem
    with open(toml_path, "rb") as f:
        scenario = tomllib.load(f)
    crit = criteria_for(name, table)
    csv_path = out / f"{name}.csv"
    run_daemon(daemon, toml_path, csv_path, crit["telemetry_rate_hz"])
    run = C.load_csv(str(csv_path))
    verdict = judge(run, crit, effective_params(daemon, scenario), scenario, csv_path.with_suffix(".log"))
    if plot:
        import plot as P  # matplotlib only where plots are wanted

        P.plot_run(run, scenario.get("name", name), verdict, out / f"{name}.png")
    return name, verdict, scenario.get("name", name)


def print_table(results: list[tuple[str, C.Verdict, str]]) -> None:
    keys = ["trips", "alt max F", "thermal util", "reg mV", "float creep mV", "abs exits", "dump peak mV", "dump back s",
            "field off s", "absorptions", "min SoC", "stale s", "cell offs/swings", "end"]
    print(f"{'scenario':<28} {'result':<6} " + " ".join(f"{k:>14}" for k in keys))
    for name, v, _ in results:
        cells = " ".join(f"{v.figures.get(k, ''):>14}" for k in keys)
        print(f"{name:<28} {'PASS' if v.passed else 'FAIL':<6} {cells}")
    for name, v, _ in results:
        for msg in v.failures:
            print(f"  {name}: {msg}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--daemon")
    ap.add_argument("--out")
    ap.add_argument("--only", action="append", help="scenario name (file stem); repeatable")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--list-judged", action="store_true",
                    help="print the scenarios without known_failure (what ctest registers) and exit")
    a = ap.parse_args()
    if not a.list_judged and not (a.daemon and a.out):
        ap.error("--daemon and --out are required")
    out = Path(a.out or ".")
    out.mkdir(parents=True, exist_ok=True)
    with open(HERE / "criteria.toml", "rb") as f:
        table = tomllib.load(f)
    files = sorted(SCENARIOS.glob("*.toml"))
    if a.list_judged:
        print(";".join(p.stem for p in files if not criteria_for(p.stem, table).get("known_failure")))
        return 0
    if a.only:
        files = [p for p in files if p.stem in a.only]
        missing = set(a.only) - {p.stem for p in files}
        if missing:
            print(f"no such scenario: {', '.join(sorted(missing))}", file=sys.stderr)
            return 2
    try:
        with concurrent.futures.ProcessPoolExecutor(max_workers=a.jobs) as ex:
            futs = [ex.submit(run_one, a.daemon, p, out, table, not a.no_plot) for p in files]
            results = [f.result() for f in futs]
    except (RuntimeError, ValueError, subprocess.CalledProcessError) as e:
        print(e, file=sys.stderr)
        return 2
    print_table(results)
    return 0 if all(v.passed for _, v, _ in results) else 1


if __name__ == "__main__":
    sys.exit(main())
