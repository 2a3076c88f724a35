// Pairing without a terminal (docs/security.md "Pairing without a
// terminal"), in Debian's Chromium against the real daemon on a new state
// database: the owner's phone pairs with no code and no shell in the first
// 15 minutes and is the owner; a second phone then needs a code, which the
// owner's phone makes; the second phone cannot revoke the owner; the owner
// revokes it; pairing and revoking are in the dashboard's event list.
import { createRequire } from "node:module";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import assert from "node:assert/strict";
import { startServer } from "./server.mjs";

const args = Object.fromEntries(
  process.argv.slice(2).reduce((acc, a, i, all) => (a.startsWith("--") ? [...acc, [a.slice(2), all[i + 1]]] : acc), []));
const require = createRequire(path.join(path.resolve(args["web-dir"]), "package.json"));
const { chromium } = require("playwright-core");
const token = "browser-test-token-0123456789";
const stateDir = fs.mkdtempSync(path.join(os.tmpdir(), "xr-pairwin-"));
const server = await startServer({ mode: "daemon", args, token, stateDir });
const browser = await chromium.launch({
  executablePath: "/usr/bin/chromium", headless: true,
  args: ["--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking", "--disable-sync"],
});
let failed = false;
try {
  const phone = async () => {
    const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
    const page = await ctx.newPage();
    page.setDefaultTimeout(20000);
    await page.goto(server.base + "/#system");
    await page.waitForSelector("#pair-start:not([hidden])");
    return page;
  };
  const openPairDialog = async (page) => {
    await page.click("#pair-start");
    await page.waitForSelector("#pair-dialog[open]");
  };

  // The owner's phone: no code, no shell.
  assert.match(server.log(), /the first device to pair needs no code/);
  const owner = await phone();
  await openPairDialog(owner);
  await owner.waitForFunction(() => /No code needed/.test(document.getElementById("pair-msg").textContent));
  await owner.fill("#pair-name", "Skipper's phone");
  await owner.click("#pair-ok");
  await owner.waitForSelector("#pair-dialog[open]", { state: "detached" });
  await owner.waitForSelector('#pair-list li:has-text("Skipper\'s phone (owner) (this device)")');
  console.log("ok - a new phone pairs with no code and no shell in the first-start window, as the owner");

  // A second phone: the window closed with the first pairing.
  const crew = await phone();
  await openPairDialog(crew);
  await crew.waitForTimeout(1000);  // the window question has been answered
  assert.doesNotMatch(await crew.textContent("#pair-msg"), /No code needed/);
  await crew.fill("#pair-name", "Crew tablet");
  await crew.click("#pair-ok");
  await crew.waitForFunction(() => /6 digits/.test(document.getElementById("pair-msg").textContent));
  const refused = await fetch(server.base + "/api/pair", { method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ name: "stranger" }) });
  assert.equal(refused.status, 403);
  // The owner makes a code on its System page; the crew types it.
  await owner.click("#pair-code-new");
  await owner.waitForSelector("#pair-newcode:not([hidden])");
  const code = (await owner.textContent("#pair-newcode")).match(/(\d{6})/)[1];
  await crew.fill("#pair-code", code);
  await crew.click("#pair-ok");
  await crew.waitForSelector("#pair-dialog[open]", { state: "detached" });
  await crew.waitForSelector('#pair-list li:has-text("Crew tablet (this device)")');
  // The crew sees the owner but has no button to revoke it, nor "Revoke all".
  const ownerRow = crew.locator("#pair-list li", { hasText: "Skipper's phone (owner)" });
  assert.equal(await ownerRow.locator("button").count(), 0);
  assert.equal(await crew.isDisabled("#pair-revoke-all"), true);
  console.log("ok - the second phone needs a code made by the owner's phone, and cannot revoke the owner");

  // The owner revokes the crew's tablet.
  await owner.goto(server.base + "/#live");
  await owner.goto(server.base + "/#system");
  await owner.locator("#pair-list li", { hasText: "Crew tablet" }).locator("button").click();
  await owner.waitForSelector("#confirm-dialog[open]");
  await owner.click("#confirm-ok");
  await owner.waitForFunction(() => !/Crew tablet/.test(document.getElementById("pair-list").textContent));

  // Both are events in the dashboard's list, naming the devices.
  await owner.goto(server.base + "/#events");
  await owner.waitForSelector("#events-body tr");
  await owner.waitForFunction(() => /Revoked device “?"?Crew tablet/.test(document.getElementById("events-body").textContent));
  const events = await owner.textContent("#events-body");
  assert.match(events, /Paired device "Skipper's phone" \([0-9a-f]{8}\) as the owner without a code/);
  assert.match(events, /Paired device "Crew tablet"/);
  assert.match(events, /Revoked device "Crew tablet" \([0-9a-f]{8}\) by device "Skipper's phone"/);
  assert.match(server.log(), /security: Revoked device "Crew tablet"/);
  console.log("ok - pairing and revoking appear as events naming the devices, and in the journal");
} catch (e) {
  failed = true;
  console.error(e);
  console.error(server.log().slice(-3000));
} finally {
  await browser.close();
  await server.stop();
  fs.rmSync(stateDir, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
