// Writes (or, with --check, compares) daemon/integrations/reason_words.cpp
// from REASONS in web/www/js/names.js: a push to the owner's phone and Home
// Assistant say the same title and "what to do" as the dashboard's banner,
// because they come from one table.
//   node web/tools/reasons-cpp.mjs [--check] [path/to/reason_words.cpp]
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));

// A C++ string literal; the text is UTF-8 (°C, quotes), kept as written.
const lit = (t) => JSON.stringify(String(t).replace(/\s+/g, " ").trim()).replace(/\?\?/g, "?\\?");

export async function reasonWordsSource() {
  const { REASONS } = await import(pathToFileURL(path.join(here, "../www/js/names.js")).href);
  const rows = Object.entries(REASONS).filter(([code]) => code !== "NONE").map(([code, r]) =>
    `    {${lit(code)}, ${lit(r.kind)},\n     ${lit(r.title)},\n     ${lit(r.meaning)},\n     ${lit(r.action)}},`);
  return `// Generated from web/www/js/names.js by web/tools/reasons-cpp.mjs; edit there.
// The integrations.reason_words_match_dashboard test fails when the two differ.
#include "integrations/reason_words.h"

namespace xr::integrations {
namespace {
// clang-format off
constexpr ReasonWords kWords[] = {
${rows.join("\n")}
};
// clang-format on
}  // namespace

const ReasonWords* reasonWords(std::string_view code) {
  for (const auto& w : kWords)
    if (w.code == code) return &w;
  return nullptr;
}

}  // namespace xr::integrations
`;
}

if (import.meta.url === pathToFileURL(process.argv[1]).href) {
  const check = process.argv.includes("--check");
  const file = process.argv.slice(2).find((a) => !a.startsWith("--")) ||
    path.join(here, "../../daemon/integrations/reason_words.cpp");
  const next = await reasonWordsSource();
  const now = fs.existsSync(file) ? fs.readFileSync(file, "utf8") : "";
  if (check) {
    if (next !== now) { console.error(`${file}: differs from web/www/js/names.js; run node web/tools/reasons-cpp.mjs`); process.exit(1); }
    console.log("ok - reason_words.cpp matches names.js");
  } else if (next !== now) { fs.writeFileSync(file, next); console.log(`wrote ${file}`); }
}
