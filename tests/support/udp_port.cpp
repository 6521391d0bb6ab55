#include "udp_port.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>

namespace swlio::test {
namespace {

constexpr int kLowestPort = 10'000;
// The default port mapping of OMG DDSI-RTPS (§9.6.1 in 2.3): PB 7400, DG 250, offsets
// d0..d3 = 0, 10, 1, 11, PG 2. With participant indices up to 50 a domain uses
// PB + DG·d + 0..111; 150 leaves a margin.
constexpr int kDdsBase = 7400;
constexpr int kDdsDomainGain = 250;
constexpr int kDdsBandWidth = 150;

int EphemeralLow() {
  std::ifstream in("/proc/sys/net/ipv4/ip_local_port_range");
  int low = 32'768;
  in >> low;
  return low;
}

bool InDdsBand(int port) {
  return port >= kDdsBase && (port - kDdsBase) % kDdsDomainGain < kDdsBandWidth;
}

bool CanBind(int port) {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  const bool ok = bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  close(fd);
  return ok;
}

}  // namespace

uint16_t QuietUdpPort() {
  static std::mutex mutex;
  static std::set<int> given;
  static std::mt19937 rng{std::random_device{}()};
  const std::lock_guard lock(mutex);
  const int high = EphemeralLow();  // exclusive
  if (high <= kLowestPort) throw std::runtime_error("ephemeral port range starts below 10000");
  const int span = high - kLowestPort;
  const int start = std::uniform_int_distribution<int>(0, span - 1)(rng);
  for (int i = 0; i < span; ++i) {
    const int port = kLowestPort + (start + i) % span;
    if (InDdsBand(port) || given.count(port) != 0 || !CanBind(port)) continue;
    given.insert(port);
    return static_cast<uint16_t>(port);
  }
  throw std::runtime_error("no free UDP port outside the DDS bands below the ephemeral range");
}

}  // namespace swlio::test
