#pragma once
/// @file
/// Xsens device-configuration messages and their replies (MT0101P "Message listing"):
///   GoToConfig 0x30 → GoToConfigAck 0x31         GoToMeasurement 0x10 → Ack 0x11
///   ReqDID 0x00 → DeviceID 0x01 (4-byte id; 8 bytes on newer devices)
///   SetOutputConfiguration 0xC0 (n × {XDI u16, rate u16}, rate 0xFFFF = every sample)
///     → OutputConfiguration 0xC1 (the configuration the device applied, same layout)
///   SetBaudrate 0x18 (1-byte baud code) → SetBaudrateAck 0x19
///   Error 0x42 (1-byte error code; the MTi sends it instead of the acknowledgement).
/// Baud codes from Xsens' XsBaudCode list (xstypes/xsbaudcode.h): 9600 0x09, 19200 0x07,
/// 38400 0x05, 57600 0x04, 115200 0x02, 230400 0x01, 460800 0x00, 921600 0x0A (legacy 0x80,
/// accepted when parsing), 2000000 0x0C.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace swlio::drivers::xsens {

/// One entry of SetOutputConfiguration / OutputConfiguration.
struct XsensOutputItem {
  uint16_t xdi = 0;
  uint16_t rate_hz = 0;  ///< 0xFFFF: every sample ("Max")
  bool operator==(const XsensOutputItem&) const = default;
};
inline constexpr uint16_t kXsensRateMax = 0xFFFF;

/// Xsens baud code for a line rate; nullopt for rates the MTi does not know.
std::optional<uint8_t> XsensBaudCode(int64_t baud);
/// Line rate for a baud code (both 921600 codes accepted); nullopt when unknown.
std::optional<int64_t> XsensBaudFromCode(uint8_t code);

/// Frame builders: each writes a complete Xbus frame, returns its size or 0 if `out` is small.
size_t BuildGoToConfig(std::span<uint8_t> out);
size_t BuildGoToMeasurement(std::span<uint8_t> out);
size_t BuildReqDid(std::span<uint8_t> out);
size_t BuildSetOutputConfiguration(std::span<const XsensOutputItem> items, std::span<uint8_t> out);
/// 0 also when `baud` has no Xsens code.
size_t BuildSetBaudrate(int64_t baud, std::span<uint8_t> out);

/// Serializes output items as the SetOutputConfiguration payload (4 bytes each); returns the
/// size or 0 when `out` is too small.
size_t EncodeOutputConfiguration(std::span<const XsensOutputItem> items, std::span<uint8_t> out);
/// Parses an (Set)OutputConfiguration payload into `items`; returns the count, or nullopt when
/// the size is not a multiple of 4 or more entries than `items` holds.
std::optional<size_t> ParseOutputConfiguration(std::span<const uint8_t> payload,
                                               std::span<XsensOutputItem> items);
/// DeviceID payload (4 or 8 bytes, big-endian) → id.
std::optional<uint64_t> ParseDeviceId(std::span<const uint8_t> payload);
/// Error payload → error code (first byte).
std::optional<uint8_t> ParseErrorCode(std::span<const uint8_t> payload);

}  // namespace swlio::drivers::xsens
