// SerialBacklog: a reader that does not read for seconds loses no byte and gets them in order,
// as from a real USB-serial adapter; beyond the adapter's limit bytes are dropped and counted.

#include "live/serial_backlog.h"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <vector>

namespace swlio::sim {
namespace {

struct Pty {
  int master = -1, slave = -1;
  Pty() {
    openpty(&master, &slave, nullptr, nullptr, nullptr);
    termios tio{};
    tcgetattr(slave, &tio);
    cfmakeraw(&tio);
    tcsetattr(slave, TCSANOW, &tio);
    fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
  }
  ~Pty() {
    close(master);
    close(slave);
  }
  /// Reads whatever comes within `quiet_ms` of silence.
  std::vector<uint8_t> ReadAll(SerialBacklog* backlog, int quiet_ms) const {
    std::vector<uint8_t> out;
    std::vector<uint8_t> buf(65536);
    for (;;) {
      backlog->Flush(master, 0);
      pollfd p{slave, POLLIN, 0};
      if (poll(&p, 1, quiet_ms) <= 0) return out;
      const ssize_t n = read(slave, buf.data(), buf.size());
      if (n <= 0) return out;
      out.insert(out.end(), buf.begin(), buf.begin() + n);
    }
  }
};

std::vector<uint8_t> Frame(size_t k) {  // 60 bytes numbered by k, as an MTi frame is long
  std::vector<uint8_t> f(60);
  for (size_t i = 0; i < f.size(); ++i) f[i] = static_cast<uint8_t>((k * 7 + i) & 0xFF);
  return f;
}

TEST(SerialBacklog, AReaderSecondsLateLosesNothing) {
  Pty pty;
  ASSERT_GE(pty.master, 0);
  SerialBacklog backlog;
  std::vector<uint8_t> sent;
  constexpr size_t kFrames = 400 * 3;  // 3 s of 400 Hz frames, 72 KB: more than a pty holds
  for (size_t k = 0; k < kFrames; ++k) {
    const std::vector<uint8_t> f = Frame(k);
    backlog.Send(pty.master, f, k, k + 1, static_cast<int64_t>(k));
    sent.insert(sent.end(), f.begin(), f.end());
  }
  EXPECT_GT(backlog.stats().max_backlog, 0u) << "the pty alone would have refused some";
  const std::vector<uint8_t> got = pty.ReadAll(&backlog, 200);
  EXPECT_EQ(backlog.stats().dropped, 0u);
  EXPECT_EQ(got.size(), sent.size());
  EXPECT_TRUE(got == sent) << "the same bytes, in order";
  EXPECT_TRUE(backlog.empty());
}

TEST(SerialBacklog, BeyondTheAdaptersLimitWholeChunksAreDroppedAndCounted) {
  Pty pty;
  ASSERT_GE(pty.master, 0);
  SerialBacklog backlog(4096);  // a small adapter
  uint64_t offered = 0;
  for (size_t k = 0; k < 2000; ++k) {
    backlog.Send(pty.master, Frame(k), k, k + 1, 0);
    offered += 60;
  }
  const std::vector<uint8_t> got = pty.ReadAll(&backlog, 200);
  EXPECT_GT(backlog.stats().dropped, 0u);
  EXPECT_EQ(backlog.stats().dropped % 60, 0u) << "never part of a frame";
  EXPECT_EQ(got.size() + backlog.stats().dropped, offered);
  EXPECT_EQ(backlog.stats().written, got.size());
}

}  // namespace
}  // namespace swlio::sim
