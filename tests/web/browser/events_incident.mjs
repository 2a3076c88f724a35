// One thermal fault is one row on the Events page (docs/dashboard.md,
// Events), in Debian's Chromium at phone size against the real daemon in
// --sim: the alternator's sensor reads 170 °F (above the critical limit) from
// 8 s to 20 s. The daemon stores about fourteen events for it; the owner reads
// one row that names the fault, what the regulator did and what to do, with
// the events folded out under it.
import fs from "node:fs";
import path from "node:path";
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";

const scenario = `name = "a thermal fault"
duration_s = 3600
seed = 3
[battery]
chemistry = "agm"
capacity_ah = 300
soc_pct = 50
[engine]
rpm = 1700
[config]
BatteryProfile = "agm"
[[events]]
at_s = 8
fault = "temp_value"
value = 170
[[events]]
at_s = 20
clear = "temp_value"
`;

// The History check below expects one day of history. The daemon's clock
// starts at the wall clock and runs 4 times as fast, so a run started in the
// last minutes before local midnight would see the next day too: such a run
// first waits for midnight to pass (at most 240 s, and only then).
const untilMidnightMs = new Date().setHours(24, 0, 0, 0) - Date.now();
if (untilMidnightMs < 240000) {
  console.log(`# ${Math.ceil(untilMidnightMs / 1000)} s to midnight: waiting for the new day before the run`);
  await new Promise((resolve) => setTimeout(resolve, untilMidnightMs + 2000));
}

// At --speed 4: the fault's 12 s and the settle after it are simulated time.
await runDaemonBrowserTest({ args, token, scenario, prefix: "xr-incident-", speed: 4 }, async ({ server, browser, stateDir, get }) => {
  const cleared = async () => (await get("/api/events?limit=200")).events.some(
    (e) => e.code === "ProtectionClear" && e.reason === "REASON_TEMP_CRITICAL");
  await until("the thermal fault to trip and clear", cleared, 60000);
  await until("the field back on and the buzzer quiet", async () => {
    const st = await get("/api/status");
    return st.field_enable === true && Number(st.alarm) === 0;
  }, 30000);
  const stored = (await get("/api/events?limit=200")).events.filter((e) => e.id);
  const thermal = stored.filter((e) => /TEMP_(CRITICAL|WARNING)/.test(e.reason));
  assert.ok(thermal.length >= 4, `the daemon stored the fault's events (${thermal.length})`);

  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#events");
  await page.waitForSelector("#events-body tr");
  const rows = page.locator("#events-body tr", { hasText: "Alternator far too hot" });
  assert.equal(await rows.count(), 1, "one row for the thermal fault");
  const row = await rows.first().locator("td.incident").innerText();
  assert.match(row, /cut the field at once/);
  assert.match(row, /What to do: Let it cool/);
  assert.match(row, /Over after \d+ s\./);
  assert.match(await rows.first().locator("td").nth(1).textContent(), /critical/);
  // The fault's own events are in the row, folded; none is a row of its own.
  const alone = await page.locator("#events-body > tr > td:not(.incident)", { hasText: /immediate cut|Alarm ON|Protection cleared/ }).count();
  assert.equal(alone, 0, "the cut, the alarm and the clears fold into the incident");
  assert.equal(await rows.first().locator("details").getAttribute("open"), null, "folded until asked");
  await rows.first().locator("summary").click();
  assert.match(await rows.first().locator("details").innerText(), /Field immediate cut: alternator far too hot/);
  await page.screenshot({ path: path.join(stateDir, "events-incident.png"), fullPage: false });
  if (args["docs-dir"]) fs.copyFileSync(path.join(stateDir, "events-incident.png"), path.join(args["docs-dir"], "events-incident.png"));
  console.log(`ok - one thermal fault (${thermal.length} stored events) is one row with its action: ${row.split("\n")[0]}`);

  // The History page (docs/dashboard.md "History"): today's bar and this
  // charge, which the 12 s fault did not end (a charge ends after 5 min off).
  await page.click('nav a[href="#history"]');
  await page.waitForSelector("#history-days .day-line");
  const api = await get("/api/history/days?n=30");
  assert.equal(api.days.length, 1);
  const day = await page.locator("#history-days .day-line").first().textContent();
  assert.match(day, new RegExp(`^${api.days[0].day} · \\d+(\\.\\d)? Ah · \\d+\\.\\d\\d kWh · .* alternator up to \\d+ °C`), day);
  assert.ok(api.days[0].alt_ah > 0 && api.days[0].field_on_h > 0, JSON.stringify(api.days[0]));
  // One day of history: the time axis names that day and no other (not 1 Jan).
  await page.waitForSelector('.history-chart[data-title="Into the bank"] canvas');
  const dayTicks = await page.evaluate(() =>
    document.querySelector('.history-chart[data-title="Into the bank"]').uplot.axes[0]._values);
  const todayShort = await page.evaluate((d) => new Date(`${d}T12:00:00`).toLocaleDateString([], { day: "numeric", month: "short" }), api.days[0].day);
  assert.deepEqual([...new Set(dayTicks)], [todayShort], `the day axis of one day: ${dayTicks}`);
  const charges = await page.locator("#history-charges tr").allTextContents();
  assert.equal(charges.length, 1, charges.join(" | "));
  assert.match(charges[0], /still charging$/);
  const bad = await fetch(server.base + "/api/history/days?n=0");
  assert.equal(bad.status, 400);
  await page.screenshot({ path: path.join(stateDir, "history.png") });
  if (args["docs-dir"]) fs.copyFileSync(path.join(stateDir, "history.png"), path.join(args["docs-dir"], "history.png"));
  console.log(`ok - the History page: ${day}; one charge, still going`);
});
