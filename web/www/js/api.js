// HTTP helpers and this device's write credential: a paired device's token
// (POST /api/pair) or the installer's static token, kept in localStorage.
const TOKEN_KEY = "xregulator.token";
const DEVICE_KEY = "xregulator.device";  // {id, name} of this device's pairing; absent for the static token

export function getToken() { return localStorage.getItem(TOKEN_KEY) || ""; }
// This device's pairing ({id, name}) or null (not paired, or the installer's token).
export function getDevice() {
  try { return JSON.parse(localStorage.getItem(DEVICE_KEY) || "null"); } catch { return null; }
}
export function saveCredential(token, device = null) {
  localStorage.setItem(TOKEN_KEY, token);
  if (device) localStorage.setItem(DEVICE_KEY, JSON.stringify({ id: device.id, name: device.name }));
  else localStorage.removeItem(DEVICE_KEY);
}
export function forgetToken() { localStorage.removeItem(TOKEN_KEY); localStorage.removeItem(DEVICE_KEY); }

// How a write gets a credential when it has none or the server refused it:
// pairing.js installs the "Pair this device" dialog here. It resolves with a
// token, or "" when the user cancels.
let authorise = async () => "";
export function setAuthoriser(fn) { authorise = fn; }

async function send(method, path, payload, token) {
  const headers = {};
  if (payload !== undefined) headers["Content-Type"] = "application/json";
  if (token) headers.Authorization = "Bearer " + token;
  const res = await fetch(path, { method, headers, cache: "no-store",
    body: payload === undefined ? undefined : JSON.stringify(payload) });
  const body = await res.json().catch(() => ({}));
  return { res, body };
}
const failure = (res, body) => Object.assign(new Error(body.error || res.statusText), { status: res.status, body });

export async function getJson(path) {
  const { res, body } = await send("GET", path, undefined, getToken());
  if (!res.ok) throw failure(res, body);
  return body;
}

// A write (PATCH /api/params, POST /api/commands, the pairing list). Without
// a credential, or when the server refuses it (401/403: never paired, or this
// device was revoked), asks to pair, then retries once with the new token.
export async function write(method, path, payload) {
  let token = getToken() || (await authorise("Changes need a paired device."));
  if (!token) throw new Error("not paired: nothing was changed");
  for (let attempt = 0; attempt < 2; attempt++) {
    const { res, body } = await send(method, path, payload, token);
    if ((res.status === 401 || res.status === 403) && attempt === 0) {
      forgetToken();
      token = await authorise("This device is no longer allowed to change things (it was revoked, or the token changed). Pair it again.");
      if (!token) throw new Error("not paired: nothing was changed");
      continue;
    }
    if (!res.ok) throw failure(res, body);
    return body;
  }
  throw new Error("the regulator refused this device's credential");
}

// A request with this device's credential that never asks to pair (the
// System page's list: a revoked device shows that, not a dialog).
export async function quietRequest(method, path) {
  const { res, body } = await send(method, path, undefined, getToken());
  return { ok: res.ok, status: res.status, body };
}

// A question to the server with this device's credential that never asks
// to pair (the set-up page's dry run as the owner picks a battery): the
// answer's body, or null when there is no credential or it is refused.
export async function quietAsk(method, path, payload) {
  const token = getToken();
  if (!token) return null;
  const { res, body } = await send(method, path, payload, token);
  return res.ok ? body : null;
}

// POST /api/pair: no credential needed. Resolves with {token, id, name}, or
// throws with the server's message (wrong code, locked, full).
export async function pair(code, name) {
  const { res, body } = await send("POST", "/api/pair", { code, name });
  if (!res.ok) throw failure(res, body);
  return body;
}
// Checks a token as a write credential (GET /api/pair/devices needs one).
export async function tokenWorks(token) {
  const { res } = await send("GET", "/api/pair/devices", undefined, token);
  return res.ok;
}

export function command(name, args = {}) {
  return write("POST", "/api/commands", Object.assign({ command: name }, args));
}

export function toast(text, bad = false) {
  const el = document.getElementById("toast");
  el.textContent = text;
  el.className = bad ? "toast bad" : "toast";
  el.hidden = false;
  clearTimeout(toast.timer);
  toast.timer = setTimeout(() => { el.hidden = true; }, 4000);
}
