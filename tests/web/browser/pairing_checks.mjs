// Getting in (docs/dashboard.md) and plain words (item 7), against the real
// daemon: called from daemon_checks.mjs at the points of its user's story.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import path from "node:path";

// The first change of a fresh browser opened "Pair this device". The owner
// gets a code as the dialog says: `xregulatord --pair` on the unit; types a
// digit wrong first (refused, in words, the dialog stays), then the code.
export async function pairAtFirstChange({ page, server, args, stateDir, token, docsShot, param }) {
  await page.waitForSelector("#pair-dialog[open]");
  assert.match(await page.textContent("#pair-dialog"), /xregulatord --pair/);
  const pairOut = execFileSync(args.server, ["--pair", "--config", path.join(stateDir, "xregulator.toml"),
    "--http", server.base.replace("http://", "")], { encoding: "utf8" });
  const code = pairOut.match(/pairing code (\d{6})/)[1];
  const typo = code.slice(0, 5) + String((Number(code[5]) + 1) % 10);  // one digit wrong
  await page.fill("#pair-code", typo);
  await page.fill("#pair-name", "Skipper's phone");
  await page.click("#pair-ok");
  await page.waitForFunction(() => /Wrong or expired code/.test(document.getElementById("pair-msg").textContent));
  const refused = await page.textContent("#pair-msg");
  assert.match(refused, /4 tries left/);
  assert.equal(await page.isVisible("#pair-dialog[open]"), true);  // still open: the owner corrects the code
  assert.equal(await param("BatteryCapacity_Ah") === 280, false);  // nothing was written
  await docsShot("dashboard-phone-pairing");
  await page.fill("#pair-code", code);
  await page.click("#pair-ok");
  await page.waitForSelector("#setup-start:not([hidden])");  // the write went through after pairing
  const stored = await page.evaluate(() => ({ t: localStorage.getItem("xregulator.token"), d: localStorage.getItem("xregulator.device") }));
  assert.ok(stored.t && stored.t !== token && JSON.parse(stored.d).name === "Skipper's phone", JSON.stringify(stored));
  const authed = (p, init = {}) => fetch(server.base + p, { ...init, headers: { Authorization: "Bearer " + token } });
  assert.deepEqual((await (await authed("/api/pair/devices")).json()).devices.map((d) => d.name), ["Skipper's phone"]);
  console.log(`ok - a fresh browser pairs with the code from xregulatord --pair; a wrong code is refused: "${refused}"`);
}

// The System page: this device in the list, a code for a second device,
// which pairs with it; revoking it (asks first) ends its access.
export async function pairedDevices({ page, server, send, shot }) {
  await page.goto(server.base + "/#system");
  // The first device paired is the owner (docs/security.md "Owner and devices").
  await page.waitForSelector('#pair-list li:has-text("Skipper\'s phone (owner) (this device)")');
  assert.match(await page.textContent("#pair-this"), /paired as “Skipper's phone”/);
  assert.equal(await page.isVisible("#pair-start"), false);  // no "Pair this device" once paired
  await page.click("#pair-code-new");
  await page.waitForSelector("#pair-newcode:not([hidden])");
  const code2 = (await page.textContent("#pair-newcode")).match(/(\d{6})/)[1];
  const second = await (await fetch(server.base + "/api/pair", { method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ code: code2, name: "Crew tablet" }) })).json();
  assert.ok(second.token, JSON.stringify(second));
  const asSecond = () => fetch(server.base + "/api/commands", { method: "POST", body: JSON.stringify({ command: "reset_alarm_latch" }),
    headers: { Authorization: "Bearer " + second.token, "Content-Type": "application/json" } });
  assert.equal((await asSecond()).status, 200);
  await page.goto(server.base + "/#live");
  await page.goto(server.base + "/#system");
  const crew = page.locator("#pair-list li", { hasText: "Crew tablet" });
  await crew.locator("button").click();
  await page.waitForSelector("#confirm-dialog[open]");
  await page.click("#confirm-ok");
  await page.waitForFunction(() => !/Crew tablet/.test(document.getElementById("pair-list").textContent));
  assert.equal((await asSecond()).status, 403);  // revoked: refused
  assert.equal((await send({ command: "reset_alarm_latch" })).status, 200);  // the installer token still works
  await shot("dashboard-system-pairing");
  console.log("ok - System page: paired devices listed, a new code pairs a second device, revoking it ends its access");

}

// Item 7: no developer names in what the user reads, on any page, after a
// fault (banners, events) and with every advanced setting shown.
export async function plainWordsSweep(page, base) {
  const dev = /MODE_|PHASE_|GPIO|\bcv_I\b|\bseeds?\b|REASON_|SYS_MODE|\bnan\b|-999\b/;
  const found = [];
  for (const p of ["live", "settings", "protections", "battery", "tuning", "events", "system", "setup"]) {
    await page.goto(base + "/#" + p);
    await page.waitForSelector(`#page-${p}:not([hidden])`);
    if (p === "settings") {
      await page.waitForSelector(".param");
      await page.check("#param-advanced");
      await page.evaluate(() => document.querySelectorAll("details").forEach((d) => { d.open = true; }));
    }
    if (p === "events") await page.waitForSelector("#events-body tr");
    if (p === "system") await page.waitForSelector("#sys-versions tr");
    await page.waitForTimeout(500);
    const text = await page.evaluate(() => document.body.innerText);
    for (const line of text.split("\n")) if (dev.test(line)) found.push(`${p}: ${line.trim().slice(0, 160)}`);
  }
  assert.deepEqual(found, [], "developer names shown to the user");
}
