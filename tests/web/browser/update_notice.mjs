// The System page says which release runs and when an update waits
// (docs/operations.md "Updates and the way back"), in Debian's Chromium at
// phone size against the real daemon in --sim: the package's release record
// gives the version, the channel and the install time; when the package is
// upgraded under the running daemon (the record names a newer version) the
// page says "Update installed; starts when the engine stops".
import fs from "node:fs";
import path from "node:path";
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";
const stateDir0 = fs.mkdtempSync("/tmp/xr-update-notice-rec-");
process.on("exit", () => fs.rmSync(stateDir0, { recursive: true, force: true }));
const release = path.join(stateDir0, "release");
const record = (version) => fs.writeFileSync(release + ".tmp",
  `version=${version}\nchannel=candidate\ninstalled_at=2026-12-06T07:00:00Z\nprevious=0.1.0-0\n`);
record("0.1.0-1");
fs.renameSync(release + ".tmp", release);

await runDaemonBrowserTest({ args, token, prefix: "xr-update-notice-",
  extraArgs: ["--release-file", release, "--run-dir", path.join(stateDir0, "absent")] }, async ({ server, browser }) => {
  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(30000);
  await page.goto(server.base + "/#system");
  const versions = page.locator("#sys-versions");
  await versions.locator("text=0.1.0-1").waitFor();
  const text = await versions.textContent();
  assert.match(text, /candidate/, "the channel");
  assert.match(text, /2026-12-06T07:00:00Z/, "the install time");
  assert.match(text, /none pending/);
  console.log("ok - the System page shows the package's version, channel and install time");

  record("0.1.0-2");
  fs.renameSync(release + ".tmp", release);
  await until("the update notice on the System page", async () => {
    await page.goto(server.base + "/#live");
    await page.goto(server.base + "/#system");
    await versions.locator("text=0.1.0-1").waitFor();
    return /Update installed; starts when the engine stops \(0\.1\.0-2\)/.test(await versions.textContent());
  }, 30000);
  assert.ok(server.proc.exitCode === null, "without --update-watch the daemon keeps running");
  console.log("ok - an upgrade under the running daemon: \"Update installed; starts when the engine stops\"");
});
