// The set-up's hardware step: which 1-Wire probe is on the battery, which
// CAN interface the BMS is on, and the pulley ratio (docs/configuration.md
// "Set-up: hardware choices"). The daemon opens these devices at start, so a
// choice is used from its next start and the page says so; it lists what is
// present on the board now.
import { html, parseDecimal } from "./format.js";

function options(current, found, noneLabel, label) {
  const list = [["", noneLabel], ...found.map((v) => [v, label(v)])];
  if (current && !found.includes(current)) list.push([current, `${label(current)} (not found now)`]);
  return list.map(([v, l]) => html`<option value="${v}" ${v === current ? "selected" : ""}>${l}</option>`);
}

// The pulley ratio scales the tach: the page shows the engine speed read now
// and what it would read with the ratio typed, to compare with the engine's
// own tachometer.
export function rpmHint(hw, rpmNow, typed) {
  if (!(rpmNow > 0)) return "Engine stopped: start it to compare the speed read with the engine's tachometer.";
  const r = parseDecimal(typed);
  const next = r > 0 ? Math.round((rpmNow * hw.pulley_ratio.running) / r) : null;
  return `Engine speed read now: ${Math.round(rpmNow)} rpm` +
    (next !== null && r !== hw.pulley_ratio.running ? `; with ${r}: ${next} rpm. Compare with the engine's tachometer.` : ". Compare with the engine's tachometer.");
}

export function renderHardwareStep(hw, n, rpmNow) {
  const probes = hw.probes.filter((p) => p !== hw.alternator_sensor);
  const lock = hw.savable ? "" : "disabled";
  const gx = hw.victron_bms;
  return html`<h3>${n} · Battery temperature and BMS</h3>
    <label class="field"><span>Battery temperature probe</span><select id="su-battprobe" ${lock}>
    ${options(hw.battery_temp_sensor.next, probes, "No probe on the battery", (p) => p)}</select>
    <small>A DS18B20 taped to a battery case. ${probes.length ? `${probes.length} probe(s) found besides the alternator's` : "No probe found besides the alternator's"}${hw.alternator_sensor ? ` (${hw.alternator_sensor})` : ""}.</small></label>
    <label class="field"><span>BMS</span><select id="su-bms" ${lock || (gx ? "disabled" : "")}>
    ${options(hw.bms_interface.next, hw.can_interfaces, "No BMS on CAN", (i) => `BMS on CAN ${i}`)}</select>
    <small>${gx ? "The BMS's limits come from the Victron GX ([integrations.victron] in the file): one source only." :
      hw.can_interfaces.length ? "The regulator obeys the BMS's charge limits." : "No CAN interface found on this board (a CAN HAT shows as can0)."}</small></label>
    <label class="field"><span>Pulley ratio</span><span class="row"><input id="su-pulley" inputmode="decimal" value="${hw.pulley_ratio.next}" ${lock}>
    <span class="unit">: 1</span></span><small id="su-pulley-hint">${rpmHint(hw, rpmNow, hw.pulley_ratio.next)}</small>
    <small>Alternator turns per engine turn: the crank pulley's diameter over the alternator's (1 when the tach is calibrated at the crank).</small></label>
    ${hw.savable ? "" : html`<p class="msg warn">No state database: set these in the configuration file.</p>`}`;
}

// The PUT body for what changed ({} when nothing did): a choice equal to the
// file's value is sent as null, so the file decides again. `read(id, label,
// min, max)` is the set-up's reader of a bounded number (it marks the box and
// throws when the entry is not one).
export function collectHardware(hw, read) {
  const body = {};
  for (const [key, id] of [["battery_temp_sensor", "su-battprobe"], ["bms_interface", "su-bms"]]) {
    const el = document.getElementById(id);
    if (!el || el.disabled || el.value === hw[key].next) continue;
    body[key] = el.value === hw[key].file ? null : el.value;
  }
  const p = document.getElementById("su-pulley");
  if (p && !p.disabled) {
    const r = read("su-pulley", "Pulley ratio", 0.01, 100);
    if (r !== hw.pulley_ratio.next) body.pulley_ratio = r === hw.pulley_ratio.file ? null : r;
  }
  return body;
}

// Result rows: what runs now and what the next start will use.
export function hardwareRows(hw) {
  const word = (v, none) => (v ? v : none);
  const row = (c, none) => word(c.running, none) + (c.restart_needed ? ` → ${word(c.next, none)} from the next start` : "");
  return [["Battery temperature probe", row(hw.battery_temp_sensor, "none")], ["BMS on CAN", row(hw.bms_interface, "none")],
    ["Pulley ratio", row({ ...hw.pulley_ratio, running: `${hw.pulley_ratio.running} : 1`, next: `${hw.pulley_ratio.next} : 1` }, "")]];
}

export const restartNeeded = (hw) =>
  hw.battery_temp_sensor.restart_needed || hw.bms_interface.restart_needed || hw.pulley_ratio.restart_needed;
