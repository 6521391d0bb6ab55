// RS-LiDAR-16 header time (User Manual Appendix B.10 "UTC_TIME", 10 bytes: year 2000–2255,
// month, day, hour, min, s, ms, µs), both layouts in rs_driver basic_attr.hpp: RSTimestampYMD (6
// bytes year−2000/month/day/hour/minute/second, then ms and µs as big-endian u16) and
// RSTimestampUTC (48-bit big-endian seconds since 1970, then 32-bit big-endian µs). Calendar
// conversion by the days-from-civil algorithm (H. Hinnant, "chrono-compatible low-level date
// algorithms").

#include <cstdint>

#include "swlio/core/time.h"
#include "swlio/drivers/bytes.h"
#include "swlio/drivers/rs16_protocol.h"

namespace swlio::drivers::rs16 {
namespace {

int64_t DaysFromCivil(int64_t y, int64_t m, int64_t d) {
  y -= m <= 2 ? 1 : 0;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const int64_t yoe = y - era * 400;
  const int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

void CivilFromDays(int64_t z, int64_t* y, int64_t* m, int64_t* d) {
  z += 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const int64_t doe = z - era * 146097;
  const int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const int64_t mp = (5 * doy + 2) / 153;
  *d = doy - (153 * mp + 2) / 5 + 1;
  *m = mp < 10 ? mp + 3 : mp - 9;
  *y = yoe + era * 400 + (*m <= 2 ? 1 : 0);
}

constexpr int64_t kSecPerDay = 86'400;
constexpr uint64_t kMaxUtcSec = (uint64_t{1} << 33);  // year 2242: beyond that the ns overflow

bool ParseYmd(const uint8_t* p, int64_t* t_ns) {
  // User Manual B.10: set_month[3:0], set_day[4:0], set_hour[4:0]; the upper bits are reserved.
  const int64_t month = p[1] & 0x0F, day = p[2] & 0x1F, hour = p[3] & 0x1F;
  const int64_t minute = p[4], second = p[5];
  const int64_t ms = bytes::ReadU16Be(p + 6), us = bytes::ReadU16Be(p + 8);
  if (month < 1 || month > 12 || day < 1 || day > 31 || hour > 23 || minute > 59 || second > 60 ||
      ms > 999 || us > 999) {
    return false;
  }
  const int64_t days = DaysFromCivil(2000 + p[0], month, day);
  const int64_t sec = days * kSecPerDay + hour * 3600 + minute * 60 + second;
  *t_ns = sec * kNsPerSec + ms * kNsPerMs + us * kNsPerUs;
  return true;
}

bool ParseUtc(const uint8_t* p, int64_t* t_ns) {
  const uint64_t sec = bytes::ReadUBe(p, 6);
  const uint32_t us = bytes::ReadU32Be(p + 6);
  if (sec >= kMaxUtcSec || us >= 1'000'000) return false;
  *t_ns = static_cast<int64_t>(sec) * kNsPerSec + static_cast<int64_t>(us) * kNsPerUs;
  return true;
}

}  // namespace

bool ParseTime(const uint8_t* p, TimeFormat format, int64_t* t_ns) {
  if (format == TimeFormat::kAuto) {
    format = (p[0] == 0 && p[1] == 0) ? TimeFormat::kUtc : TimeFormat::kYmd;
  }
  return format == TimeFormat::kUtc ? ParseUtc(p, t_ns) : ParseYmd(p, t_ns);
}

bool WriteTime(uint8_t* p, TimeFormat format, int64_t t_ns) {
  if (t_ns < 0) return false;
  const int64_t sec = t_ns / kNsPerSec;
  const int64_t us = (t_ns % kNsPerSec) / kNsPerUs;
  if (format == TimeFormat::kUtc) {
    if (static_cast<uint64_t>(sec) >= kMaxUtcSec) return false;
    bytes::WriteUBe(p, static_cast<uint64_t>(sec), 6);
    bytes::WriteU32Be(p + 6, static_cast<uint32_t>(us));
    return true;
  }
  int64_t y = 0, m = 0, d = 0;
  CivilFromDays(sec / kSecPerDay, &y, &m, &d);
  if (y < 2000 || y > 2255) return false;
  const int64_t sod = sec % kSecPerDay;
  p[0] = static_cast<uint8_t>(y - 2000);
  p[1] = static_cast<uint8_t>(m);
  p[2] = static_cast<uint8_t>(d);
  p[3] = static_cast<uint8_t>(sod / 3600);
  p[4] = static_cast<uint8_t>((sod / 60) % 60);
  p[5] = static_cast<uint8_t>(sod % 60);
  bytes::WriteU16Be(p + 6, static_cast<uint16_t>(us / 1000));
  bytes::WriteU16Be(p + 8, static_cast<uint16_t>(us % 1000));
  return true;
}

}  // namespace swlio::drivers::rs16
