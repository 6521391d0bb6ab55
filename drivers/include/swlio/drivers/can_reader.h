#pragma once
/// @file
/// SocketCAN CAN_RAW reader: reads `struct can_frame` records (linux/can.h, 16 bytes each)
/// from any file descriptor, so tests drive it through a `socketpair(AF_UNIX,
/// SOCK_SEQPACKET)`; on a real CAN_RAW socket it sets the kernel's identifier filters instead of
/// filtering itself. Receive time: the kernel's SO_TIMESTAMPNS stamp converted to
/// CLOCK_MONOTONIC (rx_timestamp.h), else CLOCK_MONOTONIC at read. No allocation after
/// construction.

#include <linux/can.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "swlio/drivers/can_frame.h"

namespace swlio::drivers {

/// Accepts a frame when (frame key & mask) == (id key & mask), where the key is the id plus bit
/// 31 for extended identifiers — the semantics of SocketCAN's `struct can_filter`.
struct CanIdFilter {
  uint32_t id = 0;
  bool extended = false;
  uint32_t mask = kCanMaxExtendedId;  ///< bits of the id that must match
};

/// A frame with its host receive time.
struct CanRxFrame {
  CanFrame frame;
  int64_t t_ns = 0;           ///< CLOCK_MONOTONIC ns
  bool kernel_stamp = false;  ///< t_ns came from the kernel's receive timestamp
};

struct CanReaderCounters {
  uint64_t frames = 0;           ///< frames returned
  uint64_t filtered_out = 0;     ///< dropped by the user-space filter (non-CAN fds)
  uint64_t bad_size = 0;         ///< records that were not one classic `struct can_frame`
  uint64_t read_errors = 0;      ///< poll/recvmsg failures other than "no data"
  uint64_t stamp_fallbacks = 0;  ///< no or implausible kernel stamp; read time used
  uint64_t closed = 0;           ///< peer closed (end of stream) observed
};

/// SocketCAN's kernel record ↔ CanFrame (id flags CAN_EFF_FLAG/CAN_RTR_FLAG/CAN_ERR_FLAG).
CanFrame FromSocketCan(const can_frame& in);
can_frame ToSocketCan(const CanFrame& in);

/// Opens a CAN_RAW socket bound to interface `ifname` (socket(PF_CAN, SOCK_RAW, CAN_RAW),
/// bind to its ifindex). Returns the fd, or -1 with a reason in `*error`. Not covered by tests
/// beyond its failure path: the test kernel has no CAN support.
int OpenCanRawSocket(const std::string& ifname, std::string* error);

class CanReader {
 public:
  /// Does not own `fd`. Filters empty = accept everything. On an AF_CAN socket the filters are
  /// installed with CAN_RAW_FILTER; kernel receive timestamps are requested on any socket.
  CanReader(int fd, std::span<const CanIdFilter> filters);

  /// Waits up to `timeout_ms` (0 = don't wait, −1 = forever) for data, then reads without
  /// blocking until `out` is full or no frame is left. Returns the number of frames stored,
  /// 0 on timeout, −1 once the peer has closed the stream.
  int Read(std::span<CanRxFrame> out, int timeout_ms);

  bool kernel_filtering() const { return kernel_filtering_; }
  bool kernel_timestamps() const { return kernel_timestamps_; }
  const CanReaderCounters& counters() const { return counters_; }

 private:
  bool Accept(const CanFrame& frame) const;
  /// One non-blocking record: 1 = stored in *out, 0 = none left, −1 = closed, 2 = dropped.
  int ReadOne(CanRxFrame* out);

  int fd_;
  std::vector<CanIdFilter> filters_;
  bool kernel_filtering_ = false;
  bool kernel_timestamps_ = false;
  CanReaderCounters counters_;
};

}  // namespace swlio::drivers
