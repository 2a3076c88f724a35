// The dashboard an owner reads at a glance (docs/dashboard.md "At a glance",
// "Offline", "Settings", "Units", "Events"), in Debian's Chromium at phone
// size (390 x 844) against the real daemon in --sim, charging an AGM bank:
//   - Live: one hero value of at least 64 px near the top, values larger
//     than 23 px, a bottom bar of at most 5 tabs with "More";
//   - Settings: the one-line notice with Keep / Drop dashboard values, plain
//     labels found by search, "Default" the profile's value, °C;
//   - the Alternator page's bands in °C (65/80/95/105);
//   - Events under date headers;
//   - the daemon killed: the last values stay, Import and every control
//     disabled, the badge says unreachable, Settings keeps the last list.
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, until } from "./server.mjs";

const args = parseArgs();
const token = "browser-test-token-0123456789";
const PHONE = { width: 390, height: 844 };

const scenario = `name = "charging for the glance test"
duration_s = 3600
seed = 5
[battery]
chemistry = "agm"
capacity_ah = 300
soc_pct = 50
[engine]
rpm = 1700
[config]
BatteryProfile = "agm"
`;

async function glance(page) {
  const m = await page.evaluate(() => {
    const box = (el) => { const r = el.getBoundingClientRect(); return { top: r.top, bottom: r.bottom, left: r.left, right: r.right }; };
    const hero = document.getElementById("hero-value");
    const tabs = [...document.querySelectorAll("nav a, nav button")].filter((el) => el.getBoundingClientRect().height > 0);
    return {
      heroPx: parseFloat(getComputedStyle(hero).fontSize), hero: box(hero), heroText: hero.textContent,
      state: document.getElementById("hero-state").textContent,
      cardPx: parseFloat(getComputedStyle(document.getElementById("v-bcur_a")).fontSize),
      tabs: tabs.map((el) => ({ text: el.textContent.trim(), ...box(el) })),
    };
  });
  assert.ok(m.heroPx >= 64, `hero ${m.heroPx} px`);
  assert.match(m.heroText, /\d/, "the hero shows a number");
  assert.ok(m.state.length > 0 && m.state !== "—", `state word "${m.state}"`);
  assert.ok(m.hero.top >= 0 && m.hero.bottom <= PHONE.height / 3, `the hero within the top third: ${JSON.stringify(m.hero)}`);
  assert.ok(m.cardPx > 23, `card values ${m.cardPx} px`);
  assert.ok(m.tabs.length <= 5, `tabs shown: ${m.tabs.map((t) => t.text).join(", ")}`);
  assert.equal(m.tabs[m.tabs.length - 1].text, "More");
  for (const t of m.tabs) assert.ok(t.top >= PHONE.height - 80 && t.bottom <= PHONE.height + 1, `${t.text} at the bottom: ${JSON.stringify(t)}`);
  console.log(`ok - at a glance: hero ${m.heroText} at ${m.heroPx} px (top ${Math.round(m.hero.top)} px), cards ${m.cardPx} px, ` +
    `${m.tabs.length} tabs at the bottom: ${m.tabs.map((t) => t.text).join(" ")}`);
  await page.click("#tab-more");
  await page.click('nav a[href="#system"]');
  await page.waitForSelector("#page-system:not([hidden])");
  assert.equal(await page.isVisible('nav a[href="#settings"]'), false, "More closes after a choice");
  assert.ok(await page.locator("#tab-more.current").count(), "More is marked while a page behind it shows");
}

async function settingsNotice(page, server, get) {
  const patch = (body) => fetch(server.base + "/api/params", { method: "PATCH",
    headers: { Authorization: "Bearer " + token, "Content-Type": "application/json" }, body: JSON.stringify(body) });
  assert.equal((await patch({ FloatVoltage: 13.2 })).status, 200);
  await page.goto(server.base + "/#settings");
  await page.waitForSelector("#param-file-note:not([hidden])");
  assert.equal(await page.textContent("#param-file-text"), "1 value set on the dashboard differs from the file.");
  await page.click("#param-keep");
  await page.waitForSelector("#param-file-note", { state: "hidden" });
  await page.reload();
  await page.waitForSelector('.param[data-name="FloatVoltage"]');
  assert.equal(await page.isVisible("#param-file-note"), false, "kept: the line stays away");
  assert.equal((await patch({ AbsorptionVoltage: 14.3 })).status, 200);
  await page.reload();
  await page.waitForSelector("#param-file-note:not([hidden])");
  assert.match(await page.textContent("#param-file-text"), /^2 values set on the dashboard differ from the file\.$/);
  await page.click("#param-drop");
  await until("the dashboard values dropped", async () =>
    (await get("/api/params")).params.filter((p) => p.source === "dashboard").length === 0);
  await page.waitForSelector("#param-file-note", { state: "hidden" });
  console.log("ok - settings: one line with Keep (stays away until values change) and Drop dashboard values");

  // Plain labels; raw names only under Advanced; search finds both.
  assert.equal(await page.isVisible('.param[data-name="BulkVoltage"] .pname'), false);
  await page.fill("#param-filter", "charge is done");
  await page.waitForSelector('.param[data-name="TailCurrent_A"]');
  await page.fill("#param-filter", "TailCurrent_A");
  await page.waitForSelector('.param[data-name="TailCurrent_A"]');
  await page.fill("#param-filter", "");
  await page.check("#param-advanced");
  assert.equal(await page.isVisible('.param[data-name="BulkVoltage"] .pname'), true);
  await page.uncheck("#param-advanced");
  // "Default" is the AGM profile's value, which the server says.
  const abs = (await get("/api/params")).params.find((p) => p.name === "FloatVoltage");
  assert.ok(abs.profile_owned && typeof abs.effective_default === "number", JSON.stringify(abs));
  assert.notEqual(abs.effective_default, abs.default, "the AGM profile's float is not the firmware default");
  assert.match(await page.textContent('.param[data-name="FloatVoltage"] .meta'), new RegExp(`default ${abs.effective_default} ·`));
  // A °F parameter in °C.
  const lim = page.locator('.param[data-name="TemperatureLimitF"]');
  assert.equal(await lim.locator(".unit").textContent(), "°C");
  assert.equal(await lim.locator("input").inputValue(), "65.6");
  console.log(`ok - settings: plain labels, search by label or name, Default = profile's ${abs.effective_default} V, limit in °C`);
}

async function bandsAndEvents(page, server) {
  await page.goto(server.base + "/#alternator");
  await page.waitForFunction(() => document.querySelectorAll("#alt-table tr").length >= 5);
  const alt = await page.textContent("#alt-table");
  for (const c of [65, 80, 95, 105]) assert.match(alt, new RegExp(`at or above ${c} °C`));
  assert.doesNotMatch(alt, /°F/);
  await page.goto(server.base + "/#events");
  await page.waitForSelector("#events-body tr.day-head");
  const first = await page.locator("#events-body tr").first();
  assert.equal(await first.getAttribute("class"), "day-head", "the list starts with its day");
  assert.match(await first.textContent(), /^Today · \w+ \d+ \w+$/);
  assert.match(await page.locator("#events-body tr:not(.day-head) td").first().textContent(), /^\d\d:\d\d$/);
  console.log(`ok - alternator bands in °C (65/80/95/105); events under "${await first.textContent()}"`);
}

async function offline(page, server) {
  await page.goto(server.base + "/#live");
  await page.waitForSelector("#conn.on");
  await server.stop();
  await page.waitForFunction(() => document.getElementById("hdr-mode").textContent === "Regulator unreachable");
  const before = await page.textContent("#hero-value");
  await page.waitForTimeout(2000);
  const look = await page.evaluate(() => ({
    hero: document.getElementById("hero-value").textContent, battery: document.getElementById("v-battery_v").textContent,
    alarm: document.getElementById("hdr-alarm").hidden, importOff: document.getElementById("config-import").disabled,
    importLook: Number(getComputedStyle(document.getElementById("config-import-label")).opacity),
  }));
  assert.equal(look.hero, before, "the last hero value stays");
  assert.match(look.hero, /\d/, "a number, not a dash");
  assert.match(look.battery, /\d/, "the last battery voltage stays");
  assert.ok(look.importOff && look.importLook < 0.6, JSON.stringify(look));
  await page.click('nav a[href="#events"]');  // a tab still works
  await page.click("#tab-more");
  await page.click('nav a[href="#settings"]');
  await page.waitForSelector("#param-offline:not([hidden])");
  assert.match(await page.textContent("#param-offline"), /cannot be reached: these are the settings read at \d\d:\d\d/);
  assert.ok(await page.locator(".param").count() > 10, "the last settings, not a blank page");
  await page.waitForFunction(() => [...document.querySelectorAll("#page-settings input, #page-settings button")].every((el) => el.disabled));
  console.log(`ok - offline: hero ${look.hero} and the values stay, badge "Regulator unreachable", Import and every control disabled, ` +
    "Settings shows the last list read-only");
}

await runDaemonBrowserTest({ args, token, scenario, prefix: "xr-glance-" }, async ({ server, browser, get }) => {
  const ctx = await browser.newContext({ viewport: PHONE, locale: "en-GB", colorScheme: "light" });
  await ctx.addInitScript((t) => localStorage.setItem("xregulator.token", t), token);
  const page = await ctx.newPage();
  page.setDefaultTimeout(20000);
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  await page.goto(server.base + "/#live");
  await page.waitForSelector("#conn.on");
  await until("a charging current", async () => (await get("/api/status")).alt_a > 1);
  await glance(page);
  await settingsNotice(page, server, get);
  await bandsAndEvents(page, server);
  await offline(page, server);
  assert.deepEqual(errors, [], "no script error");
});
