// Serial I/O shell over a pseudo-terminal: raw bytes arrive intact and time-stamped; the
// device vanishes (pty master closed, its path removed) and comes back (a new pty behind the
// same path), and the port re-opens by itself.

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>

#include "swlio/drivers/serial_port.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"
#include "test_data.h"

namespace swlio::drivers {
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

/// A pty pair whose slave is reachable through `link` (a symlink, like /dev/serial/by-id).
struct FakeDevice {
  int master = -1;
  fs::path slave_path;
  FakeDevice(const fs::path& link) {
    int slave = -1;
    char name[256] = {};
    EXPECT_EQ(::openpty(&master, &slave, name, nullptr, nullptr), 0);
    slave_path = name;
    ::close(slave);  // the port under test opens it by path
    fs::remove(link);
    fs::create_symlink(slave_path, link);
  }
  ~FakeDevice() { Vanish(); }
  void Vanish() {
    if (master >= 0) ::close(master);
    master = -1;
  }
  void Write(const std::vector<uint8_t>& bytes) {
    ASSERT_EQ(::write(master, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  }
};

std::vector<uint8_t> SomeFrames(uint16_t first_counter, int n) {
  std::vector<uint8_t> stream;
  for (int i = 0; i < n; ++i) {
    xsens::MtData2Sample s;
    s.packet_counter = static_cast<uint16_t>(first_counter + i);
    const double acc[] = {0.1, -0.2, 9.81};
    s.acc_mps2 = xsens::MakeXsensReal(acc);
    std::array<uint8_t, 64> payload;
    const size_t len = xsens::EncodeMtData2(s, payload);
    std::array<uint8_t, 80> frame;
    const size_t f = xsens::EncodeXbusFrame(xsens::mid::kMtData2, {payload.data(), len}, frame);
    stream.insert(stream.end(), frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(f));
  }
  return stream;
}

/// Reads until `want` frames arrived or `deadline` passes; returns the packet counters.
std::vector<uint16_t> ReadFrames(SerialPort& port, size_t want, int64_t budget_ns) {
  xsens::XbusFramer framer;
  std::vector<uint16_t> counters;
  const int64_t deadline = MonotonicNowNs() + budget_ns;
  std::array<uint8_t, 256> buf;
  while (counters.size() < want && MonotonicNowNs() < deadline) {
    const int64_t before = MonotonicNowNs();
    const SerialRead r = port.Read(buf, 50 * kMs);
    if (r.status != SerialReadStatus::kData) continue;
    EXPECT_GE(r.t_host_ns, before);
    EXPECT_LE(r.t_host_ns, MonotonicNowNs());
    framer.Feed({buf.data(), r.bytes});
    xsens::XbusFrame f;
    while (framer.Next(&f)) {
      xsens::MtData2Sample s;
      EXPECT_EQ(xsens::DecodeMtData2(f.payload, &s), xsens::MtData2Status::kOk);
      counters.push_back(s.packet_counter.value_or(0));
    }
  }
  EXPECT_EQ(framer.stats().checksum_errors, 0u);
  return counters;
}

TEST(SerialPort, RawBytesArriveIntactOverPty) {
  if (!PtyAvailable()) GTEST_SKIP() << "no pseudo-terminals (openpty failed)";
  const fs::path dir = test::MakeTempDir("serial");
  FakeDevice dev(dir / "ttyMTI");
  SerialPort port({(dir / "ttyMTI").string(), 921600, 20 * kMs});
  ASSERT_TRUE(port.Open()) << port.last_error();
  // Bytes that a cooked tty would alter: CR, LF, XON/XOFF, ^C, ^D, 0xFF.
  const std::vector<uint8_t> tricky = {0x0D, 0x0A, 0x11, 0x13, 0x03, 0x04, 0xFF, 0x00, 0x7F};
  dev.Write(tricky);
  std::vector<uint8_t> got;
  std::array<uint8_t, 64> buf;
  for (int i = 0; i < 20 && got.size() < tricky.size(); ++i) {
    const SerialRead r = port.Read(buf, 50 * kMs);
    if (r.status == SerialReadStatus::kData)
      got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.bytes));
  }
  EXPECT_EQ(got, tricky);
  dev.Write(SomeFrames(100, 50));
  const auto counters = ReadFrames(port, 50, 2000 * kMs);
  ASSERT_EQ(counters.size(), 50u);
  EXPECT_EQ(counters.front(), 100);
  EXPECT_EQ(counters.back(), 149);
  // Nothing pending: a read times out after about the requested time.
  const int64_t t0 = MonotonicNowNs();
  EXPECT_EQ(port.Read(buf, 30 * kMs).status, SerialReadStatus::kTimeout);
  EXPECT_GE(MonotonicNowNs() - t0, 25 * kMs);
}

TEST(SerialPort, ReopensWhenTheDeviceVanishesAndComesBack) {
  if (!PtyAvailable()) GTEST_SKIP() << "no pseudo-terminals (openpty failed)";
  const fs::path dir = test::MakeTempDir("serial");
  const fs::path link = dir / "ttyMTI";
  auto dev = std::make_unique<FakeDevice>(link);
  SerialPort port({link.string(), 921600, 20 * kMs});
  ASSERT_TRUE(port.Open()) << port.last_error();
  dev->Write(SomeFrames(1, 10));
  ASSERT_EQ(ReadFrames(port, 10, 2000 * kMs).size(), 10u);

  // Unplug: the master goes away and the path disappears.
  dev.reset();
  fs::remove(link);
  std::array<uint8_t, 64> buf;
  SerialRead r;
  for (int i = 0; i < 10 && r.status != SerialReadStatus::kClosed; ++i)
    r = port.Read(buf, 50 * kMs);
  EXPECT_EQ(r.status, SerialReadStatus::kClosed);
  EXPECT_FALSE(port.is_open());
  EXPECT_EQ(port.stats().disconnects, 1u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(port.Read(buf, 30 * kMs).status, SerialReadStatus::kClosed);
  EXPECT_GE(port.stats().open_failures, 2u);

  // Plug back in: a new pty behind the same path.
  dev = std::make_unique<FakeDevice>(link);
  for (int i = 0; i < 50 && r.status != SerialReadStatus::kReopened; ++i)
    r = port.Read(buf, 30 * kMs);
  ASSERT_EQ(r.status, SerialReadStatus::kReopened) << port.last_error();
  EXPECT_TRUE(port.is_open());
  EXPECT_EQ(port.stats().opens, 2u);
  dev->Write(SomeFrames(500, 20));
  const auto counters = ReadFrames(port, 20, 2000 * kMs);
  ASSERT_EQ(counters.size(), 20u);
  EXPECT_EQ(counters.front(), 500);
}

TEST(SerialPort, BaudRates) {
  if (!PtyAvailable()) GTEST_SKIP() << "no pseudo-terminals (openpty failed)";
  const fs::path dir = test::MakeTempDir("serial");
  FakeDevice dev(dir / "tty");
  for (int64_t baud : {9600, 115200, 460800, 921600, 2000000}) {
    SerialPort port({(dir / "tty").string(), baud, 20 * kMs});
    EXPECT_TRUE(port.Open()) << baud << ": " << port.last_error();
  }
  SerialPort bad({(dir / "tty").string(), 1234, 20 * kMs});
  EXPECT_FALSE(bad.Open());
  EXPECT_NE(bad.last_error().find("1234"), std::string::npos);
  EXPECT_FALSE(IsSupportedSerialBaud(1234));
  SerialPort missing({(dir / "absent").string(), 921600, 20 * kMs});
  EXPECT_FALSE(missing.Open());
  EXPECT_EQ(missing.Read({}, 0).status, SerialReadStatus::kClosed);
}

TEST(SerialPort, WriteReachesTheDevice) {
  if (!PtyAvailable()) GTEST_SKIP() << "no pseudo-terminals (openpty failed)";
  const fs::path dir = test::MakeTempDir("serial");
  FakeDevice dev(dir / "tty");
  SerialPort port({(dir / "tty").string(), 921600, 20 * kMs});
  ASSERT_TRUE(port.Open());
  std::array<uint8_t, 8> go;
  const size_t n = xsens::EncodeXbusFrame(xsens::mid::kGoToConfig, {}, go);
  ASSERT_TRUE(port.Write({go.data(), n}, 100 * kMs));
  std::array<uint8_t, 8> got{};
  ::fcntl(dev.master, F_SETFL, ::fcntl(dev.master, F_GETFL) | O_NONBLOCK);
  ssize_t r = -1;
  for (int i = 0; i < 100 && r <= 0; ++i) {
    r = ::read(dev.master, got.data(), got.size());
    if (r <= 0) ::usleep(1000);
  }
  ASSERT_EQ(r, static_cast<ssize_t>(n));
  EXPECT_TRUE(std::equal(go.begin(), go.begin() + static_cast<std::ptrdiff_t>(n), got.begin()));
}

}  // namespace
}  // namespace swlio::drivers
