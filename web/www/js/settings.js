// Settings page: every catalogue parameter by group, with unit, range, help,
// changed-from-default marker, reset, and the server's validation messages.
import { getJson, write } from "./api.js";

let params = [];
const pending = new Map();  // name -> raw value(s) typed by the user

const $ = (id) => document.getElementById(id);

function fmt(v) {
  if (Array.isArray(v)) return "[" + v.join(", ") + "]";
  if (typeof v === "boolean") return v ? "on" : "off";
  return String(v);
}

// What the user typed, as JSON: a number when it parses, else the raw text so
// the server (the one authority on validity) can say what is wrong.
function parseTyped(text) {
  const t = String(text).trim();
  if (t !== "" && !isNaN(Number(t))) return Number(t);
  return t;
}

function valueOf(p, row) {
  if (p.kind === "Bool") return row.querySelector("input").checked;
  if (p.kind === "Table") return [...row.querySelectorAll("input")].map((i) => parseTyped(i.value));
  return parseTyped(row.querySelector("input").value);
}

function same(a, b) { return JSON.stringify(a) === JSON.stringify(b); }

function renderRow(p) {
  const row = document.createElement("div");
  row.className = "param";
  row.dataset.name = p.name;
  const name = document.createElement("div");
  name.className = "name";
  name.textContent = p.name;
  if (p.changed) {
    const m = document.createElement("span");
    m.className = "mark";
    m.title = "changed from default (" + fmt(p.default) + ")";
    m.textContent = "●";
    name.appendChild(m);
  }
  const edit = document.createElement("div");
  if (p.kind === "Bool") {
    const cb = document.createElement("input");
    cb.type = "checkbox";
    cb.checked = !!p.value;
    edit.appendChild(cb);
  } else if (p.kind === "Table") {
    edit.className = "table";
    p.value.forEach((v) => {
      const i = document.createElement("input");
      i.inputMode = "decimal";
      i.value = v;
      edit.appendChild(i);
    });
  } else {
    const i = document.createElement("input");
    i.className = "scalar";
    i.inputMode = "decimal";
    i.value = p.value;
    i.setAttribute("aria-label", p.name);
    edit.appendChild(i);
  }
  const reset = document.createElement("button");
  reset.textContent = "Reset";
  reset.title = "back to default " + fmt(p.default);
  reset.disabled = !p.changed;
  reset.addEventListener("click", () => {
    applyChanges({ [p.name]: p.default });
  });
  const meta = document.createElement("div");
  meta.className = "meta";
  const range = p.kind === "Bool" ? "" : `${p.min} … ${p.max} ${p.unit}`.trim();
  meta.textContent = [p.unit && p.kind !== "Bool" ? "unit " + p.unit : "", range ? "range " + range : "",
    "default " + fmt(p.default), p.overridden ? "file " + fmt(p.file) : "", p.help].filter(Boolean).join(" · ");
  const err = document.createElement("div");
  err.className = "err";
  row.append(name, edit, reset, meta, err);
  edit.addEventListener("input", () => onEdit(p, row));
  edit.addEventListener("change", () => onEdit(p, row));
  return row;
}

function onEdit(p, row) {
  const v = valueOf(p, row);
  if (same(v, p.value)) pending.delete(p.name); else pending.set(p.name, v);
  row.classList.toggle("dirty", pending.has(p.name));
  updateButtons();
}

function updateButtons() {
  $("param-apply").disabled = pending.size === 0;
  $("param-discard").disabled = pending.size === 0;
  $("param-apply").textContent = pending.size ? `Apply ${pending.size} change${pending.size > 1 ? "s" : ""}` : "Apply changes";
}

function render(groups) {
  const root = $("param-groups");
  root.textContent = "";
  const filter = $("param-filter").value.trim().toLowerCase();
  for (const g of groups) {
    const list = params.filter((p) => p.group === g &&
      (!filter || p.name.toLowerCase().includes(filter) || p.help.toLowerCase().includes(filter)));
    if (!list.length) continue;
    const d = document.createElement("details");
    d.className = "group";
    d.open = !!filter || groups.indexOf(g) === 0;
    const s = document.createElement("summary");
    const changed = list.filter((p) => p.changed).length;
    s.textContent = `${g} (${list.length}${changed ? `, ${changed} changed` : ""})`;
    d.appendChild(s);
    list.forEach((p) => d.appendChild(renderRow(p)));
    root.appendChild(d);
  }
}

let groups = [];
export async function loadSettings() {
  const body = await getJson("/api/params");
  params = body.params;
  groups = body.groups;
  pending.clear();
  render(groups);
  updateButtons();
}

function showErrors(errors) {
  document.querySelectorAll(".param").forEach((row) => {
    const e = errors[row.dataset.name];
    row.classList.toggle("bad", !!e);
    row.querySelector(".err").textContent = e || "";
    if (e) row.closest("details").open = true;
  });
}

async function applyChanges(only) {
  const msg = $("param-msg");
  const payload = only && !(only instanceof Event) ? only : Object.fromEntries(pending);
  try {
    await write("PATCH", "/api/params", payload);
    msg.textContent = `Applied: ${Object.keys(payload).join(", ")}`;
    msg.className = "msg ok";
    await loadSettings();
  } catch (e) {
    msg.textContent = e.message;
    msg.className = "msg bad";
    showErrors((e.body && e.body.errors) || {});
  }
}

export function initSettings() {
  $("param-apply").addEventListener("click", () => applyChanges());
  $("param-discard").addEventListener("click", () => { $("param-msg").textContent = ""; loadSettings(); });
  $("param-filter").addEventListener("input", () => render(groups));
}

// Sets one parameter (Tuning page toggles).
export async function setParam(name, value) {
  await write("PATCH", "/api/params", { [name]: value });
}
