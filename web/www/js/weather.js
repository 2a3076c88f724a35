// The forecast panel (docs/integrations.md "Weather"): the three days the
// forecast client read, their UV index and radiation, and whether weather
// mode holds the alternator off and why. Shown only when
// [integrations.weather] is enabled; reads /api/system and the live frames.
import { getJson } from "./api.js";
import { ago, isNum } from "./format.js";
import { latestStatus } from "./live.js";

const PERIOD_MS = 30000;
// Where the position came from (docs/integrations.md "Where the forecast is asked for").
const SOURCES = {
  nmea2000: "from the boat's GPS on NMEA 2000",
  signalk: "from Signal K",
  file: "from the configuration file",
};

function num(v, digits) {
  return typeof v === "number" && Number.isFinite(v) ? v.toFixed(digits) : "—";
}

function row(cells, tag = "td") {
  const tr = document.createElement("tr");
  for (const c of cells) {
    const td = document.createElement(tag);
    td.textContent = c;
    tr.appendChild(td);
  }
  return tr;
}

// The decision in force now, in plain words: the regulator's reason in the
// latest live frame is the truth (the SoC floor or weatherModeEnabled may
// keep it charging while the forecast is sunny), so the panel, the headline
// and the badge say the same thing.
export function verdict(w, reason) {
  const v = w.values || {};
  if (reason === "REASON_WEATHER_MODE")
    return `Holding the alternator off: ${v.sunny_days} of 3 days above UV ${num(v.uv_threshold, 1)}.`;
  if (!isNum(v.age_s)) return "Charging as usual: no forecast yet.";
  if (v.active === 1) return "Charging: the forecast is sunny, but weather mode is off or the SoC is under WeatherModeMinSoC.";
  return `Charging as usual: ${num(v.sunny_days, 0)} of 3 days above UV ${num(v.uv_threshold, 1)}.`;
}

// A failed fetch is a note with its time, never the decision; it goes when a
// fetch succeeds. The daemon's text ends with what it does meanwhile and the
// next try, which the verdict above already says.
export function fetchNote(w) {
  const v = w.values || {};
  if (!isNum(v.failed_s_ago) || !w.last_error) return "";
  const why = String(w.last_error).split(";")[0];
  const kept = isNum(v.age_s) ? `; the forecast from ${ago(v.age_s)} stays in force` : "";
  return `The last forecast fetch failed ${ago(v.failed_s_ago)} (${why})${kept}.`;
}

let latestW = null;
function render(panel, w) {
  const v = w.values || {};
  panel.replaceChildren();
  const h = document.createElement("h2");
  h.textContent = "Weather mode";
  const p = document.createElement("p");
  p.id = "weather-verdict";
  const t = document.createElement("table");
  t.appendChild(row(["", "Day 1", "Day 2", "Day 3"], "th"));
  t.appendChild(row(["UV index", num(v.uv_day1, 1), num(v.uv_day2, 1), num(v.uv_day3, 1)]));
  t.appendChild(row(["Radiation MJ/m²", num(v.radiation_day1, 1), num(v.radiation_day2, 1), num(v.radiation_day3, 1)]));
  const src = document.createElement("p");
  src.className = "hint";
  src.id = "weather-position";
  const note = document.createElement("p");
  note.className = "hint";
  note.id = "weather-note";
  panel.append(h, p, t, src, note);
  latestW = w;
  update(panel);
}

// Every second: the verdict from the latest frame, the ages counted on.
function update(panel) {
  if (!latestW || panel.hidden) return;
  const w = latestW;
  const v = w.values || {};
  const s = latestStatus();
  const verdictEl = document.getElementById("weather-verdict");
  if (s && verdictEl) verdictEl.textContent = verdict(w, s.reason);
  const age = isNum(v.age_s) ? `${Math.round((v.age_s + (Date.now() - fetchedAt) / 1000) / 60)} min ago` : "none yet";
  const from = SOURCES[(w.texts || {}).position_source] || "no position yet";
  document.getElementById("weather-position").textContent =
    `Position ${num(v.latitude, 3)}, ${num(v.longitude, 3)} (${from}); forecast ${age}.`;
  const note = fetchNote(w);
  const noteEl = document.getElementById("weather-note");
  noteEl.textContent = note;
  noteEl.hidden = !note;
}

let fetchedAt = 0;
async function refresh(panel) {
  try {
    const sys = await getJson("/api/system");
    fetchedAt = Date.now();
    const w = (sys.integrations || []).find((i) => i.name === "weather");
    panel.hidden = !(w && w.enabled);
    if (!panel.hidden) render(panel, w);
  } catch {
    // The live page shows the connection state; this panel keeps the last.
  }
}

const panel = typeof document !== "undefined" ? document.getElementById("weather-panel") : null;
if (panel) {
  refresh(panel);
  setInterval(() => refresh(panel), PERIOD_MS);
  setInterval(() => update(panel), 1000);
}
