#pragma once
/// @file
/// Writes ROS 1 bag v2.0 files for tests and fuzz seeds, laid out as rosbag's Bag::stopWriting
/// leaves them (research/bags.md §4): the version line; the bag header record padded to 4096
/// bytes; per chunk a Chunk record (connection records for connections first used in it, then
/// message records) followed by one IndexData record per connection in it; at index_pos every
/// Connection record, then one ChunkInfo record per chunk. `Finish(false)` leaves the bag as an
/// unclosed recording: index_pos 0 and no index section.

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swlio/drivers/bag/compress.h"
#include "swlio/drivers/bag/ros1_bag_records.h"

namespace swlio::test {

struct Ros1Connection {
  uint32_t id = 0;
  std::string topic;
  std::string type;
  std::string md5sum = "*";
  std::string definition;
};

class Ros1BagWriter {
 public:
  using Fields = std::vector<std::pair<std::string, std::vector<uint8_t>>>;

  /// `compression`: "none", "bz2" or "lz4"; a chunk closes past `chunk_bytes`.
  explicit Ros1BagWriter(std::string compression = "none", size_t chunk_bytes = 4096)
      : compression_(std::move(compression)), chunk_bytes_(chunk_bytes) {}

  void AddConnection(const Ros1Connection& c) { connections_[c.id] = c; }

  void Write(uint32_t conn, int64_t t_ns, const std::vector<uint8_t>& data) {
    const bool first_in_chunk = chunk_index_.empty();
    if (first_use_.insert(conn).second) ConnectionRecord(connections_[conn], &chunk_);
    chunk_index_[conn].emplace_back(t_ns, static_cast<uint32_t>(chunk_.size()));
    drivers::bag::ros1::AppendRecord({Op(0x02), U32("conn", conn), Time("time", t_ns)}, data,
                                     &chunk_);
    chunk_start_ = first_in_chunk ? t_ns : std::min(chunk_start_, t_ns);
    chunk_end_ = first_in_chunk ? t_ns : std::max(chunk_end_, t_ns);
    if (chunk_.size() >= chunk_bytes_) CloseChunk();
  }

  std::vector<uint8_t> Finish(bool write_index = true) {
    CloseChunk();
    uint64_t index_pos = 0;
    if (write_index) {
      index_pos = body_.size() + kHeaderEnd;
      for (const auto& [id, c] : connections_) ConnectionRecord(c, &body_);
      for (const auto& info : chunk_infos_) body_.insert(body_.end(), info.begin(), info.end());
    }
    std::vector<uint8_t> out(drivers::bag::ros1::kVersionLine.begin(),
                             drivers::bag::ros1::kVersionLine.end());
    const Fields header = {Op(0x03), U64("index_pos", index_pos),
                           U32("conn_count", static_cast<uint32_t>(connections_.size())),
                           U32("chunk_count", static_cast<uint32_t>(chunk_infos_.size()))};
    // 4 (header length) + header + 4 (data length) + spaces = 4096.
    size_t header_bytes = 0;
    for (const auto& [n, v] : header) header_bytes += 4 + n.size() + 1 + v.size();
    const std::vector<uint8_t> pad(4096 - 8 - header_bytes, ' ');
    drivers::bag::ros1::AppendRecord(header, pad, &out);
    out.insert(out.end(), body_.begin(), body_.end());
    return out;
  }

 private:
  static constexpr size_t kHeaderEnd = 13 + 4096;  // version line + bag header record

  static std::pair<std::string, std::vector<uint8_t>> Op(uint8_t op) { return {"op", {op}}; }
  static std::pair<std::string, std::vector<uint8_t>> U32(const std::string& n, uint32_t v) {
    std::vector<uint8_t> b(4);
    for (size_t i = 0; i < 4; ++i) b[i] = static_cast<uint8_t>(v >> (8 * i));
    return {n, b};
  }
  static std::pair<std::string, std::vector<uint8_t>> U64(const std::string& n, uint64_t v) {
    std::vector<uint8_t> b(8);
    for (size_t i = 0; i < 8; ++i) b[i] = static_cast<uint8_t>(v >> (8 * i));
    return {n, b};
  }
  static std::vector<uint8_t> TimeBytes(int64_t t_ns) {
    const auto sec = static_cast<uint32_t>(t_ns / 1'000'000'000);
    const auto nsec = static_cast<uint32_t>(t_ns % 1'000'000'000);
    std::vector<uint8_t> b(8);
    for (size_t i = 0; i < 4; ++i) {
      b[i] = static_cast<uint8_t>(sec >> (8 * i));
      b[4 + i] = static_cast<uint8_t>(nsec >> (8 * i));
    }
    return b;
  }
  static std::pair<std::string, std::vector<uint8_t>> Time(const std::string& n, int64_t t) {
    return {n, TimeBytes(t)};
  }
  static std::pair<std::string, std::vector<uint8_t>> Text(const std::string& n,
                                                           const std::string& v) {
    return {n, std::vector<uint8_t>(v.begin(), v.end())};
  }

  static void ConnectionRecord(const Ros1Connection& c, std::vector<uint8_t>* out) {
    std::vector<uint8_t> data;
    drivers::bag::ros1::AppendRecord(
        {Text("topic", c.topic), Text("type", c.type), Text("md5sum", c.md5sum),
         Text("message_definition", c.definition)},
        {}, &data);
    data.resize(data.size() - 4);                // a bare field block: no data length
    data.erase(data.begin(), data.begin() + 4);  // nor a header length
    drivers::bag::ros1::AppendRecord({Op(0x07), U32("conn", c.id), Text("topic", c.topic)}, data,
                                     out);
  }

  void CloseChunk() {
    if (chunk_.empty()) return;
    drivers::bag::Compression c = drivers::bag::Compression::kNone;
    drivers::bag::ParseCompression(compression_, &c);
    std::vector<uint8_t> stored;
    drivers::bag::Compress(c, chunk_, &stored);
    const uint64_t chunk_pos = body_.size() + kHeaderEnd;
    drivers::bag::ros1::AppendRecord({Op(0x05), Text("compression", compression_),
                                      U32("size", static_cast<uint32_t>(chunk_.size()))},
                                     stored, &body_);
    Fields info = {Op(0x06),
                   U32("ver", 1),
                   U64("chunk_pos", chunk_pos),
                   Time("start_time", chunk_start_),
                   Time("end_time", chunk_end_),
                   U32("count", static_cast<uint32_t>(chunk_index_.size()))};
    std::vector<uint8_t> counts;
    for (const auto& [conn, entries] : chunk_index_) {
      std::vector<uint8_t> index;
      for (const auto& [t, offset] : entries) {
        const auto tb = TimeBytes(t);
        index.insert(index.end(), tb.begin(), tb.end());
        for (int i = 0; i < 4; ++i) index.push_back(static_cast<uint8_t>(offset >> (8 * i)));
      }
      drivers::bag::ros1::AppendRecord({Op(0x04), U32("ver", 1), U32("conn", conn),
                                        U32("count", static_cast<uint32_t>(entries.size()))},
                                       index, &body_);
      for (const uint32_t v : {conn, static_cast<uint32_t>(entries.size())}) {
        for (int i = 0; i < 4; ++i) counts.push_back(static_cast<uint8_t>(v >> (8 * i)));
      }
    }
    std::vector<uint8_t> info_record;
    drivers::bag::ros1::AppendRecord(info, counts, &info_record);
    chunk_infos_.push_back(info_record);
    chunk_.clear();
    chunk_index_.clear();
  }

  std::string compression_;
  size_t chunk_bytes_;
  std::map<uint32_t, Ros1Connection> connections_;
  std::set<uint32_t> first_use_;
  std::vector<uint8_t> chunk_;
  std::map<uint32_t, std::vector<std::pair<int64_t, uint32_t>>> chunk_index_;
  int64_t chunk_start_ = 0;
  int64_t chunk_end_ = 0;
  std::vector<uint8_t> body_;
  std::vector<std::vector<uint8_t>> chunk_infos_;
};

}  // namespace swlio::test
