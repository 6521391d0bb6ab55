// UDP I/O shell (see udp_receiver.h). Linux APIs used: recvmmsg(2) to take a batch of
// datagrams in one system call, each with its own msghdr (MSG_TRUNC in msg_flags marks a
// datagram longer than its buffer); socket(7) SO_RCVBUF / SO_RCVBUFFORCE, whose value read
// back is twice the request (kernel bookkeeping) capped by net.core.rmem_max; SO_TIMESTAMPNS
// for the software receive stamp (CLOCK_REALTIME, converted in rx_timestamp.cpp).

#include "swlio/drivers/udp_receiver.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "swlio/drivers/rx_timestamp.h"

namespace swlio::drivers {
namespace {

std::string Errno(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

int64_t ReadRcvbuf(int fd) {
  int value = 0;
  socklen_t len = sizeof(value);
  return getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &value, &len) == 0 ? value : -1;
}

/// Asks for `bytes`; when the plain request is capped, tries the privileged form as well.
void RequestRcvbuf(int fd, int64_t bytes) {
  if (bytes <= 0) return;
  const int value = bytes > INT32_MAX / 2 ? INT32_MAX / 2 : static_cast<int>(bytes);
  setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &value, sizeof(value));
  if (ReadRcvbuf(fd) < bytes) setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &value, sizeof(value));
}

}  // namespace

std::optional<UdpReceiver> UdpReceiver::Open(const UdpReceiverOptions& options,
                                             std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return std::nullopt;
  };
  if (options.batch_size == 0 || options.max_datagram_bytes == 0 || options.batch_size > 1024 ||
      options.max_datagram_bytes > 65536) {
    return fail("batch_size must be 1–1024 and max_datagram_bytes 1–65536");
  }
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(options.port);
  if (inet_pton(AF_INET, options.bind_address.c_str(), &addr.sin_addr) != 1) {
    return fail("bind_address '" + options.bind_address + "' is not an IPv4 address");
  }
  UdpReceiver r;
  r.fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (r.fd_ < 0) return fail(Errno("socket(AF_INET, SOCK_DGRAM)"));
  r.rcvbuf_requested_ = options.rcvbuf_bytes;
  RequestRcvbuf(r.fd_, options.rcvbuf_bytes);
  r.rcvbuf_granted_ = ReadRcvbuf(r.fd_);
  r.kernel_timestamps_ = EnableRxTimestampNs(r.fd_);
  if (bind(r.fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) != 0) {
    return fail(
        Errno(("bind " + options.bind_address + ":" + std::to_string(options.port)).c_str()));
  }
  sockaddr_in bound{};
  socklen_t len = sizeof(bound);
  if (getsockname(r.fd_, reinterpret_cast<sockaddr*>(&bound), &len) != 0) {
    return fail(Errno("getsockname"));
  }
  r.bound_port_ = ntohs(bound.sin_port);
  r.PrepareBuffers(options);
  return r;
}

void UdpReceiver::PrepareBuffers(const UdpReceiverOptions& options) {
  const size_t n = options.batch_size;
  max_datagram_bytes_ = options.max_datagram_bytes;
  storage_.assign(n * max_datagram_bytes_, 0);
  control_.assign(n * kRxTimestampControlBytes, 0);
  iov_.resize(n);
  sources_.resize(n);
  msgs_.resize(n);
  out_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    iov_[i] = {storage_.data() + i * max_datagram_bytes_, max_datagram_bytes_};
  }
}

UdpReceiver::UdpReceiver(UdpReceiver&& o) noexcept
    : fd_(o.fd_),
      bound_port_(o.bound_port_),
      rcvbuf_requested_(o.rcvbuf_requested_),
      rcvbuf_granted_(o.rcvbuf_granted_),
      kernel_timestamps_(o.kernel_timestamps_),
      max_datagram_bytes_(o.max_datagram_bytes_),
      storage_(std::move(o.storage_)),  // moving a vector keeps its heap block, so the
      control_(std::move(o.control_)),  // iovec and msghdr pointers stay valid
      iov_(std::move(o.iov_)),
      sources_(std::move(o.sources_)),
      msgs_(std::move(o.msgs_)),
      out_(std::move(o.out_)),
      counters_(o.counters_) {
  o.fd_ = -1;
}

UdpReceiver::~UdpReceiver() {
  if (fd_ >= 0) close(fd_);
}

std::span<const ReceivedDatagram> UdpReceiver::Receive(int timeout_ms) {
  pollfd pfd{fd_, POLLIN, 0};
  const int ready = poll(&pfd, 1, timeout_ms);
  if (ready <= 0) {
    if (ready < 0 && errno != EINTR) ++counters_.errors;
    return {};
  }
  const size_t n = msgs_.size();
  for (size_t i = 0; i < n; ++i) {  // recvmmsg overwrites lengths and flags: reset them
    msghdr& h = msgs_[i].msg_hdr;
    h = msghdr{};
    h.msg_name = &sources_[i];
    h.msg_namelen = sizeof(sockaddr_in);
    h.msg_iov = &iov_[i];
    h.msg_iovlen = 1;
    h.msg_control = control_.data() + i * kRxTimestampControlBytes;
    h.msg_controllen = kRxTimestampControlBytes;
    msgs_[i].msg_len = 0;
  }
  const int got = recvmmsg(fd_, msgs_.data(), static_cast<unsigned>(n), MSG_DONTWAIT, nullptr);
  if (got <= 0) {
    if (got < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) ++counters_.errors;
    return {};
  }
  // Measured after the call, so every stamp in the batch precedes the read time.
  const RealtimeToMonotonic clock = RealtimeToMonotonic::Measure();
  const auto count = static_cast<size_t>(got);
  for (size_t i = 0; i < count; ++i) {
    const msghdr& h = msgs_[i].msg_hdr;
    ReceivedDatagram& d = out_[i];
    d.payload = {storage_.data() + i * max_datagram_bytes_, msgs_[i].msg_len};
    d.truncated = (h.msg_flags & MSG_TRUNC) != 0;
    const std::optional<timespec> stamp = FindRxTimestampNs(h);
    const std::optional<int64_t> t = stamp ? clock.Convert(*stamp) : std::nullopt;
    d.kernel_stamp = t.has_value();
    d.t_ns = t.value_or(clock.read_mono_ns);
    d.source_address = ntohl(sources_[i].sin_addr.s_addr);
    d.source_port = ntohs(sources_[i].sin_port);
    counters_.truncated += d.truncated ? 1 : 0;
    counters_.stamp_fallbacks += t ? 0 : 1;
  }
  counters_.datagrams += count;
  ++counters_.batches;
  return {out_.data(), count};
}

}  // namespace swlio::drivers
