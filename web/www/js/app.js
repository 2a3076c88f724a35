// xregulator dashboard: live view from the WebSocket, uPlot charts, pages.
import { command, forgetToken, getJson, toast } from "./api.js";
import { initSettings, loadSettings, setParam } from "./settings.js";

const $ = (id) => document.getElementById(id);
const LIVE_WINDOW_S = 300;  // "last minutes" chart
let latest = null;

// ---------------------------------------------------------------- formatting
const num = (v, d = 1) => (typeof v === "number" && isFinite(v) ? v.toFixed(d) : "—");
const fToC = (f) => (f - 32) * 5 / 9;
function setValue(id, text, unit, alt) {
  const el = $(id);
  if (!el) return;
  el.textContent = text;
  if (unit) { const u = document.createElement("span"); u.className = "unit"; u.textContent = unit; el.appendChild(u); }
  if (alt) { const a = document.createElement("span"); a.className = "alt"; a.textContent = alt; el.appendChild(a); }
}
function kvTable(id, rows) {
  const t = $(id);
  t.textContent = "";
  for (const [k, v, cls] of rows) {
    const tr = t.insertRow();
    tr.insertCell().textContent = k;
    const td = tr.insertCell();
    td.textContent = typeof v === "number" ? (Number.isInteger(v) ? String(v) : v.toFixed(3)) : String(v);
    if (cls) td.className = cls;
  }
}
const minutes = (m) => (typeof m === "number" && m >= 0 ? `${Math.floor(m / 60)} h ${Math.round(m % 60)} min` : "—");

// ---------------------------------------------------------------- live view
function renderLive(s) {
  setValue("v-battery_v", num(s.battery_v, 2), "V");
  setValue("v-bcur_a", num(s.bcur_a, 1), "A");
  setValue("v-alt_a", num(s.alt_a, 1), "A");
  setValue("v-rpm", num(s.rpm, 0));
  setValue("v-temp_f", num(s.temp_f, 0), "°F", `${num(fToC(s.temp_f), 0)} °C`);
  setValue("v-duty_pct", num(s.duty_pct, 1), "%");
  setValue("v-soc_pct", num(s.soc_pct, 1), "%");
  setValue("v-field_enable", s.field_enable ? "ON" : "OFF");
  setValue("v-target", `${num(s.target_a, 0)} A / ${num(s.target_v, 2)} V`);
  setValue("v-mode", `${s.mode} · ${s.stage} · ${s.reason}`);
  const alarms = [];
  if (s.alarm) alarms.push("buzzer");
  const p = s.protection || {};
  if (p.inaOvervoltageLatched) alarms.push("INA overvoltage latched");
  if (p.lockoutActive) alarms.push(`lockout ${num(p.lockoutRemainingS, 0)} s`);
  if (p.tempTaskAlarm) alarms.push("temperature task");
  if (s.fast_ov_active) alarms.push("fast OV clamp");
  if (s.reason && s.reason !== "NONE") alarms.push(s.reason);
  setValue("v-alarms", alarms.length ? alarms.join(", ") : "none");
  $("hdr-mode").textContent = s.mode;
  $("hdr-stage").textContent = s.stage;
  $("hdr-reason").textContent = s.reason;
  $("hdr-reason").classList.toggle("active", s.reason !== "NONE");
  $("hdr-alarm").hidden = !s.alarm;
}

// ---------------------------------------------------------------- charts
const live = { t: [], v: [], a: [], b: [] };
let liveChart = null, histChart = null;
const width = (el) => Math.max(280, el.clientWidth - 8);
function makeChart(el, series) {
  if (!window.uPlot) { el.textContent = "uPlot not installed (run make deps)"; return null; }
  return new uPlot({
    width: width(el), height: 220,
    scales: { x: { time: true }, V: { auto: true }, A: { auto: true } },
    axes: [{ stroke: "#8aa0b3", grid: { stroke: "#1f3446" } },
           { scale: "V", size: 64, stroke: "#3fb6ff", grid: { stroke: "#1f3446" }, values: (u, v) => v.map((x) => x + " V") },
           { scale: "A", side: 1, size: 56, stroke: "#ffb020", grid: { show: false }, values: (u, v) => v.map((x) => x + " A") }],
    series: [{}, ...series],
  }, [[], ...series.map(() => [])], el);
}
const SERIES = [
  { label: "Battery V", scale: "V", stroke: "#3fb6ff", width: 2 },
  { label: "Alternator A", scale: "A", stroke: "#ffb020", width: 2 },
  { label: "Battery A", scale: "A", stroke: "#3ccf7a", width: 1 },
];
function pushLive(s) {
  const t = s.wall_time_s || Date.now() / 1000;
  live.t.push(t); live.v.push(s.battery_v); live.a.push(s.alt_a); live.b.push(s.bcur_a);
  while (live.t.length && live.t[0] < t - LIVE_WINDOW_S) { live.t.shift(); live.v.shift(); live.a.shift(); live.b.shift(); }
}
let chartPending = false;
function drawLive() {
  if (chartPending || !liveChart || $("page-live").hidden) return;
  chartPending = true;
  requestAnimationFrame(() => { chartPending = false; liveChart.setData([live.t, live.v, live.a, live.b]); });
}
async function loadHistory() {
  const range = Number($("hist-range").value);
  try {
    // The store keeps ibv_v (INA228 battery voltage), not the fused battery_v.
    const h = await getJson(`/api/history?series=ibv_v,alt_a,bcur_a&from=-${range}`);
    const s = h.series;
    if (histChart) histChart.setData([h.t, s.ibv_v, s.alt_a, s.bcur_a]);
    $("hist-msg").textContent = h.t.length ? "" : "no history stored yet";
  } catch (e) {
    $("hist-msg").textContent = "history: " + e.message;
  }
}

// ---------------------------------------------------------------- pages fed by status
function renderProtections(s) {
  const p = s.protection || {};
  kvTable("prot-table", [
    ["reason (acting now)", s.reason, s.reason === "NONE" ? "good" : "warn"],
    ["field enable", s.field_enable ? "ON" : "OFF"],
    ["shutdownPhase", p.shutdownPhase],
    ["inaOvervoltageLatched", !!p.inaOvervoltageLatched, p.inaOvervoltageLatched ? "bad" : "good"],
    ["lockoutActive", !!p.lockoutActive, p.lockoutActive ? "warn" : "good"],
    ["lockoutRemainingS", p.lockoutRemainingS],
    ["fastOvClampActive", !!p.fastOvClampActive, p.fastOvClampActive ? "warn" : "good"],
    ["fastOvCurrentCap (A)", p.fastOvCurrentCap],
    ["nearBulk", !!p.nearBulk],
    ["tempTaskAlarm", !!p.tempTaskAlarm, p.tempTaskAlarm ? "bad" : "good"],
    ["thermal penalty (A)", s.thermal_penalty_a],
    ["buzzer", !!p.buzzer, p.buzzer ? "bad" : "good"],
    ["last trip", p.lastTripReason],
    ["last trip at (s)", p.lastTripTimeS],
  ]);
}
function renderBattery(s) {
  const b = s.battery || {};
  kvTable("batt-table", [
    ["SoC (%)", s.soc_pct], ["Coulomb count (Ah)", b.CoulombCount_Ah], ["battery current (A)", s.bcur_a],
    ["full charge detected", !!b.FullChargeDetected],
    ["time to full", minutes(b.timeToFullChargeMin)], ["time to empty", minutes(b.timeToFullDischargeMin)],
    ["charged (Wh)", b.ChargedEnergy_Wh], ["discharged (Wh)", b.DischargedEnergy_Wh],
    ["alternator charged (Wh)", b.AlternatorChargedEnergy_Wh], ["solar charged (Wh)", b.SolarChargedEnergy_Wh],
    ["charged lifetime (Wh)", s.charged_wh_lifetime], ["alternator lifetime (Wh)", s.alt_charged_wh_lifetime],
    ["charge cycles", b.ChargeCycles], ["charge cycles all time", b.ChargeCycles_AllTime],
    ["average SoC (%)", b.AvgSOC], ["average SoC all time (%)", b.AvgSOC_AllTime],
    ["average voltage all time (V)", b.AvgVoltage_AllTime],
    ["alternator on time (s)", b.AlternatorOnTime_s], ["fuel used (L)", b.AlternatorFuelUsed_L],
    ["shunt gain factor", b.DynamicShuntGainFactor], ["alternator current zero (A)", b.DynamicAltCurrentZero],
    ["auto-zero active", !!b.autoZeroActive],
  ]);
}
function renderTuning(s) {
  const c = s.control || {};
  const rows = [["sysMode", c.sysMode], ["govMode", c.govMode], ["uTargetAmps", c.uTargetAmps],
    ["setpointLimited", c.setpointLimited], ["pidInput", c.pidInput], ["pidOutput", c.pidOutput],
    ["innerTermP", c.innerTermP], ["innerTermI", c.innerTermI], ["innerTermD", c.innerTermD],
    ["voltageControlActive", !!c.voltageControlActive], ["ChargingVoltageTarget", c.ChargingVoltageTarget],
    ["cv_I", c.cv_I], ["Icv", c.Icv], ["dutyRequest", c.dutyRequest], ["lastAppliedDuty", c.lastAppliedDuty]];
  for (const sec of ["tuning", "system_id", "cv_tuning"])
    if (s[sec] && typeof s[sec] === "object") for (const [k, v] of Object.entries(s[sec])) rows.push([`${sec}.${k}`, v]);
  kvTable("tuning-table", rows);
}

// ---------------------------------------------------------------- events, system
let oldestEvent = null;
async function loadEvents(more = false) {
  const q = more && oldestEvent ? `&before=${oldestEvent}` : "";
  const body = await getJson(`/api/events?limit=50${q}`);
  const tb = $("events-body");
  if (!more) tb.textContent = "";
  for (const e of body.events) {
    const tr = tb.insertRow();
    tr.className = e.level;
    tr.insertCell().textContent = e.wall_time_s ? new Date(e.wall_time_s * 1000).toLocaleString() : `${num(e.t_s, 1)} s`;
    tr.insertCell().textContent = e.level;
    tr.insertCell().textContent = e.text || e.code;
    oldestEvent = e.id;
  }
  $("events-more").disabled = body.events.length < 50;
}
async function loadSystem() {
  const s = await getJson("/api/system");
  kvTable("sys-versions", Object.entries(s.versions || {}));
  kvTable("sys-loop", Object.entries(s.loop || {}).map(([k, v]) => [k, v, k === "overruns" ? (v ? "bad" : "good") : ""]));
  kvTable("sys-probes", (s.probes || []).map((p) => [p.device, `${p.ok ? "OK" : "FAIL"} ${p.detail}`, p.ok ? "good" : "bad"]));
  kvTable("sys-web", Object.entries(s.web || {}).concat([["telemetry_rate_hz", s.telemetry_rate_hz]]));
}

// ---------------------------------------------------------------- WebSocket
let ws = null, backoff = 500;
function connect() {
  const proto = location.protocol === "https:" ? "wss:" : "ws:";
  const token = localStorage.getItem("xregulator.token");
  ws = new WebSocket(`${proto}//${location.host}/ws${token ? "?token=" + encodeURIComponent(token) : ""}`);
  ws.onopen = () => { backoff = 500; $("conn").textContent = "live"; $("conn").className = "conn on"; };
  ws.onclose = () => {
    $("conn").textContent = "offline"; $("conn").className = "conn off";
    setTimeout(connect, backoff);
    backoff = Math.min(backoff * 2, 10000);
  };
  ws.onmessage = (ev) => {
    let s;
    try { s = JSON.parse(ev.data); } catch { return; }
    latest = s;
    document.body.dataset.seq = s.seq;  // lets tests see frames arrive
    renderLive(s);
    pushLive(s);
    drawLive();
    const page = currentPage();
    if (page === "protections") renderProtections(s);
    else if (page === "battery") renderBattery(s);
    else if (page === "tuning") renderTuning(s);
  };
}

// ---------------------------------------------------------------- routing
const PAGES = ["live", "settings", "protections", "battery", "tuning", "events", "system"];
const currentPage = () => { const h = location.hash.slice(1); return PAGES.includes(h) ? h : "live"; };
function route() {
  const page = currentPage();
  for (const p of PAGES) $("page-" + p).hidden = p !== page;
  document.querySelectorAll("nav a").forEach((a) => a.classList.toggle("current", a.getAttribute("href") === "#" + page));
  const fail = (e) => toast(e.message, true);
  if (page === "settings") loadSettings().catch(fail);
  if (page === "events") loadEvents().catch(fail);
  if (page === "system") loadSystem().catch(fail);
  if (page === "tuning") loadSettingsFlags().catch(fail);
  if (page === "live") { drawLive(); loadHistory(); }
  if (latest) {
    if (page === "protections") renderProtections(latest);
    if (page === "battery") renderBattery(latest);
    if (page === "tuning") renderTuning(latest);
  }
}
async function loadSettingsFlags() {
  const { params } = await getJson("/api/params");
  for (const p of params) {
    const el = document.querySelector(`input[data-param="${p.name}"]`);
    if (el) el.checked = !!p.value;
  }
}

function runCommand(name, args) {
  command(name, args).then((r) => toast(`${name}: ${r.message || "ok"}`)).catch((e) => toast(`${name}: ${e.message}`, true));
}

function init() {
  document.querySelectorAll("button[data-cmd]").forEach((b) => b.addEventListener("click", () => runCommand(b.dataset.cmd)));
  $("manual-set").addEventListener("click", () => runCommand("manual", { duty: Number($("duty-input").value) }));
  $("soc-set").addEventListener("click", () => runCommand("set_soc", { soc_pct: Number($("soc-input").value) }));
  $("weather-toggle").addEventListener("change", (e) => runCommand("weather_mode", { active: e.target.checked }));
  document.querySelectorAll("input[data-param]").forEach((el) => el.addEventListener("change", () =>
    setParam(el.dataset.param, el.checked).then(() => toast(`${el.dataset.param} ${el.checked ? "on" : "off"}`))
      .catch((e) => { el.checked = !el.checked; toast(e.message, true); })));
  $("events-more").addEventListener("click", () => loadEvents(true).catch((e) => toast(e.message, true)));
  $("hist-range").addEventListener("change", loadHistory);
  $("forget-token").addEventListener("click", () => { forgetToken(); toast("token forgotten"); });
  initSettings();
  liveChart = makeChart($("chart-live"), SERIES);
  histChart = makeChart($("chart-history"), SERIES);
  // Read-only hooks for the browser tests.
  window.xrDebug = { livePoints: () => (liveChart ? liveChart.data[0].length : 0),
                     historyPoints: () => (histChart ? histChart.data[0].length : 0) };
  window.addEventListener("resize", () => {
    for (const [c, el] of [[liveChart, "chart-live"], [histChart, "chart-history"]]) if (c) c.setSize({ width: width($(el)), height: 220 });
  });
  window.addEventListener("hashchange", route);
  setInterval(() => { if (currentPage() === "live") loadHistory(); }, 60000);
  route();
  connect();
}

if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", init); else init();
