// Browser test of the dashboard (issue 9): playwright-core drives Debian's
// /usr/bin/chromium (never a downloaded browser) against a running server:
//   --server-cmd "<argv...>"  either xr_web_testserver (fake DaemonApi) or
//                             xregulatord --sim --speed 1 --http 127.0.0.1:PORT
// Checks: the dashboard loads, values update live, a chart draws, a parameter
// change with the token applies, a bad value shows the server's error.
// Screenshots go to --artifacts DIR.
import { spawn } from "node:child_process";
import { createRequire } from "node:module";
import fs from "node:fs";
import net from "node:net";
import os from "node:os";
import path from "node:path";
import assert from "node:assert/strict";

const args = Object.fromEntries(
  process.argv.slice(2).reduce((acc, a, i, all) => (a.startsWith("--") ? [...acc, [a.slice(2), all[i + 1]]] : acc), []));
const webDir = args["web-dir"];
const artifacts = args.artifacts;
const token = args.token || "browser-test-token";
const mode = args.mode || "fake";  // fake | daemon
const require = createRequire(path.join(webDir, "package.json"));
const { chromium } = require("playwright-core");
fs.mkdirSync(artifacts, { recursive: true });

const freePort = () => new Promise((resolve, reject) => {
  const s = net.createServer();
  s.listen(0, "127.0.0.1", () => { const p = s.address().port; s.close(() => resolve(p)); });
  s.on("error", reject);
});

// Starts the server; resolves with its base URL once it answers /healthz... or
// its "LISTENING <port>" line (test server).
async function startServer() {
  let port;
  let argv;
  if (mode === "fake") {
    argv = [args.server, "--www", args.www, "--token", token, "--port", "0", "--rate", "10"];
  } else {
    port = await freePort();
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), "xr-browser-daemon-"));
    const cfg = path.join(dir, "xregulator.toml");
    fs.writeFileSync(cfg, `[web]\ntoken = "${token}"\nwww_root = "${args.www}"\n`);
    argv = [args.server, "--sim", "--speed", "1", "--config", cfg, "--state-db", path.join(dir, "state.db"),
            "--http", `127.0.0.1:${port}`];
  }
  const proc = spawn(argv[0], argv.slice(1), { stdio: ["ignore", "pipe", "pipe"] });
  let out = "";
  proc.stdout.on("data", (d) => { out += d; });
  proc.stderr.on("data", (d) => { out += d; });
  const deadline = Date.now() + 30000;
  while (Date.now() < deadline) {
    if (proc.exitCode !== null) throw new Error(`server exited (${proc.exitCode}):\n${out}`);
    if (mode === "fake") {
      const m = out.match(/LISTENING (\d+)/);
      if (m) { port = Number(m[1]); break; }
    } else {
      try { const r = await fetch(`http://127.0.0.1:${port}/api/status`); if (r.ok) break; } catch {}
    }
    await new Promise((r) => setTimeout(r, 100));
  }
  if (!port) throw new Error("server did not start:\n" + out);
  return { proc, base: `http://127.0.0.1:${port}`, log: () => out };
}

const server = await startServer();
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "xr-chromium-"));
let context;
let failed = false;
try {
  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: "/usr/bin/chromium",
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
           "--disable-component-update", "--disable-sync"],
    viewport: { width: 1100, height: 900 },
  });
  const page = context.pages()[0] || (await context.newPage());
  const consoleErrors = [];
  // Script errors only: failed requests (the deliberate 400 below) are checked explicitly.
  page.on("console", (m) => { if (m.type() === "error" && !/Failed to load resource/.test(m.text())) consoleErrors.push(m.text()); });
  page.on("pageerror", (e) => consoleErrors.push(String(e)));
  page.setDefaultTimeout(20000);

  // 1. Loads and goes live.
  await page.goto(server.base + "/");
  await page.waitForSelector("#conn.on");
  await page.waitForFunction(() => /\d+\.\d\d/.test(document.getElementById("v-battery_v").textContent));
  assert.match(await page.textContent("#v-temp_f"), /°F.*°C/);
  console.log("ok - dashboard loads and shows live values");

  // 2. Values update live: the frame sequence advances.
  const seq0 = Number(await page.getAttribute("body", "data-seq"));
  await page.waitForFunction((s) => Number(document.body.dataset.seq) >= s + 3, seq0);
  console.log("ok - values update live over the WebSocket");

  // 3. The live chart draws: uPlot holds points and painted its canvas.
  await page.waitForFunction(() => window.xrDebug && window.xrDebug.livePoints() >= 3);
  const painted = await page.evaluate(() => {
    const c = document.querySelector("#chart-live canvas");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 3; i < d.length; i += 4) if (d[i] > 0) n++;
    return n;
  });
  assert.ok(painted > 500, `live chart canvas painted ${painted} pixels`);
  if (mode === "fake") {
    // The fake has hours of history; a fresh daemon database has none yet.
    await page.waitForFunction(() => window.xrDebug.historyPoints() > 100);
    console.log("ok - history chart draws from /api/history");
  } else {
    await page.waitForFunction(() => document.getElementById("hist-msg").textContent !== "" || window.xrDebug.historyPoints() > 0);
    assert.doesNotMatch(await page.textContent("#hist-msg"), /unknown series/);
  }
  await page.screenshot({ path: path.join(artifacts, `dashboard-live-${mode}.png`), fullPage: true });
  console.log("ok - live chart draws");

  // 4. A parameter change with the token applies.
  await page.goto(server.base + "/#settings");
  const row = page.locator('.param[data-name="FloatVoltage"]');
  await row.locator("xpath=ancestor::details").evaluate((d) => { d.open = true; });
  await row.locator("input").fill("13.4");
  await page.click("#param-apply");
  await page.waitForSelector("#token-dialog[open]");
  await page.fill("#token-input", token);
  await page.click('#token-dialog button[value="ok"]');
  await page.waitForFunction(() => document.getElementById("param-msg").textContent.startsWith("Applied"));
  const params = await (await fetch(server.base + "/api/params")).json();
  const fv = params.params.find((p) => p.name === "FloatVoltage");
  assert.equal(fv.value, 13.4);
  assert.equal(await page.evaluate(() => localStorage.getItem("xregulator.token")), token);
  console.log("ok - parameter change with the token applies");

  // 5. A bad value shows the server's validation message.
  const row2 = page.locator('.param[data-name="FloatVoltage"]');
  await row2.locator("xpath=ancestor::details").evaluate((d) => { d.open = true; });
  await row2.locator("input").fill("99");
  await page.click("#param-apply");
  await page.waitForFunction(() => document.querySelector('.param[data-name="FloatVoltage"] .err').textContent !== "");
  const err = await row2.locator(".err").textContent();
  assert.match(err, /must be between 8 and 64 V/);
  assert.match(await page.textContent("#param-msg"), /rejected/);
  const after = (await (await fetch(server.base + "/api/params")).json()).params.find((p) => p.name === "FloatVoltage");
  assert.equal(after.value, 13.4);
  await page.screenshot({ path: path.join(artifacts, `dashboard-settings-${mode}.png`) });
  console.log("ok - bad value shows the server's error: " + err);

  // 6. Phone-sized screenshots of the other pages (artifacts to look at).
  await page.setViewportSize({ width: 390, height: 844 });
  for (const p of ["live", "protections", "battery", "tuning", "events", "system"]) {
    await page.goto(server.base + "/#" + p);
    await page.waitForSelector(`#page-${p}:not([hidden])`);
    await page.waitForTimeout(300);
    await page.screenshot({ path: path.join(artifacts, `phone-${p}-${mode}.png`), fullPage: true });
  }
  assert.deepEqual(consoleErrors, []);
  console.log("ok - pages render on a phone screen; screenshots in " + artifacts);
} catch (e) {
  failed = true;
  console.error("FAIL:", e);
  console.error("server log:\n" + server.log().slice(-4000));
} finally {
  if (context) await context.close().catch(() => {});
  server.proc.kill("SIGTERM");
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
