// The parameters as TOML (the sections and names of xregulator.toml) and
// back. Pure functions; tests/web/browser/units.mjs runs them under node.

// "SensorHealth" -> "sensor_health", the file's section names.
export const sectionOf = (group) => String(group).replace(/([a-z0-9])([A-Z])/g, "$1_$2").toLowerCase();

const tomlValue = (v) => (Array.isArray(v) ? "[" + v.map(tomlValue).join(", ") + "]"
  : typeof v === "boolean" ? String(v) : Number.isInteger(v) && !Number.isNaN(v) ? String(v) : String(v));

// Every parameter with its current value, by group, with its help as a comment.
export function exportToml(params, groups, stamp = "") {
  const lines = ["# xregulator parameters exported from the dashboard" + (stamp ? ` (${stamp})` : ""),
    "# Copy these sections over the same ones in /etc/xregulator/xregulator.toml to make the",
    "# dashboard's values permanent, or import this file on the Settings page.", ""];
  for (const g of groups) {
    const list = params.filter((p) => p.group === g);
    if (!list.length) continue;
    lines.push(`[${sectionOf(g)}]`);
    for (const p of list) {
      if (p.help) lines.push(`# ${String(p.help).replace(/\s+/g, " ")}`);
      // A named choice is a quoted name in the file (BatteryProfile = "agm"), as the daemon reads it.
      const named = Array.isArray(p.choices) && p.choices[p.value] !== undefined;
      lines.push(`${p.name} = ${named ? JSON.stringify(String(p.choices[p.value])) : tomlValue(p.value)}`);
    }
    lines.push("");
  }
  return lines.join("\n");
}

function parseScalar(text) {
  const t = text.trim();
  if (t === "true") return true;
  if (t === "false") return false;
  if (/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(t.replace(/_/g, ""))) {
    // "1e999" is Infinity, which JSON sends as null: "drop the dashboard's
    // value" to the daemon. Not a number a file can mean.
    const v = Number(t.replace(/_/g, ""));
    return Number.isFinite(v) ? v : undefined;
  }
  return undefined;
}

// Reads the parameter sections of a TOML file. Returns {values, errors}:
// errors name the line; sections the dashboard does not own ([hardware],
// [web], [store], ...) are skipped and listed in `skipped`.
export function parseParamsToml(text, params) {
  const byName = new Map(params.map((p) => [p.name, p]));
  const paramSections = new Set(params.map((p) => sectionOf(p.group)));
  const values = {};
  const errors = [];
  const skipped = new Set();
  let section = "";
  const lines = String(text).split(/\r?\n/);
  for (let i = 0; i < lines.length; i++) {
    const line = lines[i].replace(/\s+#.*$/, "").replace(/^#.*$/, "").trim();
    if (!line) continue;
    const sec = line.match(/^\[([A-Za-z0-9_.]+)\]$/);
    if (sec) { section = sec[1]; continue; }
    if (!paramSections.has(section)) { if (section) skipped.add(section); continue; }
    const kv = line.match(/^([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.+)$/);
    if (!kv) { errors.push(`line ${i + 1}: not "name = value"`); continue; }
    const [, name, raw] = kv;
    const p = byName.get(name);
    if (!p) { errors.push(`line ${i + 1}: unknown parameter ${name}`); continue; }
    if (sectionOf(p.group) !== section) { errors.push(`line ${i + 1}: ${name} belongs in [${sectionOf(p.group)}]`); continue; }
    let v;
    const arr = raw.trim().match(/^\[(.*)\]$/);
    if (arr) {
      v = arr[1].split(",").map((x) => x.trim()).filter((x) => x !== "").map(parseScalar);
      if (v.some((x) => typeof x !== "number")) v = undefined;
    } else v = parseScalar(raw);
    const kind = String(p.kind).toLowerCase();
    const quoted = raw.trim().match(/^"([^"\\]*)"$/);
    if (quoted && Array.isArray(p.choices)) {
      const choice = p.choices.map(String).indexOf(quoted[1]);
      if (choice < 0) { errors.push(`line ${i + 1}: ${name}: expected one of ${p.choices.join(", ")}`); continue; }
      values[name] = choice;
      continue;
    }
    if (v === undefined) { errors.push(`line ${i + 1}: ${name}: cannot read "${raw.trim()}"`); continue; }
    if (kind === "table" && (!Array.isArray(v) || v.length !== p.value.length)) {
      errors.push(`line ${i + 1}: ${name}: expected ${p.value.length} numbers`); continue;
    }
    if (kind === "bool" && typeof v === "number" && (v === 0 || v === 1)) v = v === 1;
    if (kind === "bool" && typeof v !== "boolean") { errors.push(`line ${i + 1}: ${name}: expected true or false`); continue; }
    if (kind !== "bool" && kind !== "table" && typeof v !== "number") { errors.push(`line ${i + 1}: ${name}: expected a number`); continue; }
    values[name] = v;
  }
  return { values, errors, skipped: [...skipped] };
}
