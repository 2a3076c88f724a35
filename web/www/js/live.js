// The Live page and the header: a headline in words, cards, one banner per
// active protection (texts from names.js), the mode on every page, and an
// offline state nobody can take for live.
import { ago, hmin, isNum, num, temp } from "./format.js";
import { activeProblems, ownerMode, plainStage, reasonInfo } from "./names.js";
import { command, toast } from "./api.js";

const $ = (id) => document.getElementById(id);
const STALE_AFTER_S = 3;  // no frame for this long = not live (frames come at 2..20 Hz)

let lastFrameAt = 0;      // Date.now() of the last frame
let lastStatus = null;

// °C unless the owner chose °F (the unit switch on the System page): one
// unit everywhere, whatever language the phone is set to.
export const tempUnit = () => localStorage.getItem("xregulator.tempUnit") || "C";

function setValue(id, text, unit, note) {
  const el = $(id);
  if (!el) return;
  el.textContent = text;
  if (unit) { const u = document.createElement("span"); u.className = "unit"; u.textContent = unit; el.appendChild(u); }
  if (note) { const a = document.createElement("span"); a.className = "note"; a.textContent = note; el.appendChild(a); }
}
const on = (v) => v === true || v === 1;

// The first-run notice until a battery type is chosen (docs/configuration.md
// "Not set up"); /api/params says which, and the owner's state starts with it.
export function renderSetupState(paramsBody) {
  const setUp = paramsBody.set_up !== false;
  $("first-run").hidden = setUp;
  $("first-run-limits").textContent = paramsBody.setup_limits || "";
}

// The regulator's own words (the `owner` object of the status frame,
// docs/dashboard.md "Owner model"): its state, then the current that goes
// into or out of the battery and the power while the alternator gives it:
// "Charging · Bulk · limited by Belt limit · 42 A into the battery · 580 W",
// "Not charging · Engine stopped or idling".
export function headline(s) {
  const o = s.owner;
  if (!o) return "—";
  const parts = [o.state];
  const h = o.hero || {};
  if (h.unit === "A" && isNum(h.value)) {
    parts.push(h.label === "out of the battery" ? `${num(h.value, 0)} A still from the battery` : `${num(h.value, 0)} A ${h.label}`);
    if (isNum(s.alt_a) && isNum(s.battery_v)) parts.push(`${num(s.alt_a * s.battery_v, 0)} W`);
  }
  return parts.join(" · ");
}

// "C/10 without a battery probe: 28 A" — a limit as the owner reads it.
export function limitText(l) {
  return isNum(l.amps) ? `${l.what}: ${num(l.amps, 0)} A` : l.what;
}

function renderBanners(s) {
  const root = $("banners");
  const codes = activeProblems(s);
  const key = codes.join(",");
  const p = s.protection || {};
  const countdown = on(p.lockout_active) && isNum(p.lockout_remaining_s)
    ? `Retrying in ${Math.ceil(p.lockout_remaining_s)} s.` : "";
  if (root.dataset.key !== key) {
    root.dataset.key = key;
    root.textContent = "";
    for (const code of codes) {
      const r = reasonInfo(code);
      const b = document.createElement("div");
      b.className = "banner " + (r.kind === "fault" ? "fault" : "warn");
      b.dataset.reason = code;
      b.setAttribute("role", "alert");
      const h = document.createElement("strong"); h.textContent = r.title;
      const m = document.createElement("p"); m.textContent = r.meaning;
      const a = document.createElement("p"); a.className = "action"; a.textContent = r.action ? "What to do: " + r.action : "";
      const c = document.createElement("p"); c.className = "countdown";
      b.append(h, m, a, c);
      root.appendChild(b);
    }
  }
  root.querySelectorAll(".countdown").forEach((c) => { c.textContent = countdown; });
}

// Acknowledging the alarm (docs/protections.md "Acknowledging an alarm"):
// while the buzzer sounds, one button silences it; the protection acts on.
// A write like any other: a device that is not paired is asked to pair.
function renderAlarmAck(s) {
  const row = $("alarm-ack-row");
  if (!row) return;
  row.hidden = !on(s.alarm);
  const btn = $("alarm-ack");
  if (btn.onclick) return;
  btn.onclick = async () => {
    btn.disabled = true;
    try {
      await command("acknowledge_alarm");
      toast("Alarm silenced; the protection keeps acting.");
    } catch (e) {
      toast(`Not silenced: ${e.message}`, true);
    } finally {
      btn.disabled = false;
    }
  };
}

// The SoC tile (docs/dashboard.md, "State of charge"): a BMS that reports a
// SoC is THE SoC; a SoC the regulator does not know (soc_pct null or
// soc_source "unknown") is the word "unknown", never a number; a start-up
// guess is marked "≈" until it was set, restored or a full charge was seen.
export function socDisplay(s, b = {}) {
  const sourceNote = { bms: "from the BMS", counted: "counted", ocv_estimate: "estimate from voltage" };
  const soc = (s.owner && s.owner.soc) || { pct: null, source: "unknown" };
  if (!isNum(soc.pct) || soc.source === "unknown")
    return { text: "unknown", unit: "", note: "set it on the Battery page", guess: true };
  if (soc.source === "bms") return { text: num(soc.pct, 0), unit: "%", note: "from the BMS", guess: false };
  const known = b.soc_known !== false && soc.source !== "ocv_estimate";
  const full = isNum(b.time_to_full_charge_min) && b.time_to_full_charge_min > 0 ? `full in ${hmin(b.time_to_full_charge_min)}` : "";
  const note = known ? [sourceNote[soc.source], full].filter(Boolean).join(", ")
                     : (sourceNote[soc.source] || "estimate") + " — set it on the Battery page";
  return { text: (known ? "" : "≈ ") + num(soc.pct, 0), unit: "%", note, guess: !known };
}

export function renderLive(s) {
  lastStatus = s;
  lastFrameAt = Date.now();
  // The regulator's one notice (owner.notice): what the bank reads and which size to choose.
  $("first-run-bank").textContent = (s.owner && s.owner.notice) || "";
  const p = s.protection || {};
  const b = s.battery || {};
  const currentStale = on(p.current_stale);
  const tempStale = on(p.temp_stale);
  setValue("v-battery_v", num(s.battery_v, 2), "V");
  setValue("v-bcur_a", isNum(s.bcur_a) ? num(Math.abs(s.bcur_a), 1) : "—", "A",
    currentStale ? "not live" : !isNum(s.bcur_a) ? "" : s.bcur_a >= 0 ? "into the battery" : "out of the battery");
  setValue("v-alt_a", num(s.alt_a, 1), "A", currentStale ? "not live" : "");
  setValue("v-power", isNum(s.alt_a) && isNum(s.battery_v) ? num(Math.max(0, s.alt_a * s.battery_v), 0) : "—", "W");
  $("v-bcur_a").classList.toggle("stale", currentStale);
  $("v-alt_a").classList.toggle("stale", currentStale);
  $("v-power").classList.toggle("stale", currentStale);
  const unit = tempUnit();
  setValue("v-temp", temp(s.temp_f, unit), "", tempStale ? "not live" : "");
  $("v-temp").classList.toggle("stale", tempStale);
  const hot = isNum(s.temp_f) && (on(p.temp_warning) || on(p.temp_critical) || on(p.temp_sustained));
  $("v-temp").classList.toggle("hot", hot);
  setValue("v-rpm", isNum(s.rpm) && s.rpm > 0 ? num(s.rpm, 0) : "stopped", isNum(s.rpm) && s.rpm > 0 ? "rpm" : "");
  const soc = socDisplay(s, b);
  setValue("v-soc_pct", soc.text, soc.unit, soc.note);
  $("v-soc_pct").classList.toggle("guess", soc.guess);
  setValue("v-field", on(s.field_enable) ? "On" : "Off", "", on(s.field_enable) ? `${num(s.duty_pct, 0)} %` : "");
  // The target only means something while Auto regulates with the field on;
  // the limits acting now are the regulator's (owner.limits), with amps and cause.
  const regulating = s.mode === "MODE_NORMAL_AUTO_PID" && on(s.field_enable);
  const limits = (s.owner && s.owner.limits) || [];
  const aim = regulating ? `${plainStage(s.stage)}: up to ${num(s.target_a, 0)} A, ${num(s.target_v, 2)} V`
                         : `nothing (${ownerMode(s).toLowerCase()}${on(s.field_enable) ? "" : ", field off"})`;
  setValue("v-target", aim, "", limits.length ? "limited by " + limits.map(limitText).join("; ") : "");
  $("v-target").title = limits.map((l) => `${limitText(l)} — ${l.why}`).join("\n");
  const alarms = activeProblems(s).map((c) => reasonInfo(c).title);
  if (on(s.alarm)) alarms.unshift("buzzer on");
  if (on(s.fast_ov_active)) alarms.push("fast over-voltage clamp");
  if (on(p.temp_task_alarm)) alarms.push("temperature reading stuck");
  setValue("v-alarms", alarms.length ? alarms.join(", ") : "none");
  $("v-alarms").classList.toggle("bad", alarms.length > 0);
  $("headline").textContent = headline(s);
  renderHero(s);
  renderBanners(s);
  renderAlarmAck(s);
  renderHeader(s, alarms.length > 0);
  tick();
}

// The hero (docs/dashboard.md "At a glance"): the regulator's one number
// and state word (owner.hero, owner.state); until it sends them, the
// battery voltage and the headline's first words.
export function heroOf(s) {
  const o = s.owner || {};
  const h = o.hero || {};
  if (h.value !== undefined && h.value !== null)
    return { value: typeof h.value === "number" ? num(h.value, Math.abs(h.value) < 100 ? 1 : 0) : String(h.value),
      unit: String(h.unit || ""), label: String(h.label || ""), state: String(o.state || headline(s).split(" · ")[0]) };
  return { value: num(s.battery_v, 2), unit: "V", label: "Battery", state: String(o.state || headline(s).split(" · ")[0]) };
}

function renderHero(s) {
  const h = heroOf(s);
  $("hero-value").textContent = h.value;
  $("hero-unit").textContent = h.unit;
  $("hero-label").textContent = h.label;
  $("hero-state").textContent = h.state;
}

function renderHeader(s, alarm) {
  const mode = ownerMode(s);
  $("hdr-mode").textContent = mode;
  $("hdr-mode").dataset.mode = mode;
  const ctl = $("ctl-mode");
  if (ctl) ctl.textContent = mode;
  document.querySelectorAll("[data-mode-button]").forEach((el) => el.classList.toggle("current", el.dataset.modeButton === mode));
  $("hdr-alarm").hidden = !alarm && !on(s.alarm);
}

// Once a second: the age of the values, and the offline state when frames
// stop (socket closed, or open but silent because the daemon hangs).
export function tick() {
  const age = lastFrameAt ? (Date.now() - lastFrameAt) / 1000 : NaN;
  const offline = !lastFrameAt || age > STALE_AFTER_S || document.body.dataset.ws !== "open";
  document.body.classList.toggle("offline", offline);
  $("offline-banner").hidden = !offline;
  $("offline-age").textContent = lastFrameAt ? ago(age) : "never (no data yet)";
  $("updated").textContent = lastFrameAt ? `last update ${ago(age)}` : "waiting for the regulator…";
  const conn = $("conn");
  conn.textContent = offline ? "offline" : "live";
  conn.className = offline ? "conn off" : "conn on";
  conn.hidden = offline;
  // Offline the mode is not known: the badge says the regulator cannot be
  // reached (never the last frame's "Off"), and the last alarm is not current.
  const mode = $("hdr-mode");
  if (offline) {
    const never = !lastFrameAt && document.body.dataset.ws !== "closed";
    mode.textContent = never ? "Connecting…" : "Regulator unreachable";
    mode.dataset.mode = never ? "connecting" : "unreachable";
    $("hdr-alarm").hidden = true;
  }
  disableControlsWhileOffline(offline);
}

// Offline, no control acts on values the owner cannot see: every button,
// box and choice of the pages is disabled (marked, so the ones disabled for
// their own reasons stay so when the connection is back). Every second, so
// a page drawn while offline is covered too.
function disableControlsWhileOffline(offline) {
  for (const el of document.querySelectorAll("main button, main input, main select")) {
    if (offline && !el.disabled) {
      el.disabled = true;
      el.dataset.offline = "1";
    } else if (!offline && el.dataset.offline) {
      el.disabled = false;
      delete el.dataset.offline;
    }
  }
}

export const latestStatus = () => lastStatus;
