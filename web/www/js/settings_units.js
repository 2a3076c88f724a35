// The Settings page in the owner's units (docs/dashboard.md "Units"): the
// regulator keeps alternator temperatures in °F (the specification's parameters);
// with °C chosen on the System page each is shown, typed and checked in °C
// and sent back in °F. A temperature limit converts with the offset, a
// margin ("2 °F above the limit") only with the scale.
// Temperatures (with the offset); every other "degF" parameter is a margin.
const ABSOLUTE_F = new Set(["TemperatureLimitF", "TempAlarm", "TempAlarmLow"]);

const round1 = (v) => Math.round(v * 10) / 10;

// { unit, show(v), back(v) } for a parameter in the display unit.
export function unitView(p, unit) {
  const raw = String(p.unit || "");
  if (raw === "degF" && unit !== "F") {
    const abs = ABSOLUTE_F.has(p.name);
    return {
      unit: "°C",
      show: (v) => (typeof v === "number" ? round1(abs ? ((v - 32) * 5) / 9 : (v * 5) / 9) : v),
      back: (v) => round1(abs ? (v * 9) / 5 + 32 : (v * 9) / 5),
    };
  }
  const sym = raw === "degF" ? "°F" : raw === "degC" ? "°C" : raw;
  return { unit: sym, show: (v) => v, back: (v) => v };
}

// A number in the display unit for the page's words (range, default).
export const shown = (view, v) => (typeof v === "number" ? String(view.show(v)) : String(v));

// Help texts say "degC"/"degF"; the page says °C/°F.
export const plainUnits = (text) => String(text || "").replace(/\bdegF\b/g, "°F").replace(/\bdegC\b/g, "°C");
