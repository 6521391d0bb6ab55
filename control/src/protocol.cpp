#include "swlio/control/protocol.h"

#include <array>

namespace swlio::control {
namespace {

constexpr std::array<std::pair<std::string_view, Command>, 5> kCommands = {
    {{"status", Command::kStatus},
     {"save-map", Command::kSaveMap},
     {"reset", Command::kReset},
     {"relocalize", Command::kRelocalize},
     {"mark", Command::kMark}}};

constexpr std::array<std::pair<std::string_view, ReplyStatus>, 5> kErrorCodes = {
    {{"bad-request", ReplyStatus::kBadRequest},
     {"refused", ReplyStatus::kRefused},
     {"busy", ReplyStatus::kBusy},
     {"failed", ReplyStatus::kFailed},
     {"timeout", ReplyStatus::kTimeout}}};

/// The first control byte (or DEL) in `s`, or -1.
long FirstControlByte(std::string_view s) {
  for (size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7f) return static_cast<long>(i);
  }
  return -1;
}

std::string OneLine(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return out;
}

bool Fail(std::string* error, std::string message) {
  if (error != nullptr) *error = std::move(message);
  return false;
}

bool CheckArgument(Command command, std::string_view argument, std::string* error) {
  if (command == Command::kRelocalize) {
    // The numbers are the daemon's to read (pose_hint.h); here only that there are some.
    return !argument.empty() || Fail(error, "relocalize needs x y yaw_deg [sigma_m]");
  }
  if (command == Command::kMark) return true;  // any note, or none
  if (command != Command::kSaveMap) {
    return argument.empty() || Fail(error, std::string(ToString(command)) + " takes no argument");
  }
  if (argument.empty()) return Fail(error, "save-map needs a path");
  if (argument.front() != '/') {
    return Fail(error,
                "save-map needs an absolute path (the daemon's working directory is not "
                "the client's)");
  }
  if (argument.back() == '/') return Fail(error, "save-map needs a file path, not a directory");
  return true;
}

}  // namespace

const char* ToString(Command command) {
  for (const auto& [name, c] : kCommands) {
    if (c == command) return name.data();
  }
  return "unknown";
}

const char* ToString(ReplyStatus status) {
  if (status == ReplyStatus::kOk) return "ok";
  for (const auto& [name, s] : kErrorCodes) {
    if (s == status) return name.data();
  }
  return "unknown";
}

std::optional<Request> ParseRequest(std::string_view line, std::string* error) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (line.size() + 1 > kMaxRequestBytes) {
    Fail(error, "request longer than " + std::to_string(kMaxRequestBytes) + " bytes");
    return std::nullopt;
  }
  if (const long at = FirstControlByte(line); at >= 0) {
    Fail(error, "control byte at offset " + std::to_string(at) + " (one line of text expected)");
    return std::nullopt;
  }
  const size_t space = line.find(' ');
  const std::string_view word = line.substr(0, space);
  const std::string_view argument =
      space == std::string_view::npos ? std::string_view{} : line.substr(space + 1);
  for (const auto& [name, command] : kCommands) {
    if (word != name) continue;
    if (space != std::string_view::npos && argument.empty()) {
      Fail(error, "trailing space after " + std::string(name));
      return std::nullopt;
    }
    if (!CheckArgument(command, argument, error)) return std::nullopt;
    return Request{command, std::string(argument)};
  }
  std::string message = line.empty() ? "empty request" : "leading space";
  if (!word.empty())
    message.assign("unknown command '").append(OneLine(word.substr(0, 64))).append("'");
  Fail(error, message.append(" (commands: status, save-map PATH, reset)"));
  return std::nullopt;
}

std::string FormatRequest(const Request& request) {
  std::string line = ToString(request.command);
  if (!request.argument.empty()) line += " " + request.argument;
  return line + "\n";
}

RequestReader::State RequestReader::Add(std::string_view bytes) {
  if (state_ == State::kError || bytes.empty()) return state_;
  if (state_ == State::kComplete) {
    error_ = "more than one line (one request per connection)";
    return state_ = State::kError;
  }
  const size_t newline = bytes.find('\n');
  const std::string_view part = bytes.substr(0, newline);
  if (line_.size() + part.size() + 1 > kMaxRequestBytes) {
    error_ = "request longer than " + std::to_string(kMaxRequestBytes) + " bytes";
    return state_ = State::kError;
  }
  line_.append(part);
  if (newline == std::string_view::npos) return state_;
  state_ = State::kComplete;
  if (newline + 1 < bytes.size()) {
    error_ = "more than one line (one request per connection)";
    state_ = State::kError;
  }
  return state_;
}

std::string FormatReply(const Reply& reply) {
  std::string out;
  if (reply.status != ReplyStatus::kOk) {
    // Appended piece by piece: "error " + std::string(...) trips GCC 12's -Wrestrict.
    out.append("error ").append(ToString(reply.status)).append(": ");
    out.append(OneLine(reply.message)).append("\n");
    return out;
  }
  out = "ok";
  if (!reply.message.empty()) out.append(" ").append(OneLine(reply.message));
  out += "\n";
  out += reply.body;
  if (!reply.body.empty() && reply.body.back() != '\n') out += "\n";
  return out;
}

std::optional<Reply> ParseReply(std::string_view text, std::string* error) {
  const size_t newline = text.find('\n');
  if (newline == std::string_view::npos) {
    Fail(error, "reply without a complete first line");
    return std::nullopt;
  }
  const std::string_view first = text.substr(0, newline);
  Reply reply;
  if (first == "ok" || first.substr(0, 3) == "ok ") {
    reply.status = ReplyStatus::kOk;
    if (first.size() > 3) reply.message = std::string(first.substr(3));
    reply.body = std::string(text.substr(newline + 1));
    return reply;
  }
  constexpr std::string_view kError = "error ";
  if (first.substr(0, kError.size()) == kError && newline + 1 == text.size()) {
    const std::string_view rest = first.substr(kError.size());
    const size_t colon = rest.find(": ");
    for (const auto& [name, status] : kErrorCodes) {
      if (colon == std::string_view::npos || rest.substr(0, colon) != name) continue;
      reply.status = status;
      reply.message = std::string(rest.substr(colon + 2));
      return reply;
    }
  }
  Fail(error, "unexpected reply '" + OneLine(first.substr(0, 80)) + "'");
  return std::nullopt;
}

}  // namespace swlio::control
