// candump log lines. Format (can-utils candump.c log mode and lib.c's compact frame syntax,
// also read by canplayer): "(SECONDS.FRACTION) IFACE FRAME", FRAME = ID#DATA where ID is 3 hex
// digits (11-bit) or 8 hex digits (29-bit, or an error frame with CAN_ERR_FLAG 0x20000000),
// DATA = 0–8 bytes as hex pairs optionally separated by '.', or "R" plus an optional DLC digit
// for remote frames; "ID##F…" is CAN FD. Some can-utils versions append a direction flag
// (" R"/" T"); it is accepted and ignored.

#include "swlio/drivers/candump_log.h"

#include <algorithm>

namespace swlio::drivers {
namespace {

constexpr uint32_t kCanErrFlag = 0x20000000;
constexpr int kMaxSecondsDigits = 10;
constexpr int64_t kMaxSeconds = 9'000'000'000;  // keeps seconds · 1e9 inside int64 (year 2255)

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool ParseHex(std::string_view s, uint32_t* out) {
  uint32_t v = 0;
  for (char c : s) {
    const int h = HexValue(c);
    if (h < 0) return false;
    v = (v << 4) | static_cast<uint32_t>(h);
  }
  *out = v;
  return !s.empty();
}

/// "(S.F)" → ns; `s` must start with '('. Advances past ')'.
bool ParseTime(std::string_view& s, int64_t* t_ns) {
  if (s.empty() || s[0] != '(') return false;
  const size_t close = s.find(')');
  const size_t dot = s.find('.');
  if (close == std::string_view::npos || dot == std::string_view::npos || dot > close) return false;
  const std::string_view sec = s.substr(1, dot - 1);
  const std::string_view frac = s.substr(dot + 1, close - dot - 1);
  if (sec.empty() || sec.size() > kMaxSecondsDigits || frac.empty() || frac.size() > 9) {
    return false;
  }
  int64_t seconds = 0;
  for (char c : sec) {
    if (c < '0' || c > '9') return false;
    seconds = seconds * 10 + (c - '0');
  }
  if (seconds > kMaxSeconds) return false;
  int64_t ns = 0;
  for (size_t i = 0; i < 9; ++i) {
    const char c = i < frac.size() ? frac[i] : '0';
    if (c < '0' || c > '9') return false;
    ns = ns * 10 + (c - '0');
  }
  *t_ns = seconds * 1'000'000'000 + ns;
  s.remove_prefix(close + 1);
  return true;
}

std::string_view NextToken(std::string_view& s) {
  const size_t start = s.find_first_not_of(" \t");
  if (start == std::string_view::npos) {
    s = {};
    return {};
  }
  s.remove_prefix(start);
  const size_t end = std::min(s.find_first_of(" \t"), s.size());
  const std::string_view token = s.substr(0, end);
  s.remove_prefix(end);
  return token;
}

/// The part after '#': "R", "R5", "DEADBEEF", "DE.AD.BE.EF", or "" (no data).
bool ParseData(std::string_view d, CanFrame* f) {
  if (!d.empty() && d[0] == 'R') {
    f->remote = true;
    if (d.size() == 1) return true;
    const int dlc = d.size() == 2 ? HexValue(d[1]) : -1;
    if (dlc < 0 || dlc > 8) return false;
    f->dlc = static_cast<uint8_t>(dlc);
    return true;
  }
  size_t n = 0;
  size_t i = 0;
  while (i < d.size()) {
    if (d[i] == '.') {
      ++i;
      continue;
    }
    if (d[i] == '_' && n == 8 && i + 2 == d.size() && HexValue(d[i + 1]) > 8) {
      break;  // len8_dlc suffix (raw DLC 9–15 on an 8-byte frame): accepted, not kept
    }
    if (n == 8 || i + 1 >= d.size()) return false;
    const int hi = HexValue(d[i]);
    const int lo = HexValue(d[i + 1]);
    if (hi < 0 || lo < 0) return false;
    f->data[n++] = static_cast<uint8_t>((hi << 4) | lo);
    i += 2;
  }
  f->dlc = static_cast<uint8_t>(n);
  return true;
}

CandumpLineStatus ParseFrame(std::string_view token, CanFrame* f) {
  const size_t hash = token.find('#');
  if (hash == std::string_view::npos) return CandumpLineStatus::kMalformed;
  const std::string_view id_text = token.substr(0, hash);
  uint32_t id = 0;
  if ((id_text.size() != 3 && id_text.size() != 8) || !ParseHex(id_text, &id)) {
    return CandumpLineStatus::kMalformed;
  }
  *f = CanFrame{};
  if (id_text.size() == 8) {
    f->extended = (id & kCanErrFlag) == 0;
    f->error = !f->extended;
    id &= ~kCanErrFlag;
    if (id > kCanMaxExtendedId) return CandumpLineStatus::kMalformed;
  } else if (id > kCanMaxStandardId) {
    return CandumpLineStatus::kMalformed;
  }
  f->id = id;
  const std::string_view data = token.substr(hash + 1);
  if (!data.empty() && data[0] == '#') return CandumpLineStatus::kCanFd;
  return ParseData(data, f) ? CandumpLineStatus::kFrame : CandumpLineStatus::kMalformed;
}

char HexDigit(uint32_t v) { return "0123456789ABCDEF"[v & 0xF]; }

}  // namespace

CandumpLineStatus ParseCandumpLine(std::string_view line, CandumpRecord* out) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.remove_suffix(1);
  const size_t first = line.find_first_not_of(" \t");
  if (first == std::string_view::npos || line[first] == '#') return CandumpLineStatus::kBlank;
  line.remove_prefix(first);
  CandumpRecord r;
  if (!ParseTime(line, &r.t_ns)) return CandumpLineStatus::kMalformed;
  const std::string_view iface = NextToken(line);
  const bool printable =
      std::all_of(iface.begin(), iface.end(), [](char c) { return c > ' ' && c < 0x7F; });
  if (iface.empty() || iface.size() >= r.interface.size() || !printable) {
    return CandumpLineStatus::kMalformed;
  }
  std::copy(iface.begin(), iface.end(), r.interface.begin());
  const std::string_view frame = NextToken(line);
  const std::string_view flag = NextToken(line);
  if (!NextToken(line).empty() || !(flag.empty() || flag == "R" || flag == "T")) {
    return CandumpLineStatus::kMalformed;
  }
  const CandumpLineStatus status = ParseFrame(frame, &r.frame);
  if (status == CandumpLineStatus::kFrame) *out = r;
  return status;
}

size_t FormatCandumpLine(const CandumpRecord& r, std::span<char> out) {
  const CanFrame& f = r.frame;
  const std::string_view iface = r.interface_name();
  const uint32_t max_id = f.extended || f.error ? kCanMaxExtendedId : kCanMaxStandardId;
  if (r.t_ns < 0 || iface.empty() || iface.size() >= r.interface.size() || f.dlc > 8 ||
      f.id > max_id || out.size() < kCandumpMaxLineBytes) {
    return 0;
  }
  size_t n = 0;
  auto put = [&](char c) { out[n++] = c; };
  auto put_dec = [&](int64_t v, int width) {
    char digits[20];
    int len = 0;
    do {
      digits[len++] = static_cast<char>('0' + v % 10);
      v /= 10;
    } while (v > 0 || len < width);
    while (len > 0) put(digits[--len]);
  };
  put('(');
  put_dec(r.t_ns / 1'000'000'000, 10);
  put('.');
  put_dec((r.t_ns % 1'000'000'000) / 1'000, 6);
  put(')');
  put(' ');
  for (char c : iface) put(c);
  put(' ');
  const uint32_t id = f.id | (f.error ? kCanErrFlag : 0u);
  const int id_digits = f.extended || f.error ? 8 : 3;
  for (int i = id_digits - 1; i >= 0; --i) put(HexDigit(id >> (4 * i)));
  put('#');
  if (f.remote) {
    put('R');
    if (f.dlc > 0) put(HexDigit(f.dlc));
  } else {
    for (size_t i = 0; i < f.dlc; ++i) {
      put(HexDigit(static_cast<uint32_t>(f.data[i] >> 4)));
      put(HexDigit(f.data[i]));
    }
  }
  put('\n');
  return n;
}

CandumpRecord MakeCandumpRecord(int64_t t_ns, std::string_view interface, const CanFrame& frame) {
  CandumpRecord r;
  r.t_ns = t_ns;
  const size_t n = std::min(interface.size(), r.interface.size() - 1);
  std::copy_n(interface.begin(), n, r.interface.begin());
  r.frame = frame;
  return r;
}

bool CandumpReader::Next(CandumpRecord* out) {
  while (std::getline(in_, line_)) {
    ++counters_.lines;
    switch (ParseCandumpLine(line_, out)) {
      case CandumpLineStatus::kFrame:
        ++counters_.frames;
        return true;
      case CandumpLineStatus::kBlank:
        ++counters_.blank_lines;
        break;
      case CandumpLineStatus::kCanFd:
        ++counters_.can_fd_lines;
        break;
      case CandumpLineStatus::kMalformed:
        ++counters_.malformed_lines;
        break;
    }
  }
  return false;
}

bool WriteCandumpLine(std::ostream& os, const CandumpRecord& record) {
  std::array<char, kCandumpMaxLineBytes> buf{};
  const size_t n = FormatCandumpLine(record, buf);
  if (n == 0) return false;
  os.write(buf.data(), static_cast<std::streamsize>(n));
  return static_cast<bool>(os);
}

}  // namespace swlio::drivers
