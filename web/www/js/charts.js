// uPlot charts: the last minutes (backfilled from /api/history, then fed by
// the WebSocket) and history (volts/amps; temperature, SoC and RPM) with
// fault and stage markers from the events. Legends always show the newest
// values, since a phone cannot hover.
import { getJson } from "./api.js";
import { clock, fToC } from "./format.js";
import { tempUnit } from "./live.js";

const $ = (id) => document.getElementById(id);
export const LIVE_WINDOW_S = 300;
const MIN_VOLT_SPAN = 1.0;  // V: sensor noise must not look like swings
const MIN_TEMP_SPAN = 10;   // °C or °F: a steady alternator's noise must not look like a rise
const RPM_FLOOR = 3000;     // rpm: the line from 0 up, so idle and cruising read as heights, noise as flat

const css = (name) => getComputedStyle(document.body).getPropertyValue(name).trim() || "#888";
const width = (el) => Math.max(280, el.clientWidth - 8);

// An axis range at least `span` wide around the data.
const atLeast = (span) => (u, lo, hi) => {
  if (lo == null || hi == null) return [12, 14];
  const mid = (lo + hi) / 2;
  const half = Math.max(span, hi - lo) / 2 * 1.1;
  return [mid - half, mid + half];
};

// Vertical lines at fault (red) and stage (blue) events.
function markerPlugin(getMarks) {
  return {
    hooks: {
      draw: (u) => {
        const ctx = u.ctx;
        for (const m of getMarks()) {
          const x = u.valToPos(m.t, "x", true);
          if (x < u.bbox.left || x > u.bbox.left + u.bbox.width) continue;
          ctx.save();
          ctx.strokeStyle = m.fault ? "#e53935" : "#3f7fff";
          ctx.lineWidth = 2;
          ctx.setLineDash(m.fault ? [] : [4, 4]);
          ctx.beginPath();
          ctx.moveTo(x, u.bbox.top);
          ctx.lineTo(x, u.bbox.top + u.bbox.height);
          ctx.stroke();
          ctx.restore();
        }
      },
    },
  };
}

// The newest values in the legend whenever nobody points at the chart: the
// last point with a value (the store's newest bucket may still be empty).
// uPlot sets its legend from the cursor (none) after new data, a resize or
// the pointer leaving; this hook puts the newest point back each time.
function newestInLegend() {
  return {
    hooks: {
      setLegend: (u) => {
        if (u.cursor.left >= 0) return;
        let i = u.data[0].length - 1;
        while (i > 0 && u.data.slice(1).every((s) => s[i] == null)) i--;
        if (i >= 0 && u.legend.idx !== i) u.setLegend({ idx: i }, false);
      },
    },
  };
}

let marks = [];
function make(el, scales, axes, series) {
  if (!window.uPlot) { el.textContent = "charts unavailable (uPlot not installed: run make deps)"; return null; }
  return new uPlot({
    width: width(el), height: 220, scales, legend: { live: true },
    // One 24 h clock everywhere (the event list's too): the time axis and
    // the legend's time say "14:05", never uPlot's default "2:05pm".
    axes: [{ stroke: css("--dim"), grid: { stroke: css("--grid") }, values: (u, v) => v.map((t) => clock(t, t)) }, ...axes],
    series: [{ value: (u, t) => (t == null ? "—" : clock(t)) }, ...series], plugins: [markerPlugin(() => marks), newestInLegend()],
  }, [[], ...series.map(() => [])], el);
}
const volts = { scale: "V", size: 60, grid: { stroke: "#8884" }, values: (u, v) => v.map((x) => x.toFixed(1) + " V") };
const amps = { scale: "A", side: 1, size: 56, grid: { show: false }, values: (u, v) => v.map((x) => x + " A") };
const VA = () => [
  { label: "Battery V", scale: "V", stroke: "#1e88e5", width: 2, value: (u, v) => (v == null ? "—" : v.toFixed(2) + " V") },
  { label: "Alternator A", scale: "A", stroke: "#f57c00", width: 2, value: (u, v) => (v == null ? "—" : v.toFixed(1) + " A") },
  { label: "Battery A", scale: "A", stroke: "#2e7d32", width: 1, value: (u, v) => (v == null ? "—" : v.toFixed(1) + " A") },
];
const vaScales = { x: { time: true }, V: { range: atLeast(MIN_VOLT_SPAN) }, A: { auto: true } };

let liveChart = null, histChart = null, envChart = null;
const live = { t: [], v: [], a: [], b: [] };


export function initCharts() {
  liveChart = make($("chart-live"), vaScales, [volts, amps], VA());
  histChart = make($("chart-history"), vaScales, [volts, amps], VA());
  const t = () => (tempUnit() === "F" ? "°F" : "°C");
  const rpmRange = (u, lo, hi) => [0, Math.max(hi ?? 0, RPM_FLOOR) * 1.1];
  envChart = make($("chart-env"), { x: { time: true }, T: { range: atLeast(MIN_TEMP_SPAN) }, P: { range: [0, 100] }, R: { range: rpmRange } },
    [{ scale: "T", size: 56, values: (u, v) => v.map((x) => x + t()) },
     { scale: "P", side: 1, size: 48, grid: { show: false }, values: (u, v) => v.map((x) => x + " %") }],
    [{ label: "Alternator temp", scale: "T", stroke: "#d81b60", width: 2, value: (u, v) => (v == null ? "—" : v.toFixed(0) + t()) },
     { label: "SoC", scale: "P", stroke: "#2e7d32", width: 2, value: (u, v) => (v == null ? "—" : v.toFixed(0) + " %") },
     { label: "RPM", scale: "R", stroke: "#8e24aa", width: 1, value: (u, v) => (v == null ? "—" : v.toFixed(0)) }]);
  window.addEventListener("resize", () => {
    for (const [c, el] of [[liveChart, "chart-live"], [histChart, "chart-history"], [envChart, "chart-env"]])
      if (c) c.setSize({ width: width($(el)), height: 220 });
  });
}

export function pushLive(s) {
  const t = s.wall_time_s || Date.now() / 1000;
  // A clock jump (or backfill from another clock) must not squeeze the window.
  if (live.t.length && Math.abs(t - live.t[live.t.length - 1]) > LIVE_WINDOW_S) for (const k of Object.keys(live)) live[k] = [];
  live.t.push(t); live.v.push(s.battery_v); live.a.push(s.alt_a); live.b.push(s.bcur_a);
  while (live.t.length && live.t[0] < t - LIVE_WINDOW_S) { live.t.shift(); live.v.shift(); live.a.shift(); live.b.shift(); }
}

let pending = false;
export function drawLive() {
  if (pending || !liveChart || $("page-live").hidden) return;
  pending = true;
  requestAnimationFrame(() => {
    pending = false;
    liveChart.setData([live.t, live.v, live.a, live.b]);
    describe(liveChart, $("chart-live"), "Live chart, battery volts and amps");
  });
}

// The live chart starts from the store's last minutes, not empty.
export async function backfillLive() {
  try {
    const h = await getJson(`/api/history?series=ibv_v,alt_a,bcur_a&from=-${LIVE_WINDOW_S}&step=2`);
    if (!h.t.length || live.t.length > h.t.length) return;
    const first = live.t.length ? live.t[0] : Infinity;
    const keep = h.t.map((t, i) => [t, i]).filter(([t]) => t < first);
    live.t.unshift(...keep.map(([t]) => t));
    live.v.unshift(...keep.map(([, i]) => h.series.ibv_v[i]));
    live.a.unshift(...keep.map(([, i]) => h.series.alt_a[i]));
    live.b.unshift(...keep.map(([, i]) => h.series.bcur_a[i]));
    drawLive();
  } catch { /* no store: the chart fills from the WebSocket */ }
}

export async function loadHistory() {
  const range = Number($("hist-range").value);
  try {
    // The store keeps ibv_v (INA228 battery voltage), not the fused battery_v.
    const h = await getJson(`/api/history?series=ibv_v,alt_a,bcur_a,temp_f,soc_pct,rpm&from=-${range}`);
    const s = h.series;
    try {
      const ev = await getJson("/api/events?limit=200");
      const from = h.t.length ? h.t[0] : 0;
      marks = ev.events.filter((e) => e.wall_time_s >= from && (e.code === "ProtectionTrip" || e.code === "StageChanged"))
        .map((e) => ({ t: e.wall_time_s, fault: e.code === "ProtectionTrip" && e.reason !== "REASON_RPM_LOW" }));
    } catch { marks = []; }
    const temps = (s.temp_f || []).map((f) => (f == null ? null : tempUnit() === "F" ? f : fToC(f)));
    if (histChart) histChart.setData([h.t, s.ibv_v, s.alt_a, s.bcur_a]);
    if (envChart) envChart.setData([h.t, temps, s.soc_pct || [], s.rpm || []]);
    // uPlot sets the new scales when it commits, after this task: describe them then.
    requestAnimationFrame(() => {
      describe(histChart, $("chart-history"), "History, battery volts and amps");
      describe(envChart, $("chart-env"), "History, alternator temperature, SoC and RPM");
    });
    $("hist-msg").textContent = h.t.length ? "" : "no history stored yet";
  } catch (e) {
    $("hist-msg").textContent = "history: " + e.message;
  }
}

// What a chart shows, for a screen reader (role="img" with a label) and in
// data-* attributes: how many points, from when (unix s), how many event
// markers, and the axes' spans (volts, temperature, RPM). The browser tests read the same.
function describe(u, el, what) {
  if (!u) return;
  const t = u.data[0];
  const span = u.scales.V ? u.scales.V.max - u.scales.V.min : null;
  el.setAttribute("role", "img");
  el.setAttribute("aria-label", t.length ? `${what}: ${t.length} points from ${clock(t[0])} to ${clock(t[t.length - 1])}` +
    (marks.length && u !== liveChart ? `, ${marks.length} event markers` : "") : `${what}: no data yet`);
  el.dataset.points = String(t.length);
  el.dataset.first = t.length ? String(t[0]) : "";
  el.dataset.markers = String(u === liveChart ? 0 : marks.length);
  if (span !== null && isFinite(span)) el.dataset.vspan = span.toFixed(2);
  if (u.scales.T && isFinite(u.scales.T.max - u.scales.T.min)) el.dataset.tspan = (u.scales.T.max - u.scales.T.min).toFixed(1);
  if (u.scales.R && isFinite(u.scales.R.max)) el.dataset.rpmAxis = `${u.scales.R.min}-${Math.round(u.scales.R.max)}`;
}
