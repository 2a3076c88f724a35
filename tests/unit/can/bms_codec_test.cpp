// The BMS CAN set: documented frames decode to the documented values, our
// encoder's frames decode back, and bad frames never become limits.
#include "can/bms_codec.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drivers/can/candump_log.h"

namespace xr::can {
namespace {

CanFrame fromCandump(const char* line) {
  auto l = parseCandump(line);
  EXPECT_TRUE(l.has_value()) << line;
  return l ? l->frame : CanFrame{};
}

TEST(BmsCodec, Decodes351FromTheDocumentedExample) {
  // the design's example line: CVL 0x008C = 14.0 V, CCL 0x01F4 = 50.0 A, DCL 50.0 A.
  BmsDecoder d(BmsProtocol::Victron);
  EXPECT_EQ(d.feed(fromCandump("(1700000000.000000) can0 351#8C00F401F4010000"), fromSec(3)),
            BmsFrameResult::Accepted);
  EXPECT_DOUBLE_EQ(d.limits().cvlV, 14.0);
  EXPECT_DOUBLE_EQ(d.limits().cclA, 50.0);
  EXPECT_DOUBLE_EQ(d.limits().dclA, 50.0);
  EXPECT_EQ(d.limits().stamp, fromSec(3));
  EXPECT_EQ(d.limits().source, BmsSource::Can);
}

TEST(BmsCodec, Decodes355And356AndName) {
  BmsDecoder d(BmsProtocol::Victron);
  // SoC 0x0041 = 65 %, SoH 0x0062 = 98 %.
  EXPECT_EQ(d.feed(fromCandump("(0.1) can0 355#41006200"), 1), BmsFrameResult::Accepted);
  // 0x0537 = 1335 -> 13.35 V; 0xFF9C = -100 -> -10.0 A; 0x00FA = 250 -> 25.0 degC.
  EXPECT_EQ(d.feed(fromCandump("(0.2) can0 356#37059CFFFA00"), 2), BmsFrameResult::Accepted);
  EXPECT_EQ(d.feed(fromCandump("(0.3) can0 35E#5245432D424D5320"), 3), BmsFrameResult::Accepted);
  EXPECT_DOUBLE_EQ(d.limits().socPct, 65.0);
  EXPECT_DOUBLE_EQ(d.limits().sohPct, 98.0);
  EXPECT_DOUBLE_EQ(d.limits().voltageV, 13.35);
  EXPECT_DOUBLE_EQ(d.limits().currentA, -10.0);
  EXPECT_DOUBLE_EQ(d.limits().tempC, 25.0);
  EXPECT_EQ(d.name(), "REC-BMS");
  EXPECT_EQ(d.limits().stamp, 0);  // only 0x351 moves the staleness clock
}

TEST(BmsCodec, Decodes35APairsRaisedIs01) {
  BmsDecoder d(BmsProtocol::Victron);
  // Byte 0: pairs 10 10 01 10 -> high voltage alarm raised (bits 2-3 = 01),
  // the rest normal; byte 5 bits 0-1 = 01: low temperature warning.
  EXPECT_EQ(d.feed(fromCandump("(1) can0 35A#A6AAAAAAAAA9AAAA"), 1), BmsFrameResult::Accepted);
  EXPECT_EQ(d.limits().alarms, bmswarn::HighVoltage);
  EXPECT_EQ(d.limits().warnings, bmswarn::LowTemp);
  EXPECT_TRUE(d.limits().chargeAllowed);
}

TEST(BmsCodec, PylontechProtectionBlocksChargeAndVictronIgnores359) {
  const CanFrame f = encode359(bmswarn::HighTemp, bmswarn::HighVoltage);
  BmsDecoder v(BmsProtocol::Victron);
  EXPECT_EQ(v.feed(f, 1), BmsFrameResult::Ignored);
  BmsDecoder p(BmsProtocol::Pylontech);
  EXPECT_EQ(p.feed(f, 1), BmsFrameResult::Accepted);
  EXPECT_EQ(p.limits().alarms, bmswarn::HighTemp);
  EXPECT_EQ(p.limits().warnings, bmswarn::HighVoltage);
  EXPECT_FALSE(p.limits().chargeAllowed);
  EXPECT_EQ(p.feed(encode359(0, bmswarn::HighVoltage), 2), BmsFrameResult::Accepted);
  EXPECT_TRUE(p.limits().chargeAllowed);  // a warning alone ramps, it does not block
  // Pylontech V1.2 byte 0 bit 3 = high temperature protection.
  EXPECT_EQ(f.data[0], 0x08);
  EXPECT_EQ(f.data[2], 0x02);
}

// Frames of a REC Q BMS (a 24 V pack) as its owner captured them with
// candump (natecostello/van_two_point_oh, blog/2021-4-8): the REC decoding
// of each, field by field.
TEST(BmsCodec, RecDecodesACapturedRecQ) {
  BmsDecoder d(BmsProtocol::Rec);
  // CVL 0x011F = 28.7 V, CCL 0x02BC = 70.0 A, DCL 0x03E8 = 100.0 A.
  EXPECT_EQ(d.feed(fromCandump("(1) can0 351#1F01BC02E803E700"), fromSec(1)), BmsFrameResult::Accepted);
  EXPECT_NEAR(d.limits().cvlV, 28.7, 1e-9);
  EXPECT_NEAR(d.limits().cclA, 70.0, 1e-9);
  EXPECT_NEAR(d.limits().dclA, 100.0, 1e-9);
  // SoC 50 %, SoH 100 %, and the SoC again as 0x1388 = 50.00 %.
  EXPECT_EQ(d.feed(fromCandump("(1) can0 355#320064008813"), fromSec(1)), BmsFrameResult::Accepted);
  EXPECT_DOUBLE_EQ(d.limits().socPct, 50.0);
  EXPECT_DOUBLE_EQ(d.limits().sohPct, 100.0);
  // 0x0A32 = 26.10 V, 0 A, 0x0127 = 29.5 degC.
  EXPECT_EQ(d.feed(fromCandump("(1) can0 356#320A00002701"), fromSec(1)), BmsFrameResult::Accepted);
  EXPECT_NEAR(d.limits().voltageV, 26.10, 1e-9);
  EXPECT_NEAR(d.limits().tempC, 29.5, 1e-9);
  // Every pair 10 (normal) or 00 (not supported): nothing raised.
  EXPECT_EQ(d.feed(fromCandump("(1) can0 35A#A8A082000000800A"), fromSec(1)), BmsFrameResult::Accepted);
  EXPECT_EQ(d.limits().alarms, 0u);
  EXPECT_EQ(d.limits().warnings, 0u);
  EXPECT_EQ(d.feed(fromCandump("(1) can0 35E#5245432D424D5300"), fromSec(1)), BmsFrameResult::Accepted);
  EXPECT_EQ(d.name(), "REC-BMS");
  // The ids REC adds that carry nothing the regulator uses: ignored, not bad.
  EXPECT_EQ(d.feed(fromCandump("(1) can0 35F#0000020664000000"), fromSec(1)), BmsFrameResult::Ignored);
  EXPECT_EQ(d.feed(fromCandump("(1) can0 380#31512D3138343500"), fromSec(1)), BmsFrameResult::Ignored);
  EXPECT_EQ(d.rejected(), 0u);
  EXPECT_TRUE(std::isnan(d.limits().cellMaxV));  // no 0x373 yet
}

TEST(BmsCodec, Rec373CellExtremes) {
  BmsDecoder d(BmsProtocol::Rec);
  // 0x0CE4 = 3300 mV, 0x0E1A = 3610 mV, 0x011D = 285 K = 12 degC, 0x0122 = 290 K = 17 degC.
  EXPECT_EQ(d.feed(fromCandump("(1) can0 373#E40C1A0E1D012201"), 1), BmsFrameResult::Accepted);
  EXPECT_NEAR(d.limits().cellMinV, 3.300, 1e-9);
  EXPECT_NEAR(d.limits().cellMaxV, 3.610, 1e-9);
  EXPECT_DOUBLE_EQ(d.limits().cellTempMinC, 12.0);
  EXPECT_DOUBLE_EQ(d.limits().cellTempMaxC, 17.0);
  EXPECT_EQ(d.limits().stamp, 0);  // only 0x351 moves the staleness clock
  // Our encoder writes the same bytes.
  const CanFrame f = encode373(3.300, 3.610, 12.0, 17.0);
  const CanFrame g = fromCandump("(1) can0 373#E40C1A0E1D012201");
  EXPECT_EQ(f.dlc, 8);
  EXPECT_EQ(f.data, g.data);
  // Victron and Pylontech do not read 0x373 (their BMSs may send it, but
  // the protocol chosen in config says what we act on).
  BmsDecoder v(BmsProtocol::Victron);
  EXPECT_EQ(v.feed(f, 1), BmsFrameResult::Ignored);
}

TEST(BmsCodec, RecRoundTripsAndRejectsBadCells) {
  BmsDecoder d(BmsProtocol::Rec);
  EXPECT_EQ(d.feed(encode355Rec(87.37, 99), 1), BmsFrameResult::Accepted);
  EXPECT_NEAR(d.limits().socPct, 87.37, 1e-9);  // the 0.01 % value
  EXPECT_EQ(d.feed(encode373(3.1, 3.55, -5, 40), 1), BmsFrameResult::Accepted);
  EXPECT_NEAR(d.limits().cellMaxV, 3.55, 1e-9);
  EXPECT_DOUBLE_EQ(d.limits().cellTempMinC, -5.0);
  EXPECT_DOUBLE_EQ(d.limits().cellTempMaxC, 40.0);
  CanFrame shortDlc = encode373(3.1, 3.2, 20, 20);
  shortDlc.dlc = 6;
  EXPECT_EQ(d.feed(shortDlc, 2), BmsFrameResult::Rejected);
  EXPECT_EQ(d.feed(encode373(3.1, 16.1, 20, 20), 2), BmsFrameResult::Rejected);  // over 16 V
  EXPECT_EQ(d.feed(encode373(0.4, 3.3, 20, 20), 2), BmsFrameResult::Rejected);   // under 0.5 V
  EXPECT_EQ(d.feed(encode373(3.4, 3.3, 20, 20), 2), BmsFrameResult::Rejected);   // min above max
  EXPECT_EQ(d.feed(encode373(3.1, 3.3, 20, 130), 2), BmsFrameResult::Rejected);
  EXPECT_EQ(d.lastRejectWhy(), "temperature out of range");
  CanFrame disagree = encode355Rec(40.0, 99);
  disagree.data[0] = 60;  // whole percent 60, fine value 40.00
  EXPECT_EQ(d.feed(disagree, 2), BmsFrameResult::Rejected);
  EXPECT_EQ(d.rejected(), 6u);
  EXPECT_NEAR(d.limits().cellMaxV, 3.55, 1e-9);  // the good values stand
  EXPECT_NEAR(d.limits().socPct, 87.37, 1e-9);
  // A BMS set up for 4 cells on a 24 V bank reads 6.5 V "cells": decoded,
  // for the plausibility check to name (bms_plausibility.h), not dropped.
  EXPECT_EQ(d.feed(encode373(6.4, 6.5, 20, 20), 2), BmsFrameResult::Accepted);
  EXPECT_NEAR(d.limits().cellMaxV, 6.5, 1e-9);
  EXPECT_EQ(parseBmsProtocol("rec"), BmsProtocol::Rec);
  EXPECT_FALSE(parseBmsProtocol("jk").has_value());
}

TEST(BmsCodec, EncoderRoundTripsEveryFrame) {
  BmsDecoder d(BmsProtocol::Victron);
  EXPECT_EQ(d.feed(encode351(28.4, 120.5, 200, 24.0), 7), BmsFrameResult::Accepted);
  EXPECT_EQ(d.feed(encode355(87, 99), 7), BmsFrameResult::Accepted);
  EXPECT_EQ(d.feed(encode356(27.12, -35.5, -3.5), 7), BmsFrameResult::Accepted);
  const std::uint32_t all = bmswarn::HighVoltage | bmswarn::LowVoltage | bmswarn::HighTemp |
                            bmswarn::LowTemp | bmswarn::HighChargeCurrent | bmswarn::HighDischargeCurrent |
                            bmswarn::Internal | bmswarn::CellImbalance;
  EXPECT_EQ(d.feed(encode35A(all, bmswarn::HighVoltage), 7), BmsFrameResult::Accepted);
  EXPECT_NEAR(d.limits().cvlV, 28.4, 1e-9);
  EXPECT_NEAR(d.limits().cclA, 120.5, 1e-9);
  EXPECT_NEAR(d.limits().dclA, 200, 1e-9);
  EXPECT_DOUBLE_EQ(d.limits().socPct, 87);
  EXPECT_NEAR(d.limits().voltageV, 27.12, 1e-9);
  EXPECT_NEAR(d.limits().currentA, -35.5, 1e-9);
  EXPECT_NEAR(d.limits().tempC, -3.5, 1e-9);
  EXPECT_EQ(d.limits().alarms, all);
  EXPECT_EQ(d.limits().warnings, bmswarn::HighVoltage);
  EXPECT_EQ(d.feed(encode35A(0, 0), 8), BmsFrameResult::Accepted);
  EXPECT_EQ(d.limits().alarms, 0u);
}

TEST(BmsCodec, BadFramesAreCountedAndNeverLimits) {
  BmsDecoder d(BmsProtocol::Victron);
  ASSERT_EQ(d.feed(encode351(14.2, 80, 100, 12), fromSec(1)), BmsFrameResult::Accepted);
  CanFrame shortDlc = encode351(14.2, 10, 100, 12);
  shortDlc.dlc = 5;
  EXPECT_EQ(d.feed(shortDlc, fromSec(2)), BmsFrameResult::Rejected);
  EXPECT_EQ(d.lastRejectWhy(), "short DLC");
  // A CCL of 6 000 A (raw 60000 = -5536 as s16): not a limit.
  CanFrame huge = encode351(14.2, 0, 100, 12);
  huge.data[2] = 0x60;
  huge.data[3] = 0xEA;
  EXPECT_EQ(d.feed(huge, fromSec(3)), BmsFrameResult::Rejected);
  EXPECT_EQ(d.feed(encode351(14.2, 2000.1, 100, 12), fromSec(3)), BmsFrameResult::Rejected);
  EXPECT_EQ(d.feed(encode351(14.2, 2000.0, 100, 12), fromSec(3)), BmsFrameResult::Accepted);  // at the bound
  EXPECT_EQ(d.feed(encode351(71.0, 10, 100, 12), fromSec(4)), BmsFrameResult::Rejected);
  EXPECT_EQ(d.feed(encode351(7.9, 10, 100, 12), fromSec(4)), BmsFrameResult::Rejected);
  EXPECT_EQ(d.feed(encode355(101, 100), fromSec(4)), BmsFrameResult::Rejected);
  EXPECT_EQ(d.feed(encode356(13, 0, 120), fromSec(4)), BmsFrameResult::Rejected);
  EXPECT_EQ(d.rejected(), 7u);
  // The last good limits stand, with their stamp: staleness still counts.
  EXPECT_DOUBLE_EQ(d.limits().cclA, 2000.0);
  EXPECT_EQ(d.limits().stamp, fromSec(3));
  EXPECT_TRUE(std::isnan(d.limits().socPct));  // the rejected 0x355 left it unset
}

TEST(BmsCodec, ExtendedAndErrorFramesAreIgnored) {
  BmsDecoder d(BmsProtocol::Victron);
  CanFrame f = encode351(14.2, 80, 100, 12);
  f.extended = true;
  EXPECT_EQ(d.feed(f, 1), BmsFrameResult::Ignored);
  f.extended = false;
  f.error = true;
  EXPECT_EQ(d.feed(f, 1), BmsFrameResult::Ignored);
  EXPECT_EQ(d.rejected(), 0u);
}

}  // namespace
}  // namespace xr::can
