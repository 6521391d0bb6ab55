// SocketCAN CAN_RAW reader. Protocol summary (Linux Documentation/networking/can.rst): a
// CAN_RAW socket delivers one `struct can_frame` (16 bytes: can_id with EFF/RTR/ERR flags in
// bits 31/30/29, len 0–8, 3 pad/res bytes, data[8]) per recvmsg; CAN FD frames (72 bytes) only
// arrive when CAN_RAW_FD_FRAMES is on, which we never set. Filters are `struct can_filter`
// {can_id, can_mask} set with setsockopt(SOL_CAN_RAW, CAN_RAW_FILTER); a frame passes when
// (received_id & mask) == (filter_id & mask). On other socket types (tests use
// socketpair(AF_UNIX, SOCK_SEQPACKET)) the same rule is applied here.

#include "swlio/drivers/can_reader.h"

#include <fcntl.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "swlio/drivers/rx_timestamp.h"

namespace swlio::drivers {
namespace {

uint32_t FilterKey(uint32_t id, bool extended) { return id | (extended ? CAN_EFF_FLAG : 0u); }

bool IsCanSocket(int fd) {
  int domain = 0;
  socklen_t len = sizeof(domain);
  return getsockopt(fd, SOL_SOCKET, SO_DOMAIN, &domain, &len) == 0 && domain == AF_CAN;
}

bool SetKernelFilters(int fd, std::span<const CanIdFilter> filters) {
  constexpr size_t kMaxFilters = 64;
  if (filters.empty() || filters.size() > kMaxFilters) return false;
  can_filter kf[kMaxFilters] = {};
  for (size_t i = 0; i < filters.size(); ++i) {
    kf[i].can_id = FilterKey(filters[i].id, filters[i].extended);
    // Matching the EFF flag as well keeps standard and extended ids apart; RTR is not in the
    // mask, so remote frames pass as in the user-space filter (the decoder counts them).
    kf[i].can_mask = (filters[i].mask & CAN_EFF_MASK) | CAN_EFF_FLAG;
  }
  const auto bytes = static_cast<socklen_t>(filters.size() * sizeof(can_filter));
  return setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, kf, bytes) == 0;
}

}  // namespace

CanFrame FromSocketCan(const can_frame& in) {
  CanFrame f;
  f.extended = (in.can_id & CAN_EFF_FLAG) != 0;
  f.remote = (in.can_id & CAN_RTR_FLAG) != 0;
  f.error = (in.can_id & CAN_ERR_FLAG) != 0;
  f.id = in.can_id & (f.extended || f.error ? CAN_EFF_MASK : CAN_SFF_MASK);
  f.dlc = in.len;
  const size_t n = f.remote ? 0 : std::min<size_t>(in.len, CAN_MAX_DLEN);
  std::copy_n(in.data, n, f.data.begin());
  return f;
}

can_frame ToSocketCan(const CanFrame& in) {
  can_frame out{};
  out.can_id = in.id | (in.extended ? CAN_EFF_FLAG : 0u) | (in.remote ? CAN_RTR_FLAG : 0u) |
               (in.error ? CAN_ERR_FLAG : 0u);
  out.len = in.dlc;
  std::copy(in.data.begin(), in.data.end(), out.data);
  return out;
}

int OpenCanRawSocket(const std::string& ifname, std::string* error) {
  const int fd = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    if (error) *error = std::string("socket(PF_CAN, CAN_RAW): ") + std::strerror(errno);
    return -1;
  }
  const unsigned index = if_nametoindex(ifname.c_str());
  if (index == 0) {
    if (error) *error = "no CAN interface '" + ifname + "': " + std::strerror(errno);
    close(fd);
    return -1;
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) != 0) {
    if (error) *error = "bind to '" + ifname + "': " + std::strerror(errno);
    close(fd);
    return -1;
  }
  return fd;
}

CanReader::CanReader(int fd, std::span<const CanIdFilter> filters)
    : fd_(fd), filters_(filters.begin(), filters.end()) {
  kernel_filtering_ = IsCanSocket(fd) && SetKernelFilters(fd, filters);
  kernel_timestamps_ = EnableRxTimestampNs(fd);
}

bool CanReader::Accept(const CanFrame& frame) const {
  if (kernel_filtering_ || filters_.empty()) return true;
  const uint32_t key = FilterKey(frame.id, frame.extended);
  for (const auto& f : filters_) {
    const uint32_t mask = (f.mask & CAN_EFF_MASK) | CAN_EFF_FLAG;
    if ((key & mask) == (FilterKey(f.id, f.extended) & mask)) return true;
  }
  return false;
}

int CanReader::ReadOne(CanRxFrame* out) {
  can_frame raw{};
  alignas(cmsghdr) char control[kRxTimestampControlBytes];
  iovec iov{&raw, sizeof(raw)};
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof(control);
  const ssize_t n = recvmsg(fd_, &msg, MSG_DONTWAIT);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return 0;
    ++counters_.read_errors;
    return 0;
  }
  if (n == 0) {
    ++counters_.closed;
    return -1;
  }
  if (static_cast<size_t>(n) != sizeof(raw) || (msg.msg_flags & MSG_TRUNC) != 0 ||
      raw.len > CAN_MAX_DLEN) {
    ++counters_.bad_size;
    return 2;
  }
  const RealtimeToMonotonic clock = RealtimeToMonotonic::Measure();
  out->frame = FromSocketCan(raw);
  if (!Accept(out->frame)) {
    ++counters_.filtered_out;
    return 2;
  }
  const std::optional<timespec> stamp = FindRxTimestampNs(msg);
  const std::optional<int64_t> t = stamp ? clock.Convert(*stamp) : std::nullopt;
  out->kernel_stamp = t.has_value();
  out->t_ns = t.value_or(clock.read_mono_ns);
  if (!t) ++counters_.stamp_fallbacks;
  ++counters_.frames;
  return 1;
}

int CanReader::Read(std::span<CanRxFrame> out, int timeout_ms) {
  if (out.empty()) return 0;
  pollfd pfd{fd_, POLLIN, 0};
  const int ready = poll(&pfd, 1, timeout_ms);
  if (ready < 0) {
    if (errno != EINTR) ++counters_.read_errors;
    return 0;
  }
  if (ready == 0) return 0;
  size_t stored = 0;
  // Dropped records also count as attempts, so a flood of filtered frames cannot hold us here.
  for (size_t attempts = 0; stored < out.size() && attempts < 4 * out.size(); ++attempts) {
    const int r = ReadOne(&out[stored]);
    if (r == 0) break;
    if (r == -1) return stored > 0 ? static_cast<int>(stored) : -1;
    if (r == 1) ++stored;
  }
  return static_cast<int>(stored);
}

}  // namespace swlio::drivers
