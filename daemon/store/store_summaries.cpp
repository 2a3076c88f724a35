// The History page's rows (store/charge_tally.h): one per local day and one
// per charge. A value not known is NULL, read back as NaN.
#include <sqlite3.h>

#include <cmath>

#include "store/store.h"

namespace xr {

namespace {

void bindKnown(sql::Stmt& st, int idx, double v) {
  if (std::isfinite(v))
    st.bind(idx, v);
  else
    st.bindNull(idx);
}
double colKnown(const sql::Stmt& st, int i) { return st.colIsNull(i) ? NAN : st.colDouble(i); }

constexpr const char* kDayColumns =
    "day, alt_ah, alt_wh, batt_ah_in, batt_ah_out, bulk_s, absorption_s, float_s, idle_s, field_on_s, "
    "peak_alt_temp_c, min_soc, max_soc, batt_wh_in, v_min, v_max, soc_start, soc_end, engine_s";
constexpr const char* kChargeColumns =
    "id, start_ms, end_ms, bulk_s, absorption_s, float_s, alt_ah, alt_wh, start_soc, end_soc, end_reason, "
    "open";

DaySummary dayFrom(const sql::Stmt& st) {
  DaySummary d;
  d.day = st.colText(0);
  d.altAh = st.colDouble(1);
  d.altWh = st.colDouble(2);
  d.batteryAhIn = st.colDouble(3);
  d.batteryAhOut = st.colDouble(4);
  d.bulkS = st.colDouble(5);
  d.absorptionS = st.colDouble(6);
  d.floatS = st.colDouble(7);
  d.idleS = st.colDouble(8);
  d.fieldOnS = st.colDouble(9);
  d.peakAltTempC = colKnown(st, 10);
  d.minSocPct = colKnown(st, 11);
  d.maxSocPct = colKnown(st, 12);
  d.batteryWhIn = colKnown(st, 13);
  d.minBatteryV = colKnown(st, 14);
  d.maxBatteryV = colKnown(st, 15);
  d.socStartPct = colKnown(st, 16);
  d.socEndPct = colKnown(st, 17);
  d.engineS = colKnown(st, 18);
  return d;
}

ChargeSummary chargeFrom(const sql::Stmt& st) {
  ChargeSummary c;
  c.id = st.colInt(0);
  c.startMs = st.colInt(1);
  c.endMs = st.colInt(2);
  c.bulkS = st.colDouble(3);
  c.absorptionS = st.colDouble(4);
  c.floatS = st.colDouble(5);
  c.altAh = st.colDouble(6);
  c.altWh = st.colDouble(7);
  c.startSocPct = colKnown(st, 8);
  c.endSocPct = colKnown(st, 9);
  c.endReason = st.colText(10);
  c.open = st.colInt(11) != 0;
  return c;
}

}  // namespace

StoreStatus Store::saveDay(const DaySummary& d) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(
      db_,
      std::string("INSERT OR REPLACE INTO history_days(") + kDayColumns +
          ") VALUES(?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17, ?18, ?19)");
  st.bind(1, d.day).bind(2, d.altAh).bind(3, d.altWh).bind(4, d.batteryAhIn).bind(5, d.batteryAhOut);
  st.bind(6, d.bulkS).bind(7, d.absorptionS).bind(8, d.floatS).bind(9, d.idleS).bind(10, d.fieldOnS);
  bindKnown(st, 11, d.peakAltTempC);
  bindKnown(st, 12, d.minSocPct);
  bindKnown(st, 13, d.maxSocPct);
  bindKnown(st, 14, d.batteryWhIn);
  bindKnown(st, 15, d.minBatteryV);
  bindKnown(st, 16, d.maxBatteryV);
  bindKnown(st, 17, d.socStartPct);
  bindKnown(st, 18, d.socEndPct);
  bindKnown(st, 19, d.engineS);
  return status(st.step(), "saveDay");
}

std::optional<DaySummary> Store::findDay(std::string_view day) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_, std::string("SELECT ") + kDayColumns + " FROM history_days WHERE day = ?1");
  if (st.bind(1, day).step() == SQLITE_ROW) return dayFrom(st);
  return std::nullopt;
}

std::vector<DaySummary> Store::days(std::size_t n) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  std::vector<DaySummary> out;
  sql::Stmt st(db_, std::string("SELECT ") + kDayColumns + " FROM history_days ORDER BY day DESC LIMIT ?1");
  st.bind(1, static_cast<std::int64_t>(n));
  while (st.ok() && st.step() == SQLITE_ROW) out.push_back(dayFrom(st));
  return out;
}

StoreStatus Store::saveCharge(ChargeSummary& c) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  const bool insert = c.id == 0;
  sql::Stmt st(
      db_, insert ? "INSERT INTO history_charges(start_ms, end_ms, bulk_s, absorption_s, float_s, alt_ah, "
                    "alt_wh, start_soc, end_soc, end_reason, open) "
                    "VALUES(?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)"
                  : "UPDATE history_charges SET start_ms = ?2, end_ms = ?3, bulk_s = ?4, absorption_s = ?5, "
                    "float_s = ?6, alt_ah = ?7, alt_wh = ?8, start_soc = ?9, end_soc = ?10, "
                    "end_reason = ?11, open = ?12 WHERE id = ?1");
  if (!insert) st.bind(1, c.id);
  st.bind(2, c.startMs).bind(3, c.endMs).bind(4, c.bulkS).bind(5, c.absorptionS).bind(6, c.floatS);
  st.bind(7, c.altAh).bind(8, c.altWh);
  bindKnown(st, 9, c.startSocPct);
  bindKnown(st, 10, c.endSocPct);
  st.bind(11, c.endReason).bind(12, c.open ? 1 : 0);
  const StoreStatus s = status(st.step(), "saveCharge");
  if (s && insert) c.id = sqlite3_last_insert_rowid(db_.handle());
  return s;
}

std::vector<ChargeSummary> Store::charges(std::size_t n) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  std::vector<ChargeSummary> out;
  sql::Stmt st(db_,
               std::string("SELECT ") + kChargeColumns + " FROM history_charges ORDER BY id DESC LIMIT ?1");
  st.bind(1, static_cast<std::int64_t>(n));
  while (st.ok() && st.step() == SQLITE_ROW) out.push_back(chargeFrom(st));
  return out;
}

std::vector<ChargeSummary> Store::chargesBetween(std::int64_t fromMs, std::int64_t toMs) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  std::vector<ChargeSummary> out;
  sql::Stmt st(
      db_, std::string("SELECT ") + kChargeColumns +
               " FROM history_charges WHERE start_ms >= ?1 AND start_ms < ?2 ORDER BY start_ms LIMIT 1000");
  st.bind(1, fromMs).bind(2, toMs);
  while (st.ok() && st.step() == SQLITE_ROW) out.push_back(chargeFrom(st));
  return out;
}

StoreStatus Store::closeOpenCharges(std::string_view reason) {
  const std::lock_guard<std::recursive_mutex> lock(mu_);
  sql::Stmt st(db_, "UPDATE history_charges SET open = 0, end_reason = ?1 WHERE open = 1");
  return status(st.bind(1, reason).step(), "closeOpenCharges");
}

}  // namespace xr
