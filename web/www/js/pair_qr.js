// A paired phone shows a QR code for the next phone (docs/dashboard.md
// "Pairing", docs/security.md "Pairing without a terminal"): the regulator
// makes a one-time code (POST /api/pair/qr, for a paired device only, valid
// 10 minutes, works once); this phone draws its own address with the code
// after "#pair=" as a QR code. The code rides in the fragment, which a
// browser never sends to a server, so it is in no request line or log.
// The QR drawing is qrcode-generator (npm, served from vendor/ like uPlot),
// loaded only when a QR code is shown.
import { write } from "./api.js";
import { clock } from "./format.js";

const $ = (id) => document.getElementById(id);
const QUIET_MODULES = 4;  // the white margin a scanner needs around the code

// The code in an address like ".../#pair=<32 hex digits>"; "" when none.
export function qrCodeFromAddress(hash) {
  const m = /^#pair=([0-9a-f]{32})$/.exec(hash || "");
  return m ? m[1] : "";
}

export function pairingUrl(code, loc = location) {
  return `${loc.origin}${loc.pathname}#pair=${code}`;
}

// Dark modules on white whatever the theme: cameras read dark on light.
function drawQr(canvas, modules) {
  const n = modules.getModuleCount();
  const scale = Math.max(2, Math.floor(264 / (n + 2 * QUIET_MODULES)));
  canvas.width = canvas.height = (n + 2 * QUIET_MODULES) * scale;
  const g = canvas.getContext("2d");
  g.fillStyle = "#fff";
  g.fillRect(0, 0, canvas.width, canvas.height);
  g.fillStyle = "#000";
  for (let r = 0; r < n; r++)
    for (let c = 0; c < n; c++)
      if (modules.isDark(r, c)) g.fillRect((c + QUIET_MODULES) * scale, (r + QUIET_MODULES) * scale, scale, scale);
}

export async function showPairingQr() {
  const { default: qrcode } = await import("../vendor/qrcode.mjs").catch(() => {
    throw new Error("The QR code library is missing from this installation: use “New pairing code” instead.");
  });
  const r = await write("POST", "/api/pair/qr");
  const url = pairingUrl(r.code);
  const modules = qrcode(0, "M");  // the smallest version that holds it; M: 15 % may be smudged
  modules.addData(url);
  modules.make();
  drawQr($("pair-qr-canvas"), modules);
  $("pair-qr-url").textContent = url;
  $("pair-qr-until").textContent = clock(Date.now() / 1000 + r.expires_in_s);
  $("pair-qr").hidden = false;
}
