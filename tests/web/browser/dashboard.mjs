// Browser test of the dashboard (docs/dashboard.md): playwright-core drives
// Debian's /usr/bin/chromium (never a downloaded browser) against
//   --mode fake    xr_web_testserver (fake DaemonApi): loading, charts, editing
//   --mode daemon  xregulatord --sim --speed 1: everything a user does (docs/dashboard.md
//                  "Done when"), at phone (390x844) and desktop sizes.
// Screenshots go to --artifacts DIR; --docs-dir DIR also copies the phone
// screenshots docs/dashboard.md shows (web/tools/dashboard-screenshots.sh).
import { createRequire } from "node:module";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import assert from "node:assert/strict";
import { startServer } from "./server.mjs";
import { daemonChecks } from "./daemon_checks.mjs";

const args = Object.fromEntries(
  process.argv.slice(2).reduce((acc, a, i, all) => (a.startsWith("--") ? [...acc, [a.slice(2), all[i + 1]]] : acc), []));
const webDir = path.resolve(args["web-dir"]);
const artifacts = args.artifacts;
const token = args.token || "browser-test-token";
const mode = args.mode || "fake";  // fake | daemon
const require = createRequire(path.join(webDir, "package.json"));
const { chromium } = require("playwright-core");
fs.mkdirSync(artifacts, { recursive: true });

const stateDir = fs.mkdtempSync(path.join(os.tmpdir(), "xr-browser-"));
const server = await startServer({ mode, args, token, stateDir });
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "xr-chromium-"));
let context;
let failed = false;
const servers = [server];
try {
  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: "/usr/bin/chromium",
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
           "--disable-component-update", "--disable-sync"],
    viewport: { width: 1100, height: 900 },
    acceptDownloads: true,
    locale: "en-GB",
  });
  const page = context.pages()[0] || (await context.newPage());
  const consoleErrors = [];
  // Script errors only: failed requests (the deliberate 400s below) are checked explicitly.
  page.on("console", (m) => { if (m.type() === "error" && !/Failed to load resource|WebSocket connection/.test(m.text())) consoleErrors.push(m.text()); });
  page.on("pageerror", (e) => consoleErrors.push(String(e)));
  page.setDefaultTimeout(20000);
  const shot = (name, opts = {}) => page.screenshot({ path: path.join(artifacts, `${name}-${mode}.png`), ...opts });

  // 1. Loads and goes live, with a headline in words.
  await page.goto(server.base + "/");
  await page.waitForSelector("#conn.on");
  await page.waitForFunction(() => /\d+\.\d\d/.test(document.getElementById("v-battery_v").textContent));
  assert.match(await page.textContent("#headline"), /^(Not set up · )?(Charging|Alternator on|Not charging)/);
  assert.match(await page.textContent("#v-temp"), /°[CF]/);
  assert.doesNotMatch(await page.textContent("#hdr-mode"), /MODE_|SYS_/);
  console.log("ok - dashboard loads, live values and a headline: " + (await page.textContent("#headline")));

  // 2. Values update live: the frame sequence advances.
  const seq0 = Number(await page.getAttribute("body", "data-seq"));
  await page.waitForFunction((s) => Number(document.body.dataset.seq) >= s + 3, seq0);
  console.log("ok - values update live over the WebSocket");

  // 3. The live chart draws; its legend shows values without hovering; the
  //    voltage axis spans at least 1 V (noise does not look like swings).
  // Each chart says what it shows (role="img", its label and data-* attributes).
  const chartData = (id, key) => page.evaluate(([i, k]) => document.getElementById(i).dataset[k], [id, key]);
  await page.waitForFunction(() => Number(document.getElementById("chart-live").dataset.points || 0) >= 3);
  assert.match(await page.getAttribute("#chart-live", "aria-label"), /^Live chart, battery volts and amps: \d+ points from /);
  const painted = await page.evaluate(() => {
    const c = document.querySelector("#chart-live canvas");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 3; i < d.length; i += 4) if (d[i] > 0) n++;
    return n;
  });
  assert.ok(painted > 500, `live chart canvas painted ${painted} pixels`);
  await page.waitForFunction(() => {
    const legend = [...document.querySelectorAll("#chart-live .u-legend .u-value")].slice(1).map((e) => e.textContent);
    return legend.length === 3 && legend.every((t) => /\d/.test(t));
  });
  assert.ok(Number(await chartData("chart-live", "vspan")) >= 1.0);
  if (mode === "fake") {
    await page.waitForFunction(() => Number(document.getElementById("chart-history").dataset.points || 0) > 100 &&
      Number(document.getElementById("chart-env").dataset.points || 0) > 100);
    // Their legends show the newest values with a number, though the newest
    // bucket is still empty.
    for (const id of ["chart-history", "chart-env"])
      await page.waitForFunction((i) => {
        const legend = [...document.querySelectorAll(`#${i} .u-legend .u-value`)].slice(1).map((e) => e.textContent);
        return legend.length === 3 && legend.every((t) => /\d/.test(t));
      }, id);
    // A finger that touches the chart and leaves, or a turned phone: uPlot
    // resets its legend to the cursor (none); the newest values come back.
    await page.locator("#chart-history .u-over").hover({ position: { x: 40, y: 60 } });
    await page.locator("#hist-range").hover();
    const size = page.viewportSize();
    await page.setViewportSize({ width: 700, height: size.height });
    await page.setViewportSize(size);
    for (const id of ["chart-history", "chart-env"])
      await page.waitForFunction((i) => [...document.querySelectorAll(`#${i} .u-legend .u-value`)].every((e) => /\d/.test(e.textContent)), id);
    // A steady temperature and engine speed look steady: the temperature axis
    // spans at least 10 degrees, the RPM line runs from 0 to at least 3000.
    assert.ok(Number(await chartData("chart-env", "tspan")) >= 10, `temperature axis ${await chartData("chart-env", "tspan")}`);
    const [rpmLo, rpmHi] = (await chartData("chart-env", "rpmAxis")).split("-").map(Number);
    assert.ok(rpmLo === 0 && rpmHi >= 3000, `RPM axis ${rpmLo}-${rpmHi}`);
    console.log("ok - history charts draw volts/amps and temperature/SoC/RPM from /api/history, newest values shown, steady lines flat");
  } else {
    await page.waitForFunction(() => document.getElementById("hist-msg").textContent !== "" ||
      Number(document.getElementById("chart-history").dataset.points || 0) > 0);
    assert.doesNotMatch(await page.textContent("#hist-msg"), /unknown series/);
  }
  await shot("dashboard-live", { fullPage: true });
  console.log("ok - live chart draws, legend readable without hover, voltage axis >= 1 V");

  if (mode === "daemon") {
    await daemonChecks({ page, context, server, servers, token, artifacts, args, stateDir, shot });
  } else {
    await fakeChecks(page);
  }
  assert.deepEqual(consoleErrors, []);
} catch (e) {
  failed = true;
  console.error("FAIL:", e);
  for (const s of servers) console.error("server log:\n" + s.log().slice(-4000));
} finally {
  if (context) await context.close().catch(() => {});
  for (const s of servers) if (s.proc.exitCode === null) s.proc.kill("SIGTERM");
  fs.rmSync(userDataDir, { recursive: true, force: true });
  fs.rmSync(stateDir, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);

// Against the fake: the settings editor's kinds (bool, table) and the token.
async function fakeChecks(page) {
  await page.goto(server.base + "/#settings");
  await page.check("#param-advanced");
  const cb = page.locator('.param[data-name="UseFloat"] input[type="checkbox"]');
  await cb.uncheck();
  const cells = page.locator('.param[data-name="rpmCapCurrentTable"] input');
  assert.equal(await cells.count(), 10);
  await cells.nth(4).fill("42,5");
  await page.click("#param-apply");
  // The installer's token instead of a pairing code (the fake has no journal).
  await page.waitForSelector("#pair-dialog[open]");
  await page.click("#pair-dialog summary");
  await page.fill("#token-input", token);
  await page.click("#pair-ok");
  await page.waitForFunction(() => document.getElementById("param-msg").textContent.startsWith("Applied"));
  const params = (await (await fetch(server.base + "/api/params")).json()).params;
  assert.equal(params.find((p) => p.name === "UseFloat").value, false);
  assert.equal(params.find((p) => p.name === "rpmCapCurrentTable").value[4], 42.5);
  console.log("ok - a bool switch and an RPM table cell (comma decimal) apply");
  await page.setViewportSize({ width: 390, height: 844 });
  for (const p of ["live", "settings", "protections", "battery", "alternator", "tuning", "events", "system", "setup"]) {
    await page.goto(server.base + "/#" + p);
    await page.waitForSelector(`#page-${p}:not([hidden])`);
    await page.screenshot({ path: path.join(artifacts, `phone-${p}-${mode}.png`), fullPage: true });
  }
  console.log("ok - pages render on a phone screen; screenshots in " + artifacts);
  await eventsOnPhone(page);
}

// At 390 px the Time ("3 Dec 14:05") and Level cells keep one line each, and
// the level filter hides the rows below the chosen level.
async function eventsOnPhone(page) {
  await page.goto(server.base + "/#events");
  await page.waitForSelector("#events-body tr");
  const lines = await page.evaluate(() => [...document.querySelectorAll("#events-body tr:not(.day-head)")].slice(0, 40).flatMap((tr) =>
    [0, 1].map((i) => { const r = document.createRange(); r.selectNodeContents(tr.cells[i]); return r.getClientRects().length; })));
  assert.ok(lines.length > 0);
  assert.ok(lines.every((n) => n === 1), "Time/Level cells wrap: " + lines.join(","));
  const before = await page.locator("#events-body tr:not([hidden]):not(.day-head)").count();
  await page.selectOption("#events-level", "warning");
  const shown = await page.$$eval("#events-body tr:not([hidden]):not(.day-head)", (rows) => rows.map((r) => r.dataset.level));
  assert.ok(shown.every((l) => ["warning", "error", "critical"].includes(l)), "filter shows " + shown.join(","));
  if (mode === "fake") assert.ok(shown.length > 0 && shown.length < before, `${shown.length} of ${before} rows shown`);
  await page.selectOption("#events-level", "debug");
  console.log(`ok - events at 390 px: Time and Level on one line; "warnings and worse" shows ${shown.length} of ${before}`);
}
