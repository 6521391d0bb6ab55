#pragma once
/// @file
/// candump log files (can-utils `candump -l` / `-L`, replayed by `canplayer`), one frame a line:
///
///   (1700000000.123456) can0 123#DEADBEEF      standard id: 3 hex digits
///   (1700000000.123457) can0 1ABCDEF0#0102     extended id: 8 hex digits
///   (1700000000.123458) can0 123#R             remote frame, DLC 0 (…#R4: DLC 4)
///   (1700000000.123459) can0 20000080#0000…    error frame (CAN_ERR_FLAG 0x20000000 in the id)
///
/// Data bytes may be separated by '.', as can-utils' parse_canframe() accepts. CAN FD lines
/// (`123##1…`) are recognised and counted, not decoded. The time is whatever clock the
/// recorder used (candump: CLOCK_REALTIME); it is carried through as t_ns unchanged. We write
/// microseconds, as candump does, so sub-µs parts of t_ns are truncated.

#include <array>
#include <cstddef>
#include <cstdint>
#include <istream>
#include <ostream>
#include <span>
#include <string>
#include <string_view>

#include "swlio/drivers/can_frame.h"

namespace swlio::drivers {

struct CandumpRecord {
  int64_t t_ns = 0;                   ///< the line's time, ns (≥ 0)
  std::array<char, 16> interface {};  ///< NUL-terminated interface name (≤ 15 chars)
  CanFrame frame;

  std::string_view interface_name() const { return {interface.data()}; }
};

enum class CandumpLineStatus {
  kFrame,      ///< *out holds the frame
  kBlank,      ///< empty line or '#' comment
  kCanFd,      ///< a well-formed-looking CAN FD line, not decoded
  kMalformed,  ///< anything else
};

/// Parses one line (without or with its trailing newline). Pure, allocation-free.
CandumpLineStatus ParseCandumpLine(std::string_view line, CandumpRecord* out);

/// Longest line FormatCandumpLine() writes, including the newline.
inline constexpr size_t kCandumpMaxLineBytes = 64;

/// Writes one line with its newline into `out`; returns its length, 0 when `record` cannot be
/// written (negative time, empty or over-long interface name, DLC > 8, id out of range).
size_t FormatCandumpLine(const CandumpRecord& record, std::span<char> out);

/// Convenience: builds a record (interface truncated to 15 characters).
CandumpRecord MakeCandumpRecord(int64_t t_ns, std::string_view interface, const CanFrame& frame);

struct CandumpCounters {
  uint64_t lines = 0;
  uint64_t frames = 0;
  uint64_t blank_lines = 0;
  uint64_t can_fd_lines = 0;
  uint64_t malformed_lines = 0;
};

/// Reads records from a stream, skipping (and counting) lines that are not classic frames.
class CandumpReader {
 public:
  explicit CandumpReader(std::istream& in) : in_(in) {}
  /// The next frame; false at end of stream.
  bool Next(CandumpRecord* out);
  const CandumpCounters& counters() const { return counters_; }

 private:
  std::istream& in_;
  std::string line_;
  CandumpCounters counters_;
};

/// Writes records to a stream; false when a record is invalid or the stream failed.
bool WriteCandumpLine(std::ostream& os, const CandumpRecord& record);

}  // namespace swlio::drivers
