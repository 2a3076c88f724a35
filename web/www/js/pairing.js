// Getting in (docs/dashboard.md): "Pair this device" with the 6-digit code
// the regulator prints (journal at every start, `xregulatord --pair`, or a
// device paired before), the installer's token as the fallback, and the
// System page's list of paired devices with revoke and "new code".
// The server side: web/server/pairing.h, docs/dashboard.md "Pairing".
import { forgetToken, getDevice, getToken, pair, quietRequest, saveCredential, setAuthoriser, toast, tokenWorks, write } from "./api.js";
import { confirmAction } from "./confirm.js";
import { clock } from "./format.js";
import { qrCodeFromAddress, showPairingQr } from "./pair_qr.js";

const $ = (id) => document.getElementById(id);

// A name the owner recognises in the list later; they can change it.
export function guessDeviceName(ua = navigator.userAgent) {
  if (/iPhone/.test(ua)) return "iPhone";
  if (/iPad/.test(ua)) return "iPad";
  if (/Android/.test(ua)) return /Mobile/.test(ua) ? "Android phone" : "Android tablet";
  if (/Macintosh/.test(ua)) return "Mac";
  if (/Windows/.test(ua)) return "Windows computer";
  if (/Linux/.test(ua)) return "Linux computer";
  return "phone";
}

// The server's refusal in words the owner can act on.
export function pairingError(status, body = {}, qr = false) {
  if (qr && status === 403 && typeof body.tries_left === "number")
    return "This QR code was used already or has expired (a QR code works once, for 10 minutes): show a new one on the paired phone.";
  // The window was used by another device, or this one is not on the boat's
  // own network: the server's words say which (docs/security.md).
  if (status === 403 && (body.claimed_by || /own network/.test(body.error || "")))
    return `${body.error.charAt(0).toUpperCase()}${body.error.slice(1)}.`;
  if (status === 403 && typeof body.tries_left !== "number")
    return "The first 15 minutes for pairing without a code are over: enter a pairing code.";
  if (status === 403) {
    const n = body.tries_left;
    return "Wrong or expired code" + (typeof n === "number" ? ` — ${n} ${n === 1 ? "try" : "tries"} left for this code.` : ".") +
      " Check the 6 digits; a code works once and for 10 minutes.";
  }
  if (status === 429) {
    const min = Math.ceil((body.retry_after_s || 300) / 60);
    return `Too many wrong codes: that code is void and pairing is locked for ${min} min. ` +
      "Make a new code (xregulatord --pair, or a paired device) — a new code ends the lock.";
  }
  if (status === 409) return "Too many paired devices: revoke one on a paired device's System page first.";
  if (status === 503) return "The regulator cannot save the pairing (its state database is not writable): see the System page.";
  if (status === 400) return "Enter the 6 digits of the pairing code.";
  return body.error || `The regulator answered ${status}.`;
}

// What the dialog says before anything is typed: a QR code brought this
// device (no code to type), or a pairing window is open (the first
// 15 minutes of a new regulator, the ignition turned off-on-off-on, the
// pairing button; docs/security.md "Pairing without a terminal").
function explainDialog(msg, qrCode) {
  const state = { windowOpen: false };
  msg.className = "msg";
  $("pair-code").placeholder = qrCode ? "from the QR code" : "6 digits";
  $("pair-code").disabled = !!qrCode;
  if (qrCode) {
    msg.textContent = "A paired phone's QR code brought this device here: press Pair (the code works once, for 10 min).";
    return state;
  }
  quietRequest("GET", "/api/pair/window").then((r) => {
    if (!r.ok || !r.body.open) return;
    state.windowOpen = true;
    msg.textContent = `No code needed: a pairing window is open. Press Pair within ${Math.max(1, Math.floor(r.body.closes_in_s / 60))} min — the first device to pair gets in (on a new regulator, it becomes the owner).`;
    $("pair-code").placeholder = "not needed now";
  }).catch(() => {});
  return state;
}

// Shows the dialog; resolves with the new token, or "" when cancelled. The
// dialog stays open on a wrong code, with the reason, until the owner pairs
// or cancels. qrCode: the one-time code of a paired phone's QR code.
export function askPairing(why = "", qrCode = "") {
  const dlg = $("pair-dialog");
  const msg = $("pair-msg");
  $("pair-why").textContent = why;
  $("pair-code").value = "";
  $("token-input").value = "";
  $("pair-name").value = (getDevice() && getDevice().name) || guessDeviceName();
  msg.textContent = "";
  const state = explainDialog(msg, qrCode);
  return new Promise((resolve) => {
    let done = false;
    const finish = (token) => { if (done) return; done = true; form.removeEventListener("submit", onSubmit); resolve(token); };
    const form = $("pair-form");
    const onSubmit = async (ev) => {
      if (ev.submitter && ev.submitter.value === "cancel") return;  // closes; "close" resolves ""
      ev.preventDefault();
      const ok = $("pair-ok");
      ok.disabled = true;
      msg.className = "msg";
      try {
        const token = $("token-input").value.trim();
        if (token) {
          msg.textContent = "Checking the token…";
          if (!(await tokenWorks(token))) { msg.className = "msg bad"; msg.textContent = "The regulator does not accept that token."; return; }
          saveCredential(token);
          finish(token);
          dlg.close("ok");
          toast("This device uses the installer's token");
          return;
        }
        if (qrCode) {
          msg.textContent = "Pairing…";
          const r = await pair(qrCode, $("pair-name").value.trim());
          saveCredential(r.token, { id: r.id, name: r.name });
          finish(r.token);
          dlg.close("ok");
          toast(`Paired as “${r.name}” with the QR code`);
          return;
        }
        const code = $("pair-code").value.replace(/\D/g, "");
        if (!code && state.windowOpen) {
          msg.textContent = "Pairing…";
          const r = await pair(null, $("pair-name").value.trim());
          saveCredential(r.token, { id: r.id, name: r.name });
          finish(r.token);
          dlg.close("ok");
          toast(`Paired as “${r.name}”`);
          return;
        }
        if (code.length !== 6) { msg.className = "msg bad"; msg.textContent = "Enter the 6 digits of the pairing code."; return; }
        msg.textContent = "Pairing…";
        const r = await pair(code, $("pair-name").value.trim());
        saveCredential(r.token, { id: r.id, name: r.name });
        finish(r.token);
        dlg.close("ok");
        toast(`Paired as “${r.name}”`);
      } catch (e) {
        msg.className = "msg bad";
        msg.textContent = e.status ? pairingError(e.status, e.body, !!qrCode) : "The regulator cannot be reached: " + e.message;
        $("pair-code").select();
      } finally {
        ok.disabled = false;
      }
    };
    form.addEventListener("submit", onSubmit);
    dlg.addEventListener("close", () => finish(""), { once: true });
    dlg.showModal();
    $(qrCode ? "pair-name" : "pair-code").focus();
  });
}

// ---------------------------------------------------------------- System page
export function renderThisDevice() {
  const d = getDevice();
  $("pair-this").textContent = d ? `This device is paired as “${d.name}”.`
    : getToken() ? "This device uses the installer's token." : "This device is not paired: it can look, not change.";
  $("pair-start").hidden = !!getToken();
  $("pair-forget").hidden = !getToken();
  $("pair-manage").hidden = !getToken();
}

export async function loadDevices() {
  renderThisDevice();
  const list = $("pair-list");
  if (!getToken()) { list.textContent = ""; return; }
  const r = await quietRequest("GET", "/api/pair/devices");
  if (r.status === 401 || r.status === 403) {
    forgetToken();
    renderThisDevice();
    $("pair-this").textContent = "This device's pairing was revoked (or the token changed): pair it again to change things.";
    list.textContent = "";
    return;
  }
  if (!r.ok) throw new Error(r.body.error || `paired devices: ${r.status}`);
  // The owner (the first paired device, or the installer's token) revokes
  // anyone; another device only itself (docs/security.md "Owner and devices").
  const { devices, you_are_owner: owner } = r.body;
  const me = getDevice();
  list.textContent = "";
  if (!devices.length) { const li = document.createElement("li"); li.textContent = "No paired devices."; list.appendChild(li); }
  for (const d of devices) {
    const li = document.createElement("li");
    li.dataset.id = d.id;
    const t = document.createElement("span");
    const mine = d.this_device || (me && me.id === d.id);
    t.textContent = `${d.name}${d.owner ? " (owner)" : ""}${mine ? " (this device)" : ""} · paired ${clock(d.created)}`;
    li.append(t);
    if (owner || mine) {
      const b = document.createElement("button");
      b.textContent = "Revoke";
      b.addEventListener("click", () => revoke(d).catch((e) => toast(e.message, true)));
      li.append(b);
    }
    list.appendChild(li);
  }
  $("pair-revoke-all").disabled = !devices.length || !owner;
}

async function revoke(d) {
  const me = getDevice();
  const mine = me && me.id === d.id;
  if (!(await confirmAction(`Revoke “${d.name}”? ${mine ? "This device" : "It"} can then no longer change anything until paired again.`, "Revoke"))) return;
  await write("DELETE", "/api/pair/devices/" + encodeURIComponent(d.id));
  if (mine) forgetToken();
  toast(`“${d.name}” revoked`);
  await loadDevices();
}

async function newCode() {
  const r = await write("POST", "/api/pair/code");
  $("pair-newcode").textContent = `Pairing code ${r.code} — enter it on the other phone within ${Math.round(r.expires_in_s / 60)} min (works once).`;
  $("pair-newcode").hidden = false;
}

export function initPairing() {
  setAuthoriser(askPairing);
  $("pair-qr-new").addEventListener("click", () => showPairingQr().catch((e) => toast(e.message, true)));
  // Opened from a paired phone's QR code: the code leaves the address bar
  // (and the history) at once, and the dialog asks only for a name.
  const qrCode = qrCodeFromAddress(location.hash);
  if (qrCode) {
    history.replaceState(null, "", location.pathname + "#system");
    askPairing("", qrCode).then(() => loadDevices()).catch((e) => toast(e.message, true));
  }
  // Enter in a box pairs (the form's first button is Cancel, which a bare
  // implicit submit would press).
  for (const id of ["pair-code", "pair-name", "token-input"])
    $(id).addEventListener("keydown", (e) => {
      if (e.key === "Enter") { e.preventDefault(); $("pair-form").requestSubmit($("pair-ok")); }
    });
  $("pair-start").addEventListener("click", () => askPairing().then(() => loadDevices()).catch((e) => toast(e.message, true)));
  $("pair-code-new").addEventListener("click", () => newCode().catch((e) => toast(e.message, true)));
  $("pair-revoke-all").addEventListener("click", async () => {
    if (!(await confirmAction("Revoke every paired device, this one too? The installer's token keeps working.", "Revoke all"))) return;
    try {
      const r = await write("DELETE", "/api/pair/devices");
      if (getDevice()) forgetToken();
      toast(`${r.revoked} device(s) revoked`);
      await loadDevices();
    } catch (e) { toast(e.message, true); }
  });
  // Unpair: the server forgets this device's token too, so a lost phone's copy is void.
  $("pair-forget").addEventListener("click", async () => {
    const me = getDevice();
    if (me) await quietRequest("DELETE", "/api/pair/devices/" + encodeURIComponent(me.id)).catch(() => {});
    forgetToken();
    toast(me ? "This device is unpaired" : "The token is forgotten on this device");
    loadDevices().catch(() => {});
  });
}
