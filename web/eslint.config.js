// ESLint for the dashboard's JavaScript and the browser tests (docs/dashboard.md
// "Code standard"): the recommended rules everywhere; in the shipped pages
// also functions of at most 80 lines, like the C++ outside the tests
// (tests/layout/layout_rules.py), no HTML built from data and no test hook.
// Run from the repository root: `web/node_modules/.bin/eslint -c web/eslint.config.js
// web/www/js tests/web/browser` (the ctests web.eslint and web.eslint_catches_violations).
import js from "@eslint/js";
import globals from "globals";

// Text goes in through textContent, or through the one escaping helper
// esc() (web/www/js/format.js) inside an html`` template.
const noRawHtml = [
  { selector: "AssignmentExpression[left.property.name='innerHTML']",
    message: "No innerHTML: set textContent, build elements, or use html`` (format.js), which escapes." },
  { selector: "AssignmentExpression[left.property.name='outerHTML']", message: "No outerHTML: build elements." },
  { selector: "CallExpression[callee.property.name='insertAdjacentHTML']",
    message: "No insertAdjacentHTML: build elements, or use html`` (format.js)." },
  { selector: "CallExpression[callee.object.name='document'][callee.property.name='write']",
    message: "No document.write." },
];

export default [
  { ignores: ["**/node_modules/**", "**/vendor/**", "**/www/lib/**"] },
  js.configs.recommended,
  {
    files: ["www/js/**/*.js", "web/www/js/**/*.js"],
    languageOptions: { ecmaVersion: 2022, sourceType: "module", globals: { ...globals.browser, uPlot: "readonly" } },
    rules: {
      "max-lines-per-function": ["error", { max: 80, skipBlankLines: false, skipComments: false }],
      "no-restricted-syntax": ["error", ...noRawHtml],
      "no-restricted-properties": ["error",
        { object: "window", property: "xrDebug", message: "No test hook in the shipped pages." }],
      "no-unused-vars": ["error", { args: "none" }],
    },
  },
  {
    files: ["**/*.mjs"],
    languageOptions: { ecmaVersion: 2022, sourceType: "module", globals: { ...globals.node, ...globals.browser } },
    rules: { "no-unused-vars": ["error", { args: "none" }] },
  },
];
