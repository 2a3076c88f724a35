// The owner model's limits on every screen (docs/dashboard.md "Owner
// model"), in Debian's Chromium at phone size against the real daemon in
// --sim on the shipped config/xregulator.toml: a 12 V LiFePO4 bank of 280 Ah
// with no battery temperature probe, a 120 A alternator on a belt good for
// 100 A. LiFePO4 must not charge fast without its temperature
// (BatteryTempRequired), so the regulator holds the charge to C/10 = 28 A.
// /api/status's `owner` lists that cap first with its amps and cause, and
// Live ("Aiming for" and the headline), Protections and the set-up's "Now in
// effect" show the same words and amps.
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, saveSetup, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";
const CAP = "C/10 without a battery probe: 28 A";

const scenario = `name = "12 V LiFePO4, 280 Ah, no battery probe"
duration_s = 3600
seed = 11
[battery]
chemistry = "lifepo4"
capacity_ah = 280
soc_pct = 40
temp_c = 20
temp_sensor = false
[alternator]
rated_a = 120
temp_f = 80
ambient_f = 85
[engine]
rpm = 1800
[loads]
house_a = 5
`;

await runDaemonBrowserTest({ args, token, scenario, shipped: true, prefix: "xr-owner-" },
  async ({ server, browser, get }) => {
  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#setup");
  await page.evaluate((t) => localStorage.setItem("xregulator.token", t), token);
  await page.reload();
  assert.match(await saveSetup(page, { profile: "lifepo4", capacity: 280, rating: 120, belt: 100 }), /^Saved\./);

  // The regulator's own account: the C/10 cap first, its amps and its cause.
  await until("the C/10 cap in owner.limits", async () => {
    const s = await get("/api/status");
    return s.owner.limits.length > 0 && s.owner.limits[0].id === "battery_temp_required";
  }, 30000);
  const owner = (await get("/api/status")).owner;
  const first = owner.limits[0];
  assert.equal(first.what, "C/10 without a battery probe");
  assert.equal(first.amps, 28);
  assert.match(first.why, /battery temperature sensor/);
  console.log(`ok - owner.limits: ${first.what}, ${first.amps} A, "${first.why.slice(0, 60)}…"`);

  // The set-up's "Now in effect" says it, kept current by the frames.
  await page.waitForFunction((cap) => document.getElementById("setup-now")?.textContent.includes(cap), CAP);
  console.log("ok - set-up \"Now in effect\": " + (await page.textContent("#setup-now")));

  // Live: "Aiming for" names it with its amps, and the headline while bulk holds at it.
  await page.goto(server.base + "/#live");
  await page.waitForFunction((cap) => document.getElementById("v-target").textContent.includes(cap), CAP);
  await until("charging in bulk", async () => (await get("/api/status")).field_enable === true, 30000);
  await page.waitForFunction(() => /limited by C\/10 without a battery probe/.test(document.getElementById("headline").textContent));
  const hero = await page.locator("#hero-value").evaluate((e) => parseFloat(getComputedStyle(e).fontSize));
  assert.ok(hero >= 64, `the hero value is ${hero} px`);
  console.log("ok - Live: " + (await page.textContent("#headline")) + " / Aiming for: " + (await page.textContent("#v-target")));

  // Protections: what holds the charge back, the same words.
  await page.goto(server.base + "/#protections");
  await page.waitForFunction((cap) => document.getElementById("prot-table").textContent.includes(cap), CAP);
  assert.doesNotMatch(await page.textContent("#prot-table"), /holding backnothing/);
  // No fast over-voltage clamp acts, so it shows no current of its own beside the cap.
  assert.match(await page.textContent("#prot-table"), /fast over-voltage clampnoclamp current \(A\)—/);
  console.log("ok - Protections lists the C/10 cap with its amps and cause");
  await ctx.close();
});
