#!/usr/bin/python3
"""Plot the simulator's plant models against the published points.

Runs xr_plant_curves (built with the project) into a scratch directory and
writes one PNG per model into docs/img/. Published points are the shared
plant facts' (source keys in docs/simulator.md "Sources").

    tools/plots/plot_plant.py <build dir> [<output dir, default docs/img>]
"""
import csv
import os
import subprocess
import sys
import tempfile
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Published alternator output points: (rpm, amps, hot?) at 13.5 V.
SARA_FULL = [(2000, 120), (4000, 170), (6000, 180)]  # Bosch LiX 180 A, 25 °C, full field
WB33_COLD = [(1300, 24), (2500, 50)]
WB33_HOT = [(1300, 16), (2500, 41), (5000, 48)]
MERC = [(600, 21), (1000, 37), (1500, 44), (2000, 48), (2500, 50), (3000, 51), (4000, 52), (5000, 52)]  # engine rpm, 12.6 V
# docs/sources.md P2.7, Ford 130 A (RIVAS), derived minimum field for conduction.
FORD_KNEE = [(1200, 3.30), (1500, 2.64), (1800, 2.20), (2000, 1.98), (3000, 1.32), (4000, 0.99), (6000, 0.66)]
# OCV tables (12 V values / cells).
LSOL_LFP = [(0, 2.833), (5, 3.132), (10, 3.177), (15, 3.190), (20, 3.213), (25, 3.226), (30, 3.240), (35, 3.252),
            (40, 3.262), (45, 3.264), (50, 3.265), (55, 3.268), (60, 3.271), (65, 3.275), (70, 3.283), (75, 3.296),
            (80, 3.304), (85, 3.308), (90, 3.309), (95, 3.314), (100, 3.392)]
A123 = [(95.71, 3.32), (91.47, 3.316), (87.09, 3.313), (82.85, 3.306), (78.54, 3.304), (74.18, 3.29), (69.92, 3.28),
        (65.61, 3.278), (61.31, 3.276), (57.05, 3.274), (52.74, 3.272), (48.46, 3.269), (44.14, 3.266),
        (39.83, 3.263), (35.55, 3.25), (31.24, 3.24), (26.87, 3.23), (22.59, 3.22), (18.24, 3.20), (13.88, 3.19),
        (9.63, 3.17), (5.35, 3.12)]
LL_AGM = [(0, 10.50 / 6), (25, 11.75 / 6), (50, 12.20 / 6), (75, 12.55 / 6), (100, 12.80 / 6)]
LSOL_LEAD = [(0, 11.52 / 6), (25, 11.84 / 6), (35, 11.96 / 6), (50, 12.15 / 6), (75, 12.47 / 6), (100, 12.78 / 6)]


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def col(rows, key):
    return [float(r[key]) for r in rows]


def alternator(d, out):
    rows = read(os.path.join(d, "alternator.csv"))
    groups = defaultdict(list)
    for r in rows:
        groups[(r["preset"], float(r["temp_c"]))].append(r)
    fig, axes = plt.subplots(1, 4, figsize=(19, 4.5))
    for ax, preset, title in ((axes[0], "bosch-lix-180", "Bosch LiX 180 A (SARA)"),
                              (axes[1], "westerbeke-48", "Westerbeke 33A alternator (WB33)")):
        for (p, t), g in sorted(groups.items()):
            if p != preset:
                continue
            ax.plot(col(g, "rpm"), col(g, "amps"), label=f"model, windings {t:.0f} °C",
                    color="tab:blue" if t < 100 else "tab:red")
        ax.set_title(title)
        ax.set_xlabel("shaft rpm (full field, 13.5 V)")
        ax.set_ylabel("output A")
        ax.grid(alpha=0.3)
    axes[0].plot(*zip(*SARA_FULL), "o", color="tab:blue", label="published, 25 °C")
    axes[1].plot(*zip(*WB33_COLD), "o", color="tab:blue", label="published, cold")
    axes[1].plot(*zip(*WB33_HOT), "s", color="tab:red", label="published, hot")
    for ax in axes[:2]:
        ax.legend(fontsize=8)
    merc = read(os.path.join(d, "mercury.csv"))
    axes[3].plot([float(r["engine_rpm"]) for r in merc], col(merc, "amps"), label="model, 25 °C, belt 2.33")
    axes[3].plot(*zip(*MERC), "o", label="published (MERC)")
    axes[3].set_title("Mercury 150 EFI alternator (12.6 V)")
    axes[3].set_xlabel("engine rpm")
    axes[3].set_ylabel("output A")
    axes[3].grid(alpha=0.3)
    axes[3].legend(fontsize=8)
    knee = read(os.path.join(d, "knee.csv"))
    for preset, style in (("ford-130", "-"), ("bosch-lix-180", "--")):
        g = [r for r in knee if r["preset"] == preset]
        axes[2].plot(col(g, "rpm"), col(g, "knee_field_a"), style, label=f"model {preset}")
    axes[2].plot(*zip(*FORD_KNEE), "o", label="Ford 130 A, derived table (docs/sources.md P2.7)")
    axes[2].set_title("Knee: field needed before any output (13.5 V)")
    axes[2].set_xlabel("shaft rpm")
    axes[2].set_ylabel("field A")
    axes[2].set_ylim(0, 5)
    axes[2].grid(alpha=0.3)
    axes[2].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "plant_alternator.png"), dpi=90)


def ocv(d, out):
    rows = read(os.path.join(d, "ocv.csv"))
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    lfp = [r for r in rows if r["chemistry"] == "lifepo4"]
    axes[0].plot(col(lfp, "soc_pct"), col(lfp, "cell_v"), label="model (rested, no hysteresis offset)")
    axes[0].plot(*zip(*LSOL_LFP), "o", label="Libre Solar table (LSOL)")
    axes[0].plot(*zip(*A123), "x", label="A123 table (A123J)")
    axes[0].set_ylim(3.1, 3.45)
    axes[0].set_title("LiFePO4 OCV per cell")
    for chem, pts, mark, name in (("agm", LL_AGM, "o", "Lifeline AGM (LL)"),
                                  ("flooded", LSOL_LEAD, "s", "Libre Solar lead (LSOL)")):
        g = [r for r in rows if r["chemistry"] == chem]
        axes[1].plot(col(g, "soc_pct"), col(g, "cell_v"), label=f"model {chem}")
        axes[1].plot(*zip(*pts), mark, label=name)
    axes[1].set_title("Lead-acid OCV per cell")
    for ax in axes:
        ax.set_xlabel("SoC %")
        ax.set_ylabel("V per cell")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "plant_ocv.png"), dpi=90)


def charge(d, out):
    rows = read(os.path.join(d, "charge.csv"))
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.5))
    for ax, runs, title in ((axes[0], ("agm_0.2C", "agm_0.4C"), "AGM 95.69 Ah at 14.4 V from 50 %, then rest"),
                            (axes[1], ("lfp_0.5C",), "LiFePO4 100 Ah at 50 A to 14.2 V from 45 %, then rest")):
        ax2 = ax.twinx()
        for run in runs:
            g = [r for r in rows if r["run"] == run]
            h = [float(r["t_s"]) / 3600 for r in g]
            ax.plot(h, col(g, "volts"), label=f"{run} volts")
            ax2.plot(h, col(g, "amps"), "--", label=f"{run} amps")
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("hours")
        ax.set_ylabel("V")
        ax2.set_ylabel("A")
        ax.grid(alpha=0.3)
        ax.legend(loc="lower right", fontsize=8)
        ax2.legend(loc="center right", fontsize=8)
    # MS: absorption reached at 63.3 % (0.4C) and 77.4 % (0.2C); full after ~5.5 h at 0.2C.
    for run, soc in (("agm_0.4C", 63.3), ("agm_0.2C", 77.4)):
        g = [r for r in rows if r["run"] == run]
        t = next(float(r["t_s"]) for r in g if float(r["soc_pct"]) >= soc) / 3600
        axes[0].axvline(t, color="grey", ls=":", lw=1)
        axes[0].text(t, 12.2, f" MS: 14.4 V at {soc} % ({run})", rotation=90, fontsize=7, va="bottom")
    axes[0].axvline(5.5, color="black", ls=":", lw=1)
    axes[0].text(5.5, 12.2, " MS: full ~5.5 h (0.2C)", rotation=90, fontsize=7, va="bottom")
    axes[1].axhspan(13.4, 13.6, color="green", alpha=0.15)
    axes[1].text(0.05, 13.42, "rested full 13.4-13.6 V (LOW-AUTH)", fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "plant_battery_charge.png"), dpi=90)


def thermal(d, out):
    rows = read(os.path.join(d, "thermal.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    m = [float(r["t_s"]) / 60 for r in rows]
    ax.plot(m, col(rows, "stator_c"), label="model windings")
    ax.plot(m, col(rows, "case_c"), label="model case (sensor)")
    ax.axhline(152, color="tab:red", ls=":", label="ARCO: stator 305 °F after 60 min at 3000 rpm")
    ax.axvline(60, color="grey", ls=":")
    ax.axhline(93, color="tab:orange", ls=":", label="Balmar: case can exceed 200 °F")
    ax.set_title("Bosch LiX preset, full output at 3000 rpm, 25 °C air")
    ax.set_xlabel("minutes")
    ax.set_ylabel("°C")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "plant_thermal.png"), dpi=90)


def load_dump(d, out):
    rows = read(os.path.join(d, "load_dump.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(col(rows, "t_ms"), col(rows, "bus_v"), label="model bus (BMS opens at 0, field cut at once)")
    ax.axhspan(79, 101, color="tab:red", alpha=0.12, label="ISO 16750-2 test A: Us 79-101 V")
    ax.axvspan(40, 400, color="grey", alpha=0.08, label="td 40-400 ms")
    ax.axhline(35, color="tab:green", ls=":", label="test B clamp Us* 35 V")
    ax.set_title("Load dump, Bosch LiX at 6000 rpm full output, no suppression")
    ax.set_xlabel("ms")
    ax.set_ylabel("V")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "plant_load_dump.png"), dpi=90)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    build = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "docs", "img")
    os.makedirs(out, exist_ok=True)
    tool = os.path.join(build, "tools", "xr_plant_curves")
    with tempfile.TemporaryDirectory() as d:
        subprocess.run([tool, d], check=True)
        alternator(d, out)
        ocv(d, out)
        charge(d, out)
        thermal(d, out)
        load_dump(d, out)


if __name__ == "__main__":
    main()
