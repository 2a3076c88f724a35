// Unit tests of the dashboard's pure modules under node (no browser):
// formatting and parsing (docs/dashboard.md), plain names and the one
// reasons table shared with docs/operations.md (items 2, 7), the TOML
// export/import (item 8), the settings' choices and sources (items 5, 8),
// event texts (item 11), pairing messages (item 15).
//   node units.mjs --root <repository root>
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";
import { pathToFileURL } from "node:url";

const args = Object.fromEntries(
  process.argv.slice(2).reduce((acc, a, i, all) => (a.startsWith("--") ? [...acc, [a.slice(2), all[i + 1]]] : acc), []));
const root = args.root;
const mod = (p) => import(pathToFileURL(path.join(root, p)).href);
// settings.js imports api.js, which touches the DOM only when called.
globalThis.localStorage = { getItem: () => null, setItem() {}, removeItem() {} };
globalThis.navigator = globalThis.navigator || { language: "en-GB" };

const F = await mod("web/www/js/format.js");
const N = await mod("web/www/js/names.js");
const T = await mod("web/www/js/toml.js");
const S = await mod("web/www/js/settings.js");
const D = await mod("web/tools/reasons-doc.mjs");
const P = await mod("web/www/js/pages.js");
const A = await mod("web/www/js/pairing.js");
const L = await mod("web/www/js/live.js");
const Q = await mod("web/www/js/pair_qr.js");
let n = 0;
const test = async (name, fn) => { await fn(); n++; console.log("ok - " + name); };

await test("comma and point decimals parse; empty and junk give null, never 0", () => {
  assert.equal(F.parseDecimal("13,4"), 13.4);
  assert.equal(F.parseDecimal(" 13.4 "), 13.4);
  assert.equal(F.parseDecimal("-2,5"), -2.5);
  assert.equal(F.parseDecimal("30"), 30);
  assert.equal(F.parseDecimal(""), null);
  assert.equal(F.parseDecimal("   "), null);
  assert.equal(F.parseDecimal("1,2,3"), null);
  assert.equal(F.parseDecimal("abc"), null);
  assert.equal(F.parseDecimal("13.4.1"), null);
});

await test("numbers are rounded; sentinels and NaN read as no value", () => {
  assert.equal(F.num(99.998, 0), "100");
  assert.equal(F.num(12.580859375000001, 2), "12.58");
  assert.equal(F.num(-0.04, 1), "0.0");
  assert.equal(F.num(-999, 1), "—");
  assert.equal(F.num(NaN), "—");
  assert.equal(F.num(null), "—");
  assert.equal(F.plain(0.30000000000000004), "0.3");
  assert.equal(F.plain(2327), "2327");
  assert.equal(F.plain(true), "yes");
});

await test("times read as h:min and ages in words", () => {
  assert.equal(F.hmin(125), "2 h 05 min");
  assert.equal(F.hmin(45), "45 min");
  assert.equal(F.hmin(-999), "—");
  assert.equal(F.hminFromSeconds(3600), "1 h 00 min");
  assert.equal(F.ago(4.4), "4 s ago");
  assert.equal(F.ago(600), "10 min ago");
  assert.match(F.clock(1796306371, 1796306371), /^\d\d:\d\d$/);
  assert.equal(F.clock(0), "—");
});

await test("temperatures in the chosen unit", () => {
  assert.equal(F.temp(170, "F"), "170 °F");
  assert.equal(F.temp(170, "C"), "77 °C");
  assert.equal(F.temp(-999, "C"), "—");
});

await test("every Reason of daemon/core/modes.h has plain words; normal states are not alarms", () => {
  const header = fs.readFileSync(path.join(root, "daemon/core/modes.h"), "utf8");
  const body = header.slice(header.indexOf("enum class Reason"));
  const enumBody = body.slice(body.indexOf("{") + 1, body.indexOf("}")).replace(/\/\/[^\n]*/g, "");
  const codes = enumBody.split(",").map((s) => s.trim()).filter(Boolean);
  assert.ok(codes.length >= 20, `found ${codes.length} reasons`);
  for (const c of codes) {
    const r = N.REASONS[c];
    assert.ok(r, `no entry for ${c}`);
    assert.doesNotMatch(r.title, /REASON_|_/, c);
    if (c !== "NONE") assert.ok(r.meaning && r.action, `${c} needs a meaning and an action`);
  }
  for (const c of ["REASON_SYS_OFF", "REASON_RPM_LOW", "REASON_IGNITION_OFF", "REASON_IDLE_STAGE"])
    assert.equal(N.REASONS[c].kind, "state", c);
  const modes = header.slice(header.indexOf("enum class FieldControlMode"));
  for (const m of modes.slice(modes.indexOf("{") + 1, modes.indexOf("}")).split(",").map((s) => s.trim()).filter(Boolean))
    assert.notEqual(N.plainMode(m), m, `no plain name for ${m}`);
  for (const st of ["BULK", "ABSORPTION", "FLOAT", "IDLE"]) assert.notEqual(N.plainStage(st), st);
});

await test("each active protection is one problem; a stopped engine or Off is none", () => {
  const p = { current_stale: true, temp_stale: true, lockout_active: true };
  assert.deepEqual(N.activeProblems({ reason: "REASON_LOCKOUT", protection: p }),
    ["REASON_TEMP_STALE", "REASON_CURRENT_STALE", "REASON_LOCKOUT"]);
  assert.deepEqual(N.activeProblems({ reason: "REASON_RPM_LOW", protection: {} }), []);
  assert.deepEqual(N.activeProblems({ reason: "REASON_SYS_OFF", protection: {} }), []);
  assert.deepEqual(N.activeProblems({ reason: "NONE", protection: { hard_overcurrent: true } }), ["REASON_HARD_OVERCURRENT"]);
  assert.equal(N.ownerMode({ mode: "MODE_DISABLED_RAMP", control: { sys_mode: "SYS_MODE_OFF" } }), "Off");
});

await test("docs/operations.md's reasons table is the one generated from names.js", async () => {
  const doc = fs.readFileSync(path.join(root, "docs/operations.md"), "utf8");
  assert.equal(D.replaceSection(doc, await D.reasonsTable()), doc,
    "docs/operations.md differs from names.js: run node web/tools/reasons-doc.mjs");
  assert.match(doc, /Current sensor not answering/);
});

const params = [
  { name: "BulkVoltage", group: "Voltage", kind: "float", value: 14.5, help: "Bulk." },
  { name: "UseFloat", group: "Charging", kind: "bool", value: true, help: "After absorption: 1 = float, 0 = idle." },
  { name: "TempSource", group: "Temperature", kind: "int", value: 0, help: "Temperature used: 0 = DS18B20 (1-Wire), 1 = thermistor (ADS1115 CH3)." },
  { name: "rpmCapCurrentTable", group: "RpmTables", kind: "table", value: [0, 50, 50, 50, 50, 50, 50, 50, 50, 50], help: "" },
  { name: "VoltageDisagreeThreshold", group: "SensorHealth", kind: "float", value: 0.15, help: "x" },
  { name: "BatteryProfile", group: "Battery", kind: "int", value: 1, choices: ["lifepo4", "agm", "custom"], help: "" },
];
const groups = ["Voltage", "SensorHealth", "Charging", "Temperature", "RpmTables", "Battery"];

await test("TOML export re-imports to the same values; sections are the file's", () => {
  const text = T.exportToml(params, groups);
  assert.match(text, /\[sensor_health\]\nVoltageDisagreeThreshold = 0\.15|\[sensor_health\]\n# x\nVoltageDisagreeThreshold = 0\.15/);
  assert.match(text, /\[rpm_tables\][^[]*rpmCapCurrentTable = \[0, 50,/);
  assert.match(text, /\[battery\]\nBatteryProfile = "agm"/);  // a named choice as the daemon's file has it
  const back = T.parseParamsToml(text, params);
  assert.deepEqual(back.errors, []);
  for (const p of params) assert.deepEqual(back.values[p.name], p.value, p.name);
});

// The settings export as a hostile or damaged file: 4000 seeded mutations
// (bytes changed, lines cut, duplicated or swapped, odd numbers put in).
// The import never throws, and whatever it accepts is what the PATCH can
// carry: a finite number in the parameter's kind, a table of the right
// length, a boolean, a choice that exists — never Infinity or NaN, which
// JSON would send as null ("drop the dashboard's value").
await test("TOML import of 4000 mutated exports: never throws, accepts only values a PATCH carries", () => {
  const text = T.exportToml(params, groups);
  let seed = 12345;
  const rnd = (k) => { seed = (seed * 1103515245 + 12345) % 2147483648; return seed % k; };
  const odd = ["1e999", "-1e999", "nan", "inf", "0x10", "1_000", "\u0000", "[]", "[1,]", "\"lifepo4\"", "true", "1e-400", "-0", "9".repeat(400)];
  const byName = Object.fromEntries(params.map((p) => [p.name, p]));
  for (let i = 0; i < 4000; i++) {
    let lines = text.split("\n");
    for (let m = 1 + rnd(4); m > 0; m--) {
      const at = rnd(lines.length);
      switch (rnd(5)) {
        case 0: lines[at] = lines[at].replace(/=.*$/, "= " + odd[rnd(odd.length)]); break;
        case 1: lines.splice(at, 1); break;
        case 2: lines.splice(at, 0, lines[rnd(lines.length)]); break;
        case 3: { const c = lines[at]; const k = rnd(c.length + 1); lines[at] = c.slice(0, k) + String.fromCharCode(rnd(128)) + c.slice(k + 1); break; }
        default: lines = lines.slice(0, at);
      }
    }
    const r = T.parseParamsToml(lines.join("\n"), params);
    for (const [name, v] of Object.entries(r.values)) {
      const p = byName[name];
      const kind = String(p.kind).toLowerCase();
      if (kind === "bool") assert.equal(typeof v, "boolean", `${name}: ${v}`);
      else if (kind === "table") assert.ok(Array.isArray(v) && v.length === p.value.length && v.every(Number.isFinite), `${name}: ${v}`);
      else assert.ok(Number.isFinite(v), `${name}: ${v}`);
      if (Array.isArray(p.choices)) assert.ok(Number.isInteger(v) && v >= 0 && v < p.choices.length, `${name}: ${v}`);
      assert.notEqual(JSON.stringify({ v }), '{"v":null}', `${name} would be sent as null`);
    }
  }
});

await test("a change that takes a protection away is recognised, in either polarity; its way back is not", async () => {
  const G = await mod("web/www/js/guards.js");
  assert.deepEqual(G.unsafeChanges({ IgnoreTemperature: true }).map((x) => x.name), ["IgnoreTemperature"]);
  assert.deepEqual(G.unsafeChanges({ IgnoreTemperature: false, OvGroup1Enable: true, FloatVoltage: 13.2 }), []);
  assert.deepEqual(G.unsafeChanges({ OvGroup1Enable: false, OnOff: 0 }).map((x) => x.name), ["OvGroup1Enable", "OnOff"]);
  assert.deepEqual(G.activeUnsafe([{ name: "IgnoreRPM", value: true }, { name: "AlarmActivate", value: true }])
    .map((x) => x.name), ["IgnoreRPM"]);
});

await test("TOML import refuses the whole file on any bad line and names it", () => {
  const r = T.parseParamsToml("[voltage]\nBulkVoltage = 14.2\nNoSuch = 1\n[charging]\nUseFloat = maybe\n[rpm_tables]\nrpmCapCurrentTable = [1, 2]\n[web]\nport = 80\n", params);
  assert.equal(r.errors.length, 3);
  assert.match(r.errors[0], /line 3: unknown parameter NoSuch/);
  assert.match(r.errors[1], /line 5: UseFloat/);
  assert.match(r.errors[2], /line 7: rpmCapCurrentTable: expected 10 numbers/);
  assert.deepEqual(r.skipped, ["web"]);
  const wrongSection = T.parseParamsToml("[charging]\nBulkVoltage = 14.2\n", params);
  assert.match(wrongSection.errors[0], /belongs in \[voltage\]/);
  assert.match(T.parseParamsToml('[battery]\nBatteryProfile = "lithium"\n', params).errors[0], /line 2: BatteryProfile: expected one of lifepo4/);
  const bool01 = T.parseParamsToml("[charging]\nUseFloat = 0  # off\n", params);
  assert.deepEqual(bool01, { values: { UseFloat: false }, errors: [], skipped: [] });
});

await test("choices come from the help text; sources from the API", () => {
  assert.deepEqual(S.choicesOf(params[2]), [[0, "DS18B20 (1-Wire)"], [1, "thermistor (ADS1115 CH3)"]]);
  assert.equal(S.choicesOf(params[0]), null);
  assert.deepEqual(S.choicesOf({ kind: "int", choices: ["lifepo4", "agm"], help: "" }), [[0, "lifepo4"], [1, "agm"]]);
  assert.equal(S.choicesOf(params[1]), null);  // a bool is a switch, not a choice
  assert.equal(S.sourceOf({ overridden: true, changed: true }), "dashboard");
  assert.equal(S.sourceOf({ overridden: false, changed: true }), "file");
  assert.equal(S.sourceOf({ overridden: false, changed: false }), "default");
  assert.equal(S.sourceOf({ source: "profile", overridden: false }), "profile");
});

await test("help texts lose the specification's jargon", () => {
  assert.equal(S.plainHelp("Nameplate capacity. No default in the specification: 200 Ah is a common house bank."),
    "Nameplate capacity. 200 Ah is a common house bank.");
  assert.equal(S.plainHelp("Added here: a resting field wakes."), "a resting field wakes.");
  assert.equal(S.plainHelp("Gain. Changed here: 5 (was 3)."), "Gain. 5 (was 3).");
  assert.equal(S.plainHelp("Buzzer (the original firmware: 190 degF; docs/deviations.md)."), "Buzzer.");
  assert.equal(S.plainHelp("Cap (the specification's section 4.2) in amps."), "Cap in amps.");
  assert.equal(S.plainHelp("Rate above which the bleed drains cv_I."), "Rate above which the bleed drains the voltage loop's integral.");
  assert.equal(S.plainHelp("No charging below this (REASON_BATTERY_COLD)."), `No charging below this (“${N.REASONS.REASON_BATTERY_COLD.title}”).`);
  assert.equal(S.plainHelp("Not in the specification: 500 ms is 100 ticks. 0 = always BULK, as the original firmware."), "500 ms is 100 ticks. 0 = always BULK.");
});

await test("event texts in plain words: no GPIO4, no reason codes, no nan", () => {
  assert.equal(P.eventText({ text: "Field enabled (GPIO4 HIGH)", code: "FieldOn", reason: "NONE" }), "Field enabled");
  assert.equal(P.eventText({ text: "GPIO4 immediate cut: REASON_TEMP_CRITICAL", code: "ImmediateCut", reason: "REASON_TEMP_CRITICAL" }),
    "Field immediate cut: alternator far too hot");
  assert.equal(P.eventText({ text: "Exiting normal mode: RPM_LOW", code: "ModeChanged", reason: "REASON_RPM_LOW" }),
    "Exiting normal mode: engine stopped or idling");
  assert.equal(P.eventText({ text: "RPM below minimum: nan < 200 RPM. Field off", code: "ProtectionTrip", reason: "NONE" }),
    "RPM below minimum: — < 200 RPM. Field off");
  assert.equal(P.eventText({ text: "Command manual (duty 25.5 %) applied", code: "CommandApplied", reason: "NONE" }),
    "Command Manual (duty 25.5 %) applied");
  assert.equal(P.eventText({ text: "Command reset_alarm_latch applied", code: "CommandApplied", reason: "NONE" }),
    "Command Reset alarm latch applied");
});

await test("command answers without the API's command names (item 7)", () => {
  assert.equal(N.commandAnswer("applied: limp_home"), "done");
  assert.equal(N.commandAnswer("tuning_commit refused by the regulator: TuningMode is off, or the tuning has no result to commit yet"),
    "refused — TuningMode is off, or the tuning has no result to commit yet");
  assert.equal(N.commandAnswer("command queue full, try again"), "command queue full, try again");
  assert.equal(N.plainCommand("reset_alt_zero"), "Reset alternator zero");
});

await test("settings changes are events with old → new and who made them, shown as sent", () => {
  const text = 'Settings changed by device "Anna\'s phone": FloatVoltage 13.5 → 13.4; rpmCapCurrentTable point 4 40 → 45';
  assert.equal(P.eventText({ text, code: "Message", reason: "NONE" }), text);
});

await test("pairing refusals in words the owner can act on (item 15)", () => {
  assert.match(A.pairingError(403, { error: "wrong or expired pairing code", tries_left: 4 }), /^Wrong or expired code — 4 tries left/);
  assert.match(A.pairingError(403, { tries_left: 1 }), /1 try left/);
  assert.match(A.pairingError(429, { retry_after_s: 300 }), /locked for 5 min.*xregulatord --pair/);
  assert.match(A.pairingError(409, {}), /revoke one/);
  assert.match(A.pairingError(503, {}), /cannot save/);
  // A window another device used, or a device off the boat's network: the server's words, not "15 minutes are over".
  assert.match(A.pairingError(403, { error: "a pairing code is needed: the pairing window was already used by device \"Skipper\" (1a2b3c4d) from 192.168.4.20; if that was not you, ask the owner for a code", claimed_by: "x" }),
    /^A pairing code is needed: the pairing window was already used by device "Skipper"/);
  assert.match(A.pairingError(403, { error: "pairing without a code is only for a device on the boat's own network (203.0.113.5 is not); pair with the 6-digit code from the journal or from a paired phone" }),
    /^Pairing without a code is only for a device on the boat's own network/);
  assert.match(A.pairingError(403, { error: "a pairing code is needed: no pairing window is open" }), /15 minutes/);
  assert.equal(A.guessDeviceName("Mozilla/5.0 (iPhone; CPU iPhone OS 17_0 like Mac OS X)"), "iPhone");
  assert.equal(A.guessDeviceName("Mozilla/5.0 (Linux; Android 14; Pixel 8) Mobile Safari"), "Android phone");
});

await test("a paired phone's QR code: its address carries the code in the fragment, read back exactly", () => {
  const code = "0123456789abcdef0123456789abcdef";
  const url = Q.pairingUrl(code, { origin: "http://192.168.4.1:8080", pathname: "/" });
  assert.equal(url, "http://192.168.4.1:8080/#pair=" + code);
  assert.equal(Q.qrCodeFromAddress(new URL(url).hash), code);
  for (const bad of ["", "#system", "#pair=", "#pair=123456", `#pair=${code}0`, `#pair=${code.toUpperCase()}`, `#pair=${code}&x=1`])
    assert.equal(Q.qrCodeFromAddress(bad), "", bad);
  // A used or expired QR code is told as such, not as 6 digits to check.
  assert.match(A.pairingError(403, { tries_left: 3 }, true), /QR code was used already or has expired/);
  assert.match(A.pairingError(429, { retry_after_s: 300 }, true), /locked for 5 min/);
});

await test("the Settings notice is one line; which values fold out in plain labels and the display unit", () => {
  const ps = [{ name: "FloatVoltage", value: 13.4, file: 13.5, unit: "V", overridden: true, changed: true },
    { name: "UseFloat", value: false, file: true, overridden: true, changed: true },
    { name: "TemperatureLimitF", value: 194, file: 150, unit: "degF", overridden: true, changed: true },
    { name: "BulkVoltage", value: 14.4, file: 14.4, overridden: false, changed: true }];
  assert.equal(S.fileNotice(ps), "3 values set on the dashboard differ from the file.");
  assert.equal(S.fileNotice([ps[0]]), "1 value set on the dashboard differs from the file.");
  assert.deepEqual(S.noticeItems(ps, "C"), ["Float voltage: 13.4 V here, 13.5 V in the file",
    "Float after absorption: off here, on in the file", "Alternator temperature limit: 90 °C here, 65.6 °C in the file"]);
  assert.match(S.noticeItems(ps, "F")[2], /194 °F here, 150 °F in the file/);
  assert.equal(S.fileNotice([ps[3]]), "");
});

await test("Default is the battery profile's value where the server gives one", () => {
  assert.equal(S.defaultOf({ default: 14.6, effective_default: 28.8 }), 28.8);
  assert.equal(S.defaultOf({ default: 14.6 }), 14.6);
  assert.equal(S.labelOf({ name: "AbsorptionVoltage" }), "Absorption voltage");
  assert.equal(S.labelOf({ name: "VoltageDisagreeThreshold" }), "VoltageDisagreeThreshold");
});

await test("°F settings show, and are typed, in °C when °C is chosen; margins convert without the offset", async () => {
  const U = await mod("web/www/js/settings_units.js");
  const lim = U.unitView({ name: "TemperatureLimitF", unit: "degF" }, "C");
  assert.equal(lim.unit, "°C");
  assert.equal(lim.show(194), 90);
  assert.equal(lim.back(90), 194);
  const margin = U.unitView({ name: "TempWarnExcess", unit: "degF" }, "C");
  assert.equal(margin.show(9), 5);
  assert.equal(margin.back(5), 9);
  assert.equal(U.unitView({ name: "TemperatureLimitF", unit: "degF" }, "F").unit, "°F");
  assert.equal(U.unitView({ name: "ChargeMinTempC", unit: "degC" }, "F").unit, "°C");
  assert.equal(U.plainUnits("resumes 3 degC below; 120 degF"), "resumes 3 °C below; 120 °F");
});

await test("the Alternator page's bands read in the display unit, °C rounded to 5", async () => {
  const Hh = await mod("web/www/js/health.js");
  assert.deepEqual([150, 175, 200, 225].map((f) => Hh.bandLabel(f, "C")), ["65 °C", "80 °C", "95 °C", "105 °C"]);
  assert.deepEqual([150, 225].map((f) => Hh.bandLabel(f, "F")), ["150 °F", "225 °F"]);
});

await test("the badge says Off only when someone switched it off; a weather hold reads Solar first", () => {
  const off = { mode: "MODE_DISABLED_RAMP", control: { sys_mode: "SYS_MODE_OFF" } };
  assert.equal(N.ownerMode({ ...off, reason: "REASON_SYS_OFF" }), "Off");
  assert.equal(N.ownerMode({ ...off, reason: "REASON_WEATHER_MODE" }), "Solar first");
  assert.equal(N.ownerMode({ ...off, reason: "REASON_IDLE_STAGE" }), "Auto");
  // An engine stop comes before the operator's Off in the regulator's order: it may hide an Off, so it is not "Auto".
  assert.equal(N.ownerMode({ ...off, reason: "REASON_RPM_LOW" }), "Off");
});

await test("the weather panel: the decision in force now, a failed fetch as a note with its time", async () => {
  const W = await mod("web/www/js/weather.js");
  const w = { last_error: "Connection refused: weather mode off, charging as usual; next try in 60 s",
    values: { sunny_days: 3, uv_threshold: 6, active: 1, age_s: 2400, failed_s_ago: 120 } };
  assert.match(W.verdict(w, "REASON_WEATHER_MODE"), /^Holding the alternator off: 3 of 3 days above UV 6\.0/);
  assert.doesNotMatch(W.verdict(w, "NONE"), /refused/);
  assert.equal(W.fetchNote(w), "The last forecast fetch failed 2 min ago (Connection refused: weather mode off, charging as usual); " +
    "the forecast from 40 min ago stays in force.");
  assert.equal(W.fetchNote({ ...w, values: { ...w.values, failed_s_ago: null } }), "", "a later success clears the note");
  assert.equal(W.verdict({ values: { age_s: null } }, "NONE"), "Charging as usual: no forecast yet.");
});

await test("the hero: the regulator's one number when it sends it, else the battery voltage", () => {
  const s = { mode: "MODE_NORMAL_AUTO_PID", stage: "bulk", field_enable: true, alt_a: 60, battery_v: 13.234, bcur_a: 42 };
  // No owner model yet (an older frame): the battery voltage, and no state word the page would
  // have to derive itself.
  assert.deepEqual(L.heroOf(s), { value: "13.23", unit: "V", label: "Battery", state: "—" });
  const o = L.heroOf({ ...s, owner: { state: "Bulk", hero: { value: 42.04, unit: "A", label: "into the battery" } } });
  assert.deepEqual(o, { value: "42.0", unit: "A", label: "into the battery", state: "Bulk" });
});

await test("events: a date header per day", async () => {
  const Ev = await mod("web/www/js/events.js");
  const now = new Date(2026, 11, 6, 12, 0).getTime() / 1000;
  assert.match(Ev.dayHeader(now - 3600, now), /^Today · /);
  assert.match(Ev.dayHeader(now - 86400, now), /^Yesterday · /);
  assert.doesNotMatch(Ev.dayHeader(now - 3 * 86400, now), /Today|Yesterday|2026/);
  assert.match(Ev.dayHeader(now - 400 * 86400, now), /2025$/);
  assert.equal(Ev.dayHeader(0, now), "Time since the regulator started");
});

await test("the headline is the regulator's own state words (owner.state), then the current and the power", () => {
  const base = { mode: "MODE_NORMAL_AUTO_PID", stage: "bulk", field_enable: true, alt_a: 60, battery_v: 13.2 };
  const owner = (state, value, label) => ({ state, hero: { value, unit: "A", label }, soc: { pct: null, source: "unknown" }, limits: [] });
  assert.equal(L.headline({ ...base, owner: owner("Charging · Bulk", 42, "into the battery") }),
    "Charging · Bulk · 42 A into the battery · 792 W");
  assert.equal(L.headline({ ...base, owner: owner("Alternator on · Bulk", 6, "out of the battery") }),
    "Alternator on · Bulk · 6 A still from the battery · 792 W");
  // Resting: the hero is a SoC or a voltage, not part of the sentence.
  assert.equal(L.headline({ ...base, owner: { state: "Not charging · Engine stopped or idling", hero: { value: 12.8, unit: "V", label: "battery" }, limits: [] } }),
    "Not charging · Engine stopped or idling");
  // No owner model (an old frame): no made-up words.
  assert.equal(L.headline(base), "—");
  assert.equal(L.limitText({ what: "C/10 without a battery probe", amps: 28.04 }), "C/10 without a battery probe: 28 A");
  assert.equal(L.limitText({ what: "Manual mode", amps: null }), "Manual mode");
});

await test("the System page's CAN rows say the BMS and NMEA 2000 state in words, never invent a value", () => {
  const off = P.canRows({ state: "off", protocol: null }, { state: "off", claimed: false, address: null });
  assert.deepEqual(off.map((r) => r[1]), ["not set up", "not set up"]);
  const rows = P.canRows(
    { state: "talking", protocol: "rec", cvl_v: 14.2, ccl_a: 50, soc_pct: null, cell_max_v: 3.412, age_s: 0.4,
      bad_frames: 3 },
    { state: "claimed", claimed: true, address: 35, tx_frames: 120, rx_frames: 40 });
  const m = Object.fromEntries(rows.map((r) => [r[0], r[1]]));
  assert.equal(m["Battery BMS"], "talking (rec)");
  assert.equal(m["BMS limits"], "charge voltage 14.20 V, charge current 50.0 A, SoC —");
  assert.equal(m["Highest cell"], "3.412 V");
  assert.equal(m["Limits received"], "0 s ago");
  assert.equal(m["Bad BMS frames ignored"], 3);
  assert.equal(m["NMEA 2000"], "on the network, address 35");
  const silent = Object.fromEntries(P.canRows({ state: "silent", protocol: "victron", age_s: null }, null)
    .map((r) => [r[0], r.slice(1)]));
  assert.deepEqual(silent["Battery BMS"], ["connected, but the BMS sends nothing (victron)", "bad"]);
  assert.equal(silent["Limits received"][0], "never");
  assert.equal(silent["Highest cell"], undefined);  // a BMS that does not send it: no row
});

await test("the SoC tile shows the regulator's one SoC (owner.soc): unknown is a word, a guess is marked", () => {
  const o = (pct, source) => ({ owner: { soc: { pct, source } } });
  const bms = L.socDisplay(o(81.6, "bms"), { soc_known: false });
  assert.deepEqual([bms.text, bms.unit, bms.note], ["82", "%", "from the BMS"]);
  for (const s of [o(null, "unknown"), o(50, "unknown"), {}]) {
    const u = L.socDisplay(s, {});
    assert.equal(u.text, "unknown");
    assert.equal(u.unit, "");
    assert.ok(u.guess);
  }
  const guess = L.socDisplay(o(63.2, "counted"), { soc_known: false });
  assert.equal(guess.text, "≈ 63");
  assert.ok(guess.guess);
  const ocv = L.socDisplay(o(70, "ocv_estimate"), { soc_known: true });
  assert.equal(ocv.text, "≈ 70");
  assert.match(ocv.note, /estimate from voltage/);
  const counted = L.socDisplay(o(91.4, "counted"), { soc_known: true, time_to_full_charge_min: 30 });
  assert.deepEqual([counted.text, counted.guess], ["91", false]);
  assert.match(counted.note, /^counted, full in/);
});

await test("the event filter shows a level at or above the chosen one", () => {
  assert.ok(P.levelShown("Info", "debug"));
  assert.ok(!P.levelShown("Info", "warning"));
  assert.ok(P.levelShown("Warning", "warning"));
  assert.ok(P.levelShown("Critical", "error"));
  assert.ok(!P.levelShown("Warning", "error"));
  assert.ok(!P.levelShown("Debug", "info"));
  assert.ok(P.levelShown("Something new", "error"));  // an unknown level is never hidden
});

// One thermal fault as the daemon stores it (scenarios/faults-tour.toml: the
// alternator sensor reads 170 F at 900 s and is fixed at 1000 s), between a
// command before it and the engine stopping 200 s after it.
const E = await mod("web/www/js/events.js");
const ev = (id, t, level, code, reason, text) => ({ id, t_s: t, wall_time_s: 1.7e9 + t, level, code, reason, text });
const thermal = [
  ev(21, 850, "info", "CommandApplied", "NONE", "Command auto applied"),
  ev(22, 900, "error", "ProtectionTrip", "REASON_TEMP_WARNING", "Temperature warning: 170.0 F > 152.0 F. Ramping field down"),
  ev(23, 900, "critical", "ProtectionTrip", "REASON_TEMP_CRITICAL", "Temperature critical: 170.0 F > 160.0 F. Field shut off!"),
  ev(24, 900, "warning", "ModeChanged", "REASON_TEMP_CRITICAL", "Exiting normal mode: TEMP_CRITICAL"),
  ev(25, 900, "critical", "ImmediateCut", "REASON_TEMP_CRITICAL", "GPIO4 immediate cut: TEMP_CRITICAL"),
  ev(26, 900, "info", "FieldOff", "REASON_TEMP_CRITICAL", "Field disabled (GPIO4 LOW): TEMP_CRITICAL"),
  ev(27, 900, "warning", "AlarmCondition", "NONE", "ALARM: Field protection active (0.00, limit 0.00)"),
  ev(28, 900, "warning", "AlarmOn", "NONE", "Alarm ON"),
  ev(29, 930, "warning", "AlarmCondition", "NONE", "ALARM: Field protection active (0.00, limit 0.00)"),
  ev(30, 960, "warning", "AlarmCondition", "NONE", "ALARM: Field protection active (0.00, limit 0.00)"),
  ev(31, 1000, "info", "ModeChanged", "NONE", "Entering normal mode"),
  ev(32, 1000, "info", "FieldOn", "NONE", "Field enabled (GPIO4 HIGH)"),
  ev(33, 1000, "info", "ProtectionClear", "REASON_TEMP_WARNING", "Protection cleared: TEMP_WARNING"),
  ev(34, 1000, "info", "ProtectionClear", "REASON_TEMP_CRITICAL", "Protection cleared: TEMP_CRITICAL"),
  ev(35, 1001, "info", "AlarmOff", "NONE", "Alarm OFF"),
  ev(36, 1200, "info", "ProtectionTrip", "REASON_RPM_LOW", "RPM below minimum: 199 < 200 RPM. Field off"),
  ev(37, 1200, "warning", "ModeChanged", "REASON_RPM_LOW", "Exiting normal mode: RPM_LOW"),
  ev(38, 1200, "info", "FieldOff", "REASON_RPM_LOW", "Field disabled (GPIO4 LOW): RPM_LOW"),
];

await test("one thermal fault is one incident row: what happened, what the regulator did, what to do", () => {
  const rows = E.groupIncidents(thermal);
  assert.equal(rows.length, 3, rows.map((r) => (r.incident ? r.incident.title : r.event.code)).join(" | "));
  assert.equal(rows[0].event.code, "CommandApplied");
  const hot = rows[1].incident;
  assert.equal(hot.title, N.REASONS.REASON_TEMP_CRITICAL.title);
  assert.equal(hot.level, "critical");
  assert.equal(hot.events.length, 14);
  assert.equal(hot.action, N.REASONS.REASON_TEMP_CRITICAL.action);
  assert.match(hot.did, /cut the field at once.*sounded the alarm.*resumed charging/);
  assert.equal(hot.over, "Over after 2 min.");
  const rpm = rows[2].incident;
  assert.equal(rpm.title, N.REASONS.REASON_RPM_LOW.title);
  assert.equal(rpm.over, "Still acting.");
});

await test("an incident ends: a trip after its clears and settle time, or long after its last event, is a new row", () => {
  const later = thermal.slice(1, 15).map((e) => ({ ...e, id: e.id + 100, t_s: e.t_s + 700, wall_time_s: e.wall_time_s + 700 }));
  assert.equal(E.groupIncidents([...thermal.slice(1, 15), ...later]).length, 2);
  // Just inside the settle time after the last clear, the buzzer going quiet still belongs to it.
  const quiet = { ...thermal[14], id: 99, t_s: 1004.9, wall_time_s: 1.7e9 + 1004.9 };
  assert.equal(E.groupIncidents([...thermal.slice(1, 14), quiet]).length, 1);
  assert.equal(E.groupIncidents([...thermal.slice(1, 14), { ...quiet, t_s: 1005.1, wall_time_s: 1.7e9 + 1005.1 }]).length, 2);
});

const H = await mod("web/www/js/history.js");
await test("the History page: days oldest first, blanks where unknown, the display unit, a line per day", () => {
  const days = [
    { day: "2026-07-02", alt_ah: 40, alt_wh: 560, battery_ah_in: 35, battery_wh_in: 480, bulk_h: 1.25, absorption_h: 0.5,
      float_h: 2, engine_h: 3.8, v_min: 12.41, v_max: 14.4, soc_start_pct: 61, soc_end_pct: 97, peak_alt_temp_c: 88.4 },
    { day: "2026-07-01", alt_ah: 4.2, alt_wh: 58, bulk_h: 0.1, absorption_h: 0, float_h: 0, peak_alt_temp_c: null,
      soc_start_pct: null, soc_end_pct: null, engine_h: null },
  ];
  const c = H.dayColumns(days, "F");
  assert.deepEqual(c.days, ["2026-07-01", "2026-07-02"]);
  assert.deepEqual(c.kwhIn, [null, 0.48]);
  assert.deepEqual(c.socStart, [null, 61]);
  assert.deepEqual(c.peak, [null, 88.4 * 1.8 + 32]);
  assert.ok(c.x[1] - c.x[0] >= 23 * 3600 && c.x[1] - c.x[0] <= 25 * 3600);
  assert.equal(H.dayLine(days[0], "C"),
    "2026-07-02 · 40 Ah · 0.56 kWh · battery 12.41 V–14.40 V · SoC 61 % → 97 % · engine 3.8 h · alternator up to 88 °C");
  assert.equal(H.dayLine(days[1], "F"),
    "2026-07-01 · 4.2 Ah · 0.06 kWh · battery —–— · SoC — → — · engine — · alternator up to —");
  assert.equal(H.duration(80), "1 h 20 min");
  assert.equal(H.duration(45), "45 min");
  assert.equal(H.duration(119.7), "2 h 0 min");
  assert.equal(H.endedBy({ open: true }), "still charging");
  assert.equal(H.endedBy({ open: false, ended_by: "STOPPED" }), "the regulator stopped");
  assert.equal(H.endedBy({ open: false, ended_by: "REASON_RPM_LOW" }), N.REASONS.REASON_RPM_LOW.title);
});

const HL = await mod("web/www/js/health.js");
await test("the one-tap capacity offer never proposes a value the set-up would refuse", () => {
  const range = { min: 1, max: 100000 };
  assert.deepEqual(HL.capacityOffer(170, 200, range), { useAh: 170, pct: -15 });
  assert.equal(HL.capacityOffer(195, 200, range), null);  // within 10 %: nothing to offer
  // The reproducers: a damaged ledger's 1e11 Ah, 0 Ah, and a sum that lands
  // inside the parameter's range (50,000 Ah) but 250x the setting.
  assert.equal(HL.capacityOffer(1e11, 200, range), null);
  assert.equal(HL.capacityOffer(0, 200, range), null);
  assert.equal(HL.capacityOffer(50000, 200, range), null);
  // At the 0.3x-2x bounds and just beyond.
  assert.equal(HL.capacityOffer(60, 200, range).useAh, 60);
  assert.equal(HL.capacityOffer(59.9, 200, range), null);
  assert.equal(HL.capacityOffer(400, 200, range).useAh, 400);
  assert.equal(HL.capacityOffer(400.1, 200, range), null);
  assert.equal(HL.capacityOffer(150000, 90000, range), null);  // beyond the parameter's maximum
});

const SH = await mod("web/www/js/setup_hardware.js");
const FMT = await mod("web/www/js/format.js");
await test("html`` escapes every value: the set-up result table's hardware rows", () => {
  const hostile = { running: "<img src=x onerror=alert(1)>", next: "<b>x</b>", restart_needed: true };
  const rows = SH.hardwareRows({ battery_temp_sensor: hostile, bms_interface: hostile,
    pulley_ratio: { running: 2.5, next: 2.5, restart_needed: false } });
  const html = FMT.html`${rows.map(([k, x]) => FMT.html`<tr><th>${k}</th><td>${x}</td></tr>`)}`.text;
  assert.ok(!/<img|<b>/.test(html), html);
  assert.match(html, /&lt;img src=x onerror=alert\(1\)&gt;/);
  assert.match(html, /<tr><th>Battery temperature probe<\/th>/, "the template's own markup stays");
});
await test("the set-up's hardware step shows probe ids and interface names as text, never as markup", () => {
  const step = SH.renderHardwareStep({
    probes: ["28-<img src=x onerror=alert(1)>", "28-ok"], alternator_sensor: "<b>alt</b>",
    can_interfaces: ['can0"><script>alert(1)</script>'], victron_bms: false, savable: true,
    battery_temp_sensor: { next: "", file: "" }, bms_interface: { next: "", file: "" },
    pulley_ratio: { next: "2\" onfocus=\"alert(1)", file: 1 } }, 5, null).text;
  assert.ok(!/<img|<script|<b>|" onfocus=/.test(step), step);
  assert.match(step, /28-&lt;img src=x onerror=alert\(1\)&gt;/);
  assert.match(step, /can0&quot;&gt;&lt;script&gt;/);
  assert.match(step, /\(&lt;b&gt;alt&lt;\/b&gt;\)/);
});
await test("setHtml takes only an html`` template, never a plain string", () => {
  assert.throws(() => FMT.setHtml({}, "<b>raw</b>"), TypeError);
});
await test("no file of the dashboard assigns innerHTML but setHtml", () => {
  const dir = path.join(root, "web/www/js");
  for (const f of fs.readdirSync(dir).filter((x) => x.endsWith(".js"))) {
    const uses = (fs.readFileSync(path.join(dir, f), "utf8").match(/\.innerHTML\s*=/g) || []).length;
    assert.equal(uses, f === "format.js" ? 1 : 0, `${f}: innerHTML assignments`);
  }
});

console.log(`${n} dashboard unit tests passed`);
