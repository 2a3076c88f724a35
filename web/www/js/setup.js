// First-run set-up (battery, alternator and belt, temperature, then "start
// charging") and the configuration's export / import as TOML. Every step
// is sent as ONE change: the server checks it all or applies nothing.
import { getJson, toast, write } from "./api.js";
import { fToC, parseDecimal } from "./format.js";
import { tempUnit } from "./live.js";
import { choicesOf, loadSettings } from "./settings.js";
import { exportToml, parseParamsToml } from "./toml.js";

const $ = (id) => document.getElementById(id);
const SETUP_PARAMS = ["BatteryProfile", "BatteryCapacity_Ah", "BulkVoltage", "MaxTableValue", "rpmCapCurrentTable",
  "MinRPMForField", "TemperatureLimitF"];
let params = [];
const find = (n) => params.find((p) => p.name === n);

// Charge voltages per bank size for a lead-acid/AGM default; the profile step
// (BatteryProfile, when the daemon has it) sets them per chemistry instead.
const BANK = { 12: { BulkVoltage: 14.4, AbsorptionVoltage: 14.4, FloatVoltage: 13.5 },
  24: { BulkVoltage: 28.8, AbsorptionVoltage: 28.8, FloatVoltage: 27.0 },
  48: { BulkVoltage: 57.6, AbsorptionVoltage: 57.6, FloatVoltage: 54.0 } };

function field(label, id, value, unit, help) {
  return `<label class="field"><span>${label}</span><span class="row"><input id="${id}" inputmode="decimal" value="${value ?? ""}">` +
    `<span class="unit">${unit}</span></span>${help ? `<small>${help}</small>` : ""}</label>`;
}

// Builds the steps from what the daemon offers (the profile step only when
// the BatteryProfile parameter exists).
function renderSteps() {
  const unit = tempUnit();
  const tLimit = find("TemperatureLimitF").value;
  const profile = find("BatteryProfile");
  const cells = find("BatteryCells");
  const steps = [];
  if (profile) {
    const opts = (choicesOf(profile) || []).map(([v, l]) => `<option value="${v}" ${v === profile.value ? "selected" : ""}>${l}</option>`).join("");
    steps.push(`<h3>1 · Battery type</h3><label class="field"><span>Battery profile</span><select id="su-profile">${opts}</select>` +
      `<small>Sets the charge voltages for the chemistry.</small></label>`);
  }
  const bulk = find("BulkVoltage").value;
  const bank = bulk < 18 ? 12 : bulk <= 36 ? 24 : 48;
  steps.push(`<h3>${steps.length + 1} · Battery bank</h3>` +
    `<label class="field"><span>Bank voltage</span><select id="su-bank">${[12, 24, 48].map((b) => `<option ${b === bank ? "selected" : ""}>${b}</option>`).join("")}</select></label>` +
    field("Capacity", "su-capacity", find("BatteryCapacity_Ah").value, "Ah", "The nameplate capacity of the whole bank.") +
    (cells ? field("Cells in series", "su-cells", cells.value, "", "0 = worked out from the bank voltage; LiFePO4 4/8/16, lead-acid 6/12/24.") : ""));
  steps.push(`<h3>${steps.length + 1} · Alternator and belt</h3>` +
    field("Alternator rating", "su-rating", find("MaxTableValue").value, "A", "The most current the regulator ever asks for.") +
    field("Belt limit", "su-belt", Math.max(...find("rpmCapCurrentTable").value), "A", "The most the belt and the alternator take for long; caps every engine speed.") +
    field("Lowest engine speed to charge", "su-minrpm", find("MinRPMForField").value, "rpm", ""));
  steps.push(`<h3>${steps.length + 1} · Temperature limit</h3>` +
    field("Alternator temperature limit", "su-templimit", unit === "F" ? Math.round(tLimit) : Math.round(fToC(tLimit)), unit === "F" ? "°F" : "°C",
      "Current is reduced above it; charging stops well above it."));
  $("setup-steps").innerHTML = steps.join("");
}

function read(id, label, min, max) {
  const el = $(id);
  const v = parseDecimal(el.value);
  const bad = v === null || v < min || v > max;
  el.classList.toggle("bad", bad);
  if (bad) throw new Error(`${label}: enter a number from ${min} to ${max}`);
  return v;
}

// The set-up's values as one PATCH body.
function collect() {
  const body = {};
  if ($("su-profile")) body.BatteryProfile = Number($("su-profile").value);
  const bank = Number($("su-bank").value);
  const bulk = find("BulkVoltage").value;
  const was = bulk < 18 ? 12 : bulk <= 36 ? 24 : 48;
  if (!$("su-profile") && bank !== was) {
    // A different bank: its charge voltages, and the other absolute voltages scaled.
    Object.assign(body, BANK[bank]);
    for (const n of ["RebulkVoltage", "TargetVoltageSetpoint", "ChargedVoltage", "VoltageAlarmHigh", "VoltageAlarmLow"])
      if (find(n)) body[n] = Math.round((find(n).value * bank) / was * 100) / 100;
  }
  body.BatteryCapacity_Ah = read("su-capacity", "Capacity", 1, 100000);
  // BatteryCells 0 means "from the bank voltage" (its default): the catalogue's range, not 1..64.
  if ($("su-cells")) body.BatteryCells = Math.round(read("su-cells", "Cells", find("BatteryCells").min, find("BatteryCells").max));
  const rating = read("su-rating", "Alternator rating", 1, 1000);
  const belt = read("su-belt", "Belt limit", 1, 1000);
  body.MaxTableValue = rating;
  body.rpmCapCurrentTable = find("rpmCapCurrentTable").value.map((a) => Math.min(a, belt, rating));
  body.MinRPMForField = read("su-minrpm", "Lowest engine speed", 0, 10000);
  const t = read("su-templimit", "Temperature limit", tempUnit() === "F" ? 50 : 10, tempUnit() === "F" ? 400 : 204);
  body.TemperatureLimitF = Math.round((tempUnit() === "F" ? t : (t * 9) / 5 + 32) * 10) / 10;
  return body;
}

async function saveSetup(runCommand) {
  const msg = $("setup-msg");
  let body;
  try { body = collect(); } catch (e) { msg.textContent = e.message; msg.className = "msg bad"; return; }
  try {
    await write("PATCH", "/api/params", body);
  } catch (e) {
    const errs = (e.body && e.body.errors) || {};
    msg.textContent = `${e.message}${Object.keys(errs).length ? ": " + Object.entries(errs).map(([k, v]) => `${k} ${v}`).join("; ") : ""}`;
    msg.className = "msg bad";
    return;
  }
  $("first-run").hidden = true;
  msg.textContent = "Saved. Press “Start charging” when the engine runs.";
  msg.className = "msg ok";
  $("setup-start").hidden = false;
  $("setup-start").onclick = async () => { if (await runCommand("auto")) location.hash = "#live"; };
}

export async function loadSetup() {
  params = (await getJson("/api/params")).params;
  renderSteps();
  $("setup-start").hidden = true;
  $("setup-msg").textContent = "";
}

// ---------------------------------------------------------------- export / import
async function exportConfig() {
  const body = await getJson("/api/params");
  const text = exportToml(body.params, body.groups, new Date().toISOString().slice(0, 16).replace("T", " "));
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type: "application/toml" }));
  a.download = "xregulator-parameters.toml";
  document.body.appendChild(a);
  a.click();
  a.remove();
  window.xrDebug && (window.xrDebug.lastExport = text);
}

// Everything in the file is checked here and by the server; one PATCH, so
// either all of it applies or none.
async function importConfig(file) {
  const msg = $("param-msg");
  const body = await getJson("/api/params");
  const { values, errors, skipped } = parseParamsToml(await file.text(), body.params);
  if (errors.length) {
    msg.textContent = `Import refused, nothing changed: ${errors.slice(0, 5).join("; ")}${errors.length > 5 ? ` (+${errors.length - 5} more)` : ""}`;
    msg.className = "msg bad";
    return;
  }
  const changed = Object.fromEntries(Object.entries(values).filter(([n, v]) =>
    JSON.stringify(v) !== JSON.stringify(body.params.find((p) => p.name === n).value)));
  if (!Object.keys(changed).length) { msg.textContent = "Import: the file matches the current values."; msg.className = "msg ok"; return; }
  try {
    await write("PATCH", "/api/params", changed);
    await loadSettings();
    msg.textContent = `Imported ${Object.keys(changed).length} change(s)` + (skipped.length ? `; not imported (edit the file on the unit): ${skipped.join(", ")}` : "");
    msg.className = "msg ok";
  } catch (e) {
    const errs = (e.body && e.body.errors) || {};
    msg.textContent = `Import refused, nothing changed: ${e.message}${Object.keys(errs).length ? ": " + Object.entries(errs).map(([k, v]) => `${k} ${v}`).join("; ") : ""}`;
    msg.className = "msg bad";
  }
}

export function initSetup(runCommand) {
  $("setup-save").addEventListener("click", () => saveSetup(runCommand));
  window.addEventListener("hashchange", () => { if (location.hash === "#setup") loadSetup().catch((e) => toast(e.message, true)); });
  if (location.hash === "#setup") loadSetup().catch((e) => toast(e.message, true));
  $("config-export").addEventListener("click", () => exportConfig().catch((e) => toast(e.message, true)));
  $("config-import").addEventListener("change", (e) => {
    const f = e.target.files[0];
    if (f) importConfig(f).catch((err) => toast(err.message, true)).finally(() => { e.target.value = ""; });
  });
  // A fresh install (none of the set-up's values changed from the defaults) offers the set-up.
  getJson("/api/params").then((b) => {
    $("first-run").hidden = b.params.some((p) => SETUP_PARAMS.includes(p.name) && p.changed);
  }).catch(() => {});
}
