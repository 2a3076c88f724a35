// The set-up page's hardware step (docs/configuration.md "Set-up"), in
// Debian's Chromium at phone size against the real daemon in --sim, on the
// shipped config/xregulator.toml. The simulated board has two DS18B20s: the
// alternator's and one on the battery, which the scenario's board reads. The
// owner takes the probe off (it sits in the sun) and sets the pulley ratio;
// the page says both are used from the next start, the choice is an event,
// and after a restart the daemon runs with them: no battery temperature, and
// the engine speed scaled by the ratio. Bad choices are refused with the
// setting's name and nothing saved; null gives the decision back to the file.
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, startServer } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";
const batteryProbe = "28-00000b0a77e1";  // daemon/sim_rig/sim_rig.h kSimBatteryW1Id

const scenario = `name = "12 V AGM with a probe on the battery"
duration_s = 3600
seed = 11
[battery]
chemistry = "agm"
capacity_ah = 200
nominal_v = 12
soc_pct = 60
temp_c = 20
temp_sensor = true
[engine]
rpm = 1500
`;

const put = (server, body, auth = token) => fetch(server.base + "/api/setup/hardware", {
  method: "PUT", headers: { "Content-Type": "application/json", ...(auth ? { Authorization: "Bearer " + auth } : {}) },
  body: JSON.stringify(body) });

await runDaemonBrowserTest({ args, token, scenario, shipped: true, prefix: "xr-setup-hw-" },
  async ({ server, browser, stateDir, get }) => {
  const before = await get("/api/setup/hardware");
  assert.equal(before.savable, true);
  assert.ok(before.probes.includes(batteryProbe), JSON.stringify(before));
  assert.notEqual(before.alternator_sensor, batteryProbe, "the alternator keeps its own probe");
  assert.equal(before.battery_temp_sensor.running, batteryProbe, "the scenario's board reads its probe");
  assert.equal(before.battery_temp_sensor.restart_needed, false);

  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#live");
  await page.evaluate((t) => localStorage.setItem("xregulator.token", t), token);
  await page.goto(server.base + "/#setup");
  await page.waitForSelector("#page-setup:not([hidden]) #su-battprobe");
  const offered = await page.$$eval("#su-battprobe option", (os) => os.map((o) => o.value));
  assert.deepEqual(offered, ["", batteryProbe], "no probe, or the battery's; never the alternator's");
  await page.selectOption("#su-profile", { label: "agm" });
  assert.equal(await page.inputValue("#su-battprobe"), batteryProbe, "the probe in use is shown chosen");
  await page.selectOption("#su-battprobe", "");
  // The tach reads 1500 rpm (the scenario's engine, ratio 1 in the shipped
  // file); the hint shows what 2.5 would read, to compare with the engine.
  await page.fill("#su-pulley", "2,5");
  assert.match(await page.textContent("#su-pulley-hint"), /Engine speed read now: 1\d{3} rpm; with 2\.5: \d{3} rpm/);
  await page.click("#setup-save");
  await page.waitForSelector("#setup-result:not([hidden])");
  assert.match(await page.textContent("#setup-msg"), /^Saved\..*next start/);
  assert.match(await page.textContent("#setup-result"),
    new RegExp(`Battery temperature probe${batteryProbe} → none from the next start`));
  const saved = await get("/api/setup/hardware");
  assert.equal(saved.battery_temp_sensor.chosen, "");
  assert.equal(saved.battery_temp_sensor.restart_needed, true);
  assert.equal(saved.pulley_ratio.chosen, 2.5);
  assert.match(await page.textContent("#setup-result"), /Pulley ratio1 : 1 → 2\.5 : 1 from the next start/);
  const events = (await get("/api/events?limit=50")).events.map((e) => e.text).join("\n");
  assert.match(events, new RegExp(`Set-up by .*: battery temperature probe none; pulley ratio 2\\.5; used from the next start`), events);
  assert.doesNotMatch(events, /BMS on CAN/, "only what changed is named");
  console.log("ok - the battery's probe chosen on the set-up page: saved, an event, 'from the next start'");

  // Refused with the setting's name, nothing saved.
  assert.equal((await put(server, { battery_temp_sensor: "" }, null)).status, 401);
  for (const [body, key] of [[{ battery_temp_sensor: "28-nothex" }, "hardware.battery_temp_sensor"],
    [{ battery_temp_sensor: before.alternator_sensor }, "hardware.battery_temp_sensor"],
    [{ bms_interface: "can0/x" }, "can.bms_interface"], [{ pulley_ratio: 0 }, "hardware.frontend.pulley_ratio"]]) {
    const r = await put(server, body);
    assert.equal(r.status, 400, JSON.stringify(body));
    assert.ok(key in (await r.json()).errors, `${JSON.stringify(body)} names ${key}`);
  }
  assert.equal((await put(server, { volume: 3 })).status, 400, "an unknown setting");
  assert.equal((await get("/api/setup/hardware")).battery_temp_sensor.chosen, "", "nothing saved");
  console.log("ok - a malformed probe id, the alternator's probe and a bad interface name are refused, nothing saved");

  // The next start runs with the choice.
  await server.stop();
  const again = await startServer({ mode: "daemon", args, token, stateDir, scenario, shipped: true });
  try {
    const hw = await (await fetch(again.base + "/api/setup/hardware")).json();
    assert.equal(hw.battery_temp_sensor.running, "");
    assert.equal(hw.battery_temp_sensor.restart_needed, false);
    assert.equal(hw.pulley_ratio.running, 2.5);
    // The same alternator speed now reads as 2.5 times less engine speed.
    const rpm = (await (await fetch(again.base + "/api/status")).json()).rpm;
    assert.ok(rpm > 450 && rpm < 750, `engine speed with ratio 2.5: ${rpm} rpm (1500 / 2.5 = 600)`);
    assert.match(again.log(), /set-up: battery temperature probe '', BMS on CAN '', pulley ratio 2\.5/);
    console.log("ok - after a restart the daemon runs without the battery probe and with the new pulley ratio");
    // null: the file decides again, from the next start.
    const back = await (await put(again, { battery_temp_sensor: null })).json();
    assert.equal(back.battery_temp_sensor.chosen, null);
    assert.equal(back.battery_temp_sensor.next, batteryProbe);
    assert.equal(back.battery_temp_sensor.restart_needed, true);
    console.log("ok - null gives the choice back to the file");
  } finally {
    await again.stop();
  }
});
