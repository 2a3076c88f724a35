// Writes (or, with --check, compares) the reasons table of docs/operations.md
// from REASONS in web/www/js/names.js: the dashboard's fault banners and the
// operations guide say the same words because they come from one table.
//   node web/tools/reasons-doc.mjs [--check] [path/to/operations.md]
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const BEGIN = "<!-- reasons:begin — generated from web/www/js/names.js by web/tools/reasons-doc.mjs; edit there -->";
const END = "<!-- reasons:end -->";

export async function reasonsTable() {
  const { REASONS } = await import(pathToFileURL(path.join(here, "../www/js/names.js")).href);
  const cell = (t) => String(t).replace(/\|/g, "\\|").replace(/\s+/g, " ").trim();
  const lines = ["| Reason | Dashboard shows | What it means | What to do | Details |", "|---|---|---|---|---|"];
  for (const [code, r] of Object.entries(REASONS)) {
    if (code === "NONE") continue;
    const kind = r.kind === "fault" ? "fault banner" : r.kind === "warn" ? "notice banner" : "normal state";
    lines.push(`| \`${code}\` | ${cell(r.title)} (${kind}) | ${cell(r.meaning)} | ${cell(r.action)} | ${cell(r.detail)} |`);
  }
  return lines.join("\n");
}

export function replaceSection(doc, table) {
  const a = doc.indexOf(BEGIN), b = doc.indexOf(END);
  if (a < 0 || b < a) throw new Error("operations.md has no reasons:begin/end markers");
  return doc.slice(0, a) + BEGIN + "\n" + table + "\n" + doc.slice(b);
}

if (import.meta.url === pathToFileURL(process.argv[1]).href) {
  const check = process.argv.includes("--check");
  const file = process.argv.slice(2).find((a) => !a.startsWith("--")) || path.join(here, "../../docs/operations.md");
  const doc = fs.readFileSync(file, "utf8");
  const next = replaceSection(doc, await reasonsTable());
  if (check) {
    if (next !== doc) { console.error(`${file}: the reasons table differs from web/www/js/names.js; run node web/tools/reasons-doc.mjs`); process.exit(1); }
    console.log("ok - docs/operations.md reasons table matches names.js");
  } else if (next !== doc) { fs.writeFileSync(file, next); console.log(`wrote ${file}`); }
}
