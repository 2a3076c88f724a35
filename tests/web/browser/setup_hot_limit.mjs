// The set-up page saves a normal alternator limit (docs/configuration.md
// "Derived values"), in Debian's Chromium at phone size against the real
// daemon in --sim on the shipped config/xregulator.toml: a 12 V AGM bank
// whose owner enters 90 °C for the alternator. The high-temperature alarm
// follows the limit (TempAlarm 0 = TemperatureLimitF + 40 °F), so the save
// meets no refusal naming a field that is not on the page.
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, saveSetup } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";

const scenario = `name = "12 V AGM, 200 Ah, before its set-up"
duration_s = 3600
seed = 9
[battery]
chemistry = "agm"
capacity_ah = 200
soc_pct = 60
[alternator]
rated_a = 100
temp_f = 80
ambient_f = 85
[engine]
rpm = 1700
[loads]
house_a = 5
`;

await runDaemonBrowserTest({ args, token, scenario, shipped: true, prefix: "xr-setup-hot-" },
  async ({ server, browser, get }) => {
  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#live");
  await page.evaluate((t) => localStorage.setItem("xregulator.token", t), token);
  await page.reload();
  await page.goto(server.base + "/#setup");
  const msg = await saveSetup(page,
    { profile: "agm", bank: "12", capacity: 200, rating: 100, belt: 90, tempLimit: 90 });
  assert.match(msg, /^Saved\./, `saved with no error: ${msg}`);
  assert.doesNotMatch(msg, /TempAlarm|degF/, msg);
  const p = Object.fromEntries((await get("/api/params")).params.map((x) => [x.name, x]));
  assert.equal(p.TemperatureLimitF.value, 194);
  assert.equal(p.TempAlarm.value, 0, "the alarm is left to follow the limit");
  console.log("ok - the set-up saves 90 °C with no error; TempAlarm follows the limit");

  // One event line for the whole set-up, not one per value.
  const events = (await get("/api/events")).events ?? [];
  const setup = events.filter((e) => /Set-up: AGM 12 V 200 Ah, alternator 100 A, belt 90 A/.test(e.text ?? e.message ?? ""));
  assert.equal(setup.length, 1, JSON.stringify(events.slice(0, 5)));
  console.log("ok - the set-up is one event line");
});
