// libFuzzer target for swliod's control protocol (swlio/control/protocol.h, docs/control.md):
// the input is what a client might send on the control socket, and, read the other way, what
// a daemon might answer swlioctl. Whatever the bytes, nothing may crash, hang or allocate
// beyond the bounds, and:
// - the request reader, fed the bytes in chunks (sizes from the first byte), never holds more
//   than kMaxRequestBytes, and a complete line contains no newline;
// - a request that parses formats back to a line that parses to the same request;
// - a reply that parses formats to text that is a fixed point of parse → format.
// Any violated invariant is a bug (__builtin_trap). Seeds: none needed (the command words come
// from the comparisons).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "swlio/control/protocol.h"

namespace {

using namespace swlio::control;

void Check(bool ok) {
  if (!ok) __builtin_trap();
}

void FuzzRequest(std::string_view bytes) {
  RequestReader reader;
  const size_t chunk = bytes.empty() ? 1 : static_cast<unsigned char>(bytes[0]) % 64 + 1;
  for (size_t at = 0; at < bytes.size(); at += chunk) {
    reader.Add(bytes.substr(at, chunk));
    Check(reader.line().size() < kMaxRequestBytes);
  }
  if (reader.state() != RequestReader::State::kComplete) return;
  Check(reader.line().find('\n') == std::string::npos);
  std::string error;
  const std::optional<Request> request = ParseRequest(reader.line(), &error);
  if (!request) {
    Check(!error.empty());
    return;
  }
  std::string line = FormatRequest(*request);
  Check(!line.empty() && line.back() == '\n');
  line.pop_back();
  const std::optional<Request> again = ParseRequest(line, &error);
  Check(again.has_value() && again->command == request->command &&
        again->argument == request->argument);
}

void FuzzReply(std::string_view bytes) {
  std::string error;
  const std::optional<Reply> reply = ParseReply(bytes, &error);
  if (!reply) {
    Check(!error.empty());
    return;
  }
  const std::string text = FormatReply(*reply);
  const std::optional<Reply> again = ParseReply(text, &error);
  Check(again.has_value() && again->status == reply->status);
  Check(FormatReply(*again) == text);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  FuzzRequest(bytes);
  FuzzReply(bytes);
  return 0;
}
