// The Battery page offers the measured capacity (docs/batteries.md
// "Measured capacity"), in Debian's Chromium at phone size against the real
// daemon in --sim. First the daemon runs two days of a LiFePO4 bank that
// holds 160 Ah, set up as 200 Ah, with its BMS on CAN, at full speed: it
// measures the capacity and keeps it in its state database. Then it starts
// again on that database, as after a reboot; the owner opens the Battery
// page, reads that the bank measures about 154 Ah, and taps "Use".
// The Alternator page shows the hours counted in the first run.
import { spawnSync } from "node:child_process";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";
const config = `
[battery]
BatteryProfile = "lifepo4"
BatteryCapacity_Ah = 200
`;
const bank = `[battery]
chemistry = "lifepo4"
capacity_ah = 160
soc_pct = 90
[alternator]
rated_a = 100
temp_f = 80
ambient_f = 85
[loads]
house_a = 5
[bms]
can = true
protocol = "pylontech"
`;
const days = `name = "LiFePO4 160 Ah set up as 200 Ah: two cycles"
duration_s = 57600
seed = 6
${bank}[engine]
rpm = 1600
[[events]]
at_s = 7200
rpm = 0
house_a = 25
[[events]]
at_s = 16200
house_a = 1
[[events]]
at_s = 23400
rpm = 1600
house_a = 5
[[events]]
at_s = 34200
rpm = 0
house_a = 25
[[events]]
at_s = 43200
house_a = 1
`;

// The first run, at full speed, into its own state database.
const first = fs.mkdtempSync(path.join(os.tmpdir(), "xr-health-first-"));
const cfg = path.join(first, "xregulator.toml");
fs.writeFileSync(cfg, `[web]\ntoken = "${token}"\nwww_root = "${args.www}"\n` + config);
fs.writeFileSync(path.join(first, "days.toml"), days);
const run = spawnSync(args.server, ["--sim", "--speed", "max", "--config", cfg, "--scenario", path.join(first, "days.toml"),
                                    "--state-db", path.join(first, "state.db")], { encoding: "utf8", timeout: 240000 });
assert.equal(run.status, 0, run.stderr.slice(-2000));
assert.match(run.stderr + run.stdout, /Battery capacity measured: \d+ Ah over a \d+ % swing \(2 so far\)/);
console.log("ok - two days at full speed: the capacity was measured twice");

const quiet = `name = "the next morning"
duration_s = 3600
seed = 7
${bank}[engine]
rpm = 0
`;
await runDaemonBrowserTest({ args, token, scenario: quiet, extraConfig: config, prefix: "xr-health-",
                             seedState: path.join(first, "state.db") },
  async ({ server, browser, stateDir, get }) => {
  const st = await get("/api/status");
  assert.ok(st.capacity_measured_ah > 144 && st.capacity_measured_ah < 176, `measured ${st.capacity_measured_ah} Ah`);
  assert.ok(st.battery.capacity_cycles >= 2);
  const offered = Math.round(st.capacity_measured_ah);
  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  await page.goto(server.base + "/#live");
  await page.evaluate((t) => localStorage.setItem("xregulator.token", t), token);
  await page.goto(server.base + "/#battery");
  await page.reload();
  await page.waitForSelector("#capacity-offer:not([hidden])");
  const text = await page.textContent("#capacity-offer");
  assert.match(text, new RegExp(`measures ${offered} Ah over \\d+ swings, \\d+ % less than the 200 Ah set`), text);
  assert.equal((await page.textContent("#capacity-use")).trim(), `Use ${offered} Ah`);
  const table = await page.textContent("#health-table");
  assert.match(table, new RegExp(`measured capacity \\(Ah\\)${offered} \\(from \\d+ swings\\)`), table);
  console.log(`ok - the Battery page says the bank measures ${offered} Ah and offers to use it`);
  await page.locator("#capacity-offer").scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(stateDir, "battery-health.png") });
  if (args["docs-dir"]) fs.copyFileSync(path.join(stateDir, "battery-health.png"), path.join(args["docs-dir"], "battery-health.png"));

  await page.click("#capacity-use");
  await until("the setting", async () => {
    const p = (await get("/api/params")).params.find((x) => x.name === "BatteryCapacity_Ah");
    return p.value === offered;
  });
  await page.waitForSelector("#capacity-offer", { state: "hidden" });
  console.log(`ok - one tap: BatteryCapacity_Ah is ${offered} and the offer is gone`);

  await page.goto(server.base + "/#alternator");
  await page.waitForFunction(() => /running\s*[1-9]\d* h \d\d min/.test(document.getElementById("alt-table").textContent));
  const alt = await page.textContent("#alt-table");
  assert.match(alt, /insulation life used \(%\)/, alt);
  assert.match(alt, /belt slips seen0/, alt);
  console.log("ok - the Alternator page shows the running hours, the life used and no belt slip");
  assert.deepEqual(errors, []);
});
fs.rmSync(first, { recursive: true, force: true });
