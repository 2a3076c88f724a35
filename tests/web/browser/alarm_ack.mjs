// Acknowledging an alarm from the dashboard (docs/protections.md
// "Acknowledging an alarm"), in Debian's Chromium at phone size against the
// real daemon in --sim: the alternator's sensor reads 170 °F from 3 s on (a
// critical thermal trip that does not clear). The Live page offers "Silence
// the alarm" while the buzzer sounds; a paired phone presses it: the buzzer
// stops, the fault's banner stays, the field stays cut, the protection acts on.
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";

const scenario = `name = "a thermal fault that stays"
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
at_s = 3
fault = "temp_value"
value = 170
`;

await runDaemonBrowserTest({ args, token, scenario, prefix: "xr-alarm-ack-" }, async ({ server, browser, get }) => {
  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#live");
  await page.evaluate((t) => localStorage.setItem("xregulator.token", t), token);
  await page.reload();
  await until("the buzzer to sound", async () => Number((await get("/api/status")).alarm) === 1, 30000);
  await page.waitForSelector("#alarm-ack-row:not([hidden])");
  await page.waitForSelector('.banner[data-reason="REASON_TEMP_CRITICAL"]');
  assert.match(await page.textContent("#alarm-ack-row"), /protection keeps acting/);
  await page.click("#alarm-ack");
  await page.waitForSelector("#toast:not([hidden])");
  assert.match(await page.textContent("#toast"), /Alarm silenced/);
  await until("the buzzer to stop", async () => Number((await get("/api/status")).alarm) === 0, 10000);
  await page.waitForSelector("#alarm-ack-row", { state: "hidden" });
  // Some seconds later: still quiet, still protecting.
  await new Promise((r) => setTimeout(r, 3000));
  const s = await get("/api/status");
  assert.equal(Number(s.alarm), 0, "the buzzer stays quiet");
  assert.equal(Number(s.field_enable), 0, "the field stays cut");
  assert.match(s.reason, /REASON_TEMP_(CRITICAL|SUSTAINED)/, `the protection still acts: ${s.reason}`);
  assert.equal(await page.locator('.banner[data-reason^="REASON_TEMP_"]').count() >= 1, true, "its banner stays");
  const events = (await get("/api/events?limit=200")).events;
  assert.ok(events.some((e) => e.code === "CommandApplied" && /acknowledge_alarm/.test(e.text)),
    "the acknowledgement is an event");
  console.log(`ok - silenced from the dashboard: buzzer off, field cut, ${s.reason} still acting`);
});
