// One SoC and one BMS state on every screen (docs/dashboard.md "State of
// charge", "Owner model"), in Debian's Chromium at phone size against the
// real daemon in --sim: a 12 V LiFePO4 bank whose BMS talks on (simulated)
// CAN and reports 40 %. Live's SoC tile, the Battery page, the System page's
// BMS row and the set-up's "Now in effect" all show the regulator's owner
// model: 40 % from the BMS, the BMS talking; no page shows another SoC
// (the counted one's "unknown until the first full charge", its averages or
// its count in Ah).
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, saveSetup, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";

const scenario = `name = "12 V LiFePO4 with a BMS on CAN reporting 40 %"
duration_s = 3600
seed = 13
[config]
BmsLimitsEnabled = true
[battery]
chemistry = "lifepo4"
capacity_ah = 280
soc_pct = 40
temp_c = 20
[alternator]
rated_a = 120
temp_f = 80
ambient_f = 85
[engine]
rpm = 0
[bms]
can = true
protocol = "pylontech"
`;

await runDaemonBrowserTest({ args, token, scenario, shipped: true, prefix: "xr-socwalk-" },
  async ({ server, browser, get }) => {
  await until("the BMS's SoC as the owner's", async () => (await get("/api/status")).owner.soc.source === "bms", 30000);
  const owner = (await get("/api/status")).owner;
  const pct = Math.round(owner.soc.pct);
  assert.ok(Math.abs(pct - 40) <= 1, `the BMS reports about 40 %: ${owner.soc.pct}`);
  assert.equal(owner.bms.state, "talking");
  const status = await get("/api/status");
  assert.equal(Math.round(status.soc_pct), pct, "soc_pct is the same SoC");
  assert.equal(status.soc_source, "bms");

  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#live");
  await page.evaluate((t) => localStorage.setItem("xregulator.token", t), token);
  await page.reload();
  await page.waitForFunction((p) => document.getElementById("v-soc_pct").textContent.startsWith(String(p)), pct);
  assert.match(await page.textContent("#v-soc_pct"), /from the BMS/);
  console.log("ok - Live: SoC " + (await page.textContent("#v-soc_pct")));

  await page.goto(server.base + "/#battery");
  await page.waitForFunction((p) => document.getElementById("batt-table").textContent.includes(`${p} (from the BMS)`), pct);
  const battery = await page.textContent("#batt-table");
  assert.doesNotMatch(battery, /unknown until the first full charge/);
  assert.match(battery, /average SoC \(%\)—/, "no average of another SoC beside the BMS's");
  assert.match(battery, /charge counted \(Ah\)—/, "no count of another SoC in Ah beside the BMS's");
  console.log("ok - Battery: the same SoC from the BMS, no other");

  await page.goto(server.base + "/#system");
  await page.waitForFunction((w) => document.getElementById("sys-can").textContent.includes(w), owner.bms.words);
  console.log("ok - System: Battery BMS " + owner.bms.words);

  await page.goto(server.base + "/#setup");
  await saveSetup(page, { profile: "lifepo4", capacity: 280 });
  await page.waitForFunction((w) => document.getElementById("setup-now")?.textContent.includes("BMS now" + w), owner.bms.words);
  console.log("ok - set-up \"Now in effect\": BMS now " + owner.bms.words);
  await ctx.close();
});
