// Capture-file I/O through libpcap. Link-layer layouts: Ethernet II (IEEE 802.3, EtherType at
// byte 12, 802.1Q tag 0x8100/0x88A8 adds 4 bytes); Linux cooked v1 (16-byte header, protocol
// at byte 14) and v2 (20-byte header, protocol at byte 0) per tcpdump.org/linktypes; raw IP
// (no link header). IPv4 per RFC 791, UDP per RFC 768. All fields big-endian (network order).

#include "swlio/drivers/pcap_file.h"

#include <pcap/pcap.h>

#include <algorithm>

#include "swlio/drivers/bytes.h"

namespace swlio::drivers {
namespace {

constexpr uint16_t kEtherTypeIpv4 = 0x0800;
constexpr uint16_t kEtherTypeVlan = 0x8100;
constexpr uint16_t kEtherTypeQinQ = 0x88A8;
constexpr uint8_t kIpProtoUdp = 17;
constexpr size_t kEthernetHeader = 14;
constexpr size_t kIpv4MinHeader = 20;
constexpr size_t kUdpHeader = 8;
constexpr int kDltLinuxSll2 = 276;  // not defined by older libpcap headers
constexpr int kDltIpv4 = 228;

// RFC 1071 one's-complement sum over the IPv4 header.
uint16_t Ipv4HeaderChecksum(const uint8_t* header, size_t length) {
  uint32_t sum = 0;
  for (size_t i = 0; i + 1 < length; i += 2) sum += bytes::ReadU16Be(header + i);
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<uint16_t>(~sum);
}

}  // namespace

PcapReader::PcapReader(pcap* handle, PcapUdpFilter filter)
    : handle_(handle), filter_(std::move(filter)), link_type_(pcap_datalink(handle)) {}

PcapReader::~PcapReader() {
  if (handle_ != nullptr) pcap_close(handle_);
}

std::unique_ptr<PcapReader> PcapReader::Open(const std::string& path,
                                             PcapUdpFilter filter,
                                             std::string* error) {
  char errbuf[PCAP_ERRBUF_SIZE] = {};
  pcap* handle =
      pcap_open_offline_with_tstamp_precision(path.c_str(), PCAP_TSTAMP_PRECISION_NANO, errbuf);
  if (handle == nullptr) {
    if (error != nullptr) *error = "cannot open '" + path + "': " + errbuf;
    return nullptr;
  }
  return std::unique_ptr<PcapReader>(new PcapReader(handle, std::move(filter)));
}

std::unique_ptr<PcapReader> PcapReader::OpenStream(FILE* file,
                                                   PcapUdpFilter filter,
                                                   std::string* error) {
  if (file == nullptr) {
    if (error != nullptr) *error = "no stream";
    return nullptr;
  }
  char errbuf[PCAP_ERRBUF_SIZE] = {};
  pcap* handle = pcap_fopen_offline_with_tstamp_precision(file, PCAP_TSTAMP_PRECISION_NANO, errbuf);
  if (handle == nullptr) {
    fclose(file);  // libpcap leaves the stream open when it fails
    if (error != nullptr) *error = std::string("not a capture: ") + errbuf;
    return nullptr;
  }
  return std::unique_ptr<PcapReader>(new PcapReader(handle, std::move(filter)));
}

bool PcapReader::Next(UdpDatagram* out) {
  while (!finished_) {
    pcap_pkthdr* header = nullptr;
    const u_char* data = nullptr;
    const int rc = pcap_next_ex(handle_, &header, &data);
    if (rc == PCAP_ERROR_BREAK || rc == 0) {  // end of file (0 cannot happen offline)
      finished_ = true;
      break;
    }
    if (rc != 1) {
      error_ = pcap_geterr(handle_);
      if (error_.empty()) error_ = "read error";
      finished_ = true;
      break;
    }
    ++stats_.records;
    // With nanosecond precision requested, libpcap puts nanoseconds in tv_usec.
    out->t_ns = static_cast<int64_t>(header->ts.tv_sec) * 1'000'000'000 +
                static_cast<int64_t>(header->ts.tv_usec);
    const size_t caplen = std::min<size_t>(header->caplen, header->len);
    if (!ParseRecord(std::span<const uint8_t>(data, caplen), out)) continue;
    ++stats_.udp;
    if (!Accepts(*out)) {
      ++stats_.filtered_out;
      continue;
    }
    ++stats_.returned;
    return true;
  }
  return false;
}

bool PcapReader::Accepts(const UdpDatagram& d) const {
  auto has = [](const std::vector<uint16_t>& ports, uint16_t p) {
    return ports.empty() || std::find(ports.begin(), ports.end(), p) != ports.end();
  };
  return has(filter_.dst_ports, d.dst_port) && has(filter_.src_ports, d.src_port);
}

bool PcapReader::ParseRecord(std::span<const uint8_t> record, UdpDatagram* out) {
  size_t offset = 0;
  uint16_t ether_type = kEtherTypeIpv4;
  switch (link_type_) {
    case DLT_EN10MB: {
      if (record.size() < kEthernetHeader) {
        ++stats_.malformed;
        return false;
      }
      ether_type = bytes::ReadU16Be(record.data() + 12);
      offset = kEthernetHeader;
      for (int tags = 0; tags < 2 && (ether_type == kEtherTypeVlan || ether_type == kEtherTypeQinQ);
           ++tags) {
        if (record.size() < offset + 4) {
          ++stats_.malformed;
          return false;
        }
        ether_type = bytes::ReadU16Be(record.data() + offset + 2);
        offset += 4;
      }
      break;
    }
    case DLT_LINUX_SLL:
      if (record.size() < 16) {
        ++stats_.malformed;
        return false;
      }
      ether_type = bytes::ReadU16Be(record.data() + 14);
      offset = 16;
      break;
    case kDltLinuxSll2:
      if (record.size() < 20) {
        ++stats_.malformed;
        return false;
      }
      ether_type = bytes::ReadU16Be(record.data());
      offset = 20;
      break;
    case DLT_RAW:
    case kDltIpv4:
      break;  // the record starts with the IP header; the version nibble is checked below
    default:
      ++stats_.not_udp;
      return false;
  }
  if (ether_type != kEtherTypeIpv4) {
    ++stats_.not_udp;
    return false;
  }
  return ParseIpv4(record.subspan(offset), out);
}

bool PcapReader::ParseIpv4(std::span<const uint8_t> ip, UdpDatagram* out) {
  if (ip.empty()) {
    ++stats_.malformed;
    return false;
  }
  if ((ip[0] >> 4) != 4) {
    ++stats_.not_udp;  // IPv6 on a raw-IP link, or not IP at all
    return false;
  }
  const size_t ihl = static_cast<size_t>(ip[0] & 0x0F) * 4;
  if (ihl < kIpv4MinHeader || ip.size() < ihl) {
    ++stats_.malformed;
    return false;
  }
  const size_t total = bytes::ReadU16Be(ip.data() + 2);
  if (total < ihl || total > ip.size()) {
    ++stats_.malformed;  // truncated capture (snaplen) or bogus length
    return false;
  }
  if (ip[9] != kIpProtoUdp) {
    ++stats_.not_udp;
    return false;
  }
  const uint16_t frag = bytes::ReadU16Be(ip.data() + 6);
  if ((frag & 0x3FFF) != 0) {  // more-fragments flag or non-zero fragment offset
    ++stats_.fragments;
    return false;
  }
  const auto udp = ip.subspan(ihl, total - ihl);
  if (udp.size() < kUdpHeader) {
    ++stats_.malformed;
    return false;
  }
  const size_t udp_len = bytes::ReadU16Be(udp.data() + 4);
  if (udp_len < kUdpHeader || udp_len > udp.size()) {
    ++stats_.malformed;
    return false;
  }
  std::copy_n(ip.data() + 12, 4, out->src_ip.begin());
  std::copy_n(ip.data() + 16, 4, out->dst_ip.begin());
  out->src_port = bytes::ReadU16Be(udp.data());
  out->dst_port = bytes::ReadU16Be(udp.data() + 2);
  out->payload = udp.subspan(kUdpHeader, udp_len - kUdpHeader);
  return true;
}

PcapWriter::PcapWriter(pcap* dead, pcap_dumper* dumper, const PcapWriterOptions& options)
    : dead_(dead),
      dumper_(dumper),
      options_(options),
      frame_(kEthernetHeader + kIpv4MinHeader + kUdpHeader + kMaxPayload) {}

PcapWriter::~PcapWriter() {
  if (dumper_ != nullptr) pcap_dump_close(dumper_);
  if (dead_ != nullptr) pcap_close(dead_);
}

std::unique_ptr<PcapWriter> PcapWriter::Create(const std::string& path,
                                               const PcapWriterOptions& options,
                                               std::string* error) {
  const unsigned precision =
      options.nanosecond_timestamps ? PCAP_TSTAMP_PRECISION_NANO : PCAP_TSTAMP_PRECISION_MICRO;
  pcap* dead = pcap_open_dead_with_tstamp_precision(DLT_EN10MB, 65535, precision);
  if (dead == nullptr) {
    if (error != nullptr) *error = "pcap_open_dead failed";
    return nullptr;
  }
  pcap_dumper* dumper = pcap_dump_open(dead, path.c_str());
  if (dumper == nullptr) {
    if (error != nullptr) *error = "cannot create '" + path + "': " + pcap_geterr(dead);
    pcap_close(dead);
    return nullptr;
  }
  return std::unique_ptr<PcapWriter>(new PcapWriter(dead, dumper, options));
}

bool PcapWriter::Write(int64_t t_ns,
                       uint16_t src_port,
                       uint16_t dst_port,
                       std::span<const uint8_t> payload) {
  if (payload.size() > kMaxPayload || t_ns < 0) return false;
  uint8_t* f = frame_.data();
  std::copy(options_.dst_mac.begin(), options_.dst_mac.end(), f);
  std::copy(options_.src_mac.begin(), options_.src_mac.end(), f + 6);
  bytes::WriteU16Be(f + 12, kEtherTypeIpv4);
  uint8_t* ip = f + kEthernetHeader;
  const auto udp_len = static_cast<uint16_t>(kUdpHeader + payload.size());
  ip[0] = 0x45;  // IPv4, 20-byte header
  ip[1] = 0;
  bytes::WriteU16Be(ip + 2, static_cast<uint16_t>(kIpv4MinHeader + udp_len));
  bytes::WriteU16Be(ip + 4, ip_id_++);
  bytes::WriteU16Be(ip + 6, 0x4000);  // don't fragment
  ip[8] = 64;                         // TTL
  ip[9] = kIpProtoUdp;
  bytes::WriteU16Be(ip + 10, 0);
  std::copy(options_.src_ip.begin(), options_.src_ip.end(), ip + 12);
  std::copy(options_.dst_ip.begin(), options_.dst_ip.end(), ip + 16);
  bytes::WriteU16Be(ip + 10, Ipv4HeaderChecksum(ip, kIpv4MinHeader));
  uint8_t* udp = ip + kIpv4MinHeader;
  bytes::WriteU16Be(udp, src_port);
  bytes::WriteU16Be(udp + 2, dst_port);
  bytes::WriteU16Be(udp + 4, udp_len);
  bytes::WriteU16Be(udp + 6, 0);  // checksum optional over IPv4 (RFC 768)
  std::copy(payload.begin(), payload.end(), udp + kUdpHeader);

  pcap_pkthdr header{};
  const int64_t sub_divisor = options_.nanosecond_timestamps ? 1 : 1000;
  header.ts.tv_sec = static_cast<time_t>(t_ns / 1'000'000'000);
  header.ts.tv_usec = static_cast<suseconds_t>((t_ns % 1'000'000'000) / sub_divisor);
  header.caplen = static_cast<bpf_u_int32>(kEthernetHeader + kIpv4MinHeader + udp_len);
  header.len = header.caplen;
  pcap_dump(reinterpret_cast<u_char*>(dumper_), &header, f);
  return true;
}

bool PcapWriter::Flush() { return pcap_dump_flush(dumper_) == 0; }

}  // namespace swlio::drivers
