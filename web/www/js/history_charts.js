// uPlot charts of days (the History page) and of hours or days (Trends):
// dates on the time axis, the unit on each value axis, bars side by side
// for the series that ask for one. A tap on a day calls back with its index.
import { num } from "./format.js";

const css = (name) => getComputedStyle(document.body).getPropertyValue(name).trim() || "#888";
const width = (el) => Math.max(280, el.clientWidth - 8);
const COLORS = ["#3f7fff", "#8e44ad", "#f39c12", "#27ae60", "#e53935", "#16a085"];

// "3 Dec" (a day), or "3 Dec 14:00" when hours are asked for.
export function dateText(unixS, withHour = false) {
  const d = new Date(unixS * 1000);
  const day = d.toLocaleDateString([], { day: "numeric", month: "short" });
  if (!withHour) return day;
  return `${day} ${d.toLocaleTimeString([], { hour: "2-digit", minute: "2-digit", hour12: false })}`;
}

// A value axis labelled with its unit, on the left (0) or the right (1).
export function dayAxis(unit, side) {
  return {
    scale: unit, side: side ? 1 : 3, size: 64, grid: { show: !side, stroke: "#8884" },
    label: unit, values: (u, v) => v.map((x) => `${num(x, Math.abs(x) < 10 ? 1 : 0)} ${unit}`),
  };
}

// Bar `k` of `n` in each column of width spanS (seconds): side by side,
// together 80 % of the column, centred on the column's time.
function sideBySide(k, n, spanS) {
  const w = (0.8 * spanS) / n;
  return uPlot.paths.bars({
    disp: {
      x0: { unit: 1, values: (u) => u.data[0].map((t) => t - 0.4 * spanS + k * w) },
      size: { unit: 1, values: (u) => u.data[0].map(() => w) },
    },
  });
}

// The days themselves as the time axis's ticks, at most `n`, the newest
// always: uPlot's own time ticks fall between days, and with a single day
// of history at 1 Jan 1970 (docs/dashboard.md "History").
function daySplits(x, n) {
  const every = Math.max(1, Math.ceil(x.length / n));
  return x.filter((t, i) => (x.length - 1 - i) % every === 0);
}

function chart(host, title, x, series, axes, opts) {
  if (!window.uPlot) { host.textContent = "charts unavailable (uPlot not installed: run make deps)"; return null; }
  const box = document.createElement("div");
  box.className = "chart history-chart";
  box.dataset.title = title;
  const h = document.createElement("h3");
  h.textContent = title;
  host.append(h, box);
  const bars = series.filter((s) => s.bar !== undefined).length;
  const span = opts.spanS || 86400;
  // Bars need half a column of room at each end.
  const scales = { x: { time: true, range: bars ? (u, lo, hi) => [lo - span / 2, hi + span / 2] : undefined } };
  for (const s of series) scales[s.scale] = { auto: true, range: s.bar !== undefined ? (u, lo, hi) => [0, Math.max(1, hi) * 1.1] : undefined };
  const u = new uPlot({
    width: width(box), height: 200, scales, legend: { live: true },
    cursor: { drag: { x: false, y: false } },
    axes: [{
      stroke: css("--dim"), grid: { stroke: css("--grid") }, values: (p, v) => v.map((t) => dateText(t, opts.hours)),
      splits: opts.hours ? undefined : () => daySplits(x, 5),
    }, ...axes],
    series: [{ value: (p, t) => (t == null ? "—" : dateText(t, opts.hours)) }, ...series.map((s, i) => ({
      label: s.label, scale: s.scale, stroke: s.color || COLORS[i % COLORS.length],
      fill: s.bar !== undefined ? (s.color || COLORS[i % COLORS.length]) + "cc" : undefined,
      width: s.bar !== undefined ? 0 : (s.width ?? 2), dash: s.dash,
      points: { show: s.bar === undefined && x.length <= 62 },
      paths: s.bar !== undefined && uPlot.paths.bars ? sideBySide(s.bar, bars, span) : undefined,
      value: (p, v) => (v == null ? "—" : num(v, Math.abs(v) < 10 ? 2 : 1)),
    }))],
    hooks: opts.onPick ? { ready: [(p) => p.over.addEventListener("click", () => {
      if (p.cursor.idx != null) opts.onPick(p.cursor.idx);
    })] } : {},
  }, [x, ...series.map((s) => s.data)], box);
  box.uplot = u;  // the tests read the drawn tick labels (axes[i]._values)
  return u;
}

// A chart of days; a tap on one opens it (onDay(index)).
export function dayPlot(host, title, x, onDay, series, axes) {
  return chart(host, title, x, series, axes, { hours: false, onPick: onDay });
}

// A chart of trend rows (hours or days).
export function trendPlot(host, title, x, series, axes, hours) {
  return chart(host, title, x, series, axes, { hours });
}
