// The event list (docs/dashboard.md, Events): one row per incident. A
// protection that trips leaves a dozen events behind it in the journal (the
// trip, the mode change, the cut, the field off, the buzzer rows, the
// cooldown, the clears, the field on again); the owner wants to read one
// line: what happened, what the regulator did, what to do. The events of an
// incident fold out under it.
import { getJson } from "./api.js";
import { clock, plain } from "./format.js";
import { REASONS, plainCommand, reasonInfo } from "./names.js";

const $ = (id) => document.getElementById(id);

// An event's words: the stored text (a command's event carries its argument)
// without "nan", GPIO numbers or reason codes.
export function eventText(e) {
  // The journal keeps the firmware's console words; the list says them plainly:
  // "GPIO4" is the field enable, reason codes get their titles.
  let text = String(e.text || e.code).replace(/\bnan\b/gi, "—")
    .replace(/\s*\(GPIO4 (HIGH|LOW)\)/g, "").replace(/\bGPIO4\b/g, "Field")
    .replace(/^Command ([a-z_]+)/, (m, c) => "Command " + plainCommand(c))
    .replace(/\b(?:REASON_)?([A-Z]{2,}(?:_[A-Z0-9]+)+)\b/g, (m, code) =>
      (REASONS["REASON_" + code] ? REASONS["REASON_" + code].title.toLowerCase() : m));
  if (e.reason && e.reason !== "NONE" && !text.toLowerCase().includes(reasonInfo(e.reason).title.toLowerCase()))
    text += ` (${reasonInfo(e.reason).title})`;
  return text;
}

// The filter by level: a row shows when its level is at least the chosen
// one, so "warning" hides the routine stage changes.
const LEVELS = ["debug", "info", "warning", "error", "critical"];
const rank = (level) => LEVELS.indexOf(String(level).toLowerCase());
export function levelShown(level, min = "debug") {
  const at = rank(level);
  return at < 0 || at >= Math.max(0, rank(min));
}

// ---------------------------------------------------------------- incidents
// What opens an incident, and what a protection's trip brings with it.
const OPENS = new Set(["ProtectionTrip", "VoltageDisagreement", "InaLatchSet", "TempSensorStale", "TempTaskHung"]);
const CONSEQUENCES = new Set(["ModeChanged", "ImmediateCut", "CutAfterSettle", "FieldOff", "FieldOn", "AlarmCondition",
  "AlarmOn", "AlarmOff", "LockoutStarted", "LockoutExpired", "ProtectionClear", "InaLatchCleared", ...OPENS]);
// A consequence further than this from the incident's last event is a new
// story: the longest cooldown (FieldLockoutSec) is minutes, not an hour.
const JOIN_S = 600;
// After the last trip cleared, the field coming back on and the buzzer going
// quiet still belong to the incident.
const SETTLE_S = 5;

const timeOf = (e) => (typeof e.wall_time_s === "number" && e.wall_time_s > 0 ? e.wall_time_s : e.t_s);

// events: oldest first. Returns the list's rows, oldest first: { event } for
// an event on its own, { incident } for an incident with its events.
export function groupIncidents(events) {
  const rows = [];
  let open = null;  // { events, tripped: Set, clearedAt }
  for (const e of events) {
    const t = timeOf(e);
    const last = open && timeOf(open.events[open.events.length - 1]);
    if (open && (t - last > JOIN_S || (open.clearedAt !== null && t - open.clearedAt > SETTLE_S))) open = null;
    if (open && CONSEQUENCES.has(e.code)) {
      open.events.push(e);
      if (e.code === "ProtectionTrip" && e.reason !== "NONE") open.tripped.add(e.reason);
      if (e.code === "ProtectionClear") open.tripped.delete(e.reason);
      if (OPENS.has(e.code)) open.clearedAt = null;
      else if (!open.tripped.size && open.clearedAt === null && e.code === "ProtectionClear") open.clearedAt = t;
      continue;
    }
    if (OPENS.has(e.code)) {
      open = { events: [e], tripped: new Set(e.reason && e.reason !== "NONE" ? [e.reason] : []), clearedAt: null };
      rows.push({ incident: open });
      continue;
    }
    rows.push({ event: e });
  }
  return rows.map((r) => (r.incident ? { incident: summarize(r.incident.events) } : r));
}

// The incident in words, from its events: the worst reason names it.
export function summarize(events) {
  const worst = events.reduce((w, e) => (rank(e.level) > rank(w.level) && e.reason !== "NONE" ? e : w), events[0]);
  const reason = worst.reason !== "NONE" ? worst.reason : events.find((e) => e.reason !== "NONE")?.reason || "NONE";
  const info = reasonInfo(reason);
  const has = (code) => events.some((e) => e.code === code);
  const did = [];
  if (has("ImmediateCut")) did.push("cut the field at once");
  else if (has("CutAfterSettle")) did.push("ramped the field down and cut it");
  else if (has("FieldOff")) did.push("switched the field off");
  if (has("LockoutStarted")) did.push("waited out a cooldown");
  if (has("AlarmOn")) did.push("sounded the alarm");
  const cleared = has("ProtectionClear") && events[events.length - 1].code !== "ProtectionTrip";
  const resumed = has("FieldOn") && events.findLastIndex((e) => e.code === "FieldOn") > events.findLastIndex((e) => e.code === "FieldOff");
  if (resumed) did.push("resumed charging");
  const level = events.reduce((l, e) => (rank(e.level) > rank(l) ? String(e.level).toLowerCase() : l), "debug");
  const start = timeOf(events[0]);
  const span = timeOf(events[events.length - 1]) - start;
  return {
    reason, level, title: info.title, meaning: info.meaning, action: info.action, events, start,
    wall: typeof events[0].wall_time_s === "number" && events[0].wall_time_s > 0,
    did: did.length ? `The regulator ${did.join(", ")}.` : "",
    over: cleared ? `Over after ${span < 60 ? `${plain(span, 0)} s` : `${plain(span / 60, 0)} min`}.` : "Still acting.",
  };
}

// ---------------------------------------------------------------- the list
const minLevel = () => ($("events-level") ? $("events-level").value : "debug");
export function applyEventFilter() {
  // A day header shows while a row under it does.
  let head = null, any = false;
  for (const tr of $("events-body").rows) {
    if (tr.classList.contains("day-head")) {
      if (head) head.hidden = !any;
      head = tr;
      any = false;
      continue;
    }
    tr.hidden = !levelShown(tr.dataset.level, minLevel());
    any = any || !tr.hidden;
  }
  if (head) head.hidden = !any;
}

function dayRow(text) {
  const tr = document.createElement("tr");
  tr.className = "day-head";
  const th = document.createElement("th");
  th.colSpan = 3;
  th.scope = "colgroup";
  th.textContent = text;
  tr.appendChild(th);
  return tr;
}

const when = (e) => (typeof e.wall_time_s === "number" && e.wall_time_s > 0 ? clock(e.wall_time_s) : `${plain(e.t_s, 0)} s after start`);
// In the list the day is its header's, so a row says only the time.
const hm = (e) => (typeof e.wall_time_s === "number" && e.wall_time_s > 0
  ? new Date(e.wall_time_s * 1000).toLocaleTimeString([], { hour: "2-digit", minute: "2-digit", hour12: false })
  : when(e));

// The day header of an event: "Today · Sun 6 Dec", "Yesterday · Sat 5 Dec",
// "Thu 3 Dec 2026"; events stored without a clock go under one header.
export function dayHeader(wallS, nowS = Date.now() / 1000) {
  if (typeof wallS !== "number" || !(wallS > 0)) return "Time since the regulator started";
  const d = new Date(wallS * 1000);
  const now = new Date(nowS * 1000);
  const day = d.toLocaleDateString([], { weekday: "short", day: "numeric", month: "short" });
  const daysAgo = Math.round((new Date(now.toDateString()) - new Date(d.toDateString())) / 86400000);
  if (daysAgo === 0) return `Today · ${day}`;
  if (daysAgo === 1) return `Yesterday · ${day}`;
  return d.getFullYear() === now.getFullYear() ? day : `${day} ${d.getFullYear()}`;
}

function rowFor(level, time, fill) {
  const tr = document.createElement("tr");
  tr.className = "level-" + level;
  tr.dataset.level = level;
  tr.hidden = !levelShown(level, minLevel());
  tr.insertCell().textContent = time;
  tr.insertCell().textContent = level;
  fill(tr.insertCell());
  return tr;
}

function eventRow(e) {
  return rowFor(String(e.level).toLowerCase(), hm(e), (td) => { td.textContent = eventText(e); });
}

function incidentRow(inc) {
  return rowFor(inc.level, hm(inc.events[0]), (td) => {
    td.className = "incident";
    const head = document.createElement("p");
    const b = document.createElement("b");
    b.textContent = inc.title;
    head.append(b, ` ${[inc.meaning, inc.did, inc.over].filter(Boolean).join(" ")}`);
    const todo = document.createElement("p");
    todo.className = "action";
    todo.textContent = inc.action ? "What to do: " + inc.action : "";
    const more = document.createElement("details");
    const sum = document.createElement("summary");
    sum.textContent = `${inc.events.length} events`;
    const list = document.createElement("ul");
    for (const e of inc.events) {
      const li = document.createElement("li");
      li.textContent = `${when(e)} ${eventText(e)}`;
      list.appendChild(li);
    }
    more.append(sum, list);
    td.append(head, todo, more);
  });
}

// Stored events (earlier runs too), paged with "Older"; each load regroups
// everything loaded, so an incident split by a page boundary joins up.
const loaded = new Map();  // id -> event
let oldestEvent = null;
function render() {
  const asc = [...loaded.values()].sort((a, b) => a.id - b.id);
  const tb = $("events-body");
  tb.textContent = "";
  let day = null;
  for (const r of groupIncidents(asc).reverse()) {
    const first = r.incident ? r.incident.events[0] : r.event;
    const head = dayHeader(first.wall_time_s);
    if (head !== day) { tb.appendChild(dayRow(head)); day = head; }
    tb.appendChild(r.incident ? incidentRow(r.incident) : eventRow(r.event));
  }
  applyEventFilter();
}

export async function loadEvents(mode = "first") {
  if (mode === "refresh" && loaded.size) {
    const body = await getJson("/api/events?limit=100");
    const fresh = body.events.filter((e) => !loaded.has(e.id));
    if (!fresh.length) return;
    for (const e of fresh) loaded.set(e.id, e);
    render();
    return;
  }
  const q = mode === "more" && oldestEvent !== null ? `&before=${oldestEvent}` : "";
  const body = await getJson(`/api/events?limit=50${q}`);
  if (mode !== "more") loaded.clear();
  for (const e of body.events) { loaded.set(e.id, e); oldestEvent = e.id; }
  render();
  $("events-more").disabled = body.events.length < 50;
}
