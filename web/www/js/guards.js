// Switches that take a protection away (docs/dashboard.md "A protection
// switched off"): a change that turns one of these to its unsafe side asks
// first, and while one is there a banner on every page says so.
import { confirmAction } from "./confirm.js";

// name, the unsafe value, and what it means in words.
export const UNSAFE_SWITCHES = [
  { name: "IgnoreTemperature", unsafe: true,
    text: "Alternator temperature protection is OFF (IgnoreTemperature): nothing stops it overheating." },
  { name: "IgnoreRPM", unsafe: true,
    text: "The engine-speed gate is OFF (IgnoreRPM): the field may stay on with the engine stopped." },
  { name: "INADisconnected", unsafe: true,
    text: "The INA228 is marked absent (INADisconnected): no hardware over-voltage cut, and Auto cannot run." },
  { name: "OvGroup1Enable", unsafe: false,
    text: "Fast over-voltage protection group 1 is OFF (OvGroup1Enable)." },
  { name: "OvGroup2Enable", unsafe: false,
    text: "Fast over-voltage protection group 2 is OFF (OvGroup2Enable)." },
  { name: "AlarmActivate", unsafe: false, text: "The alarm buzzer is OFF (AlarmActivate)." },
  { name: "OnOff", unsafe: false, text: "Charging is switched off in the settings (OnOff)." },
];

const isUnsafe = (sw, v) => (sw.unsafe ? v === true || v === 1 : v === false || v === 0);

// The switches a PATCH body would turn to their unsafe side.
export function unsafeChanges(body) {
  return UNSAFE_SWITCHES.filter((sw) => sw.name in body && isUnsafe(sw, body[sw.name]));
}

// The switches that are on their unsafe side in /api/params' list.
export function activeUnsafe(params) {
  const byName = Object.fromEntries(params.map((p) => [p.name, p.value]));
  return UNSAFE_SWITCHES.filter((sw) => sw.name in byName && isUnsafe(sw, byName[sw.name]));
}

// Resolves true when the body takes nothing away, or the owner confirmed.
export async function confirmUnsafe(body) {
  const list = unsafeChanges(body);
  if (!list.length) return true;
  return confirmAction(`${list.map((sw) => sw.text).join(" ")} Switch it off anyway?`, "Switch off");
}

export function renderGuardBanner(params) {
  const el = document.getElementById("guard-banner");
  if (!el) return;
  const list = activeUnsafe(params);
  el.hidden = !list.length;
  el.textContent = list.map((sw) => sw.text).join(" ");
}
