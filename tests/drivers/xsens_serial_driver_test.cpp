// End to end over a pseudo-terminal: a fake MTi answers the configure-on-start handshake,
// then streams MTData2; the driver delivers decoded samples with host times, survives the
// device vanishing and reconfigures it when it comes back.

#include <fcntl.h>
#include <pty.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <span>

#include "swlio/drivers/xsens/xbus_messages.h"
#include "swlio/drivers/xsens/xsens_serial_driver.h"
#include "test_data.h"
#include "xsens_test_util.h"

namespace swlio::drivers::xsens {
namespace {

namespace fs = std::filesystem;
constexpr int64_t kMs = 1'000'000;

/// False where the system offers no pseudo-terminals (then the test is skipped).
bool PtyAvailable() {
  int m = -1, s = -1;
  if (::openpty(&m, &s, nullptr, nullptr, nullptr) != 0) return false;
  ::close(m);
  ::close(s);
  return true;
}

/// The device side of a pty, reachable through a symlink; answers configuration requests.
class FakeMti {
 public:
  explicit FakeMti(const fs::path& link, bool answer_config = true) : answer_(answer_config) {
    int slave = -1;
    char name[256] = {};
    EXPECT_EQ(::openpty(&master_, &slave, name, nullptr, nullptr), 0);
    ::close(slave);
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    fs::remove(link);
    fs::create_symlink(name, link);
  }
  ~FakeMti() { ::close(master_); }

  /// Reads what the host sent and answers each request like an MTi would.
  void Serve() {
    std::array<uint8_t, 512> buf;
    const ssize_t n = ::read(master_, buf.data(), buf.size());
    if (n <= 0) return;
    framer_.Feed({buf.data(), static_cast<size_t>(n)});
    XbusFrame f;
    while (framer_.Next(&f)) {
      requests.push_back(f.mid);
      if (!answer_) continue;
      std::vector<uint8_t> payload(f.payload.begin(), f.payload.end());
      if (f.mid == mid::kReqDid) payload = {0x07, 0x70, 0x12, 0x34};
      Send(static_cast<uint8_t>(f.mid + 1), payload);
      if (f.mid == mid::kGoToMeasurement && sample_after_ack) SendSample(*sample_after_ack);
    }
  }

  void Send(uint8_t mid, const std::vector<uint8_t>& payload) {
    std::array<uint8_t, kXbusMaxFrame> frame;
    const size_t n = EncodeXbusFrame(mid, payload, frame);
    ASSERT_EQ(::write(master_, frame.data(), n), static_cast<ssize_t>(n));
  }

  void SendSample(uint16_t counter) { Send(mid::kMtData2, test::LevelSamplePayload(counter)); }

  std::vector<uint8_t> requests;
  /// Streams this sample right behind the GoToMeasurement acknowledgement (as a real MTi does).
  std::optional<uint16_t> sample_after_ack;

 private:
  int master_ = -1;
  bool answer_;
  XbusFramer framer_;
};

struct Received {
  std::vector<uint16_t> counters;
  std::vector<int64_t> t_host_ns;
};

XsensSampleSink Collect(Received* r) {
  return [r](const MtData2Sample& s, int64_t t) {
    r->counters.push_back(s.packet_counter.value_or(0));
    r->t_host_ns.push_back(t);
    EXPECT_TRUE(ToImuSample(s, t).has_value());
  };
}

ImuConfig Config(const fs::path& link) {
  ImuConfig c;
  c.device = link.string();
  c.baud = 921600;
  c.reply_timeout_ms = 50;
  c.configure_retries = 2;
  return c;
}

void PollUntil(XsensSerialDriver& d, FakeMti& dev, const std::function<bool()>& done) {
  for (int i = 0; i < 400 && !done(); ++i) {
    d.Poll(5 * kMs);
    dev.Serve();
  }
}

TEST(XsensSerialDriver, ConfiguresStreamsAndReconfiguresAfterReconnect) {
  if (!PtyAvailable()) GTEST_SKIP() << "no pseudo-terminals (openpty failed)";
  const fs::path link = test::MakeTempDir("xsens_driver") / "ttyMTI";
  auto dev = std::make_unique<FakeMti>(link);
  Received rx;
  XsensSerialDriver driver(Config(link), Collect(&rx));
  PollUntil(driver, *dev, [&] { return driver.state() == XsensDriverState::kStream; });
  ASSERT_EQ(driver.state(), XsensDriverState::kStream);
  EXPECT_TRUE(driver.configured());
  EXPECT_EQ(dev->requests, (std::vector<uint8_t>{0x30, 0x00, 0xC0, 0x10}));
  EXPECT_EQ(driver.configurator().device_id(), 0x07701234u);

  for (uint16_t c = 10; c <= 30; ++c) {
    if (c != 20) dev->SendSample(c);  // packet 20 lost
  }
  PollUntil(driver, *dev, [&] { return rx.counters.size() >= 20; });
  ASSERT_EQ(rx.counters.size(), 20u);
  EXPECT_EQ(rx.counters.front(), 10);
  EXPECT_EQ(rx.counters.back(), 30);
  EXPECT_EQ(driver.stats().stream.counter_gaps, 1u);
  EXPECT_EQ(driver.stats().stream.missing_packets, 1u);
  EXPECT_TRUE(std::is_sorted(rx.t_host_ns.begin(), rx.t_host_ns.end()));

  dev.reset();  // unplugged
  for (int i = 0; i < 20 && driver.state() != XsensDriverState::kOpen; ++i) driver.Poll(5 * kMs);
  EXPECT_EQ(driver.state(), XsensDriverState::kOpen);

  dev = std::make_unique<FakeMti>(link);  // plugged back in
  PollUntil(driver, *dev, [&] { return driver.stats().configurations == 2; });
  EXPECT_EQ(driver.stats().configurations, 2u);
  dev->SendSample(500);
  PollUntil(driver, *dev, [&] { return rx.counters.back() == 500; });
  EXPECT_EQ(rx.counters.back(), 500);
  EXPECT_EQ(driver.stats().framer.checksum_errors, 0u);
  EXPECT_EQ(driver.port().stats().opens, 2u);
}

TEST(XsensSerialDriver, SilentDeviceFailsConfigurationButStillStreams) {
  if (!PtyAvailable()) GTEST_SKIP() << "no pseudo-terminals (openpty failed)";
  const fs::path link = test::MakeTempDir("xsens_driver") / "ttyMTI";
  FakeMti dev(link, /*answer_config=*/false);
  Received rx;
  XsensSerialDriver driver(Config(link), Collect(&rx));
  PollUntil(driver, dev, [&] { return driver.stats().config_failures > 0; });
  ASSERT_EQ(driver.stats().config_failures, 1u);
  EXPECT_EQ(driver.stats().last_config_failure, XsensConfigFailure::kTimeout);
  EXPECT_EQ(driver.stats().last_failed_step, XsensConfigStep::kGoToConfig);
  EXPECT_EQ(dev.requests, (std::vector<uint8_t>{0x30, 0x30}));  // two attempts
  EXPECT_FALSE(driver.configured());
  dev.SendSample(7);
  PollUntil(driver, dev, [&] { return !rx.counters.empty(); });
  ASSERT_EQ(rx.counters.size(), 1u);
  EXPECT_EQ(rx.counters[0], 7);
}

// With a hand-over the driver decodes nothing while streaming: the bytes from the end of the
// handshake on (those behind the acknowledgement in the same read too) go out with their read
// time and the port's open epoch, and a decoder fed with them elsewhere sees the samples, the
// lost packet and the reconnect where they happened.
TEST(XsensSerialDriver, WithAHandoverTheStreamGoesOutUndecoded) {
  if (!PtyAvailable()) GTEST_SKIP() << "no pseudo-terminals (openpty failed)";
  const fs::path link = test::MakeTempDir("xsens_driver") / "ttyMTI";
  auto dev = std::make_unique<FakeMti>(link);
  dev->sample_after_ack = 9;
  Received here, decoded;
  XsensSerialDriver driver(Config(link), Collect(&here));
  XsensStreamDecoder decoder(Collect(&decoded));
  std::vector<uint32_t> epochs;
  driver.SetStreamHandover([&](std::span<const uint8_t> bytes, int64_t t, uint32_t epoch) {
    epochs.push_back(epoch);
    decoder.Process(bytes, t, epoch);
  });
  PollUntil(driver, *dev, [&] { return driver.state() == XsensDriverState::kStream; });
  ASSERT_EQ(driver.state(), XsensDriverState::kStream);
  for (uint16_t c = 10; c <= 30; ++c) {
    if (c != 20) dev->SendSample(c);  // packet 20 lost
  }
  PollUntil(driver, *dev, [&] { return decoded.counters.size() >= 21; });
  ASSERT_EQ(decoded.counters.size(), 21u);
  EXPECT_EQ(decoded.counters.front(), 9) << "the sample behind the acknowledgement";
  EXPECT_EQ(decoded.counters.back(), 30);
  EXPECT_TRUE(here.counters.empty()) << "the driver decoded the stream itself";
  EXPECT_EQ(driver.stats().stream.samples, 0u);
  EXPECT_EQ(decoder.stats().missing_packets, 1u);
  EXPECT_EQ(decoder.stats().counter_gaps, 1u);
  EXPECT_EQ(std::count(epochs.begin(), epochs.end(), 1u), static_cast<long>(epochs.size()));

  dev.reset();  // unplugged
  for (int i = 0; i < 20 && driver.state() != XsensDriverState::kOpen; ++i) driver.Poll(5 * kMs);
  dev = std::make_unique<FakeMti>(link);  // plugged back in, its counter elsewhere
  dev->sample_after_ack = 500;
  PollUntil(driver, *dev, [&] { return driver.stats().configurations == 2; });
  dev->SendSample(501);
  PollUntil(driver, *dev, [&] { return decoded.counters.back() == 501; });
  EXPECT_EQ(decoded.counters.back(), 501);
  EXPECT_EQ(decoded.counters[decoded.counters.size() - 2], 500);
  EXPECT_EQ(epochs.back(), 2u);
  EXPECT_EQ(driver.epoch(), 2u);
  EXPECT_EQ(decoder.stats().restarts, 1u);
  EXPECT_EQ(decoder.stats().missing_packets, 1u) << "a reconnect is not a loss";
  EXPECT_EQ(decoder.stats().counter_gaps, 1u);
  EXPECT_EQ(decoder.stats().framer.checksum_errors, 0u);
  EXPECT_EQ(driver.stats().framer.checksum_errors, 0u);
  EXPECT_TRUE(here.counters.empty());
}

}  // namespace
}  // namespace swlio::drivers::xsens
