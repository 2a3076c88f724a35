// First start on a 24 V bank (docs/configuration.md "Not set up"), in
// Debian's Chromium at phone size against the real daemon in --sim on the
// shipped config/xregulator.toml: a 24 V AGM bank, nothing chosen yet.
//
// The regulator reads the bank's size from the battery before it arms a
// voltage trip: no ALARM, no error or critical event, one calm notice that
// names 24 V and the set-up page, and it charges within the not-set-up
// limits for 24 V. The owner then chooses AGM 24 V on the set-up page and
// the regulator aims for the profile's 28.8 V.
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, saveSetup, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";

const scenario = `name = "24 V AGM, 200 Ah, as delivered"
duration_s = 3600
seed = 24
set_up = false
[battery]
chemistry = "agm"
capacity_ah = 200
nominal_v = 24
soc_pct = 50
temp_c = 20
temp_sensor = true
[alternator]
rated_a = 120
temp_f = 80
ambient_f = 85
[engine]
rpm = 1800
[loads]
house_a = 5
`;

await runDaemonBrowserTest({ args, token, scenario, shipped: true, prefix: "xr-first24-" },
  async ({ server, browser, get }) => {
  // The bank read as 24 V; the not-set-up limits are the 24 V ones.
  await until("the bank read as 24 V", async () => /choose 24 V on the set-up page/.test((await get("/api/status")).owner?.notice ?? ""));
  const body = await get("/api/params");
  assert.equal(body.set_up, false);
  assert.match(body.setup_limits, /at most 28 V, float 26\.8 V/, body.setup_limits);
  const p0 = Object.fromEntries(body.params.map((x) => [x.name, x]));
  assert.equal(p0.BulkVoltage.value, 28, "the shown set is the one that runs");
  await until("charging within the 24 V limits", async () => (await get("/api/status")).field_enable === true, 30000);
  const s = await get("/api/status");
  assert.equal(s.alarm, false, "no ALARM");
  assert.ok(s.target_v <= 28.0 + 1e-9, `target ${s.target_v} V within the not-set-up 28 V`);
  const bad = (await get("/api/events?limit=200")).events.filter((e) => /error|critical/.test(e.level));
  assert.deepEqual(bad.map((e) => e.message ?? e.text), [], "no error or critical event");
  console.log(`ok - shipped file on a 24 V AGM bank: no ALARM, no critical event, charging to ${s.target_v} V`);

  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#live");
  await page.evaluate((t) => localStorage.setItem("xregulator.token", t), token);
  await page.reload();
  await page.waitForFunction(() => /choose 24 V on the set-up page/.test(document.getElementById("first-run")?.textContent ?? ""));
  assert.equal(await page.isVisible("#first-run"), true, "the one notice is shown");
  const notice = await page.textContent("#first-run");
  assert.match(notice, /The bank reads 2\d\.\d V: choose 24 V on the set-up page/, notice);
  assert.match(notice, /at most 28 V/, notice);
  assert.equal(await page.locator("#banners > *").count(), 0, "no red banner");
  assert.doesNotMatch(await page.textContent("#page-live"), /over-voltage|too high|makes no sense|another bank size/);
  console.log("ok - Live shows one calm notice naming 24 V and the set-up page, no banner");

  await page.click("#first-run a[href='#setup']");
  const msg = await saveSetup(page, { profile: "agm", bank: "24", capacity: 200, rating: 120, belt: 100 });
  assert.match(msg, /^Saved\./, `saved with no error: ${msg}`);
  const p = Object.fromEntries((await get("/api/params")).params.map((x) => [x.name, x]));
  assert.equal(p.AbsorptionVoltage.value, 28.8);
  assert.equal(p.BulkVoltage.value, 28.8);
  // The profile's 28.8 V at 25 °C; AGM's temperature compensation moves it
  // with the battery's 20 °C (docs/batteries.md), never back to the 28 V ceiling.
  let last = {};
  await until("aiming for the profile's 28.8 V", async () => {
    last = await get("/api/status");
    return last.field_enable === true && last.target_v > 28.4 && last.target_v < 29.3 && last.alarm === false;
  }, 30000).catch((e) => { throw new Error(`${e.message}: ${JSON.stringify({ t: last.target_v, f: last.field_enable, r: last.reason, s: last.owner?.state })}`); });
  const after = await get("/api/params");
  assert.equal(after.set_up, true);
  await page.goto(server.base + "/#live");
  await page.waitForFunction(() => document.getElementById("first-run")?.hidden === true);
  const bad2 = (await get("/api/events?limit=200")).events.filter((e) => /error|critical/.test(e.level));
  assert.deepEqual(bad2.map((e) => e.message ?? e.text), [], "no error or critical event after the set-up");
  console.log("ok - after choosing AGM 24 V the regulator charges to the profile's 28.8 V; the notice is gone");
});
