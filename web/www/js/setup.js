// First-run set-up (battery, alternator and belt, temperature, then "start
// charging") and the configuration's export / import as TOML. Every step
// is sent as ONE change: the server checks it all or applies nothing. The
// page knows no rule of the catalogue or the battery profiles: the bank
// voltage goes to the daemon as the set-up's bank choice (?bank=), and the
// voltages a chemistry and bank give are the daemon's answer to a dry run
// (PATCH /api/params?dry_run=1, docs/dashboard.md "Set-up").
import { getJson, quietAsk, toast, write } from "./api.js";
import { fToC, html, parseDecimal, setHtml } from "./format.js";
import { latestStatus, limitText, renderSetupState, tempUnit } from "./live.js";
import { choicesOf, loadSettings } from "./settings.js";
import { collectHardware, hardwareRows, renderHardwareStep, restartNeeded, rpmHint } from "./setup_hardware.js";
import { exportToml, parseParamsToml } from "./toml.js";

const $ = (id) => document.getElementById(id);
let params = [];
let hardware = null;  // GET /api/setup/hardware
let rpmNow = null;  // the engine speed read when the page opened
let bankNow = 12;  // the bank the settings in force are for (GET's bank_v)
const find = (n) => params.find((p) => p.name === n);
// The set-up's fields by the parameter each sets, so the daemon's refusal
// marks the field it is about.
const FIELD_OF = { BatteryCapacity_Ah: ["su-capacity", "Capacity"], MaxTableValue: ["su-rating", "Alternator rating"],
  rpmCapCurrentTable: ["su-belt", "Belt limit"], MinRPMForField: ["su-minrpm", "Lowest engine speed"],
  TemperatureLimitF: ["su-templimit", "Temperature limit"] };

function field(label, id, value, unit, help) {
  return html`<label class="field"><span>${label}</span><span class="row"><input id="${id}" inputmode="decimal" value="${value}">
    <span class="unit">${unit}</span></span>${help ? html`<small>${help}</small>` : ""}</label>`;
}

// Builds the steps from what the daemon offers (the profile step only when
// the BatteryProfile parameter exists). Every value is escaped (html``).
function renderSteps() {
  const unit = tempUnit();
  const tLimit = find("TemperatureLimitF").value;
  const profile = find("BatteryProfile");
  const steps = [];
  if (profile) {
    const opts = (choicesOf(profile) || []).map(([v, l]) => html`<option value="${v}" ${v === profile.value ? "selected" : ""}>${l}</option>`);
    steps.push(html`<h3>1 · Battery type</h3><label class="field"><span>Battery profile</span><select id="su-profile">${opts}</select>
      <small>Sets the charge voltages, currents and temperature limits for the chemistry and the bank voltage; custom keeps the values in Settings.</small></label>`);
  }
  const banks = [12, 24, 48].map((b) => html`<option ${b === bankNow ? "selected" : ""}>${b}</option>`);
  steps.push(html`<h3>${steps.length + 1} · Battery bank</h3>
    <label class="field"><span>Bank voltage</span><select id="su-bank">${banks}</select></label>
    <p class="msg" id="su-charge" aria-live="polite"></p>
    ${field("Capacity", "su-capacity", find("BatteryCapacity_Ah").value, "Ah", "The nameplate capacity of the whole bank.")}`);
  const table = find("rpmCapCurrentTable").value;
  const cap = Math.max(...table);
  steps.push(html`<h3>${steps.length + 1} · Alternator and belt</h3>
    ${field("Alternator rating", "su-rating", find("MaxTableValue").value, "A", "The rated output on its label: the most current the regulator ever asks for.")}
    ${field("Belt limit", "su-belt", cap, "A", "The most the belt takes for long (a single V-belt about 80 A, a serpentine belt about 150 A); caps every engine speed.")}
    <label class="field"><span>Small alternator</span><span class="row"><input type="checkbox" id="su-small" ${table[1] < cap ? "checked" : ""}>
    <span>less current at idle</span></span><small>Half the limit at the lowest engine speeds, where a small alternator runs hot.</small></label>
    ${field("Lowest engine speed to charge", "su-minrpm", find("MinRPMForField").value, "rpm", "")}`);
  steps.push(html`<h3>${steps.length + 1} · Temperature limit</h3>
    ${field("Alternator temperature limit", "su-templimit", unit === "F" ? Math.round(tLimit) : Math.round(fToC(tLimit)), unit === "F" ? "°F" : "°C",
      "Current is reduced above it; charging stops well above it.")}`);
  if (hardware) steps.push(renderHardwareStep(hardware, steps.length + 1, rpmNow));
  setHtml($("setup-steps"), html`${steps}`);
  for (const id of ["su-profile", "su-bank"]) if ($(id)) $(id).addEventListener("change", () => showCharge());
  showCharge();
  const pulley = $("su-pulley");
  if (pulley) pulley.addEventListener("input", () => { $("su-pulley-hint").textContent = rpmHint(hardware, rpmNow, pulley.value); });
}

// A number as typed (ranges are the daemon's to check, with the
// catalogue's; the hardware step passes its own, which are not parameters).
function read(id, label, min = -Infinity, max = Infinity) {
  const el = $(id);
  const v = parseDecimal(el.value);
  const bad = v === null || v < min || v > max;
  el.classList.toggle("bad", bad);
  if (bad) throw new Error(Number.isFinite(min) ? `${label}: enter a number from ${min} to ${max}` : `${label}: enter a number`);
  return v;
}

// The battery's part: the profile and the capacity; the bank voltage goes
// as the query (?bank=), which the daemon turns into the chemistry's cells
// (its values again where the dashboard had set them), or a custom set's
// voltages moved to that bank.
function collectBattery(body) {
  const sel = $("su-profile");
  if (sel) body.BatteryProfile = Number(sel.value);
  body.BatteryCapacity_Ah = read("su-capacity", "Capacity");
}
const paramsPath = (dryRun) => `/api/params?bank=${Number($("su-bank").value)}${dryRun ? "&dry_run=1" : ""}`;

// What the chosen chemistry and bank charge at, as the daemon answers a dry
// run (nothing saved); its refusal when the choice does not fit the bank it
// measures. Only the answer to the latest choice is shown.
let chargeAsked = 0;
async function showCharge() {
  const out = $("su-charge");
  if (!out) return;
  const body = {};
  if ($("su-profile")) body.BatteryProfile = Number($("su-profile").value);
  const n = ++chargeAsked;
  const r = await quietAsk("PATCH", paramsPath(true), body).catch(() => null);
  if (n !== chargeAsked) return;
  if (!r || !r.values) { out.textContent = ""; return; }
  const v = r.values;
  out.textContent = `Charges at: bulk ${v.BulkVoltage} V, absorption ${v.AbsorptionVoltage} V, ` +
    (v.UseFloat ? `float ${v.FloatVoltage} V` : "no float (rests after absorption)") +
    (r.ok ? "" : ` — ${Object.values(r.errors).join("; ")}`);
  out.className = r.ok ? "msg" : "msg bad";
}

// The alternator's part: the rating is MaxTableValue; the cap table is the
// belt limit (never above the rating) at every running speed, half and
// three quarters of it at the two lowest for a small alternator; the low
// charge-rate table keeps its quarter. The current alarm is the daemon's to
// check (alarmFollowsCap).
function collectAlternator(body) {
  const rating = read("su-rating", "Alternator rating");
  const cap = Math.min(read("su-belt", "Belt limit"), rating);
  const small = $("su-small").checked;
  const table = find("rpmCapCurrentTable").value.map((_, i) =>
    i === 0 ? 0 : Math.round(cap * (small && i === 1 ? 0.5 : small && i === 2 ? 0.75 : 1) * 10) / 10);
  body.MaxTableValue = rating;
  body.rpmCapCurrentTable = table;
  body.rpmCapCurrentTableLo = table.map((a) => Math.round(a * 2.5) / 10);
  body.MinRPMForField = read("su-minrpm", "Lowest engine speed");
}

// The set-up's values as one PATCH body.
function collect() {
  const body = {};
  collectBattery(body);
  collectAlternator(body);
  const t = read("su-templimit", "Temperature limit");
  body.TemperatureLimitF = Math.round((tempUnit() === "F" ? t : (t * 9) / 5 + 32) * 10) / 10;
  return body;
}

// What the regulator itself says holds the charge back now, and its BMS
// state (owner.limits and owner.bms of each status frame, docs/dashboard.md
// "Owner model"): the same words as Live and Protections, kept current.
export function renderSetupOwner(s) {
  const t = document.getElementById("setup-now");
  const o = s && s.owner;
  if (!t || !o) return;
  const rows = [["Holding back now", o.limits.length ? o.limits.map(limitText).join("; ") : "nothing"],
    ["BMS now", o.bms.words]];
  t.textContent = "";
  for (const [k, x] of rows) {
    const tr = t.insertRow();
    const th = document.createElement("th");
    th.textContent = k;
    tr.appendChild(th);
    tr.insertCell().textContent = x;
  }
}

// What now runs, read back from the daemon, and what the file still pins
// over the profile (only the file can release those).
function renderResult() {
  const v = (n) => find(n) && find(n).value;
  const rows = [["Bulk", `${v("BulkVoltage")} V`], ["Absorption", `${v("AbsorptionVoltage")} V`],
    ["Float", v("UseFloat") ? `${v("FloatVoltage")} V` : "off (rests after absorption)"],
    ["Battery current limit", `${v("MaximumAllowedBatteryAmps")} A`],
    ["Alternator limit", `${Math.max(...v("rpmCapCurrentTable"))} A`], ...(hardware ? hardwareRows(hardware) : [])];
  const pinned = params.filter((p) => p.profile_owned && p.source === "file").map((p) => p.name);
  setHtml($("setup-result"), html`<h3>Now in effect</h3><table class="kv">${rows.map(([k, x]) => html`<tr><th>${k}</th><td>${x}</td></tr>`)}</table>
    <table class="kv" id="setup-now"></table>
    ${pinned.length ? html`<p class="msg warn">Still set by the configuration file, not by the profile: ${pinned.join(", ")}. Comment them out in xregulator.toml to let the profile decide.</p>` : ""}`);
  $("setup-result").hidden = false;
  renderSetupOwner(latestStatus());
}

// The daemon's refusal in the set-up's words: each error under the label of
// the field it is about (marked), else under the parameter's name.
function showRefusal(msg, e) {
  const errs = (e.body && e.body.errors) || {};
  for (const [, [id]] of Object.entries(FIELD_OF)) if ($(id)) $(id).classList.remove("bad");
  const words = Object.entries(errs).map(([k, v]) => {
    const f = FIELD_OF[k];
    if (f && $(f[0])) $(f[0]).classList.add("bad");
    return `${f ? f[1] : k}: ${v}`;
  });
  msg.textContent = `${e.message}${words.length ? ": " + words.join("; ") : ""}`;
  msg.className = "msg bad";
}

// A current alarm the owner set below the new belt limit would sound in
// every charge: when the daemon's dry run refuses it, it follows the limit
// (0) instead, and the page says so.
async function alarmFollowsCap(body) {
  if (!(find("CurrentAlarmHigh")?.value > 0)) return "";
  const r = await write("PATCH", paramsPath(true), body);
  if (!r.errors || !("CurrentAlarmHigh" in r.errors)) return "";
  body.CurrentAlarmHigh = 0;
  return " The alternator current alarm now follows the new limit.";
}

async function saveSetup(runCommand) {
  const msg = $("setup-msg");
  let body, hwBody, note;
  try {
    body = collect();
    hwBody = hardware ? collectHardware(hardware, read) : {};
  } catch (e) { msg.textContent = e.message; msg.className = "msg bad"; return; }
  try {
    note = await alarmFollowsCap(body);
    await write("PATCH", paramsPath(false), body);
    if (Object.keys(hwBody).length) hardware = await write("PUT", "/api/setup/hardware", hwBody);
  } catch (e) { showRefusal(msg, e); return; }
  const after = await getJson("/api/params");
  params = after.params;
  bankNow = after.bank_v;
  renderResult();
  renderSetupState(after);
  msg.textContent = "Saved. Press “Start charging” when the engine runs." + note +
    (hardware && restartNeeded(hardware) ? " The probe and BMS choices are used from the regulator’s next start (switch it off and on)." : "");
  msg.className = "msg ok";
  $("setup-start").hidden = false;
  $("setup-start").onclick = async () => { if (await runCommand("auto")) location.hash = "#live"; };
}

export async function loadSetup() {
  const body = await getJson("/api/params");
  params = body.params;
  bankNow = body.bank_v;
  hardware = await getJson("/api/setup/hardware").catch(() => null);
  rpmNow = (await getJson("/api/status").catch(() => ({}))).rpm ?? null;
  renderSteps();
  $("setup-result").hidden = true;
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
}
