// The detail pages fed by the status frames (Protections, Battery, Tuning),
// the event list and the System page. Plain names, rounded numbers, clock times.
import { getJson } from "./api.js";
import { ago, clock, hmin, hminFromSeconds, num, plain } from "./format.js";
import { limitText, latestStatus } from "./live.js";
import { plainMode, reasonInfo } from "./names.js";

const $ = (id) => document.getElementById(id);

export function kvTable(id, rows) {
  const t = $(id);
  t.textContent = "";
  for (const [k, v, cls] of rows) {
    const tr = t.insertRow();
    tr.insertCell().textContent = k;
    const td = tr.insertCell();
    td.textContent = plain(v);
    if (cls) td.className = cls;
  }
}
const yes = (v) => v === true || v === 1;
const flag = (v, bad = "bad") => [yes(v), yes(v) ? bad : "good"];

export function renderProtections(s) {
  const p = s.protection || {};
  const now = s.wall_time_s, tNow = s.t_s;
  // The last trip's clock time from its daemon-time stamp.
  const tripAt = typeof p.last_trip_time_s === "number" && typeof now === "number" && p.last_trip_reason !== "NONE"
    ? clock(now - (tNow - p.last_trip_time_s)) : "—";
  const row = (label, v, bad) => { const [val, cls] = flag(v, bad); return [label, val, cls]; };
  kvTable("prot-table", [
    ["acting now", reasonInfo(s.reason).title, s.reason === "NONE" ? "good" : reasonInfo(s.reason).kind === "state" ? "" : "warn"],
    ["field", yes(s.field_enable) ? "on" : "off"],
    ["shutdown step", p.shutdown_phase === "PHASE_NONE" ? "none" : String(p.shutdown_phase || "—").replace("PHASE_", "").replace("DONE", "finished")],
    row("over-voltage latch", p.ina_overvoltage_latched),
    row("cooldown running", p.lockout_active, "warn"),
    ["cooldown left", p.lockout_active ? `${Math.ceil(p.lockout_remaining_s || 0)} s` : "—"],
    row("fast over-voltage clamp", p.fast_ov_clamp_active, "warn"),
    // The supervisors' cap means something only while they clamp; idle it is the request itself.
    ["clamp current (A)", yes(p.fast_ov_clamp_active) ? plain(p.fast_ov_current_cap, 1) : "—"],
    row("temperature reading stuck", p.temp_task_alarm),
    ["heat derate (A)", s.thermal_penalty_a],
    row("buzzer", p.buzzer),
    ["last trip", p.last_trip_reason && p.last_trip_reason !== "NONE" ? reasonInfo(p.last_trip_reason).title : "none"],
    ["last trip at", tripAt],
    ...holdingBack(s),
  ]);
}

// What holds the charge back now: the regulator's limits (owner.limits,
// docs/dashboard.md "Owner model"), most restrictive first, with amps and cause.
function holdingBack(s) {
  const limits = (s.owner && s.owner.limits) || [];
  if (!limits.length) return [["holding back", "nothing", "good"]];
  return limits.map((l, i) => [i ? "also holding back" : "holding back", `${limitText(l)} — ${l.why}`, "warn"]);
}

// The SoC row: the regulator's one SoC (owner.soc), the same as Live's.
function socRow(s) {
  const soc = (s.owner && s.owner.soc) || { pct: null, source: "unknown" };
  if (soc.pct === null || soc.source === "unknown") return "unknown until the first full charge (or set it below)";
  if (soc.source === "bms") return `${plain(soc.pct, 0)} (from the BMS)`;
  if (soc.source === "ocv_estimate") return `≈ ${plain(soc.pct, 0)} (estimate from the rested voltage)`;
  return (s.battery || {}).soc_known === false ? `≈ ${plain(soc.pct, 0)} (estimate)` : plain(soc.pct, 1);
}

// The charge counted in Ah is the counted SoC in other units: shown only while
// that SoC is the one shown, marked "≈" while it is a start-up guess
// (docs/dashboard.md "State of charge").
function countedAhRow(b, counted) {
  if (!counted) return "—";
  return b.soc_known === false ? `≈ ${plain(b.coulomb_count_ah, 0)}` : plain(b.coulomb_count_ah, 1);
}

export function renderBattery(s) {
  const b = s.battery || {};
  // Averages of the counted SoC mean something only while it is the SoC shown.
  const counted = s.owner && s.owner.soc && s.owner.soc.source === "counted";
  kvTable("batt-table", [
    ["state of charge (%)", socRow(s)],
    ["charge counted (Ah)", countedAhRow(b, counted)], ["battery current (A)", plain(s.bcur_a, 1)],
    ["full charge seen", yes(b.full_charge_detected)],
    ["time to full", b.soc_known === false ? "unknown until the SoC is known" : hmin(b.time_to_full_charge_min)],
    ["time to empty", b.soc_known === false ? "unknown until the SoC is known" : hmin(b.time_to_full_discharge_min)],
    ["charged this run (Wh)", plain(b.charged_energy_wh, 0)], ["discharged this run (Wh)", plain(b.discharged_energy_wh, 0)],
    ["from the alternator (Wh)", plain(b.alternator_charged_energy_wh, 0)], ["from solar (Wh)", plain(b.solar_charged_energy_wh, 0)],
    ["charged, lifetime (Wh)", plain(s.charged_wh_lifetime, 0)], ["alternator, lifetime (Wh)", plain(s.alt_charged_wh_lifetime, 0)],
    ["charge cycles", plain(b.charge_cycles, 2)], ["charge cycles, lifetime", plain(b.charge_cycles_all_time, 1)],
    ["average SoC (%)", counted ? plain(b.avg_soc, 0) : "—"],
    ["average SoC, lifetime (%)", counted ? plain(b.avg_soc_all_time, 0) : "—"],
    ["average voltage, lifetime (V)", plain(b.avg_voltage_all_time, 2)],
    ["alternator running (h:min)", hminFromSeconds(b.alternator_on_time_s)], ["fuel used (L)", plain(b.alternator_fuel_used_l, 1)],
    ["shunt gain correction", plain(b.dynamic_shunt_gain_factor, 3)], ["alternator current zero (A)", plain(b.dynamic_alt_current_zero, 2)],
    ["re-zeroing now", yes(b.auto_zero_active)],
  ]);
}

export function renderTuning(s) {
  const c = s.control || {};
  const rows = [["mode", plainMode(s.mode)], ["current target (A)", plain(c.u_target_amps, 1)],
    ["set-point after slew (A)", plain(c.setpoint_limited, 1)], ["measured, filtered (A)", plain(c.pid_input, 1)],
    ["field duty asked (%)", plain(c.pid_output, 1)],
    ["current loop P / I / D", [c.inner_term_p, c.inner_term_i, c.inner_term_d].map((x) => plain(x, 2)).join(" / ")],
    ["voltage loop active", yes(c.voltage_control_active)], ["voltage target (V)", plain(c.charging_voltage_target, 2)],
    ["voltage loop integral", plain(c.cv_i, 2)], ["voltage loop current limit (A)", plain(c.icv, 1)],
    ["duty applied (%)", plain(c.last_applied_duty, 1)]];
  for (const sec of ["tuning", "system_id", "cv_tuning"])
    if (s[sec] && typeof s[sec] === "object") for (const [k, v] of Object.entries(s[sec])) rows.push([`${sec.replace("_", " ")}: ${k.replace(/_/g, " ")}`, v]);
  kvTable("tuning-table", rows);
}

// ---------------------------------------------------------------- events
// The event list lives in events.js; these names stay here for the pages' callers.
export { applyEventFilter, eventText, levelShown, loadEvents } from "./events.js";

// /api/system "bms" and "n2k" (docs/integrations.md) in plain words; a value the daemon
// does not know is shown as a dash, never made up.
const BMS_WORDS = {
  off: ["not set up", ""],
  bus_error: ["CAN interface not open (retrying)", "bad"],
  silent: ["connected, but the BMS sends nothing", "bad"],
  talking: ["talking", "good"],
};
const N2K_WORDS = {
  off: ["not set up", ""],
  bus_error: ["CAN interface not open (retrying)", "bad"],
  no_address: ["no free address on the network", "bad"],
  claimed: ["on the network", "good"],
};
// ownerBms: the regulator's own BMS state (owner.bms), the one every page shows.
const OWNER_BMS_CLASS = { talking: "good", warning: "warn", no_charge: "warn", silent: "bad", none: "" };
export function canRows(bms, n2k, ownerBms) {
  const v = (x, unit, digits = 1) => (num(x, digits) === "—" ? "—" : `${num(x, digits)} ${unit}`);
  const rows = [];
  const [bw, bc] = ownerBms ? [ownerBms.words, OWNER_BMS_CLASS[ownerBms.state] || ""]
    : BMS_WORDS[bms?.state] || [bms?.state || "unknown", ""];
  rows.push(["Battery BMS", bms?.protocol ? `${bw} (${bms.protocol})` : bw, bc]);
  if (bms && bms.state !== "off")
    rows.push(["BMS limits are", bms.follow === false ? "shown only (monitor only: not followed)" : "followed", bms.follow === false ? "warn" : ""]);
  if (bms && bms.state !== "off") {
    rows.push(["BMS limits", `charge voltage ${v(bms.cvl_v, "V", 2)}, charge current ${v(bms.ccl_a, "A")}, SoC ${v(bms.soc_pct, "%")}`]);
    if (bms.cell_max_v !== null && bms.cell_max_v !== undefined) rows.push(["Highest cell", v(bms.cell_max_v, "V", 3)]);
    rows.push(["Limits received", ago(bms.age_s)]);
    rows.push(["Bad BMS frames ignored", bms.bad_frames, bms.bad_frames ? "bad" : ""]);
  }
  const [nw, nc] = N2K_WORDS[n2k?.state] || [n2k?.state || "unknown", ""];
  rows.push(["NMEA 2000", n2k?.claimed ? `${nw}, address ${n2k.address}` : nw, nc]);
  if (n2k && n2k.state !== "off") rows.push(["NMEA 2000 frames", `sent ${n2k.tx_frames}, received ${n2k.rx_frames}`]);
  return rows;
}

export async function loadSystem() {
  const s = await getJson("/api/system");
  const obj = (o) => Object.entries(o || {}).filter(([, v]) => typeof v !== "object" || v === null);
  kvTable("sys-versions", obj(s.versions));
  kvTable("sys-loop", obj(s.loop).map(([k, v]) => [k.replace(/_/g, " "), v, k === "overruns" ? (v ? "bad" : "good") : ""]));
  kvTable("sys-probes", (s.probes || []).map((p) => [p.device, `${p.ok ? "OK" : "FAIL"} ${p.detail || ""}`, p.ok ? "good" : "bad"]));
  const status = latestStatus();
  kvTable("sys-can", canRows(s.bms, s.n2k, status && status.owner ? status.owner.bms : null));
  kvTable("sys-web", obj(s.web).map(([k, v]) => [k.replace(/_/g, " "), v]).concat([["telemetry rate (Hz)", s.telemetry_rate_hz]]));
}
