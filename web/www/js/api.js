// HTTP helpers and the write token (asked once, kept in localStorage).
const TOKEN_KEY = "xregulator.token";

export function getToken() { return localStorage.getItem(TOKEN_KEY) || ""; }
export function forgetToken() { localStorage.removeItem(TOKEN_KEY); }

// Shows the token dialog; resolves with the token or "" when cancelled.
export function askToken() {
  const dlg = document.getElementById("token-dialog");
  const input = document.getElementById("token-input");
  input.value = "";
  return new Promise((resolve) => {
    dlg.addEventListener("close", () => {
      if (dlg.returnValue === "ok" && input.value.trim()) {
        localStorage.setItem(TOKEN_KEY, input.value.trim());
        resolve(input.value.trim());
      } else resolve("");
    }, { once: true });
    dlg.showModal();
    input.focus();
  });
}

export async function getJson(path) {
  const headers = {};
  const t = getToken();
  if (t) headers.Authorization = "Bearer " + t;
  const res = await fetch(path, { headers, cache: "no-store" });
  const body = await res.json().catch(() => ({}));
  if (!res.ok) throw Object.assign(new Error(body.error || res.statusText), { status: res.status, body });
  return body;
}

// A write (PATCH /api/params, POST /api/commands). Asks for the token when
// none is stored, or when the server says 401/403, then retries once.
export async function write(method, path, payload) {
  let token = getToken() || (await askToken());
  if (!token) throw new Error("no token");
  for (let attempt = 0; attempt < 2; attempt++) {
    const res = await fetch(path, {
      method, body: JSON.stringify(payload),
      headers: { "Content-Type": "application/json", Authorization: "Bearer " + token },
    });
    const body = await res.json().catch(() => ({}));
    if ((res.status === 401 || res.status === 403) && attempt === 0) {
      forgetToken();
      token = await askToken();
      if (!token) throw new Error("no token");
      continue;
    }
    if (!res.ok) throw Object.assign(new Error(body.error || res.statusText), { status: res.status, body });
    return body;
  }
  throw new Error("token refused");
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
