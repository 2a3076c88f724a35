// Settings page: basic settings first, the rest behind "advanced"; switches
// for booleans, a row of boxes for the RPM tables, choices as choices, where
// each value comes from, and the server's messages next to each field.
import { getJson, write } from "./api.js";
import { clock, parseDecimal } from "./format.js";
import { confirmUnsafe, renderGuardBanner } from "./guards.js";
import { tempUnit } from "./live.js";
import { REASONS } from "./names.js";
import { plainUnits, shown, unitView } from "./settings_units.js";

let params = [];
let groups = [];
const pending = new Map();  // name -> value to send
const invalid = new Map();  // name -> why the typed text cannot be sent

const $ = (id) => document.getElementById(id);

// What a boat owner sets; everything else is advanced (loop gains, filters).
export const BASIC = ["BatteryProfile", "BatteryCells", "BatteryCapacity_Ah", "BulkVoltage", "AbsorptionVoltage",
  "FloatVoltage", "UseFloat", "RebulkVoltage", "TailCurrent_A", "MaxTableValue", "MaximumAllowedBatteryAmps",
  "MinRPMForField", "TemperatureLimitF", "TempSource", "BatteryCurrentSource", "VoltageAlarmHigh", "VoltageAlarmLow",
  "OnOff", "weatherModeEnabled", "rpmCapCurrentTable", "rpmTableRPMPoints"];

// Plain words first; the parameter's own name (the specification's, which the file,
// the docs and the journal use) under it. A name without a label shows as is.
export const LABELS = {
  BatteryProfile: "Battery type", BatteryCells: "Cells in series", BatteryCapacity_Ah: "Battery capacity",
  BulkVoltage: "Bulk charge voltage", AbsorptionVoltage: "Absorption voltage", FloatVoltage: "Float voltage",
  UseFloat: "Float after absorption", RebulkVoltage: "Start a new charge below", TailCurrent_A: "Charge is done below",
  MaxTableValue: "Alternator rating", MaximumAllowedBatteryAmps: "Battery charge current limit",
  MinRPMForField: "Lowest engine speed to charge", TemperatureLimitF: "Alternator temperature limit",
  TempSource: "Alternator temperature sensor", BatteryCurrentSource: "Battery current measured by",
  VoltageAlarmHigh: "High battery voltage alarm", VoltageAlarmLow: "Low battery voltage alarm",
  OnOff: "Charging allowed", weatherModeEnabled: "Weather mode (solar first)",
  rpmCapCurrentTable: "Alternator current limit by engine speed", rpmTableRPMPoints: "Engine speeds of the tables",
  CurrentAlarmHigh: "High alternator current alarm", IgnoreTemperature: "Ignore the alternator temperature",
  IgnoreRPM: "Ignore the engine speed", ChargeMinTempC: "No charging below (battery temperature)",
  ChargeMaxTempC: "No charging above (battery temperature)", TempAlarm: "Alternator temperature alarm",
  AlarmActivate: "Alarm buzzer",
};

// The catalogue's groups in an owner's words.
export const GROUP_TITLES = {
  Voltage: "Charge voltages and the voltage loop", Overvoltage: "Fast over-voltage protection",
  SensorHealth: "Sensor checks", Shutdown: "How the field is switched off", Current: "Alternator current and belt",
  Tuning: "Current loop (tuning)", Charging: "Charge stages", Battery: "Battery", Temperature: "Temperatures",
  Alarms: "Alarms", Modes: "Modes: weather, tuning", Can: "BMS and NMEA 2000 (CAN bus)",
  RpmTables: "Engine-speed tables",
};

const kindOf = (p) => String(p.kind).toLowerCase();  // the API says "bool"/"table"/"int"/"float"
export const labelOf = (p) => LABELS[p.name] || p.name;
// "Default" is what the regulator would use with nothing written: the battery
// profile's value where the profile sets it (the server's effective_default),
// else the firmware's.
export const defaultOf = (p) => (p.effective_default !== undefined ? p.effective_default : p.default);

// "0 = DS18B20 (1-Wire), 1 = thermistor (ADS1115 CH3)." -> [[0, "DS18B20 (1-Wire)"], [1, ...]]
export function choicesOf(p) {
  if (Array.isArray(p.choices) && p.choices.length) return p.choices.map((name, i) => [i, String(name)]);  // named choices
  if (kindOf(p) !== "int" || !p.help) return null;
  const out = [];
  for (const m of String(p.help).matchAll(/(\d+)\s*=\s*([^,;:]+?)(?=,\s*\d+\s*=|[.;]|$)/g)) out.push([Number(m[1]), m[2].trim()]);
  return out.length >= 2 ? out : null;
}

// Where the value comes from: the API's `source` when it sends one
// (profiles), else from the flags: a dashboard change, the file, the default.
export function sourceOf(p) {
  if (p.source) return String(p.source);
  if (p.overridden) return "dashboard";
  if (p.changed) return "file";
  return "default";
}

// Help texts cite the firmware's specification ("No default in the specification: ...",
// "Added here: ...") and its variable names (cv_I, REASON_*): the owner needs only
// the sentence itself, in words (docs/parameters.md keeps the engineer's text).
export const plainHelp = (h) => String(h || "").replace(/(No default in the specification|Not in the specification)[:.]?\s*/gi, "")
  .replace(/\b(Added|Changed) here:\s*/g, "").replace(/\s*\([^)]*\b(specification|original firmware)\b[^)]*\)/gi, "")
  .replace(/,\s*as the original firmware\b/gi, "")
  .replace(/\bCV seed\b/g, "voltage-loop restart").replace(/\bcv_I_aw_cap\b/g, "the voltage loop's integral cap")
  .replace(/\bcv_I\b/g, "the voltage loop's integral")
  .replace(/\bREASON_[A-Z0-9_]+\b/g, (c) => (REASONS[c] ? `“${REASONS[c].title}”` : c)).trim();

const choiceLabel = (choices, v) => (choices.find(([c]) => c === v) || [v, String(v)])[1];

function fmt(v) {
  if (Array.isArray(v)) return "[" + v.join(", ") + "]";
  if (typeof v === "boolean") return v ? "on" : "off";
  return String(v);
}

// The value to send, or an error text: never an empty box as 0, commas as
// decimal points.
function valueOf(p, row) {
  const kind = kindOf(p);
  if (kind === "bool") return { value: row.querySelector("input").checked };
  if (choicesOf(p)) return { value: Number(row.querySelector("select").value) };
  const boxes = [...row.querySelectorAll("input")];
  const nums = boxes.map((i) => parseDecimal(i.value));
  const bad = nums.findIndex((n) => n === null);
  if (bad >= 0) return { error: boxes[bad].value.trim() === "" ? "enter a value" : `"${boxes[bad].value}" is not a number` };
  return { value: kind === "table" ? nums : unitView(p, tempUnit()).back(nums[0]) };
}

const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);

// The value's control: a switch, a choice, a row of boxes for a table, or
// a box in the display unit.
function editorFor(p, kind, choices, view) {
  const edit = document.createElement("div");
  edit.className = "edit";
  if (kind === "bool") {
    const sw = document.createElement("label");
    sw.className = "switch";
    const cb = document.createElement("input");
    cb.type = "checkbox";
    cb.checked = !!p.value;
    cb.setAttribute("aria-label", p.name);
    const txt = document.createElement("span");
    txt.textContent = cb.checked ? "on" : "off";
    cb.addEventListener("change", () => { txt.textContent = cb.checked ? "on" : "off"; });
    sw.append(cb, txt);
    edit.appendChild(sw);
  } else if (choices) {
    const sel = document.createElement("select");
    sel.setAttribute("aria-label", p.name);
    const list = choices.some(([v]) => v === p.value) ? choices : [...choices, [p.value, `value ${p.value}`]];
    for (const [v, label] of list) sel.add(new Option(`${label}`, String(v), false, v === p.value));
    edit.appendChild(sel);
  } else if (kind === "table") {
    edit.classList.add("table");
    p.value.forEach((v, i) => {
      const inp = document.createElement("input");
      inp.inputMode = "decimal";
      inp.value = v;
      inp.setAttribute("aria-label", `${p.name} ${i + 1}`);
      edit.appendChild(inp);
    });
  } else {
    const inp = document.createElement("input");
    inp.className = "scalar";
    inp.inputMode = "decimal";
    inp.value = view.show(p.value);
    inp.setAttribute("aria-label", p.name);
    edit.appendChild(inp);
    if (view.unit) { const u = document.createElement("span"); u.className = "unit"; u.textContent = view.unit; edit.appendChild(u); }
  }
  return edit;
}

function renderRow(p) {
  const kind = kindOf(p);
  const row = document.createElement("div");
  row.className = "param";
  row.dataset.name = p.name;
  row.dataset.kind = kind;
  const name = document.createElement("label");
  name.className = "name";
  name.textContent = labelOf(p);
  if (LABELS[p.name]) {
    const code = document.createElement("small");
    code.className = "pname";
    code.textContent = p.name;
    name.append(" ", code);
  }
  const choices = choicesOf(p);
  const view = unitView(p, tempUnit());
  const edit = editorFor(p, kind, choices, view);
  const reset = document.createElement("button");
  reset.textContent = "Default";
  reset.title = "back to the default " + fmt(shown(view, defaultOf(p)));
  reset.disabled = same(p.value, defaultOf(p));
  reset.addEventListener("click", () => applyChanges({ [p.name]: defaultOf(p) }));
  const controls = [reset];
  if (sourceOf(p) === "dashboard") {
    // Forget the dashboard's value: the file's (or the profile's) applies again.
    const back = document.createElement("button");
    back.textContent = "Use the file's";
    back.title = "forget this dashboard value; the file has " + fmt(p.file);
    back.addEventListener("click", () => applyChanges({ [p.name]: null }));
    controls.push(back);
  }
  const meta = document.createElement("div");
  meta.className = "meta";
  const range = kind === "bool" || choices ? "" : `${shown(view, p.min)} … ${shown(view, p.max)} ${view.unit}`.trim();
  const src = sourceOf(p);
  const from = document.createElement("span");
  from.className = "source source-" + src.replace(/ /g, "-");
  // "not set up": lowered to the limits safe for every battery until the set-up chose one.
  from.textContent = src === "not set up" ? "lowered until set up" : `from ${src}`;
  const def = kind === "table" || kind === "bool" || choices ? fmt(defaultOf(p)) : shown(view, defaultOf(p));
  meta.append(from, " · " + [range ? "range " + range : "", "default " + (choices ? choiceLabel(choices, defaultOf(p)) : def),
    src === "dashboard" ? "file has " + (kind === "table" || kind === "bool" || choices ? fmt(p.file) : shown(view, p.file)) : "",
    plainUnits(plainHelp(p.help))].filter(Boolean).join(" · "));
  const err = document.createElement("div");
  err.className = "err";
  err.setAttribute("role", "alert");
  const actions = document.createElement("div");
  actions.className = "actions";
  actions.append(...controls);
  row.append(name, edit, actions, meta, err);
  edit.addEventListener("input", () => onEdit(p, row));
  edit.addEventListener("change", () => onEdit(p, row));
  return row;
}

function onEdit(p, row) {
  const r = valueOf(p, row);
  invalid.delete(p.name);
  pending.delete(p.name);
  if (r.error) invalid.set(p.name, r.error);
  else if (!same(r.value, p.value)) pending.set(p.name, r.value);
  row.classList.toggle("dirty", pending.has(p.name) || invalid.has(p.name));
  row.classList.toggle("bad", invalid.has(p.name));
  row.querySelector(".err").textContent = invalid.get(p.name) || "";
  updateButtons();
}

function updateButtons() {
  const n = pending.size + invalid.size;
  $("param-apply").disabled = n === 0;
  $("param-discard").disabled = n === 0;
  $("param-apply").textContent = n ? `Apply ${n} change${n > 1 ? "s" : ""}` : "Apply changes";
}

function render() {
  const root = $("param-groups");
  root.textContent = "";
  const filter = $("param-filter").value.trim().toLowerCase();
  const advanced = $("param-advanced").checked;
  // Search finds the plain label, the parameter's own name and its help.
  const match = (p) => !filter || [p.name, labelOf(p), plainHelp(p.help)].some((t) => String(t).toLowerCase().includes(filter));
  root.classList.toggle("show-names", advanced);
  const basic = params.filter((p) => BASIC.includes(p.name) && match(p));
  const sections = [["Basic settings", basic, true]];
  if (advanced || filter)
    for (const g of groups) sections.push([GROUP_TITLES[g] || g, params.filter((p) => p.group === g && !BASIC.includes(p.name) && match(p)), !!filter]);
  for (const [title, list, open] of sections) {
    if (!list.length) continue;
    const d = document.createElement("details");
    d.className = "group";
    d.open = open;
    const s = document.createElement("summary");
    const changed = list.filter((p) => p.changed).length;
    s.textContent = `${title} (${list.length}${changed ? `, ${changed} changed` : ""})`;
    d.appendChild(s);
    list.forEach((p) => d.appendChild(renderRow(p)));
    root.appendChild(d);
  }
}

// Dashboard changes are kept in the regulator's state database and win over
// xregulator.toml; the file is never rewritten (docs/dashboard.md "Dashboard
// changes and the file"). The page says so in one line, with the choice:
// keep them (the line goes until they change) or drop them (the file's
// values apply again). Which ones is folded under it, in plain labels.
const KEPT_KEY = "xregulator.keptDashboardValues";
const dashboardValues = (list) => list.filter((p) => sourceOf(p) === "dashboard");
export function fileNotice(list) {
  const n = dashboardValues(list).length;
  if (!n) return "";
  return `${n} value${n > 1 ? "s" : ""} set on the dashboard differ${n > 1 ? "" : "s"} from the file.`;
}
export function noticeItems(list, unit = "C") {
  return dashboardValues(list).map((p) => {
    const view = unitView(p, unit);
    const v = (x) => (Array.isArray(x) || typeof x === "boolean" ? fmt(x) : `${shown(view, x)} ${view.unit}`.trim());
    return `${labelOf(p)}: ${v(p.value)} here, ${v(p.file)} in the file`;
  });
}
const noticeKey = (list) => JSON.stringify(dashboardValues(list).map((p) => [p.name, p.value]));
function renderNotice() {
  const text = fileNotice(params);
  $("param-file-note").hidden = !text || localStorage.getItem(KEPT_KEY) === noticeKey(params);
  $("param-file-text").textContent = text;
  $("param-file-list").replaceChildren(...noticeItems(params, tempUnit()).map((t) => {
    const li = document.createElement("li");
    li.textContent = t;
    return li;
  }));
}

// The last list read is kept on this device: offline, the page shows it,
// read-only (every control is disabled while offline), never a blank page.
const CACHE_KEY = "xregulator.params";
async function readParams() {
  try {
    const body = await getJson("/api/params");
    try { localStorage.setItem(CACHE_KEY, JSON.stringify({ at: Date.now() / 1000, body })); } catch { /* full: not kept */ }
    $("param-offline").hidden = true;
    return body;
  } catch (e) {
    let kept = null;
    try { kept = JSON.parse(localStorage.getItem(CACHE_KEY) || "null"); } catch { kept = null; }
    if (!kept || !kept.body || !Array.isArray(kept.body.params)) throw e;
    $("param-offline").textContent = `The regulator cannot be reached: these are the settings read at ${clock(kept.at)}. ` +
      "Nothing can be changed until it is back.";
    $("param-offline").hidden = false;
    return kept.body;
  }
}

export async function loadSettings() {
  const body = await readParams();
  params = body.params;
  groups = body.groups;
  renderGuardBanner(params);
  pending.clear();
  invalid.clear();
  renderNotice();
  render();
  updateButtons();
}
export const currentParams = () => params;

// The server keys cross-field errors by bare parameter name; an error for a
// parameter that is not on screen (advanced, filtered) still shows in the
// message line, and its row is shown.
function showErrors(errors) {
  const missing = Object.keys(errors).filter((n) => !document.querySelector(`.param[data-name="${n}"]`));
  if (missing.length && !$("param-advanced").checked && missing.some((n) => params.find((p) => p.name === n))) {
    $("param-advanced").checked = true;
    render();
  }
  document.querySelectorAll(".param").forEach((row) => {
    const e = errors[row.dataset.name];
    row.classList.toggle("bad", !!e);
    row.querySelector(".err").textContent = e || "";
    if (e) row.closest("details").open = true;
  });
}

async function applyChanges(only) {
  const msg = $("param-msg");
  if (!only && invalid.size) {
    showErrors(Object.fromEntries(invalid));
    msg.textContent = "Fix the marked fields first; nothing was sent.";
    msg.className = "msg bad";
    return;
  }
  const payload = only || Object.fromEntries(pending);
  if (!(await confirmUnsafe(payload))) {
    msg.textContent = "Nothing was sent.";
    msg.className = "msg";
    return;
  }
  try {
    await write("PATCH", "/api/params", payload);
    msg.textContent = `Applied: ${Object.keys(payload).join(", ")}`;
    msg.className = "msg ok";
    await loadSettings();
  } catch (e) {
    const errors = (e.body && e.body.errors) || {};
    msg.textContent = e.message + (Object.keys(errors).length ? ": " + Object.entries(errors).map(([k, v]) => `${k} ${v}`).join("; ") : "");
    msg.className = "msg bad";
    showErrors(errors);
  }
}

export function initSettings() {
  $("param-apply").addEventListener("click", () => applyChanges());
  $("param-discard").addEventListener("click", () => { $("param-msg").textContent = ""; loadSettings(); });
  $("param-filter").addEventListener("input", render);
  $("param-advanced").addEventListener("change", render);
  $("param-keep").addEventListener("click", () => { localStorage.setItem(KEPT_KEY, noticeKey(params)); renderNotice(); });
  $("param-drop").addEventListener("click", () =>
    applyChanges(Object.fromEntries(dashboardValues(params).map((p) => [p.name, null]))));
}

// Sets one parameter (Tuning page toggles, set-up steps).
// Refused (an Error) when it would switch a protection off and the owner
// does not confirm.
export async function setParam(name, value) {
  if (!(await confirmUnsafe({ [name]: value }))) throw new Error("cancelled: nothing was sent");
  await write("PATCH", "/api/params", { [name]: value });
}
