"""One PNG per cruising-day run: voltage and target, currents, duty and
alternator temperature, stage and protection trips, on a shared time axis."""
from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import criteria as C  # noqa: E402

STAGES = ["IDLE", "FLOAT", "ABSORPTION", "BULK"]


def plot_run(run: C.Run, title: str, verdict: C.Verdict, path) -> None:
    span = run.t[-1] - run.t[0]
    scale, unit = (3600.0, "h") if span > 3 * 3600 else (60.0, "min") if span > 600 else (1.0, "s")
    t = [x / scale for x in run.t]
    fig, ax = plt.subplots(4, 1, figsize=(11, 9), sharex=True, height_ratios=[3, 3, 2, 1.4])
    status = "PASS" if verdict.passed else "FAIL: " + "; ".join(verdict.failures)[:140]
    fig.suptitle(f"{title}\n{status}", fontsize=10)

    ax[0].plot(t, run.v, lw=0.8, label="battery V (plant)")
    ax[0].plot(t, run.target_v, lw=0.8, ls="--", label="target V")
    ax[0].set_ylabel("V")
    ax[0].legend(loc="lower right", fontsize=8)

    ax[1].plot(t, run.alt_a, lw=0.8, label="alternator A (plant)")
    ax[1].plot(t, run.bcur, lw=0.8, label="battery A (measured)")
    ax[1].plot(t, run.target_a, lw=0.6, ls=":", label="current target A")
    ax[1].set_ylabel("A")
    ax[1].legend(loc="upper right", fontsize=8)

    ax[2].plot(t, run.duty, lw=0.6, color="tab:green", label="duty %")
    ax[2].set_ylabel("duty %")
    tw = ax[2].twinx()
    tw.plot(t, run.alt_temp_f, lw=0.9, color="tab:red", label="alternator degF (plant)")
    tw.set_ylabel("degF")
    ax[2].legend(loc="upper left", fontsize=8)
    tw.legend(loc="upper right", fontsize=8)

    ax[3].step(t, [STAGES.index(s) if s in STAGES else -1 for s in run.stage], where="post", lw=0.9)
    ax[3].set_yticks(range(len(STAGES)), STAGES, fontsize=7)
    trips = [t[i] for i in range(1, len(t)) if run.mode[i] in C.TRIP_MODES and run.mode[i - 1] not in C.TRIP_MODES]
    for x in trips:
        ax[3].axvline(x, color="tab:red", lw=0.8)
    ax[3].set_xlabel(f"time ({unit}); red lines: protection trips")
    for a in ax:
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
