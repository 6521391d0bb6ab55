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
#include <vector>

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

// Every port that may be given, so that each is drawn with the same chance. Walking from a
// random start to the next allowed port would not be uniform: the 60 % of starts that fall in a
// DDS band would all land on the port just above it, and two processes would pick the same one
// with a chance of 0.4 % instead of 1 in 9,100.
std::vector<int> CandidatePorts() {
  const int high = EphemeralLow();  // exclusive
  if (high <= kLowestPort) throw std::runtime_error("ephemeral port range starts below 10000");
  std::vector<int> ports;
  for (int port = kLowestPort; port < high; ++port) {
    if (!InDdsBand(port)) ports.push_back(port);
  }
  return ports;
}

}  // namespace

uint16_t QuietUdpPort() {
  static std::mutex mutex;
  static std::set<int> given;
  static std::mt19937 rng{std::random_device{}()};
  const std::lock_guard lock(mutex);
  static const std::vector<int> candidates = CandidatePorts();
  const size_t n = candidates.size();
  const size_t start = std::uniform_int_distribution<size_t>(0, n - 1)(rng);
  for (size_t i = 0; i < n; ++i) {
    const int port = candidates[(start + i) % n];
    if (given.count(port) != 0 || !CanBind(port)) continue;
    given.insert(port);
    return static_cast<uint16_t>(port);
  }
  throw std::runtime_error("no free UDP port outside the DDS bands below the ephemeral range");
}

}  // namespace swlio::test
