// History at a glance and trends over a season (docs/dashboard.md "History",
// "Trends"), in Debian's Chromium against the real daemon in --sim, started
// on a state database that xr_history_fill filled with a simulated year
// through the daemon's own store code (the last 30 days every 30 s): the
// History page draws 30 days of bars, a tap on a day opens its charges, the
// Trends page draws a year, and the CSV export answers a range and refuses a
// bad one.
import { execFileSync } from "node:child_process";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";
// Filled in memory (/dev/shm where there is one): the store's commits are
// durable on a disk, and a year of them would wait on the disk for minutes.
const fillDir = fs.mkdtempSync(path.join(fs.existsSync("/dev/shm") ? "/dev/shm" : os.tmpdir(), "xr-history-fill-"));
const filledDb = path.join(fillDir, "state.db");
const t0 = Date.now();
console.log(execFileSync(args.fill, ["--state-db", filledDb, "--days", "365", "--fine-days", "30"]).toString().trim());
console.log(`# filled in ${((Date.now() - t0) / 1000).toFixed(1)} s`);

// Pixels of a chart's canvas in a colour (r, g, b within 60): what was drawn.
const inked = (page, title, rgb) => page.evaluate(([title, rgb]) => {
  const c = document.querySelector(`.history-chart[data-title="${title}"] canvas`);
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let n = 0;
  for (let i = 0; i < d.length; i += 4)
    if (d[i + 3] > 0 && Math.abs(d[i] - rgb[0]) < 60 && Math.abs(d[i + 1] - rgb[1]) < 60 && Math.abs(d[i + 2] - rgb[2]) < 60) n++;
  return n;
}, [title, rgb]);
const BLUE = [0x3f, 0x7f, 0xff];
// The tick labels uPlot drew on a chart's axes (on the canvas, so not in the DOM).
const ticks = (page, title) => page.evaluate((title) =>
  document.querySelector(`.history-chart[data-title="${title}"]`).uplot.axes.map((a) => (a._values || []).join(" ")), title);

await runDaemonBrowserTest({ args, token, prefix: "xr-history-", seedState: filledDb }, async ({ server, browser, stateDir, get }) => {
  const api = await get("/api/history/days?n=30");
  assert.equal(api.days.length, 30, "30 days in the store");
  const charged = api.days.filter((d) => d.alt_ah > 1);
  assert.ok(charged.length >= 15, `most days have a charge (${charged.length})`);
  for (const d of charged) {
    assert.ok(d.v_min > 11 && d.v_max <= 14.5 && d.v_min < d.v_max, JSON.stringify(d));
    assert.ok(d.engine_h > 0.9 && d.battery_wh_in > 0, JSON.stringify(d));
  }

  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#history");
  await page.waitForSelector('.history-chart[data-title="Into the bank"] canvas');
  assert.equal(await page.locator(".history-chart").count(), 4, "four charts of days");
  assert.equal(await page.locator("#history-days .day-line").count(), 30, "a line per day");
  const bars = await inked(page, "Into the bank", BLUE);
  assert.ok(bars > 500, `the Ah bars are drawn (${bars} px)`);
  const axes = await ticks(page, "Into the bank");
  assert.ok(axes.some((a) => / Ah/.test(a)) && axes.some((a) => / kWh/.test(a)), `units on the axes: ${axes}`);
  assert.ok(axes.some((a) => /\d{1,2} [A-Z][a-z]{2}/.test(a)), `dates on the time axis: ${axes}`);
  const dayLabels = new Set(api.days.map((d) => new Date(`${d.day}T12:00:00`).toLocaleDateString("en-GB", { day: "numeric", month: "short" })));
  const timeTicks = await page.evaluate(() =>
    document.querySelector('.history-chart[data-title="Into the bank"]').uplot.axes[0]._values);
  assert.ok(timeTicks.length >= 3 && timeTicks.every((t) => dayLabels.has(t)), `the time axis names days of the store: ${timeTicks}`);
  assert.match(await page.locator("#history-days .day-line").first().textContent(),
    /^\d{4}-\d\d-\d\d · .* Ah · .* kWh · battery .*V–.*V · SoC .* → .* · engine .* h · alternator up to .* °C$/);

  // A tap on a day with a charge opens its charges; the engine stop ended them.
  const day = charged[1].day;
  const want = await get(`/api/history/charges?day=${day}`);
  assert.ok(want.charges.length >= 1, JSON.stringify(want));
  await page.click(`#history-days .day-line[data-day="${day}"]`);
  await page.waitForSelector("#history-day:not([hidden]) #history-day-charges tr");
  assert.equal(await page.locator("#history-day-title").textContent(), `Charges on ${day}`);
  const rows = await page.locator("#history-day-charges tr").allTextContents();
  assert.equal(rows.length, want.charges.length, rows.join(" | "));
  assert.match(rows[0], /\d+ Ah, \d+\.\d\d kWh/);
  assert.match(rows[0], /bulk .* absorption .* float/);
  assert.match(rows[0], /\d+ % → \d+ %/);
  // A tap on the chart opens the day under the cursor too.
  const over = page.locator('.history-chart[data-title="Hours"] .u-over');
  await over.scrollIntoViewIfNeeded();
  const box = await over.boundingBox();
  await over.hover({ position: { x: box.width * 0.5, y: box.height * 0.5 } });
  await over.click({ position: { x: box.width * 0.5, y: box.height * 0.5 } });
  await page.waitForFunction((d) => !document.querySelector("#history-day-title").textContent.endsWith(d), day);
  assert.match(await page.locator("#history-day-title").textContent(), /^Charges on \d{4}-\d\d-\d\d$/);
  await page.screenshot({ path: path.join(stateDir, "history-30-days.png"), fullPage: true });
  if (args["docs-dir"]) fs.copyFileSync(path.join(stateDir, "history-30-days.png"), path.join(args["docs-dir"], "history-30-days.png"));
  console.log(`ok - History: 30 days of bars (${bars} px of Ah bars), ${day} opens ${rows.length} charge(s): ${rows[0]}`);

  // Trends: a year of daily rows, drawn.
  await page.goto(server.base + "/#trends");
  await page.waitForSelector('.history-chart[data-title="Battery voltage"] canvas');
  await page.click('#trends-range button[data-range="1y"]');
  await page.waitForFunction(() => document.querySelector('#trends-range button[data-range="1y"]').classList.contains("current"));
  const year = await get(`/api/history/trends?from=-${365 * 86400}&step=day`);
  assert.ok(year.t.length >= 360, `a year of daily rows (${year.t.length})`);
  await page.waitForTimeout(300);
  const line = await inked(page, "Battery voltage", BLUE);
  assert.ok(line > 300, `the year's battery voltage is drawn (${line} px)`);
  const taxis = await ticks(page, "Battery voltage");
  assert.ok(taxis.some((a) => / V/.test(a)), `volts on the axis: ${taxis}`);
  await page.screenshot({ path: path.join(stateDir, "trends-year.png"), fullPage: true });
  if (args["docs-dir"]) fs.copyFileSync(path.join(stateDir, "trends-year.png"), path.join(args["docs-dir"], "trends-year.png"));
  console.log(`ok - Trends: a year of ${year.t.length} days drawn (${line} px)`);

  // The CSV of a month: a header and one row an hour; a bad range is a 400.
  const csv = await (await fetch(server.base + `/api/history/export?from=-${30 * 86400}`)).text();
  const lines = csv.trim().split("\r\n");
  assert.match(lines[0], /^time_utc,time_unix_s,samples,battery_v_min,/);
  assert.ok(lines.length >= 700 && lines.length <= 722, `a month of hours (${lines.length - 1} rows)`);
  for (const q of ["from=x", "from=1780000000&to=1770000000", "step=week"])
    assert.equal((await fetch(server.base + `/api/history/export?${q}`)).status, 400, q);
  assert.deepEqual(errors, [], "no script error");
  console.log(`ok - export: ${lines.length - 1} hourly rows for 30 days; bad ranges refused`);
});
fs.rmSync(fillDir, { recursive: true, force: true });
