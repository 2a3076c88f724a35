// Pairing a phone later without a shell (docs/security.md "Pairing without a
// terminal"), in Debian's Chromium against the real daemon in --sim: the
// owner's phone shows a QR code; the test reads it off the page's canvas
// (jsQR) and a second phone, a fresh browser, opens that address and is
// paired; the code then fails a second time; a client that is not paired
// cannot make one. And the simulated pairing button ([pairing] button_line):
// a 10 ms glitch opens nothing, a press opens the 2-minute window with an event.
import { createRequire } from "node:module";
import path from "node:path";
import assert from "node:assert/strict";
import { parseArgs, runDaemonBrowserTest, startServer, until } from "./server.mjs";

const args = parseArgs();
const require = createRequire(path.join(path.resolve(args["web-dir"]), "package.json"));
const jsQR = require("jsqr");
const token = "browser-test-token-0123456789";
const buttonConfig = "[pairing]\nbutton_line = 17\n";
const noEngine = `name = "the phones"
duration_s = 3600
[engine]
rpm = 0
`;
// The pairing button on the second start: a glitch on its line at 3 s, a
// real press at 8 s (simulated time; the edges carry the loop clock's time,
// so the hold is judged the same at any --speed).
const buttonScenario = noEngine + `[[events]]
at_s = 3.0
pairing_button = "pressed"
[[events]]
at_s = 3.01
pairing_button = "released"
[[events]]
at_s = 8.0
pairing_button = "pressed"
[[events]]
at_s = 8.3
pairing_button = "released"
`;
const buttonEvents = (log) => (log.match(/Pairing window opened for 2 min by the pairing button/g) || []).length;

await runDaemonBrowserTest({ args, token, scenario: noEngine, extraConfig: buttonConfig,
  prefix: "xr-pairqr-" }, async ({ server, browser, stateDir }) => {
  const phone = async (url) => {
    const ctx = await browser.newContext({ viewport: { width: 390, height: 844 }, locale: "en-GB" });
    const page = await ctx.newPage();
    page.setDefaultTimeout(20000);
    await page.goto(url);
    return page;
  };
  // The owner's phone pairs in the new regulator's first-start window.
  const owner = await phone(server.base + "/#system");
  await owner.click("#pair-start");
  await owner.waitForFunction(() => /No code needed/.test(document.getElementById("pair-msg").textContent));
  await owner.fill("#pair-name", "Skipper's phone");
  await owner.click("#pair-ok");
  await owner.waitForSelector('#pair-list li:has-text("Skipper\'s phone (owner) (this device)")');

  // It shows a QR code; the test reads it as a camera would read the screen.
  await owner.click("#pair-qr-new");
  await owner.waitForSelector("#pair-qr:not([hidden])");
  const img = await owner.evaluate(() => {
    const c = document.getElementById("pair-qr-canvas");
    return { w: c.width, h: c.height, data: Array.from(c.getContext("2d").getImageData(0, 0, c.width, c.height).data) };
  });
  const decoded = jsQR(Uint8ClampedArray.from(img.data), img.w, img.h);
  assert.ok(decoded, "the QR code on the owner's phone decodes");
  const url = decoded.data;
  assert.match(url, new RegExp(`^${server.base.replace(/\./g, "\\.")}/#pair=[0-9a-f]{32}$`));
  assert.equal(await owner.textContent("#pair-qr-url"), url);
  if (args.shot) {  // --shot FILE: the page as docs/dashboard.md shows it
    await owner.locator("#pair-qr").scrollIntoViewIfNeeded();
    await owner.screenshot({ path: args.shot });
  }
  console.log("ok - the paired phone shows a QR code of its address and a one-time code");

  // A second phone opens it and pairs, with a name and one press.
  const crew = await phone(url);
  await crew.waitForSelector("#pair-dialog[open]");
  assert.match(await crew.textContent("#pair-msg"), /QR code brought this device here/);
  await crew.fill("#pair-name", "Crew phone");
  await crew.click("#pair-ok");
  await crew.waitForSelector("#pair-dialog[open]", { state: "detached" });
  await crew.waitForSelector('#pair-list li:has-text("Crew phone (this device)")');
  assert.equal(await crew.evaluate(() => location.hash), "#system", "the code left the address bar");
  assert.match(server.log(), /Paired device "Crew phone" \([0-9a-f]{8}\) with a QR code made by device "Skipper's phone"/);
  console.log("ok - a second phone opens the QR code's address and is paired");

  // The code works once: a third phone with the same address is told so.
  const third = await phone(url);
  await third.waitForSelector("#pair-dialog[open]");
  await third.click("#pair-ok");
  await third.waitForFunction(() => /used already or has expired/.test(document.getElementById("pair-msg").textContent));
  const code = url.split("#pair=")[1];
  const again = await fetch(server.base + "/api/pair", { method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ code, name: "stranger" }) });
  assert.equal(again.status, 403);
  // Someone not paired cannot make a QR code.
  const mint = await fetch(server.base + "/api/pair/qr", { method: "POST" });
  assert.equal(mint.status, 401);
  const devices = await (await fetch(server.base + "/api/pair/devices", { headers: { Authorization: `Bearer ${token}` } })).json();
  assert.deepEqual(devices.devices.map((d) => d.name).sort(), ["Crew phone", "Skipper's phone"]);
  console.log("ok - the QR code fails a second time, and an unpaired client cannot make one");

  // The pairing button, on a second start from the same state: the phones
  // stay paired, so no first-start window is open when it is pressed.
  await server.stop();
  const board = await startServer({ mode: "daemon", args, token, stateDir, scenario: buttonScenario, speed: 5,
                                    extraConfig: buttonConfig });
  try {
    const get = async (p) => (await fetch(board.base + p)).json();
    await until("the glitch at 3 s passed", async () => (await get("/api/status")).t_s >= 5);
    assert.equal(buttonEvents(board.log()), 0, "a 10 ms glitch opens nothing");
    assert.equal((await get("/api/pair/window")).open, false, "no window before the press");
    await until("the pairing button's event", async () => buttonEvents(board.log()) > 0, 30000);
    const w = await get("/api/pair/window");
    assert.equal(w.open, true);
    assert.ok(w.closes_in_s > 60 && w.closes_in_s <= 120, JSON.stringify(w));
    await new Promise((r) => setTimeout(r, 1000));
    assert.equal(buttonEvents(board.log()), 1, "one press, one event");
  } finally {
    await board.stop();
  }
  console.log("ok - a press of the pairing button opens the 2-minute window with an event; a 10 ms glitch does not");
});
