// xregulator dashboard: WebSocket, routing, commands with confirmation.
import { command, getJson, toast } from "./api.js";
import { backfillLive, drawLive, initCharts, loadHistory, pushLive } from "./charts.js";
import { CONFIRM_TEXT, confirmAction } from "./confirm.js";
import { parseDecimal } from "./format.js";
import { latestStatus, renderLive, renderSetupState, tempUnit, tick } from "./live.js";
import { commandAnswer, plainCommand } from "./names.js";
import { applyEventFilter, loadEvents, loadSystem, renderBattery, renderProtections, renderTuning } from "./pages.js";
import { initPairing, loadDevices } from "./pairing.js";
import { initSettings, loadSettings, setParam } from "./settings.js";
import { initSetup, renderSetupOwner } from "./setup.js";
import { loadHistoryPage } from "./history.js";
import { initTrends, loadTrendsPage } from "./trends.js";
import { renderGuardBanner } from "./guards.js";
import { loadCapacitySetting, renderAlternator, renderHealth, useMeasuredCapacity } from "./health.js";

const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------- theme
// "auto" follows the system (prefers-color-scheme); light is for sunlight.
function applyTheme() {
  const choice = localStorage.getItem("xregulator.theme") || "auto";
  const dark = choice === "dark" || (choice === "auto" && window.matchMedia("(prefers-color-scheme: dark)").matches);
  document.documentElement.dataset.theme = dark ? "dark" : "light";
  $("theme-select").value = choice;
}

// ---------------------------------------------------------------- WebSocket
let ws = null, backoff = 500;
function connect() {
  const proto = location.protocol === "https:" ? "wss:" : "ws:";
  const token = localStorage.getItem("xregulator.token");
  ws = new WebSocket(`${proto}//${location.host}/ws${token ? "?token=" + encodeURIComponent(token) : ""}`);
  ws.onopen = () => { backoff = 500; document.body.dataset.ws = "open"; tick(); };
  ws.onclose = () => {
    document.body.dataset.ws = "closed";
    tick();
    setTimeout(connect, backoff);
    backoff = Math.min(backoff * 2, 10000);
  };
  ws.onmessage = (ev) => {
    let s;
    try { s = JSON.parse(ev.data); } catch { return; }
    document.body.dataset.seq = s.seq;  // lets tests see frames arrive
    renderLive(s);
    pushLive(s);
    drawLive();
    const page = currentPage();
    if (page === "protections") renderProtections(s);
    else if (page === "battery") { renderBattery(s); renderHealth(s); }
    else if (page === "alternator") renderAlternator(s);
    else if (page === "tuning") renderTuning(s);
    else if (page === "setup") renderSetupOwner(s);
  };
}

// ---------------------------------------------------------------- routing
const PAGES = ["live", "settings", "protections", "battery", "alternator", "history", "trends", "tuning", "events", "system", "setup"];
const currentPage = () => { const h = location.hash.slice(1); return PAGES.includes(h) ? h : "live"; };
function route() {
  const page = currentPage();
  for (const p of PAGES) $("page-" + p).hidden = p !== page;
  document.querySelectorAll("nav a").forEach((a) => a.classList.toggle("current", a.getAttribute("href") === "#" + page));
  // On a phone a page behind "More" marks "More"; the list closes on a choice.
  const behindMore = !!document.querySelector(`nav a.more-item[href="#${page}"]`);
  $("tab-more").classList.toggle("current", behindMore);
  $("tabs").classList.remove("open");
  $("tab-more").setAttribute("aria-expanded", "false");
  const fail = (e) => toast(e.message, true);
  if (page === "settings") loadSettings().catch(fail);
  if (page === "events") loadEvents().catch(fail);
  if (page === "history") loadHistoryPage().catch(fail);
  if (page === "trends") loadTrendsPage().catch(fail);
  if (page === "system") { loadSystem().catch(fail); loadDevices().catch(fail); }
  if (page === "tuning") loadSettingsFlags().catch(fail);
  if (page === "battery") loadCapacitySetting().then(() => latestStatus() && renderHealth(latestStatus())).catch(fail);
  if (page === "live") { drawLive(); loadHistory(); }
  const s = latestStatus();
  if (s) {
    if (page === "protections") renderProtections(s);
    if (page === "battery") { renderBattery(s); renderHealth(s); }
    if (page === "alternator") renderAlternator(s);
    if (page === "tuning") renderTuning(s);
  }
}
async function loadSettingsFlags() {
  const { params } = await getJson("/api/params");
  for (const p of params) {
    const el = document.querySelector(`input[data-param="${p.name}"]`);
    if (el) el.checked = !!p.value;
  }
}

// ---------------------------------------------------------------- commands
// Dangerous commands ask first; a command needing a number never goes out
// without one (an empty box is not 0).
export async function runCommand(name, args = {}) {
  if (CONFIRM_TEXT[name]) {
    const [text, ok] = CONFIRM_TEXT[name](args);
    if (!(await confirmAction(text, ok))) { toast(`${plainCommand(name)}: cancelled`); return false; }
  }
  try {
    const r = await command(name, args);
    toast(`${plainCommand(name)}: ${commandAnswer(r.message)}`);
    return true;
  } catch (e) {
    toast(`${plainCommand(name)}: ${commandAnswer(e.message)}`, true);
    return false;
  }
}
function numberFrom(input, label, min, max) {
  const v = parseDecimal(input.value);
  input.classList.toggle("bad", v === null || v < min || v > max);
  if (v === null) { toast(`Enter the ${label} first (${min} to ${max})`, true); input.focus(); return null; }
  if (v < min || v > max) { toast(`The ${label} must be between ${min} and ${max}`, true); input.focus(); return null; }
  return v;
}

function init() {
  applyTheme();
  window.matchMedia("(prefers-color-scheme: dark)").addEventListener("change", applyTheme);
  $("theme-select").addEventListener("change", (e) => { localStorage.setItem("xregulator.theme", e.target.value); applyTheme(); });
  $("theme-toggle").addEventListener("click", () => {
    localStorage.setItem("xregulator.theme", document.documentElement.dataset.theme === "dark" ? "light" : "dark");
    applyTheme();
  });
  $("temp-unit").value = tempUnit();  // the unit every page shows (°C unless °F was chosen)
  $("temp-unit").addEventListener("change", (e) => {
    localStorage.setItem("xregulator.tempUnit", e.target.value);
    const s = latestStatus();
    if (s) { renderLive(s); renderAlternator(s); }
    loadHistory();
  });
  document.querySelectorAll("button[data-cmd]").forEach((b) => b.addEventListener("click", () => runCommand(b.dataset.cmd)));
  $("manual-set").addEventListener("click", () => {
    const duty = numberFrom($("duty-input"), "field duty %", 0, 100);
    if (duty !== null) runCommand("manual", { duty });
  });
  $("capacity-use").addEventListener("click", () =>
    useMeasuredCapacity().then(() => toast("Battery capacity set")).catch((e) => toast(e.message, true)));
  $("soc-set").addEventListener("click", () => {
    const soc = numberFrom($("soc-input"), "state of charge %", 0, 100);
    if (soc !== null) runCommand("set_soc", { soc_pct: soc });
  });
  $("weather-toggle").addEventListener("change", (e) => runCommand("weather_mode", { active: e.target.checked }));
  document.querySelectorAll("input[data-param]").forEach((el) => el.addEventListener("change", () =>
    setParam(el.dataset.param, el.checked).then(() => toast(`${el.dataset.param} ${el.checked ? "on" : "off"}`))
      .catch((e) => { el.checked = !el.checked; toast(e.message, true); })));
  $("events-more").addEventListener("click", () => loadEvents("more").catch((e) => toast(e.message, true)));
  $("events-level").addEventListener("change", applyEventFilter);
  $("hist-range").addEventListener("change", loadHistory);
  $("tab-more").addEventListener("click", () => {
    const open = $("tabs").classList.toggle("open");
    $("tab-more").setAttribute("aria-expanded", String(open));
  });
  initPairing();
  initSettings();
  initSetup(runCommand);
  initCharts();
  initTrends(toast);
  window.addEventListener("hashchange", route);
  setInterval(() => { if (currentPage() === "live") loadHistory(); }, 60000);
  // The event list follows new events while it is open.
  setInterval(() => { if (currentPage() === "events") loadEvents("refresh").catch(() => {}); }, 3000);
  setInterval(tick, 1000);
  // A protection switched off shows on every page, whoever switched it
  // (this page, another phone, the file): the parameters are read again.
  const guards = () => getJson("/api/params").then((b) => { renderGuardBanner(b.params); renderSetupState(b); })
    .catch(() => {});
  guards();
  setInterval(guards, 15000);
  route();
  backfillLive();
  connect();
}

if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", init); else init();
