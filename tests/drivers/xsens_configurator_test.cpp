// Configure-on-start handshake, driven without I/O: a scripted fake device answers the
// requests the state machine emits; time is passed in.

#include <gtest/gtest.h>

#include <algorithm>

#include "swlio/drivers/xsens/configurator.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "xsens_test_util.h"

namespace swlio::drivers::xsens {
namespace {

constexpr int64_t kMs = 1'000'000;

/// Parses the single frame the configurator wants to send.
test::OwnedFrame Sent(const XsensConfigurator& c) {
  const auto frames = test::CollectFrames(c.PendingTx(), 1);
  EXPECT_EQ(frames.size(), 1u);
  return frames.empty() ? test::OwnedFrame{} : frames[0];
}

/// Frame `mid` with `payload`, returned as a framer frame over storage kept by the caller.
struct Reply {
  std::vector<uint8_t> payload;
  XbusFrame frame;
  Reply(uint8_t mid, std::vector<uint8_t> p) : payload(std::move(p)) {
    frame.mid = mid;
    frame.bid = 0xFF;
    frame.payload = payload;
  }
};

/// A well-behaved MTi: acknowledges each request; echoes the output configuration.
Reply Answer(const test::OwnedFrame& req) {
  switch (req.mid) {
    case mid::kReqDid:
      return {mid::kDeviceId, {0x03, 0x70, 0x03, 0xF8}};
    case mid::kSetOutputConfiguration:
      return {mid::kOutputConfiguration, req.payload};
    default:
      return {static_cast<uint8_t>(req.mid + 1), {}};
  }
}

XsensConfiguratorOptions Options() {
  ImuConfig config;
  config.output_rate_hz = 400;
  config.reply_timeout_ms = 100;
  config.configure_retries = 3;
  return ConfiguratorOptionsFromConfig(config);
}

TEST(XsensConfigurator, HappyPathSendsTheFullSequence) {
  XsensConfigurator c(Options());
  c.Start(0);
  std::vector<uint8_t> mids;
  int64_t t = 0;
  while (!c.done() && !c.failed() && mids.size() < 10) {
    const auto req = Sent(c);
    mids.push_back(req.mid);
    if (req.mid == mid::kSetOutputConfiguration) {
      std::array<XsensOutputItem, 8> items;
      ASSERT_EQ(ParseOutputConfiguration(req.payload, items), 6u);
      EXPECT_EQ(items[4], (XsensOutputItem{xdi::kAcceleration, 400}));
      EXPECT_EQ(items[0], (XsensOutputItem{xdi::kPacketCounter, kXsensRateMax}));
    }
    c.MarkSent();
    EXPECT_TRUE(c.PendingTx().empty());
    // The device keeps streaming MTData2 for a while: ignored.
    Reply data(mid::kMtData2, {0x10, 0x20, 0x02, 0x00, 0x01});
    c.OnFrame(data.frame, t += kMs);
    const Reply ack = Answer(req);
    c.OnFrame(ack.frame, t += kMs);
  }
  ASSERT_TRUE(c.done()) << ToString(c.failure());
  EXPECT_EQ(mids, (std::vector<uint8_t>{0x30, 0x00, 0xC0, 0x10}));
  EXPECT_EQ(c.device_id(), 0x037003F8u);
  EXPECT_EQ(c.stats().retries, 0u);
  EXPECT_EQ(c.stats().ignored_frames, 4u);
}

TEST(XsensConfigurator, RetriesOnTimeoutThenSucceeds) {
  XsensConfigurator c(Options());
  c.Start(1000 * kMs);
  EXPECT_EQ(c.deadline_ns(), 1100 * kMs);
  c.MarkSent();
  c.OnTick(1099 * kMs);  // not yet
  EXPECT_TRUE(c.PendingTx().empty());
  c.OnTick(1100 * kMs);  // timeout: resend GoToConfig
  ASSERT_FALSE(c.PendingTx().empty());
  EXPECT_EQ(Sent(c).mid, mid::kGoToConfig);
  EXPECT_EQ(c.deadline_ns(), 1200 * kMs);
  c.MarkSent();
  const Reply ack(mid::kGoToConfigAck, {});
  c.OnFrame(ack.frame, 1150 * kMs);
  EXPECT_EQ(c.step(), XsensConfigStep::kReqDid);
  EXPECT_EQ(c.stats().timeouts, 1u);
  EXPECT_EQ(c.stats().retries, 1u);
}

TEST(XsensConfigurator, FailsAfterAllAttemptsTimeOut) {
  XsensConfigurator c(Options());
  c.Start(0);
  for (int64_t t = 0; t <= 1000 * kMs && !c.failed(); t += 10 * kMs) {
    c.MarkSent();
    c.OnTick(t);
  }
  ASSERT_TRUE(c.failed());
  EXPECT_EQ(c.failure(), XsensConfigFailure::kTimeout);
  EXPECT_EQ(c.failed_step(), XsensConfigStep::kGoToConfig);
  EXPECT_EQ(c.stats().sent, 3u);
  EXPECT_EQ(c.stats().timeouts, 3u);
}

TEST(XsensConfigurator, ErrorMessageCostsAnAttemptAndIsReported) {
  XsensConfigurator c(Options());
  c.Start(0);
  const Reply go(mid::kGoToConfigAck, {});
  c.OnFrame(go.frame, 1);
  const Reply did(mid::kDeviceId, {0, 0, 0, 1});
  c.OnFrame(did.frame, 2);
  ASSERT_EQ(c.step(), XsensConfigStep::kSetOutputConfiguration);
  const Reply err(mid::kError, {0x21});
  for (int i = 0; i < 3; ++i) {
    ASSERT_FALSE(c.failed());
    EXPECT_EQ(Sent(c).mid, mid::kSetOutputConfiguration);
    c.MarkSent();
    c.OnFrame(err.frame, 10 + i);
  }
  ASSERT_TRUE(c.failed());
  EXPECT_EQ(c.failure(), XsensConfigFailure::kDeviceError);
  EXPECT_EQ(c.failed_step(), XsensConfigStep::kSetOutputConfiguration);
  EXPECT_EQ(c.last_error_code(), 0x21);
  EXPECT_EQ(c.stats().errors, 3u);
}

TEST(XsensConfigurator, OutputConfigurationMismatchFails) {
  XsensConfigurator c(Options());
  c.Start(0);
  const Reply go(mid::kGoToConfigAck, {});
  c.OnFrame(go.frame, 1);
  const Reply did(mid::kDeviceId, {0, 0, 0, 1});
  c.OnFrame(did.frame, 2);
  auto req = Sent(c);
  req.payload[req.payload.size() - 1] ^= 1;  // the device applied another rate
  const Reply echo(mid::kOutputConfiguration, req.payload);
  c.OnFrame(echo.frame, 3);
  ASSERT_TRUE(c.failed());
  EXPECT_EQ(c.failure(), XsensConfigFailure::kOutputMismatch);
}

TEST(XsensConfigurator, OutputConfigurationEchoInAnotherOrderIsAccepted) {
  XsensConfigurator c(Options());
  c.Start(0);
  const Reply go(mid::kGoToConfigAck, {});
  c.OnFrame(go.frame, 1);
  const Reply did(mid::kDeviceId, {0, 0, 0, 1});
  c.OnFrame(did.frame, 2);
  auto req = Sent(c);
  std::rotate(req.payload.begin(), req.payload.begin() + 4, req.payload.end());  // first → last
  const Reply echo(mid::kOutputConfiguration, req.payload);
  c.OnFrame(echo.frame, 3);
  EXPECT_EQ(c.step(), XsensConfigStep::kGoToMeasurement);
}

TEST(XsensConfigurator, OptionalBaudrateStepAndBadBaud) {
  auto options = Options();
  options.set_baud = 921600;
  XsensConfigurator c(options);
  c.Start(0);
  std::vector<uint8_t> mids;
  for (int i = 0; i < 6 && !c.done(); ++i) {
    const auto req = Sent(c);
    mids.push_back(req.mid);
    if (req.mid == mid::kSetBaudrate) {
      EXPECT_EQ(req.payload, std::vector<uint8_t>{0x0A});
    }
    const Reply ack = Answer(req);
    c.OnFrame(ack.frame, i);
  }
  EXPECT_TRUE(c.done());
  EXPECT_EQ(mids, (std::vector<uint8_t>{0x30, 0x00, 0xC0, 0x18, 0x10}));

  options.set_baud = 12345;
  XsensConfigurator bad(options);
  bad.Start(0);
  for (int i = 0; i < 4 && !bad.failed(); ++i) {
    const Reply ack = Answer(Sent(bad));
    bad.OnFrame(ack.frame, i);
  }
  EXPECT_TRUE(bad.failed());
  EXPECT_EQ(bad.failure(), XsensConfigFailure::kBadRequest);
  EXPECT_EQ(bad.failed_step(), XsensConfigStep::kSetBaudrate);
}

TEST(XbusMessages, BaudCodesAndBuilders) {
  EXPECT_EQ(XsensBaudCode(115200), 0x02);
  EXPECT_EQ(XsensBaudCode(921600), 0x0A);
  EXPECT_EQ(XsensBaudCode(2000000), 0x0C);
  EXPECT_FALSE(XsensBaudCode(1234).has_value());
  EXPECT_EQ(XsensBaudFromCode(0x80), 921600);
  for (int64_t b : {9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600, 2000000}) {
    EXPECT_EQ(XsensBaudFromCode(*XsensBaudCode(b)), b);
  }
  std::array<uint8_t, 16> out;
  // MT0101P examples: GoToMeasurement = FA FF 10 00 F1.
  ASSERT_EQ(BuildGoToMeasurement(out), 5u);
  EXPECT_EQ(out[4], 0xF1);
  EXPECT_EQ(BuildSetBaudrate(115200, out), 6u);
  EXPECT_EQ(out[2], 0x18);
  EXPECT_EQ(out[4], 0x02);
  EXPECT_EQ(BuildSetBaudrate(1, out), 0u);
  std::array<XsensOutputItem, 1> one;
  EXPECT_FALSE(ParseOutputConfiguration(std::vector<uint8_t>{1, 2, 3}, one).has_value());
  EXPECT_FALSE(ParseOutputConfiguration(std::vector<uint8_t>(8), one).has_value());
  EXPECT_EQ(ParseErrorCode(std::vector<uint8_t>{0x04}), 0x04);
  EXPECT_FALSE(ParseDeviceId(std::vector<uint8_t>{1, 2}).has_value());
}

}  // namespace
}  // namespace swlio::drivers::xsens
