// Number, time and unit formatting, and parsing what a user types. Pure
// functions (tests/web/browser/format_test.mjs runs them under node).

export const isNum = (v) => typeof v === "number" && isFinite(v);

// ---- HTML from data: the one escaping helper (docs/dashboard.md "Code
// standard"). Text goes in through textContent; where a piece of page is
// built as HTML, it is an html`` template, whose every ${value} is escaped
// (a nested html`` or an array of them stays as built), and only setHtml
// puts it in the page. The lint (web/eslint.config.js) refuses innerHTML
// anywhere else.
export const esc = (s) => String(s).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
class SafeHtml {
  constructor(text) { this.text = text; }
}
const htmlPart = (v) => (v instanceof SafeHtml ? v.text : Array.isArray(v) ? v.map(htmlPart).join("") : esc(v ?? ""));
export function html(strings, ...values) {
  return new SafeHtml(strings.reduce((out, s, i) => out + htmlPart(values[i - 1]) + s));
}
export function setHtml(el, safe) {
  if (!(safe instanceof SafeHtml)) throw new TypeError("setHtml takes an html`` template");
  el.innerHTML = safe.text;  // eslint-disable-line no-restricted-syntax -- escaped by html``
}

// A fixed number of decimals, or "—" for no value (null, NaN, a -999 sentinel).
export function num(v, d = 1) {
  if (!isNum(v) || v <= -999) return "—";
  const r = Number(v.toFixed(d));
  return (Object.is(r, -0) ? 0 : r).toFixed(d);
}

// Minutes as "2 h 05 min" / "45 min"; "—" for no value.
export function hmin(minutes) {
  if (!isNum(minutes) || minutes < 0) return "—";
  const m = Math.round(minutes);
  const h = Math.floor(m / 60);
  return h ? `${h} h ${String(m % 60).padStart(2, "0")} min` : `${m} min`;
}
export const hminFromSeconds = (s) => (isNum(s) && s >= 0 ? hmin(s / 60) : "—");

// Age in words for "last update N s ago".
export function ago(seconds) {
  if (!isNum(seconds)) return "never";
  const s = Math.max(0, Math.round(seconds));
  if (s < 90) return `${s} s ago`;
  if (s < 5400) return `${Math.round(s / 60)} min ago`;
  return `${hminFromSeconds(s)} ago`;
}

// A clock time for a Unix time: "14:05" today, else "3 Dec 14:05".
export function clock(unixS, now = Date.now() / 1000) {
  if (!isNum(unixS) || unixS <= 0) return "—";
  const d = new Date(unixS * 1000);
  const hm = d.toLocaleTimeString([], { hour: "2-digit", minute: "2-digit", hour12: false });
  if (new Date(now * 1000).toDateString() === d.toDateString()) return hm;
  return `${d.toLocaleDateString([], { day: "numeric", month: "short" })} ${hm}`;
}

// What a user typed as a number: "13,4" (a comma decimal, usual on European
// phones) and "13.4" both give 13.4. Empty or not a number gives null, so an
// empty box is never sent as 0.
export function parseDecimal(text) {
  const t = String(text ?? "").trim().replace(/\s/g, "");
  if (t === "") return null;
  const n = /^[-+]?\d*[.,]?\d+$|^[-+]?\d+[.,]$/.test(t) ? Number(t.replace(",", ".")) : NaN;
  return isFinite(n) ? n : null;
}

export const fToC = (f) => ((f - 32) * 5) / 9;
// Alternator temperature in the user's unit ("C" or "F").
export function temp(f, unit) {
  if (!isNum(f) || f <= -999) return "—";
  return unit === "F" ? `${num(f, 0)} °F` : `${num(fToC(f), 0)} °C`;
}

// A value for the detail tables: integers stay whole, other numbers get at
// most `d` decimals, booleans read yes/no.
export function plain(v, d = 2) {
  if (typeof v === "boolean") return v ? "yes" : "no";
  if (v === null || v === undefined) return "—";
  if (typeof v === "number") {
    if (!isFinite(v) || v <= -999) return "—";
    return Number.isInteger(v) ? String(v) : String(Number(v.toFixed(d)));
  }
  return String(v);
}
