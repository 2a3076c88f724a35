// Every dashboard page at phone size (390 x 844), light and dark, against the
// real daemon in --sim (docs/dashboard.md "Every page"). As a test: each page
// shows, has content, and raises no script error in either theme. With
// --docs-dir (make dashboard-screenshots) the pictures go to docs/img/pages.
import fs from "node:fs";
import path from "node:path";
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";
const PAGES = ["live", "settings", "protections", "battery", "alternator", "history", "tuning", "events", "system", "setup"];

// An AGM bank that is set up, charging at cruise, with one sensor fault to
// give the Events page an incident.
const scenario = `name = "screenshots: AGM 300 Ah at cruise"
duration_s = 3600
seed = 11
[battery]
chemistry = "agm"
capacity_ah = 300
soc_pct = 55
[engine]
rpm = 1700
[config]
BatteryProfile = "agm"
[[events]]
at_s = 5
fault = "temp_value"
value = 170
[[events]]
at_s = 12
clear = "temp_value"
`;

// At --speed 4 (the incident's settle and the charts' samples are simulated
// time): 20 s of the daemon's clock give the charts data and the fault is over.
await runDaemonBrowserTest({ args, token, scenario, prefix: "xr-shots-", speed: 4 }, async ({ server, browser, stateDir, get }) => {
  const outDir = args["docs-dir"] ? path.join(args["docs-dir"], "pages") : path.join(stateDir, "pages");
  fs.mkdirSync(outDir, { recursive: true });
  await until("20 s of simulated time: charts with data, the fault over", async () => (await get("/api/status")).t_s >= 20, 60000);
  for (const theme of ["light", "dark"]) {
    const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, colorScheme: theme, locale: "en-GB" });
    const page = await ctx.newPage();
    const errors = [];
    page.on("pageerror", (e) => errors.push(e.message));
    page.setDefaultTimeout(30000);
    await page.goto(server.base + "/#live");
    await page.evaluate((t) => localStorage.setItem("xregulator.token", t), token);
    for (const name of PAGES) {
      await page.goto(`${server.base}/#${name}`);
      await page.reload();
      await page.waitForSelector(`#page-${name}:not([hidden])`);
      // The page's first fetch answered, then one status frame drawn after it.
      await page.waitForLoadState("networkidle");
      const seq = Number(await page.getAttribute("body", "data-seq") ?? -1);
      await page.waitForFunction((s) => Number(document.body.dataset.seq ?? -1) > s, seq);
      assert.equal(await page.evaluate(() => document.documentElement.dataset.theme), theme);
      const text = (await page.textContent(`#page-${name}`)).replace(/\s+/g, " ").trim();
      assert.ok(text.length > 40, `${name} (${theme}) shows almost nothing: "${text}"`);
      await page.screenshot({ path: path.join(outDir, `${name}-${theme}.png`) });
    }
    assert.deepEqual(errors, [], `script errors in the ${theme} theme`);
    await ctx.close();
  }
  console.log(`ok - ${PAGES.length} pages in light and dark at 390 x 844, no script error (${outDir})`);
});
