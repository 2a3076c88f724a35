// The Trends page (docs/dashboard.md "Trends"): a week, a month or a year of
// the hourly (or, for a year, daily) minimum, mean and maximum of the
// battery's voltage and current, the alternator's current and temperature,
// the battery's temperature and the SoC, from /api/history/trends; the same
// range as CSV from /api/history/export.
import { getJson, getToken } from "./api.js";
import { tempUnit } from "./live.js";
import { dayAxis, trendPlot } from "./history_charts.js";

const $ = (id) => document.getElementById(id);
export const RANGES = { "7d": { days: 7, step: "hour" }, "30d": { days: 30, step: "hour" }, "1y": { days: 365, step: "day" } };
let range = "7d";

// °C from the API in the display unit (null stays null).
const inUnit = (unit) => (v) => (v == null ? null : unit === "F" ? v * 1.8 + 32 : v);

// The query of a range ending now: Unix seconds, whole hours.
export function rangeQuery(key, nowS = Date.now() / 1000) {
  const r = RANGES[key];
  const to = Math.floor(nowS);
  return `from=${to - r.days * 86400}&to=${to}&step=${r.step}`;
}

let charts = [];
function draw(r, unit) {
  for (const c of charts) c.destroy();
  charts = [];
  const host = $("trends-charts");
  host.textContent = "";
  $("trends-empty").hidden = r.t.length > 0;
  if (!r.t.length) return;
  const hours = r.step === "hour";
  const s = r.series;
  const band = (name, label, scale, conv = (v) => v) => [
    { label: `${label} mean`, data: s[name].mean.map(conv), scale },
    { label: `${label} lowest`, data: s[name].min.map(conv), scale, width: 1, dash: [4, 4] },
    { label: `${label} highest`, data: s[name].max.map(conv), scale, width: 1, dash: [4, 4] },
  ];
  const t = unit === "F" ? "°F" : "°C";
  const plot = (title, series, axes) => charts.push(trendPlot(host, title, r.t, series, axes, hours));
  plot("Battery voltage", band("battery_v", "battery", "V"), [dayAxis("V", 0)]);
  plot("Currents", [...band("battery_a", "battery", "A"), { label: "alternator mean", data: s.alt_a.mean, scale: "A" },
    { label: "alternator highest", data: s.alt_a.max, scale: "A", width: 1, dash: [4, 4] }], [dayAxis("A", 0)]);
  plot("Temperatures", [{ label: "alternator highest", data: s.alt_temp_c.max.map(inUnit(unit)), scale: t },
    { label: "alternator mean", data: s.alt_temp_c.mean.map(inUnit(unit)), scale: t },
    { label: "battery mean", data: s.battery_temp_c.mean.map(inUnit(unit)), scale: t }], [dayAxis(t, 0)]);
  plot("State of charge", band("soc_pct", "SoC", "%"), [dayAxis("%", 0)]);
}

export async function loadTrendsPage(key = range) {
  range = key;
  for (const b of document.querySelectorAll("#trends-range button")) b.classList.toggle("current", b.dataset.range === key);
  const q = rangeQuery(key);
  $("trends-export").dataset.query = q;
  const r = await getJson(`/api/history/trends?${q}`);
  draw(r, tempUnit());
}

// The CSV of the range shown, saved as a file (fetched with this device's
// credential: a token never goes into a link).
async function exportCsv() {
  const q = $("trends-export").dataset.query || rangeQuery(range);
  const token = getToken();
  const res = await fetch(`/api/history/export?${q}`, { headers: token ? { Authorization: "Bearer " + token } : {} });
  if (!res.ok) throw new Error(`export failed: ${res.status}`);
  const name = /filename="([^"]+)"/.exec(res.headers.get("Content-Disposition") || "")?.[1] || "xregulator.csv";
  const a = document.createElement("a");
  a.href = URL.createObjectURL(await res.blob());
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

export function initTrends(toast) {
  $("trends-export").addEventListener("click", () => exportCsv().catch((e) => toast(e.message, true)));
  for (const b of document.querySelectorAll("#trends-range button"))
    b.addEventListener("click", () => loadTrendsPage(b.dataset.range).catch((e) => toast(e.message, true)));
}
