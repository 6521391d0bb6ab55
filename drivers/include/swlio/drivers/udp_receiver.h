#pragma once
/// @file
/// UDP I/O shell: the only code that touches UDP sockets. Binds an IPv4 address and port,
/// receives datagrams in batches with one recvmmsg(2) call, stamps each with the kernel's
/// SO_TIMESTAMPNS receive time converted to CLOCK_MONOTONIC (rx_timestamp.h; read time when
/// absent), and counts what it drops. All buffers are allocated by Open(); Receive() does not
/// allocate.

#include <netinet/in.h>
#include <sys/socket.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace swlio::drivers {

struct UdpReceiverOptions {
  std::string bind_address = "0.0.0.0";             ///< IPv4 address to bind (0.0.0.0 = all)
  uint16_t port = 0;                                ///< 0 = any free port (tests)
  int64_t rcvbuf_bytes = int64_t{8} * 1024 * 1024;  ///< requested SO_RCVBUF; 0 = leave the default
  size_t max_datagram_bytes = 2048;                 ///< longer datagrams are truncated and counted
  size_t batch_size = 32;                           ///< datagrams per recvmmsg call
};

/// One received datagram. `payload` points into the receiver's buffers and stays valid until
/// the next Receive().
struct ReceivedDatagram {
  std::span<const uint8_t> payload;
  int64_t t_ns = 0;             ///< CLOCK_MONOTONIC ns
  bool kernel_stamp = false;    ///< t_ns came from the kernel's receive timestamp
  bool truncated = false;       ///< longer than max_datagram_bytes; payload is the first part
  uint32_t source_address = 0;  ///< IPv4, host byte order
  uint16_t source_port = 0;
};

struct UdpReceiverCounters {
  uint64_t datagrams = 0;        ///< datagrams returned (truncated ones included)
  uint64_t truncated = 0;        ///< longer than max_datagram_bytes
  uint64_t errors = 0;           ///< poll/recvmmsg failures other than "no data"
  uint64_t stamp_fallbacks = 0;  ///< no or implausible kernel stamp; read time used
  uint64_t batches = 0;          ///< recvmmsg calls that returned data
};

class UdpReceiver {
 public:
  /// Opens, configures and binds the socket; std::nullopt with a reason in `*error`.
  static std::optional<UdpReceiver> Open(const UdpReceiverOptions& options, std::string* error);

  UdpReceiver(UdpReceiver&& other) noexcept;
  UdpReceiver& operator=(UdpReceiver&&) = delete;
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;
  ~UdpReceiver();

  /// Waits up to `timeout_ms` (0 = don't wait, −1 = forever) for data, then takes up to
  /// batch_size datagrams in one recvmmsg. Empty on timeout or error (counted).
  std::span<const ReceivedDatagram> Receive(int timeout_ms);

  int fd() const { return fd_; }
  uint16_t bound_port() const { return bound_port_; }
  int64_t rcvbuf_requested() const { return rcvbuf_requested_; }
  /// SO_RCVBUF as read back with getsockopt: Linux doubles the request for its bookkeeping and
  /// caps it at net.core.rmem_max unless SO_RCVBUFFORCE (CAP_NET_ADMIN) succeeded.
  int64_t rcvbuf_granted() const { return rcvbuf_granted_; }
  bool kernel_timestamps() const { return kernel_timestamps_; }
  const UdpReceiverCounters& counters() const { return counters_; }

 private:
  UdpReceiver() = default;
  void PrepareBuffers(const UdpReceiverOptions& options);

  int fd_ = -1;
  uint16_t bound_port_ = 0;
  int64_t rcvbuf_requested_ = 0;
  int64_t rcvbuf_granted_ = 0;
  bool kernel_timestamps_ = false;
  size_t max_datagram_bytes_ = 0;
  std::vector<uint8_t> storage_;  ///< batch × max_datagram_bytes
  std::vector<uint8_t> control_;  ///< batch × control bytes for the timestamp
  std::vector<iovec> iov_;
  std::vector<sockaddr_in> sources_;
  std::vector<mmsghdr> msgs_;
  std::vector<ReceivedDatagram> out_;
  UdpReceiverCounters counters_;
};

}  // namespace swlio::drivers
