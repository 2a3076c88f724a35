// What a boat owner and an installer do, against the real daemon in --sim
// (docs/dashboard.md). Each step asserts what the user sees and what the
// daemon then holds (its API), so a page that only looks right fails.
import assert from "node:assert/strict";
import { spawnSync } from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import { pairAtFirstChange, pairedDevices, plainWordsSweep } from "./pairing_checks.mjs";
import { startServer } from "./server.mjs";

const PHONE = { width: 390, height: 844 };
const DESKTOP = { width: 1100, height: 900 };

export async function daemonChecks(t) {
  const { page, artifacts, args, token, stateDir, servers, shot } = t;
  let server = t.server;
  const get = async (p) => (await fetch(server.base + p)).json();
  const param = async (name) => (await get("/api/params")).params.find((p) => p.name === name).value;
  const status = () => get("/api/status");
  const send = (body) => fetch(server.base + "/api/commands", {
    method: "POST", body: JSON.stringify(body), headers: { Authorization: "Bearer " + token, "Content-Type": "application/json" } });
  const until = async (what, fn, ms = 20000) => {
    const end = Date.now() + ms;
    for (;;) {
      if (await fn()) return;
      if (Date.now() > end) throw new Error("timed out waiting for " + what);
      await new Promise((r) => setTimeout(r, 200));
    }
  };
  // Pages back with "Older" until an event matching re is listed.
  const olderUntil = async (re, what) => {
    for (let i = 0; !re.test(await page.textContent("#events-body")); i++) {
      assert.ok(i < 20 && !(await page.isDisabled("#events-more")), `${what} is not listed`);
      const n = await page.locator("#events-body tr").count();
      await page.click("#events-more");
      await page.waitForFunction((k) => document.querySelectorAll("#events-body tr").length > k, n);
    }
  };
  const docsShot = async (name) => {
    const file = path.join(artifacts, `${name}.png`);
    await page.screenshot({ path: file });
    if (args["docs-dir"]) fs.copyFileSync(file, path.join(args["docs-dir"], `${name}.png`));
  };
  await page.evaluate(() => localStorage.setItem("xregulator.tempUnit", "C"));

  // ---- A fresh install with no battery type chosen does not know its SoC:
  // the API gives no number and says so; the tile says "unknown", not a guess
  // (docs/batteries.md "State of charge at first start").
  const s0 = await status();
  assert.equal(s0.schema, 2);
  assert.equal(s0.battery.soc_known, false);
  assert.equal(s0.soc_pct, null);
  assert.equal(s0.soc_source, "unknown");
  await page.waitForFunction(() => document.getElementById("v-soc_pct").textContent.startsWith("unknown"));
  assert.doesNotMatch(await page.textContent("#v-soc_pct"), /\d/);
  console.log("ok - a fresh install shows the SoC as unknown, with no number: " + (await page.textContent("#v-soc_pct")));

  // ---- Item 16: /api/status for programs.
  assert.equal(typeof s0.field_enable, "boolean");
  assert.ok(Number.isInteger(s0.seq) && Number.isInteger(s0.loop.ticks) && Number.isInteger(s0.runtime.watchdog_feeds));
  for (const k of ["time_to_full_charge_min", "time_to_full_discharge_min"])  // -999 ("none") is null now
    assert.ok(s0.battery[k] === null || s0.battery[k] >= 0, `${k} = ${s0.battery[k]}`);
  for (const [k, v] of Object.entries({ ...s0, ...s0.control, ...s0.protection, ...s0.battery }))
    if (typeof v === "number") assert.ok(String(v).replace(/^-?\d+\.?/, "").length <= 4, `${k} = ${v} is not rounded`);
  for (const sec of ["control", "protection", "battery", "loop", "runtime"])
    for (const k of Object.keys(s0[sec])) assert.match(k, /^[a-z0-9_]+$/, `${sec}.${k} is not snake_case`);
  console.log("ok - /api/status: schema 2, booleans, integer counters, null sentinels, rounded, snake_case");

  // ---- Set-up on a phone: fresh install offers it; run it to charging.
  await page.setViewportSize(PHONE);
  await page.reload();
  await page.waitForSelector("#first-run:not([hidden])");
  assert.equal((await send({ command: "off" })).status, 200);
  await page.waitForFunction(() => document.getElementById("headline").textContent.startsWith("Not set up · Not charging"));
  // Not set up is a state: the limits safe for every battery are named, and in force.
  assert.match(await page.textContent("#first-run"), /at most 14 V, float 13\.4 V, battery 5-45 °C/);
  assert.equal(await param("BulkVoltage"), 14);
  assert.equal(await param("ChargeMinTempC"), 5);
  await page.click("#first-run a");
  await page.waitForSelector("#page-setup:not([hidden]) #su-capacity");
  await page.fill("#su-capacity", "280");
  await page.fill("#su-rating", "90");
  await page.fill("#su-belt", "40");
  await page.fill("#su-minrpm", "600");
  await page.fill("#su-templimit", "85");
  await page.evaluate(() => { document.activeElement.blur(); window.scrollTo(0, 0); });
  await docsShot("dashboard-phone-setup");
  // ---- Item 15: the first change asks to pair this (fresh) browser.
  await page.click("#setup-save");
  await pairAtFirstChange({ page, server, args, stateDir, token, docsShot, param });
  assert.equal(await param("BatteryCapacity_Ah"), 280);
  assert.equal(await param("MaxTableValue"), 90);
  assert.equal(Math.max(...(await param("rpmCapCurrentTable"))), 40);  // the belt caps every speed
  assert.equal(await param("MinRPMForField"), 600);
  assert.equal(await param("TemperatureLimitF"), 185);
  assert.equal((await get("/api/params")).set_up, true, "saving the set-up chose the battery");
  assert.notEqual(await param("ChargeMinTempC"), 5, "the not-set-up limits are lifted");
  await page.click("#setup-start");
  await page.waitForSelector("#page-live:not([hidden])");
  await page.waitForFunction(() => /^(Charging|Alternator on)/.test(document.getElementById("headline").textContent));
  assert.equal((await status()).control.sys_mode, "SYS_MODE_AUTO");
  await page.waitForSelector("#first-run", { state: "hidden" });
  console.log("ok - first-run set-up on a phone, to charging: " + (await page.textContent("#headline")));

  // ---- Items 4, 9: dangerous commands ask first; cancel changes nothing.
  assert.equal(await page.textContent("#hdr-mode"), "Auto");
  await page.click("#off-button");
  await page.waitForSelector("#confirm-dialog[open]");
  assert.match(await page.textContent("#confirm-text"), /OFF/);
  await page.click("#confirm-cancel");
  await page.waitForTimeout(500);
  assert.equal((await status()).control.sys_mode, "SYS_MODE_AUTO");
  assert.equal(await page.textContent("#hdr-mode"), "Auto");
  await page.click("#off-button");
  await page.click("#confirm-ok");
  await page.waitForFunction(() => document.getElementById("hdr-mode").textContent === "Off");
  assert.equal((await status()).control.sys_mode, "SYS_MODE_OFF");
  // Item 10: no target while off, and the headline says so in words.
  await page.waitForFunction(() => document.getElementById("v-target").textContent.startsWith("nothing"));
  await page.waitForFunction(() => document.getElementById("headline").textContent.startsWith("Not charging · Switched off"));
  // Item 7: the owner's own Off is not an alarm.
  assert.equal(await page.textContent("#v-alarms"), "none");
  assert.equal(await page.isVisible("#hdr-alarm"), false);
  const offBox = await page.locator("#off-button").boundingBox();
  assert.ok(offBox.height >= 44 && offBox.width >= 300, `Off button ${offBox.width}x${offBox.height}`);
  // Manual with an empty box sends nothing; a comma decimal is a number.
  await page.fill("#duty-input", "");
  await page.click("#manual-set");
  await page.waitForSelector("#toast:not([hidden])");
  assert.match(await page.textContent("#toast"), /Enter the field duty/);
  assert.equal(await page.isVisible("#confirm-dialog[open]"), false);
  assert.equal((await status()).control.sys_mode, "SYS_MODE_OFF");
  await page.fill("#duty-input", "25,5");
  await page.click("#manual-set");
  assert.match(await page.textContent("#confirm-text"), /25\.5 %/);
  await page.click("#confirm-ok");
  await page.waitForFunction(() => document.getElementById("hdr-mode").textContent === "Manual");
  await page.click('button[data-cmd="limp_home"]');
  await page.waitForSelector("#confirm-dialog[open]");
  await page.click("#confirm-cancel");
  assert.notEqual((await status()).mode, "MODE_LIMP_HOME");
  await page.click('button[data-cmd="auto"]');
  await page.waitForFunction(() => document.getElementById("hdr-mode").textContent === "Auto");
  // The mode is in the header on every page.
  await page.goto(server.base + "/#system");
  assert.equal(await page.isVisible("#hdr-mode"), true);
  assert.equal(await page.textContent("#hdr-mode"), "Auto");
  console.log("ok - Off, Manual and Limp home ask first; cancel changes nothing; no empty duty is sent");

  // Set SoC: empty refused, a value after confirmation; the SoC is then known.
  await page.goto(server.base + "/#battery");
  await page.click("#soc-set");
  assert.match(await page.textContent("#toast"), /Enter the state of charge/);
  const unset = await status();
  assert.equal(unset.battery.soc_known, false);
  // No count of the whole bank beside an SoC that is not the counted one
  // (docs/dashboard.md "State of charge").
  assert.notEqual(unset.owner.soc.source, "counted", "no SoC counted before Set SoC");
  await page.waitForFunction(() => document.getElementById("batt-table").textContent.includes("charge counted (Ah)—"));
  await page.fill("#soc-input", "60");
  await page.click("#soc-set");
  await page.click("#confirm-ok");
  await until("SoC set", async () => Math.abs((await status()).soc_pct - 60) < 1);
  await page.waitForFunction(() => !document.getElementById("v-soc_pct").textContent.startsWith("≈"));
  // The charge counted is the same SoC in Ah: 60 % of the bank set.
  const capacityAh = await param("BatteryCapacity_Ah");
  await page.waitForFunction((ah) => {
    const m = document.getElementById("batt-table").textContent.match(/charge counted \(Ah\)([0-9.]+)/);
    return m && Math.abs(Number(m[1]) - ah) <= 0.02 * ah;
  }, 0.6 * capacityAh);
  console.log("ok - Set SoC asks first, never sends an empty box; the SoC is then shown as known");

  // ---- Item 9: every page reachable at 390 px, 44 px targets: the bottom
  // bar's tabs, and the rest behind "More".
  for (const a of await page.locator("nav a:not(.more-item), #tab-more").all()) {
    const b = await a.boundingBox();
    assert.ok(b.x >= 0 && b.x + b.width <= PHONE.width && b.height >= 44, `${await a.textContent()} at ${JSON.stringify(b)}`);
  }
  for (const a of await page.locator("nav a.more-item").all()) {
    await page.click("#tab-more");
    const b = await a.boundingBox();
    assert.ok(b && b.x >= 0 && b.x + b.width <= PHONE.width && b.height >= 44, `${await a.textContent()} at ${JSON.stringify(b)}`);
    await a.click();
    await page.waitForFunction((h) => location.hash === h, await a.getAttribute("href"));
  }
  // Item 14: the theme follows the system, with a switch; °C or °F by choice.
  await page.evaluate(() => localStorage.removeItem("xregulator.theme"));
  await page.emulateMedia({ colorScheme: "light" });
  await page.reload();
  assert.equal(await page.getAttribute("html", "data-theme"), "light");
  await page.emulateMedia({ colorScheme: "dark" });
  await page.waitForFunction(() => document.documentElement.dataset.theme === "dark");
  await page.click("#theme-toggle");
  assert.equal(await page.getAttribute("html", "data-theme"), "light");
  await page.goto(server.base + "/#system");
  await page.selectOption("#temp-unit", "F");
  await page.goto(server.base + "/#live");
  await page.waitForFunction(() => /°F/.test(document.getElementById("v-temp").textContent));
  await page.goto(server.base + "/#system");
  await page.selectOption("#temp-unit", "C");
  console.log("ok - light theme follows the system and switches; °F and °C by choice");
  console.log("ok - every page reachable at 390 px: four tabs and More at the bottom, each at least 44 px");

  // ---- Item 15: paired devices on the System page.
  await pairedDevices({ page, server, send, shot });

  await page.click('nav a[href="#events"]');
  await page.waitForSelector("#page-events:not([hidden])");

  // ---- Item 11: events coloured by level, commands with their arguments, live.
  await page.waitForSelector("#events-body tr.level-warning");
  const colours = await page.evaluate(() => ["level-warning", "level-info"].map((c) => {
    const td = document.querySelector(`#events-body tr.${c} td`);
    return td ? getComputedStyle(td).color : null;
  }));
  assert.ok(colours[0] && colours[1] && colours[0] !== colours[1], `warning ${colours[0]} vs info ${colours[1]}`);
  assert.match(await page.textContent("#events-body"), /Command Manual \(duty 25\.5 %\) applied/);
  // A settings change names each value, old → new, and who made it (the set-up's PATCH).
  // The set-up is one line: what was chosen and who chose it (docs/configuration.md).
  await olderUntil(/Set-up: /, "the set-up's settings change");
  const setupRow = await page.locator("#events-body tr", { hasText: "Set-up: " }).first().textContent();
  assert.match(setupRow, /Set-up: \w+ \d+ V 280 Ah, alternator \d+ A, belt \d+ A, by device "Skipper's phone"/);
  const rows0 = await page.locator("#events-body tr").count();
  await send({ command: "reset_alarm_latch" });
  await page.waitForFunction((n) => document.querySelectorAll("#events-body tr").length > n, rows0);
  assert.match(await page.locator("#events-body tr:not(.day-head)").first().textContent(), /Command Reset alarm latch applied/);
  console.log("ok - events: warnings coloured, command arguments and settings changes (old → new, by whom) shown, new events appear live");
  // Item 7: a refused command's answer in words, without the API's command name (TuningMode is off).
  await page.goto(server.base + "/#tuning");
  await page.click('button[data-cmd="tuning_commit"]');
  await page.waitForFunction(() => /^Commit current-loop tuning:/.test(document.getElementById("toast").textContent));
  assert.match(await page.textContent("#toast"), /^Commit current-loop tuning: refused — TuningMode is off/);

  // ---- Items 5, 6, 8: settings on the desktop.
  await page.setViewportSize(DESKTOP);
  await page.goto(server.base + "/#settings");
  await page.waitForSelector('.param[data-name="UseFloat"]');
  assert.equal(await page.isVisible('.param[data-name="VoltageKp"]'), false);  // advanced is hidden
  const src = page.locator('.param[data-name="BatteryCapacity_Ah"] .source');
  assert.equal(await src.textContent(), "from dashboard");
  const choice = page.locator('.param[data-name="TempSource"] select');
  assert.match(await choice.locator("option").first().textContent(), /DS18B20/);
  await page.locator('.param[data-name="UseFloat"] input[type="checkbox"]').uncheck();
  await page.locator('.param[data-name="rpmCapCurrentTable"] input').nth(3).fill("45");
  await page.locator('.param[data-name="FloatVoltage"] input').fill("13,4");
  await page.click("#param-apply");
  await page.waitForFunction(() => document.getElementById("param-msg").textContent.startsWith("Applied"));
  assert.equal(await param("UseFloat"), false);
  assert.equal((await param("rpmCapCurrentTable"))[3], 45);
  assert.equal(await param("FloatVoltage"), 13.4);
  // Item 8: one line says values now differ from the file, with Keep / Drop; which ones fold out in plain labels.
  await page.waitForSelector("#param-file-note:not([hidden])");
  assert.match(await page.textContent("#param-file-text"), /^\d+ values? set on the dashboard differs? from the file\.$/);
  assert.match(await page.textContent("#param-file-list"), /Float voltage: 13\.4 V here, [\d.]+ V in the file/);
  assert.ok(await page.isVisible("#param-keep") && await page.isVisible("#param-drop"));
  console.log("ok - a bool switch, an RPM table cell and a comma decimal apply; the page lists what differs from the file");
  // A cross-field error next to its field; nothing applied.
  await page.locator('.param[data-name="FloatVoltage"] input').fill("14.9");
  await page.click("#param-apply");
  await page.waitForFunction(() => document.querySelector('.param[data-name="FloatVoltage"] .err').textContent !== "");
  const crossErr = await page.textContent('.param[data-name="FloatVoltage"] .err');
  assert.equal(await param("FloatVoltage"), 13.4);
  // A set-point for another bank size.
  await page.click("#param-discard");
  await page.waitForSelector('.param[data-name="BulkVoltage"]');
  await page.locator('.param[data-name="BulkVoltage"] input').fill("28.8");
  await page.click("#param-apply");
  await page.waitForFunction(() => /for a 24 V bank.*measures as a 12 V bank/.test(document.querySelector('.param[data-name="BulkVoltage"] .err').textContent));
  assert.equal(await param("BulkVoltage"), 14.5);
  // An emptied box is never sent.
  await page.click("#param-discard");
  await page.waitForSelector('.param[data-name="FloatVoltage"]');
  await page.locator('.param[data-name="FloatVoltage"] input').fill("");
  await page.click("#param-apply");
  assert.equal(await page.textContent('.param[data-name="FloatVoltage"] .err'), "enter a value");
  assert.match(await page.textContent("#param-msg"), /nothing was sent/);
  assert.equal(await param("FloatVoltage"), 13.4);
  await shot("dashboard-settings");
  console.log(`ok - errors beside their fields: "${crossErr}", 28.8 V on a 12 V bank, an empty box`);

  // ---- Item 8: export, then import the changed file; a bad file changes nothing.
  await page.click("#param-discard");
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#config-export")]);
  const exported = fs.readFileSync(await download.path(), "utf8");
  assert.match(exported, /\[voltage\][\s\S]*FloatVoltage = 13\.4/);
  // What the page says to do with it: the file is a configuration the daemon takes as it is.
  const asFile = path.join(stateDir, "exported.toml");
  fs.writeFileSync(asFile, exported);
  const checked = spawnSync(args.server, ["--check-config", "--config", asFile], { encoding: "utf8" });
  assert.equal(checked.status, 0, `--check-config of the export: ${checked.stdout}${checked.stderr}`);
  const edited = exported.replace("FloatVoltage = 13.4", "FloatVoltage = 13.3");
  await page.setInputFiles("#config-import", { name: "x.toml", mimeType: "text/plain", buffer: Buffer.from(edited) });
  await page.waitForFunction(() => /^Imported 1 change/.test(document.getElementById("param-msg").textContent));
  assert.equal(await param("FloatVoltage"), 13.3);
  await until("the import's event", async () =>
    (await get("/api/events?limit=5")).events.some((e) => /Settings changed by device "Skipper's phone": FloatVoltage 13\.4 → 13\.3$/.test(e.text)));
  const bad = edited.replace("FloatVoltage = 13.3", "FloatVoltage = 13.2").replace("BulkVoltage = 14.5", "BulkVoltage = 99");
  await page.setInputFiles("#config-import", { name: "bad.toml", mimeType: "text/plain", buffer: Buffer.from(bad) });
  await page.waitForFunction(() => /^Import refused/.test(document.getElementById("param-msg").textContent));
  assert.equal(await param("FloatVoltage"), 13.3);  // all or nothing
  assert.equal(await param("BulkVoltage"), 14.5);
  console.log("ok - configuration exported as TOML (a file --check-config takes) and re-imported; a bad file changes nothing");

  // ---- A switch that takes a protection away asks first; while it is off a
  // banner on every page says so; switching it back asks nothing.
  await page.goto(server.base + "/#settings");
  await page.waitForSelector(".param");
  if (!(await page.isChecked("#param-advanced"))) await page.check("#param-advanced");
  const ignoreTemp = 'input[aria-label="IgnoreTemperature"]';
  await page.evaluate((sel) => { document.querySelector(sel).closest("details").open = true; }, ignoreTemp);
  await page.check(ignoreTemp);
  await page.click("#param-apply");
  await page.waitForSelector("#confirm-dialog[open]");
  assert.match(await page.textContent("#confirm-text"), /temperature protection is OFF/);
  await page.click("#confirm-cancel");
  assert.equal(await param("IgnoreTemperature"), false, "cancel sends nothing");
  await page.click("#param-apply");
  await page.waitForSelector("#confirm-dialog[open]");
  await page.click("#confirm-ok");
  await until("IgnoreTemperature on", async () => (await param("IgnoreTemperature")) === true);
  await page.goto(server.base + "/#battery");
  await page.waitForSelector("#guard-banner:not([hidden])");
  assert.match(await page.textContent("#guard-banner"), /temperature protection is OFF \(IgnoreTemperature\)/);
  // The settings page keeps its last rendering while it loads the new one: clear it so
  // the wait below is for the new one (on a loaded machine the old one can be there a
  // while, then be replaced under the click).
  await page.evaluate(() => { document.getElementById("param-groups").textContent = ""; });
  await page.goto(server.base + "/#settings");
  await page.waitForSelector(".param");
  await page.evaluate((sel) => { document.querySelector(sel).closest("details").open = true; }, ignoreTemp);
  await page.uncheck(ignoreTemp);
  await page.click("#param-apply");
  await until("IgnoreTemperature off", async () => (await param("IgnoreTemperature")) === false);
  await page.waitForSelector("#guard-banner", { state: "hidden" });
  console.log("ok - switching the temperature protection off asks first and shows a banner on every page until it is back");

  // ---- Item 3: the daemon stops; the page goes unmistakably offline.
  await page.setViewportSize(PHONE);
  await page.goto(server.base + "/#live");
  await page.waitForSelector("#conn.on");
  await server.stop();
  await page.waitForSelector("#offline-banner:not([hidden])");
  await page.waitForFunction(() => /s ago/.test(document.getElementById("offline-age").textContent));
  // The last values stay readable (dimmed, not struck out); the badge says unreachable, never "Off".
  const look = await page.evaluate(() => ({ offline: document.body.classList.contains("offline"),
    opacity: Number(getComputedStyle(document.getElementById("v-battery_v")).opacity),
    strike: getComputedStyle(document.getElementById("v-battery_v")).textDecorationLine,
    value: document.getElementById("v-battery_v").textContent, badge: document.getElementById("hdr-mode").textContent }));
  assert.ok(look.offline && look.opacity === 1 && look.strike === "none" && /\d/.test(look.value) &&
    look.badge === "Regulator unreachable", JSON.stringify(look));
  await page.waitForFunction(() => document.getElementById("off-button").disabled);
  const live = await page.evaluate(() => [...document.querySelectorAll("main button, main input, main select")]
    .filter((el) => !el.disabled).map((el) => el.id || el.name || el.outerHTML.slice(0, 40)));
  assert.deepEqual(live, [], "every control is disabled while offline");
  await shot("dashboard-offline");
  console.log("ok - daemon stopped: offline banner with the age, last values readable, badge unreachable, every control disabled");

  // ---- Items 2, 11, 12: a second run (same state database) with a sensor
  // fault: charging, then the banner with what to do; earlier events kept.
  const scenario = `name = "browser fault"\nduration_s = 3600\nseed = 3\n[battery]\nchemistry = "agm"\ncapacity_ah = 280\n` +
    `soc_pct = 50\n[engine]\nrpm = 1700\n[[events]]\nat_s = 25\nfault = "ina228_nack"\n`;
  // At --speed 3: the ramp and the 25 s before the fault are simulated time.
  server = await startServer({ mode: "daemon", args, token, stateDir, scenario, speed: 3 });
  servers.push(server);
  await page.emulateMedia({ colorScheme: "light" });  // the docs show the sunlight theme
  const loadedAt = Date.now() / 1000;
  await page.goto(server.base + "/#live");
  await page.waitForSelector("#conn.on");
  // Backfilled from the store: the live chart's first point (data-first) is older than the page.
  await page.waitForFunction((t0) => Number(document.getElementById("chart-live").dataset.first || Infinity) < t0 - 5, loadedAt);
  await page.waitForFunction(() => /^(Charging|Alternator on)/.test(document.getElementById("headline").textContent));
  // The docs' "while charging" shows current going into the battery: the
  // field ramps up for a few seconds, and the scenario's fault comes at 25 s.
  await page.waitForFunction(() => /into the battery/.test(document.getElementById("headline").textContent), null, { timeout: 15000 })
    .catch(() => console.log("note: the alternator did not yet cover the loads: " + "the charging screenshot shows the ramp"));
  await page.waitForTimeout(1000);
  await docsShot("dashboard-phone-charging");
  await page.waitForSelector(".banner.fault", { timeout: 60000 });
  const banner = await page.locator(".banner.fault").first();
  const bannerText = await banner.textContent();
  assert.match(bannerText, /What to do: \S/);
  assert.doesNotMatch(bannerText, /REASON_/);
  assert.doesNotMatch(await page.textContent("#headline"), /REASON_/);
  await page.waitForTimeout(1000);
  await docsShot("dashboard-phone-fault");
  console.log("ok - sensor fault: banner \"" + (await banner.locator("strong").textContent()) + "\" with what to do");
  // Fault and stage markers on the history chart.
  await page.goto(server.base + "/#battery");
  await page.goto(server.base + "/#live");
  await page.waitForFunction(() => Number(document.getElementById("chart-history").dataset.markers || 0) > 0 &&
    Number(document.getElementById("chart-env").dataset.points || 0) > 0);
  await page.goto(server.base + "/#events");
  await page.waitForSelector("#events-body tr");
  // Page back with "Older" until the first run's manual command and settings changes show.
  await olderUntil(/FloatVoltage 13\.4 → 13\.3/, "the first run's import");
  await olderUntil(/duty 25\.5/, "the first run's manual command");
  await olderUntil(/Set-up: \w+ \d+ V 280 Ah/, "the first run's set-up change");
  console.log("ok - events from before the restart are listed, settings changes and command arguments included");
  await plainWordsSweep(page, server.base);
  console.log("ok - no MODE_/PHASE_/GPIO/cv_I/REASON_ names on any page, after a fault, advanced settings shown");
}
