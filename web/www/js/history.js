// The History page (docs/dashboard.md "History"): the last 30 days at a
// glance as bars (energy into the bank, hours in each stage and of the
// engine, the battery's lowest and highest voltage, the alternator's peak
// temperature, the SoC at the start and end of the day), and, for the day
// tapped, its charges: how long, how much, and why each ended. Read from
// /api/history/days and /api/history/charges?day=.
import { getJson } from "./api.js";
import { clock, num } from "./format.js";
import { tempUnit } from "./live.js";
import { reasonInfo } from "./names.js";
import { dayAxis, dayPlot } from "./history_charts.js";

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
  const total = Math.round(minutes);  // 119.7 min is "2 h 0 min", never "1 h 60 min"
  const h = Math.floor(total / 60), m = total - 60 * h;
  return h ? `${h} h ${m} min` : `${m} min`;
}

// The alternator's temperature (the API's °C) in the display unit.
export function tempIn(c, unit) {
  if (typeof c !== "number") return null;
  return unit === "F" ? c * 1.8 + 32 : c;
}

// Oldest first, one x value per day (its local noon, so a bar sits on its date).
export function dayColumns(days, unit) {
  const rows = [...days].sort((a, b) => (a.day < b.day ? -1 : 1));
  const col = (f) => rows.map((d) => (typeof f(d) === "number" ? f(d) : null));
  return {
    days: rows.map((d) => d.day),
    x: rows.map((d) => new Date(`${d.day}T12:00:00`).getTime() / 1000),
    ahIn: col((d) => d.battery_ah_in), altAh: col((d) => d.alt_ah),
    kwhIn: col((d) => (typeof d.battery_wh_in === "number" ? d.battery_wh_in / 1000 : null)),
    altKwh: col((d) => (typeof d.alt_wh === "number" ? d.alt_wh / 1000 : null)),
    bulk: col((d) => d.bulk_h), absorption: col((d) => d.absorption_h), float: col((d) => d.float_h),
    engine: col((d) => d.engine_h),
    vMin: col((d) => d.v_min), vMax: col((d) => d.v_max),
    peak: col((d) => tempIn(d.peak_alt_temp_c, unit)),
    socStart: col((d) => d.soc_start_pct), socEnd: col((d) => d.soc_end_pct),
  };
}

// One line per day under the charts: a button that opens the day's charges.
export function dayLine(d, unit) {
  const t = tempIn(d.peak_alt_temp_c, unit);
  return `${d.day} · ${num(d.alt_ah, d.alt_ah < 10 ? 1 : 0)} Ah · ${num((d.alt_wh || 0) / 1000, 2)} kWh · ` +
    `battery ${dash(d.v_min, 2, " V")}–${dash(d.v_max, 2, " V")} · SoC ${dash(d.soc_start_pct, 0, " %")} → ` +
    `${dash(d.soc_end_pct, 0, " %")} · engine ${dash(d.engine_h, 1, " h")} · alternator up to ${dash(t, 0, ` °${unit}`)}`;
}

function renderDayList(days, unit) {
  const root = $("history-days");
  root.textContent = "";
  if (!days.length) { root.textContent = "No days recorded yet."; return; }
  for (const d of days) {
    const b = document.createElement("button");
    b.type = "button";
    b.className = "day-line";
    b.dataset.day = d.day;
    b.textContent = dayLine(d, unit);
    b.addEventListener("click", () => openDay(d.day));
    root.appendChild(b);
  }
}

let charts = [];
function renderCharts(cols, unit) {
  for (const c of charts) c.destroy();
  charts = [];
  const host = $("history-charts");
  host.textContent = "";
  if (!cols.days.length) return;
  const onDay = (i) => openDay(cols.days[i]);
  const x = cols.x;
  charts.push(dayPlot(host, "Into the bank", x, onDay, [
    { label: "Ah into the bank", data: cols.ahIn, scale: "Ah", bar: 0 },
    { label: "Ah from the alternator", data: cols.altAh, scale: "Ah", bar: 1 },
    { label: "kWh into the bank", data: cols.kwhIn, scale: "kWh" },
  ], [dayAxis("Ah", 0), dayAxis("kWh", 1)]));
  charts.push(dayPlot(host, "Hours", x, onDay, [
    { label: "bulk h", data: cols.bulk, scale: "h", bar: 0 },
    { label: "absorption h", data: cols.absorption, scale: "h", bar: 1 },
    { label: "float h", data: cols.float, scale: "h", bar: 2 },
    { label: "engine h", data: cols.engine, scale: "h", bar: 3 },
  ], [dayAxis("h", 0)]));
  charts.push(dayPlot(host, "Battery voltage and alternator temperature", x, onDay, [
    { label: "lowest V", data: cols.vMin, scale: "V" },
    { label: "highest V", data: cols.vMax, scale: "V" },
    { label: `alternator peak °${unit}`, data: cols.peak, scale: `°${unit}`, bar: 0 },
  ], [dayAxis("V", 0), dayAxis(`°${unit}`, 1)]));
  charts.push(dayPlot(host, "State of charge", x, onDay, [
    { label: "SoC at the start %", data: cols.socStart, scale: "%" },
    { label: "SoC at the end %", data: cols.socEnd, scale: "%" },
  ], [dayAxis("%", 0)]));
}

function renderCharges(charges, tbodyId) {
  const tb = $(tbodyId);
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

// The charges of one day, under its heading.
export async function openDay(day) {
  const r = await getJson(`/api/history/charges?day=${encodeURIComponent(day)}`);
  $("history-day-title").textContent = `Charges on ${day}`;
  $("history-day").hidden = false;
  if (!r.charges.length) $("history-day-none").hidden = false;
  else $("history-day-none").hidden = true;
  renderCharges(r.charges, "history-day-charges");
  $("history-day").scrollIntoView({ block: "nearest" });
}

export async function loadHistoryPage() {
  const [d, c] = await Promise.all([getJson("/api/history/days?n=30"), getJson("/api/history/charges?limit=20")]);
  const unit = tempUnit();
  renderCharts(dayColumns(d.days, unit), unit);
  renderDayList(d.days, unit);
  renderCharges(c.charges, "history-charges");
}
