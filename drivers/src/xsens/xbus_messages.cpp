// Xsens configuration messages (MT0101P "Message listing"; baud codes from Xsens'
// XsBaudCode list). See xbus_messages.h for the summary.

#include "swlio/drivers/xsens/xbus_messages.h"

#include <array>

#include "swlio/drivers/bytes.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::drivers::xsens {
namespace {

struct BaudEntry {
  int64_t baud;
  uint8_t code;
};
constexpr std::array<BaudEntry, 9> kBauds = {{{9600, 0x09},
                                              {19200, 0x07},
                                              {38400, 0x05},
                                              {57600, 0x04},
                                              {115200, 0x02},
                                              {230400, 0x01},
                                              {460800, 0x00},
                                              {921600, 0x0A},
                                              {2000000, 0x0C}}};
constexpr uint8_t kBaud921600Legacy = 0x80;

}  // namespace

std::optional<uint8_t> XsensBaudCode(int64_t baud) {
  for (const BaudEntry& e : kBauds) {
    if (e.baud == baud) return e.code;
  }
  return std::nullopt;
}

std::optional<int64_t> XsensBaudFromCode(uint8_t code) {
  if (code == kBaud921600Legacy) return 921600;
  for (const BaudEntry& e : kBauds) {
    if (e.code == code) return e.baud;
  }
  return std::nullopt;
}

size_t BuildGoToConfig(std::span<uint8_t> out) {
  return EncodeXbusFrame(mid::kGoToConfig, {}, out);
}

size_t BuildGoToMeasurement(std::span<uint8_t> out) {
  return EncodeXbusFrame(mid::kGoToMeasurement, {}, out);
}

size_t BuildReqDid(std::span<uint8_t> out) { return EncodeXbusFrame(mid::kReqDid, {}, out); }

size_t EncodeOutputConfiguration(std::span<const XsensOutputItem> items, std::span<uint8_t> out) {
  if (out.size() < 4 * items.size()) return 0;
  for (size_t i = 0; i < items.size(); ++i) {
    bytes::WriteU16Be(out.data() + 4 * i, items[i].xdi);
    bytes::WriteU16Be(out.data() + 4 * i + 2, items[i].rate_hz);
  }
  return 4 * items.size();
}

size_t BuildSetOutputConfiguration(std::span<const XsensOutputItem> items, std::span<uint8_t> out) {
  std::array<uint8_t, kXbusMaxPayload> payload;
  if (4 * items.size() > payload.size()) return 0;
  const size_t n = EncodeOutputConfiguration(items, payload);
  return EncodeXbusFrame(mid::kSetOutputConfiguration, {payload.data(), n}, out);
}

size_t BuildSetBaudrate(int64_t baud, std::span<uint8_t> out) {
  const std::optional<uint8_t> code = XsensBaudCode(baud);
  if (!code) return 0;
  const uint8_t payload[1] = {*code};
  return EncodeXbusFrame(mid::kSetBaudrate, payload, out);
}

std::optional<size_t> ParseOutputConfiguration(std::span<const uint8_t> payload,
                                               std::span<XsensOutputItem> items) {
  if (payload.size() % 4 != 0 || payload.size() / 4 > items.size()) return std::nullopt;
  const size_t n = payload.size() / 4;
  for (size_t i = 0; i < n; ++i) {
    items[i].xdi = bytes::ReadU16Be(payload.data() + 4 * i);
    items[i].rate_hz = bytes::ReadU16Be(payload.data() + 4 * i + 2);
  }
  return n;
}

std::optional<uint64_t> ParseDeviceId(std::span<const uint8_t> payload) {
  if (payload.size() == 4) return bytes::ReadU32Be(payload.data());
  if (payload.size() == 8) return bytes::ReadU64Be(payload.data());
  return std::nullopt;
}

std::optional<uint8_t> ParseErrorCode(std::span<const uint8_t> payload) {
  if (payload.empty()) return std::nullopt;
  return payload[0];
}

}  // namespace swlio::drivers::xsens
