#pragma once
/// @file
/// UDP datagrams from and to capture files, through libpcap.
///
/// Reading: libpcap's offline API opens classic pcap (µs or ns) and pcapng alike. Each record is
/// unwrapped by link type: Ethernet (DLT_EN10MB, with up to two 802.1Q tags), Linux cooked
/// capture v1/v2 (DLT_LINUX_SLL, DLT_LINUX_SLL2) and raw IP (DLT_RAW, DLT_IPV4); then IPv4
/// (RFC 791: IHL, total length, fragment fields) and UDP (RFC 768: 8-byte header, length field).
/// Anything that is not a complete, unfragmented IPv4/UDP datagram is counted and skipped;
/// a truncated or garbled file ends the read with `error()` set, never with a crash.
///
/// Writing: classic pcap (linktype 1, Ethernet) with each payload wrapped in Ethernet/IPv4/UDP,
/// 127.0.0.1 → 127.0.0.1 by default, so recorder and simulator output opens in any pcap tool.

#include <array>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

struct pcap;
struct pcap_dumper;

namespace swlio::drivers {

/// One UDP datagram read from a capture.
struct UdpDatagram {
  int64_t t_ns = 0;  ///< record time of the capture (ns since the Unix epoch, as recorded)
  std::array<uint8_t, 4> src_ip{};
  std::array<uint8_t, 4> dst_ip{};
  uint16_t src_port = 0;
  uint16_t dst_port = 0;
  std::span<const uint8_t> payload;  ///< valid until the next call to PcapReader::Next()
};

/// Which datagrams PcapReader::Next() returns. Empty lists accept any port.
struct PcapUdpFilter {
  std::vector<uint16_t> dst_ports;
  std::vector<uint16_t> src_ports;
};

/// What a PcapReader has seen so far.
struct PcapReadStats {
  uint64_t records = 0;       ///< capture records read
  uint64_t udp = 0;           ///< records holding a complete IPv4/UDP datagram
  uint64_t returned = 0;      ///< datagrams that passed the filter and were returned
  uint64_t filtered_out = 0;  ///< complete UDP datagrams rejected by the port filter
  uint64_t not_udp = 0;       ///< other protocols (ARP, IPv6, TCP, …)
  uint64_t fragments = 0;     ///< IPv4 fragments (not reassembled)
  uint64_t malformed = 0;     ///< records too short for the headers they claim
};

class PcapReader {
 public:
  /// Opens a classic pcap or pcapng file. Returns nullptr and sets `error` on failure.
  static std::unique_ptr<PcapReader> Open(const std::string& path,
                                          PcapUdpFilter filter,
                                          std::string* error);
  /// Same, from an open stdio stream (e.g. fmemopen); takes ownership of `file` in all cases.
  static std::unique_ptr<PcapReader> OpenStream(FILE* file,
                                                PcapUdpFilter filter,
                                                std::string* error);
  ~PcapReader();
  PcapReader(const PcapReader&) = delete;
  PcapReader& operator=(const PcapReader&) = delete;

  /// Reads up to the next datagram that passes the filter. Returns false at the end of the
  /// file or on a read error (then `error()` is non-empty; the file was truncated or garbled).
  bool Next(UdpDatagram* out);

  const PcapReadStats& stats() const { return stats_; }
  const std::string& error() const { return error_; }
  int link_type() const { return link_type_; }

 private:
  PcapReader(pcap* handle, PcapUdpFilter filter);
  /// Unwraps one record; true when it held a UDP datagram (any port).
  bool ParseRecord(std::span<const uint8_t> record, UdpDatagram* out);
  bool ParseIpv4(std::span<const uint8_t> ip, UdpDatagram* out);
  bool Accepts(const UdpDatagram& d) const;

  pcap* handle_ = nullptr;
  PcapUdpFilter filter_;
  PcapReadStats stats_;
  std::string error_;
  int link_type_ = 0;
  bool finished_ = false;
};

/// Addresses used to wrap payloads in PcapWriter.
struct PcapWriterOptions {
  std::array<uint8_t, 4> src_ip = {127, 0, 0, 1};
  std::array<uint8_t, 4> dst_ip = {127, 0, 0, 1};
  std::array<uint8_t, 6> src_mac = {0x02, 0, 0, 0, 0, 0x01};  ///< locally administered
  std::array<uint8_t, 6> dst_mac = {0x02, 0, 0, 0, 0, 0x02};
  /// true: nanosecond pcap (magic a1b23c4d); false: the older microsecond variant.
  bool nanosecond_timestamps = true;
};

class PcapWriter {
 public:
  static constexpr size_t kMaxPayload = 65507;  ///< IPv4 UDP payload limit

  /// Creates (truncates) `path`. Returns nullptr and sets `error` on failure.
  static std::unique_ptr<PcapWriter> Create(const std::string& path,
                                            const PcapWriterOptions& options,
                                            std::string* error);
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;

  /// Appends one datagram with record time `t_ns` (ns since the Unix epoch, ≥ 0).
  /// Returns false when the payload is too large or the time negative.
  bool Write(int64_t t_ns, uint16_t src_port, uint16_t dst_port, std::span<const uint8_t> payload);
  /// Flushes buffered records to the file; false on an I/O error.
  bool Flush();

 private:
  PcapWriter(pcap* dead, pcap_dumper* dumper, const PcapWriterOptions& options);

  pcap* dead_ = nullptr;
  pcap_dumper* dumper_ = nullptr;
  PcapWriterOptions options_;
  uint16_t ip_id_ = 0;
  std::vector<uint8_t> frame_;  ///< preallocated Ethernet frame buffer
};

}  // namespace swlio::drivers
