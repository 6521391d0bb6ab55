// ROS 1 bag v2.0 reader: one linear pass over the records (ros1_bag_reader.h).

#include "swlio/drivers/bag/ros1_bag_reader.h"

#include <algorithm>

namespace swlio::drivers::bag {
namespace {

constexpr std::string_view kVersionPrefix = "#ROSBAG V";

std::string_view AsText(std::span<const uint8_t> b) {
  return {reinterpret_cast<const char*>(b.data()), b.size()};
}

}  // namespace

std::unique_ptr<Ros1BagReader> Ros1BagReader::Open(const std::string& path,
                                                   const BagReadLimits& limits,
                                                   std::string* error) {
  auto mapped = MappedFile::Open(path, error);
  if (!mapped) return nullptr;
  std::unique_ptr<Ros1BagReader> reader(new Ros1BagReader(path, limits));
  reader->file_ = mapped->bytes();
  reader->mapped_ = std::move(mapped);
  if (!reader->Index(error)) return nullptr;
  return reader;
}

std::unique_ptr<Ros1BagReader> Ros1BagReader::OpenBytes(std::span<const uint8_t> bytes,
                                                        const std::string& name,
                                                        const BagReadLimits& limits,
                                                        std::string* error) {
  std::unique_ptr<Ros1BagReader> reader(new Ros1BagReader(name, limits));
  reader->owned_.assign(bytes.begin(), bytes.end());
  reader->file_ = reader->owned_;
  if (!reader->Index(error)) return nullptr;
  return reader;
}

std::string Ros1BagReader::At(size_t offset) const {
  return path_ + ": byte " + std::to_string(offset) + ": ";
}

bool Ros1BagReader::Index(std::string* error) {
  const std::string_view start = AsText(file_.first(std::min(file_.size(), size_t{16})));
  if (start.substr(0, ros1::kVersionLine.size()) != ros1::kVersionLine) {
    if (start.substr(0, kVersionPrefix.size()) == kVersionPrefix) {
      const std::string_view version = start.substr(kVersionPrefix.size(), 3);
      *error = path_ + ": ROS bag version " + std::string(version) + " is not supported (2.0 is)";
    } else {
      *error = path_ + ": not a ROS 1 bag (no \"#ROSBAG V2.0\" line)";
    }
    return false;
  }
  size_t pos = ros1::kVersionLine.size();
  while (pos < file_.size()) {
    ros1::Record r;
    ros1::RecordHeader h;
    if (!ros1::ReadRecord(file_.subspan(pos), &r)) {
      warnings_.Add(At(pos) + "record runs past the end of the file; read up to here (truncated?)");
      break;
    }
    if (!h.Parse(r.header)) {
      warnings_.Add(At(pos) + "unreadable record header; record skipped");
      ++stats_.records_skipped;
    } else {
      TopRecord(h, r, pos);
    }
    pos += r.size;
  }
  CheckCompleteness();
  BuildTopics();
  return true;
}

void Ros1BagReader::CheckCompleteness() {
  if (!have_bag_header_) {
    warnings_.Add(path_ + ": no bag header record (an incomplete file?)");
  } else if (index_pos_ > file_.size()) {
    warnings_.Add(path_ + ": the bag header places the index at byte " +
                  std::to_string(index_pos_) + ", beyond the file's " +
                  std::to_string(file_.size()) + " bytes (truncated?)");
  } else if (index_pos_ != 0 && chunks_seen_ < chunk_count_) {
    warnings_.Add(path_ + ": the bag header states " + std::to_string(chunk_count_) + " chunks; " +
                  std::to_string(chunks_seen_) + " were found");
  }
}

void Ros1BagReader::TopRecord(const ros1::RecordHeader& h, const ros1::Record& r, size_t offset) {
  uint8_t op = 0;
  if (!h.U8("op", &op)) {
    warnings_.Add(At(offset) + "record without an op field; skipped");
    ++stats_.records_skipped;
    return;
  }
  switch (op) {
    case ros1::kBagHeader:
      have_bag_header_ = true;
      h.U64("index_pos", &index_pos_);
      h.U32("chunk_count", &chunk_count_);
      return;
    case ros1::kChunk:
      ReadChunk(h, r.data, offset);
      return;
    case ros1::kConnection:
      AddConnection(h, r.data, offset);
      return;
    case ros1::kMessageData:
      AddMessage(h, r.data, IndexedMessages::kInFile,
                 static_cast<uint64_t>(r.data.data() - file_.data()), offset);
      return;
    case ros1::kIndexData:
    case ros1::kChunkInfo:
      return;  // the linear pass needs no index
    default:
      ++stats_.records_skipped;
  }
}

void Ros1BagReader::ReadChunk(const ros1::RecordHeader& h,
                              std::span<const uint8_t> data,
                              size_t offset) {
  ++chunks_seen_;
  std::string name;
  uint32_t size = 0;
  Compression compression = Compression::kNone;
  std::string why;
  if (!h.Text("compression", &name) || !h.U32("size", &size)) {
    why = "no compression or size field";
  } else if (!ParseCompression(name, &compression) || compression == Compression::kZstd) {
    why = "unknown compression '" + name + "'";
  } else if (size > limits_.max_chunk_bytes) {
    why = std::to_string(size) + " uncompressed bytes, over the limit";
  } else if (compression != Compression::kNone) {
    Decompress(compression, data, size, &scratch_, &why);
  } else if (data.size() != size) {
    why = std::to_string(data.size()) + " bytes, the chunk states " + std::to_string(size);
  }
  if (!why.empty()) {
    warnings_.Add(At(offset) + "chunk skipped: " + why);
    ++stats_.chunks_skipped;
    return;
  }
  ++chunk_compressions_[name.empty() ? "none" : name];
  const uint32_t n = index_.AddChunk(
      {static_cast<uint64_t>(data.data() - file_.data()), data.size(), size, compression});
  ReadChunkRecords(compression == Compression::kNone ? data : scratch_, n, offset);
}

void Ros1BagReader::ReadChunkRecords(std::span<const uint8_t> records,
                                     uint32_t chunk,
                                     size_t offset) {
  size_t pos = 0;
  while (pos < records.size()) {
    ros1::Record r;
    ros1::RecordHeader h;
    uint8_t op = 0;
    if (!ros1::ReadRecord(records.subspan(pos), &r)) {
      warnings_.Add(At(offset) + "chunk record at +" + std::to_string(pos) +
                    " runs past the chunk's end; the rest of the chunk skipped");
      return;
    }
    const bool parsed = h.Parse(r.header) && h.U8("op", &op);
    if (parsed && op == ros1::kConnection) {
      AddConnection(h, r.data, offset);
    } else if (parsed && op == ros1::kMessageData) {
      AddMessage(h, r.data, chunk, static_cast<uint64_t>(r.data.data() - records.data()), offset);
    } else {
      ++stats_.records_skipped;  // unreadable, or an op that has no place in a chunk
    }
    pos += r.size;
  }
}

void Ros1BagReader::AddConnection(const ros1::RecordHeader& h,
                                  std::span<const uint8_t> data,
                                  size_t offset) {
  uint32_t id = 0;
  ros1::RecordHeader fields;
  Connection c;
  if (!h.U32("conn", &id) || !h.Text("topic", &c.topic) || !fields.Parse(data) ||
      !fields.Text("type", &c.type)) {
    warnings_.Add(At(offset) + "unreadable connection record; ignored");
    return;
  }
  fields.Text("md5sum", &c.md5sum);
  fields.Text("message_definition", &c.definition);
  const auto [it, added] = connections_.emplace(id, c);
  if (!added && !(it->second == c)) {
    warnings_.Add(At(offset) + "connection " + std::to_string(id) +
                  " differs from its first definition; the first is kept");
  }
}

void Ros1BagReader::AddMessage(const ros1::RecordHeader& h,
                               std::span<const uint8_t> data,
                               uint32_t chunk,
                               uint64_t data_offset,
                               size_t at) {
  uint32_t conn = 0;
  int64_t t_ns = 0;
  std::string why;
  if (!h.U32("conn", &conn)) {
    why = "no conn field";
  } else if (!h.Time("time", &t_ns)) {
    why = "no valid time field";
  } else if (data.size() > limits_.max_message_bytes) {
    why = std::to_string(data.size()) + " bytes, over the limit";
  }
  if (!why.empty()) {
    warnings_.Add(At(at) + "message skipped: " + why);
    ++stats_.messages_skipped;
    return;
  }
  index_.Add(t_ns, conn, chunk, data_offset, data.size());
}

void Ros1BagReader::BuildTopics() {
  std::unordered_map<uint32_t, uint32_t> topic_of_connection;
  for (const auto& [id, connection] : connections_) {
    const Connection& c = connection;  // a lambda cannot capture a structured binding (C++17)
    const auto same = [&c](const BagTopic& t) { return t.name == c.topic && t.type == c.type; };
    auto it = std::find_if(topics_.begin(), topics_.end(), same);
    if (it == topics_.end()) {
      BagTopic t;
      t.name = c.topic;
      t.type = c.type;
      t.encoding_name = "ros1";
      t.encoding = MessageEncoding::kRos1;
      t.definition = c.definition;
      t.definition_encoding = "ros1msg";
      t.md5sum = c.md5sum;
      topics_.push_back(std::move(t));
      it = topics_.end() - 1;
    }
    topic_of_connection[id] = static_cast<uint32_t>(it - topics_.begin());
  }
  index_.Finish(topic_of_connection, &topics_, path_, &warnings_, &stats_);
}

std::string Ros1BagReader::StorageDescription() const {
  std::string chunks;
  for (const auto& [name, n] : chunk_compressions_) {
    chunks += (chunks.empty() ? "" : ", ") + std::to_string(n) + " " + name;
  }
  return "ROS 1 bag v2.0 (" + (chunks.empty() ? std::string("no") : chunks) + " chunks" +
         (index_pos_ != 0 ? "" : ", not closed: no index") + ")";
}

bool Ros1BagReader::Next(BagMessage* message) {
  if (!error_.empty()) return false;
  std::string error;
  if (!index_.Next(file_, message, &error)) {
    if (!error.empty()) error_ = path_ + ": " + error;
    return false;
  }
  ++stats_.messages_returned;
  stats_.bytes_returned += message->data.size();
  return true;
}

}  // namespace swlio::drivers::bag
