#!/usr/bin/env node
// NMEA 2000 cross-check (docs/integrations.md): the daemon runs a scenario in --sim with
// [can] n2k_interface set (the simulated N2K bus) and --can-log; canboatjs
// (@canboat/canboatjs from the npm registry, an independent decoder reading
// the canboat PGN database) decodes every logged frame of that bus, and
// each decoded 127508 / 127751 / 127506 / 127750 must match the daemon's
// CSV telemetry: voltage, current, SoC and operating state.
//
// Which row: the node reads the newest telemetry snapshot, which the
// control loop publishes every 40th tick at --speed max. The CSV is written
// at every tick (400 Hz), so the snapshot a message came from is one of
// the 40 rows up to the frame's time; one of them must match every field
// of the message within the PGN's resolution.
//
//   node n2k_check.mjs XREGULATORD scenarios/n2k-status.toml OUT_DIR
import { spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';

const require = createRequire(import.meta.url);
const { FromPgn } = require('@canboat/canboatjs');

const [daemon, scenario, outDir] = process.argv.slice(2);
if (!daemon || !scenario || !outDir) {
  console.error('usage: n2k_check.mjs XREGULATORD SCENARIO.toml OUT_DIR');
  process.exit(2);
}
mkdirSync(outDir, { recursive: true });
const cfg = path.join(outDir, 'n2k.toml');
const csvPath = path.join(outDir, 'n2k.csv');
const logPath = path.join(outDir, 'n2k.candump');
writeFileSync(cfg, '[can]\nn2k_interface = "can1"\nn2k_preferred_address = 35\n');

const DURATION_S = 150;
const run = spawnSync(daemon, ['--sim', '--config', cfg, '--scenario', scenario, '--speed', 'max',
  '--duration', String(DURATION_S), '--telemetry-csv', csvPath, '--telemetry-rate', '400',
  '--can-log', logPath, '--log-level', 'warn'], { encoding: 'utf8', maxBuffer: 1 << 26 });
if (run.status !== 0) {
  console.error(`daemon exited ${run.status}\n${run.stderr}`);
  process.exit(1);
}

// ---- the CSV ----
const lines = readFileSync(csvPath, 'utf8').trim().split('\n');
const head = lines[0].split(',');
const col = Object.fromEntries(head.map((h, i) => [h, i]));
const rows = lines.slice(1).map((l) => l.split(','));
const tOf = (r) => Number(r[col.t_s]);
const num = (r, k) => (r[col[k]] === '' ? NaN : Number(r[col[k]]));

// The 127750 operating state the telemetry stands for (n2k_node.cpp
// converterStateOf, restated here from docs/integrations.md).
function expectedState(r) {
  const mode = r[col.mode];
  if (['MODE_CRITICAL_RAMP', 'MODE_WARNING_RAMP_AND_LOCKOUT', 'MODE_LOCKOUT_RAMP'].includes(mode)) return 'Fault';
  if (mode === 'MODE_DISABLED_RAMP' || r[col.field_enable] !== '1') return 'Off';
  return { BULK: 'Bulk', ABSORPTION: 'Absorption', FLOAT: 'Float' }[r[col.stage]] ?? 'Off';
}

// ---- the log, decoded by canboatjs ----
const parser = new FromPgn({ checkForInvalidFields: true });
const decodeErrors = [];
parser.on('error', (pgn, error) => decodeErrors.push(`${pgn?.pgn}: ${error}`));
const messages = [];
let n2kFrames = 0;
for (const line of readFileSync(logPath, 'utf8').split('\n')) {
  const m = /^\((\d+\.\d+)\) (\S+) /.exec(line);
  if (!m || m[2] !== 'simcan1') continue;
  n2kFrames++;
  const msg = parser.parseString(line);
  if (msg) messages.push({ t: Number(m[1]), msg });
}

const failures = [];
const fail = (s) => { if (failures.length < 20) failures.push(s); };
const byPgn = (p) => messages.filter((x) => x.msg.pgn === p);
const counts = Object.fromEntries([60928, 126993, 127506, 127508, 127750, 127751].map((p) => [p, byPgn(p).length]));
if (counts[60928] < 1) fail('no address claim (60928)');
if (counts[126993] < 1) fail('no heartbeat (126993)');
for (const p of [127506, 127508, 127750, 127751]) {
  // every 1.5 s over the run, after the 250 ms claim wait
  if (counts[p] < Math.floor((DURATION_S - 1) / 1.5)) fail(`only ${counts[p]} messages of ${p} in ${DURATION_S} s`);
}
if (decodeErrors.length) fail(`canboatjs errors: ${decodeErrors.slice(0, 3).join('; ')}`);

// The rows a message may come from: the 40 ticks (0.1 s) up to its time.
function candidates(t) {
  return rows.filter((r) => tOf(r) <= t + 1e-9 && tOf(r) > t - 0.1 - 1e-9);
}
const near = (a, b, tol) => Number.isFinite(a) && Math.abs(a - b) <= tol;
const checks = {
  127508: (f, r) => near(f.voltage, num(r, 'battery_v'), 0.006) && near(f.current, num(r, 'bcur_a'), 0.06),
  127751: (f, r) => near(f.dcVoltage, num(r, 'battery_v'), 0.06) && near(f.dcCurrent, num(r, 'alt_a'), 0.006),
  // The one SoC (docs/dashboard.md "State of charge"): "not available" while the CSV's is empty.
  127506: (f, r) => (Number.isFinite(num(r, 'soc_pct')) ? near(f.stateOfCharge, num(r, 'soc_pct'), 0.51)
                                                        : f.stateOfCharge === undefined),
  127750: (f, r) => f.operatingState === expectedState(r),
};
let checked = 0;
for (const [pgn, ok] of Object.entries(checks)) {
  for (const { t, msg } of byPgn(Number(pgn))) {
    const rs = candidates(t);
    checked++;
    if (!rs.some((r) => ok(msg.fields, r))) {
      const r = rs[rs.length - 1];
      fail(`${pgn} at ${t.toFixed(3)} s: ${JSON.stringify(msg.fields)} matches none of the ${rs.length} rows before it ` +
        `(last: battery_v ${r && num(r, 'battery_v')} bcur_a ${r && num(r, 'bcur_a')} alt_a ${r && num(r, 'alt_a')} ` +
        `soc ${r && num(r, 'soc_pct')} state ${r && expectedState(r)})`);
    }
  }
}
const states = new Set(byPgn(127750).map((x) => x.msg.fields.operatingState));
// scenarios/n2k-status.toml goes through all four (bulk, absorption, the
// engine stopped, an over-temperature trip).
for (const want of ['Bulk', 'Absorption', 'Off', 'Fault']) {
  if (!states.has(want)) fail(`operating state ${want} never sent`);
}
console.log(`${n2kFrames} N2K frames, ${messages.length} messages decoded, ${checked} checked against the CSV; ` +
  `counts ${JSON.stringify(counts)}; operating states seen ${[...states].join(', ')}`);
if (failures.length) {
  for (const f of failures) console.log(`FAIL ${f}`);
  process.exit(1);
}
console.log('ok');
