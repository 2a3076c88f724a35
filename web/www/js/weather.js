// The forecast panel (docs/integrations.md "Weather"): the three days the
// forecast client read, their UV index and radiation, and whether weather
// mode holds the alternator off and why. Shown only when
// [integrations.weather] is enabled; reads /api/system and /api/status.
import { getJson } from "./api.js";

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

// Why, in plain words: the regulator's reason is the truth (the SoC floor or
// weatherModeEnabled may keep it charging while the forecast is sunny).
function verdict(w, reason) {
  const v = w.values || {};
  if (reason === "REASON_WEATHER_MODE")
    return `Holding the alternator off: ${v.sunny_days} of 3 days above UV ${num(v.uv_threshold, 1)}.`;
  if (w.last_error) return `Charging as usual: ${w.last_error}`;
  if (v.active === 1) return "Charging: the forecast is sunny, but weather mode is off or the SoC is under WeatherModeMinSoC.";
  return `Charging as usual: ${num(v.sunny_days, 0)} of 3 days above UV ${num(v.uv_threshold, 1)}.`;
}

function render(panel, w, reason) {
  const v = w.values || {};
  panel.replaceChildren();
  const h = document.createElement("h2");
  h.textContent = "Weather mode";
  const p = document.createElement("p");
  p.id = "weather-verdict";
  p.textContent = verdict(w, reason);
  const t = document.createElement("table");
  t.appendChild(row(["", "Day 1", "Day 2", "Day 3"], "th"));
  t.appendChild(row(["UV index", num(v.uv_day1, 1), num(v.uv_day2, 1), num(v.uv_day3, 1)]));
  t.appendChild(row(["Radiation MJ/m²", num(v.radiation_day1, 1), num(v.radiation_day2, 1), num(v.radiation_day3, 1)]));
  const src = document.createElement("p");
  src.className = "hint";
  const age = typeof v.age_s === "number" && Number.isFinite(v.age_s) ? `${Math.round(v.age_s / 60)} min ago` : "none yet";
  const from = SOURCES[(w.texts || {}).position_source] || "no position yet";
  src.id = "weather-position";
  src.textContent = `Position ${num(v.latitude, 3)}, ${num(v.longitude, 3)} (${from}); forecast ${age}.`;
  panel.append(h, p, t, src);
}

async function refresh(panel) {
  try {
    const [sys, st] = await Promise.all([getJson("/api/system"), getJson("/api/status")]);
    const w = (sys.integrations || []).find((i) => i.name === "weather");
    panel.hidden = !(w && w.enabled);
    if (!panel.hidden) render(panel, w, st.reason);
  } catch {
    // The live page shows the connection state; this panel just waits.
  }
}

const panel = document.getElementById("weather-panel");
if (panel) {
  refresh(panel);
  setInterval(() => refresh(panel), PERIOD_MS);
}
