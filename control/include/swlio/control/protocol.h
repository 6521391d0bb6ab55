#pragma once
/// @file
/// swliod's control protocol (docs/control.md), spoken over a UNIX stream socket: one request
/// line per connection, one reply, then the daemon closes.
///
///   request = command [ " " argument ] "\n"          at most kMaxRequestBytes in all
///   command = "status" | "save-map" | "reset" | "relocalize" | "mark"
///                                                    save-map takes an absolute path,
///                                                    relocalize "x y yaw_deg [sigma_m]",
///                                                    mark an optional note
///   reply   = "ok" [ " " text ] "\n" body             body: lines of text until EOF
///           | "error " code ": " text "\n"
///   code    = "bad-request" | "refused" | "busy" | "failed" | "timeout"
///
/// A request is printable text (UTF-8 allowed): no control bytes, no NUL; a "\r" before the
/// "\n" is accepted (nc -C). Parsing never throws and never allocates beyond the line.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace swlio::control {

/// A request longer than this (newline included) is refused without reading on.
inline constexpr size_t kMaxRequestBytes = 4096;
/// The client stops reading a reply beyond this (a status is a few kB).
inline constexpr size_t kMaxReplyBytes = 1 << 20;

enum class Command : uint8_t { kStatus, kSaveMap, kReset, kRelocalize, kMark };
/// "status", "save-map", "reset", "relocalize", "mark".
const char* ToString(Command command);

struct Request {
  Command command = Command::kStatus;
  /// save-map: the absolute path; relocalize: its numbers; mark: the note (may be empty); else
  /// empty
  std::string argument;
};

/// One request line without its "\n" (a trailing "\r" is dropped); std::nullopt with *error
/// (a sentence for the client) when it is not a request.
std::optional<Request> ParseRequest(std::string_view line, std::string* error);
/// The line a client sends, "\n" included.
std::string FormatRequest(const Request& request);

/// Collects a connection's bytes into its one request line.
class RequestReader {
 public:
  enum class State : uint8_t { kIncomplete, kComplete, kError };
  /// Takes bytes as they arrive. After the line is complete, any further byte is an error
  /// (one request per connection); so is a line longer than kMaxRequestBytes.
  State Add(std::string_view bytes);
  State state() const { return state_; }
  /// The line without "\n" (kComplete).
  const std::string& line() const { return line_; }
  /// Why (kError).
  const std::string& error() const { return error_; }

 private:
  std::string line_;
  std::string error_;
  State state_ = State::kIncomplete;
};

enum class ReplyStatus : uint8_t { kOk, kBadRequest, kRefused, kBusy, kFailed, kTimeout };
/// "ok", "bad-request", "refused", "busy", "failed", "timeout".
const char* ToString(ReplyStatus status);

struct Reply {
  ReplyStatus status = ReplyStatus::kOk;
  std::string message;  ///< one line (newlines are replaced by spaces when formatted)
  std::string body;     ///< ok only: lines after the first, each ending in "\n"
};

std::string FormatReply(const Reply& reply);
/// A whole reply (up to EOF); std::nullopt with *error when it does not follow the grammar.
std::optional<Reply> ParseReply(std::string_view text, std::string* error);

}  // namespace swlio::control
