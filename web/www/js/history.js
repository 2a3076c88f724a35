// The History page (docs/dashboard.md "History"): the last 30 days as bars
// of what the alternator gave, with the hours in each stage and the hottest
// the alternator got, and a summary of each charge — how long, how much,
// and why it ended. Read from /api/history/days and /api/history/charges.
import { getJson } from "./api.js";
import { clock, num } from "./format.js";
import { reasonInfo } from "./names.js";

const $ = (id) => document.getElementById(id);
const dash = (v, digits, unit) => (typeof v === "number" ? `${num(v, digits)}${unit}` : "—");

// Why a charge ended, in words: the reason the field went off with, or the daemon stopping.
export function endedBy(c) {
  if (c.open) return "still charging";
  if (c.ended_by === "STOPPED") return "the regulator stopped";
  if (!c.ended_by || c.ended_by === "NONE") return "the field went off";
  return reasonInfo(c.ended_by).title;
}

// "1 h 20 min", "45 min".
export function duration(minutes) {
  if (!(minutes >= 0)) return "—";
  const h = Math.floor(minutes / 60), m = Math.round(minutes - 60 * h);
  return h ? `${h} h ${m} min` : `${m} min`;
}

// One line per day, a bar scaled to the best day of the list.
export function dayRows(days) {
  const most = Math.max(1, ...days.map((d) => d.alt_ah || 0));
  return days.map((d) => ({
    day: d.day,
    barPct: Math.round(100 * (d.alt_ah || 0) / most),
    amount: `${num(d.alt_ah, d.alt_ah < 10 ? 1 : 0)} Ah · ${num(d.alt_wh / 1000, 2)} kWh`,
    stages: `bulk ${num(d.bulk_h, 1)} h · absorption ${num(d.absorption_h, 1)} h · float ${num(d.float_h, 1)} h`,
    peak: dash(d.peak_alt_temp_c, 0, " °C"),
  }));
}

function renderDays(days) {
  const root = $("history-days");
  root.textContent = "";
  if (!days.length) { root.textContent = "No days recorded yet."; return; }
  for (const r of dayRows(days)) {
    const row = document.createElement("div");
    row.className = "day";
    const head = document.createElement("div");
    head.className = "day-head";
    head.textContent = `${r.day} · ${r.amount} · alternator up to ${r.peak}`;
    const bar = document.createElement("div");
    bar.className = "bar";
    bar.style.width = `${r.barPct}%`;
    const stages = document.createElement("div");
    stages.className = "hint";
    stages.textContent = r.stages;
    row.append(head, bar, stages);
    root.appendChild(row);
  }
}

function renderCharges(charges) {
  const tb = $("history-charges");
  tb.textContent = "";
  for (const c of charges) {
    const tr = tb.insertRow();
    tr.insertCell().textContent = clock(c.start_s);
    tr.insertCell().textContent = duration((c.end_s - c.start_s) / 60);
    tr.insertCell().textContent = `${num(c.alt_ah, c.alt_ah < 10 ? 1 : 0)} Ah, ${num(c.alt_wh / 1000, 2)} kWh`;
    tr.insertCell().textContent =
      `bulk ${duration(c.bulk_min)}, absorption ${duration(c.absorption_min)}, float ${duration(c.float_min)}`;
    tr.insertCell().textContent = `${dash(c.start_soc_pct, 0, " %")} → ${dash(c.end_soc_pct, 0, " %")}`;
    tr.insertCell().textContent = endedBy(c);
  }
}

export async function loadHistoryPage() {
  const [d, c] = await Promise.all([getJson("/api/history/days?n=30"), getJson("/api/history/charges?limit=20")]);
  renderDays(d.days);
  renderCharges(c.charges);
}
