// The Weather mode panel (docs/integrations.md "Weather"), in Debian's
// Chromium at phone size against the real daemon in --sim: the scenario
// scenarios/weather-gps.toml puts a GNSS on the simulated NMEA 2000 bus and
// points the forecast client at a local server answering the recorded sunny
// forecast. The owner sees the three days, that the alternator is held off
// and why, and where the position came from; then a cloudy forecast, and
// the panel says it charges again. The daemon runs at --speed 10: the
// one-minute refresh is simulated time (docs/architecture.md "One clock").
import fs from "node:fs";
import http from "node:http";
import path from "node:path";
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest } from "./server.mjs";

const args = parseArgs();
const root = path.resolve(args.root);
const token = "browser-test-token-0123456789";

// The forecast server: whatever `answer` names, from the recorded answers.
let answer = "sunny";
const requests = [];
const forecast = http.createServer((req, res) => {
  requests.push(req.url);
  // The recorded answer made today's and for the place asked, as a real
  // server answers (the client refuses a forecast for other days or places).
  const recorded = JSON.parse(fs.readFileSync(path.join(root, "tests/integrations/weather", `${answer}.json`), "utf8"));
  const query = new URL(req.url, "http://forecast").searchParams;
  if (query.has("latitude")) recorded.latitude = Number(query.get("latitude"));
  if (query.has("longitude")) recorded.longitude = Number(query.get("longitude"));
  const today = Date.parse(new Date().toISOString().slice(0, 10));
  recorded.daily.time = recorded.daily.time.map((_, i) => new Date(today + i * 86400000).toISOString().slice(0, 10));
  const body = Buffer.from(JSON.stringify(recorded));
  res.writeHead(200, { "Content-Type": "application/json", "Content-Length": body.length });
  res.end(body);
});
await new Promise((r) => forecast.listen(0, "127.0.0.1", r));
const scenario = fs.readFileSync(path.join(root, "scenarios/weather-gps.toml"), "utf8")
  .replace("127.0.0.1:8099", `127.0.0.1:${forecast.address().port}`);

await runDaemonBrowserTest({ args, prefix: "xr-weather-", token, scenario, speed: 10,
  // 100 ms ticks: 10 ms of wall time at speed 10, lighter than speed 1 at 400 Hz.
  extraConfig: "[modes]\nweatherModeEnabled = true\nUVThresholdHigh = 6.0\n[can]\nn2k_interface = \"can1\"\n" +
    "[runtime]\ncontrol_period_us = 100000\n" },
async ({ server, browser, stateDir }) => {
  const r = await fetch(server.base + "/api/commands", { method: "POST",
    headers: { Authorization: "Bearer " + token, "Content-Type": "application/json" },
    body: JSON.stringify({ command: "set_soc", soc_pct: 80 }) });
  assert.equal(r.status, 200);
  const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
  const page = await ctx.newPage();
  page.setDefaultTimeout(40000);
  await page.goto(server.base + "/#live");
  // The panel reads every 30 s: reload until the held-off verdict shows.
  const verdict = async (re) => {
    const end = Date.now() + 90000;
    for (;;) {
      await page.waitForSelector("#weather-panel:not([hidden]) #weather-verdict");
      if (re.test(await page.textContent("#weather-verdict"))) return;
      assert.ok(Date.now() < end, `the verdict never matched ${re}: ${await page.textContent("#weather-verdict")}`);
      await page.waitForTimeout(1000);
      await page.reload();
    }
  };
  await verdict(/^Holding the alternator off: 3 of 3 days above UV 6\.0/);
  // The badge says the same as the panel and the headline: nobody pressed Off.
  await page.waitForFunction(() => document.getElementById("hdr-mode").textContent === "Solar first");
  assert.match(await page.textContent("#headline"), /solar first/i);
  assert.equal(await page.isVisible("#weather-note"), false, "no failed fetch, no note");
  const table = await page.textContent("#weather-panel table");
  assert.match(table, /UV index8\.[45]8\.97\.6/, "the three days' UV index");
  assert.match(table, /Radiation MJ\/m²29\.430\.027\.9/, "the three days' radiation");
  assert.match(await page.textContent("#weather-position"),
    /^Position -33\.857, 151\.215 \(from the boat's GPS on NMEA 2000\); forecast \d+ min ago\.$/);
  const st = await (await fetch(server.base + "/api/status")).json();
  assert.equal(st.reason, "REASON_WEATHER_MODE", "the daemon holds the alternator off, as the panel says");
  assert.ok(requests.some((u) => u.includes("latitude=-33.8568&longitude=151.2153")));
  await page.locator("#weather-panel").scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(stateDir, "weather-sunny.png") });
  if (args["docs-dir"]) fs.copyFileSync(path.join(stateDir, "weather-sunny.png"), path.join(args["docs-dir"], "weather-panel.png"));
  console.log("ok - a sunny forecast for the GPS's position: the panel says the alternator rests, and why");

  answer = "cloudy";  // read at the next refresh (refresh_min = 1)
  await verdict(/^Charging as usual: 0 of 3 days above UV 6\.0/);
  assert.notEqual((await (await fetch(server.base + "/api/status")).json()).reason, "REASON_WEATHER_MODE");
  console.log("ok - a cloudy forecast: the panel says it charges as usual");
});
