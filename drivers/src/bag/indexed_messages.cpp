// The message index of the chunked bag containers (indexed_messages.h).

#include "swlio/drivers/bag/indexed_messages.h"

#include <algorithm>

namespace swlio::drivers::bag {
namespace {

constexpr size_t kCachedChunks = 4;

}  // namespace

uint32_t IndexedMessages::AddChunk(const ChunkLocation& chunk) {
  chunks_.push_back(chunk);
  return static_cast<uint32_t>(chunks_.size() - 1);
}

void IndexedMessages::Add(
    int64_t log_time_ns, uint32_t channel, uint32_t chunk, uint64_t offset, uint64_t size) {
  entries_.push_back({log_time_ns, offset, static_cast<uint32_t>(size), chunk, channel});
}

void IndexedMessages::Finish(const std::unordered_map<uint32_t, uint32_t>& topic_of_channel,
                             std::vector<BagTopic>* topics,
                             const std::string& path,
                             WarningLog* warnings,
                             BagReadStats* stats) {
  constexpr uint32_t kOrphan = 0xFFFFFFFFu;
  std::unordered_map<uint32_t, uint64_t> orphans;  // channel → messages
  for (Entry& e : entries_) {
    const auto it = topic_of_channel.find(e.channel);
    if (it == topic_of_channel.end()) ++orphans[e.channel];
    e.channel = it == topic_of_channel.end() ? kOrphan : it->second;
  }
  std::erase_if(entries_, [](const Entry& e) { return e.channel == kOrphan; });
  for (const auto& [channel, n] : orphans) {
    warnings->Add(path + ": " + std::to_string(n) + " messages of channel/connection " +
                  std::to_string(channel) + ", which the file never defines; skipped");
    stats->messages_skipped += n;
  }
  std::stable_sort(entries_.begin(), entries_.end(),
                   [](const Entry& a, const Entry& b) { return a.log_time_ns < b.log_time_ns; });
  for (const Entry& e : entries_) {
    BagTopic& t = (*topics)[e.channel];
    if (t.message_count == 0) t.first_log_time_ns = e.log_time_ns;
    t.last_log_time_ns = e.log_time_ns;
    ++t.message_count;
  }
  next_index_.assign(topics->size(), 0);
}

bool IndexedMessages::ChunkBytes(std::span<const uint8_t> file,
                                 uint32_t chunk,
                                 std::span<const uint8_t>* out,
                                 std::string* error) {
  const ChunkLocation& c = chunks_[chunk];
  const std::span<const uint8_t> stored = file.subspan(c.file_offset, c.size);
  if (c.compression == Compression::kNone) {
    *out = stored;
    return true;
  }
  ++uses_;
  for (CachedChunk& cached : cache_) {
    if (cached.chunk != chunk) continue;
    cached.last_use = uses_;
    *out = cached.bytes;
    return true;
  }
  if (cache_.size() < kCachedChunks) cache_.emplace_back();
  CachedChunk& slot =
      *std::min_element(cache_.begin(), cache_.end(),
                        [](const auto& a, const auto& b) { return a.last_use < b.last_use; });
  slot.chunk = kInFile;
  if (!Decompress(c.compression, stored, c.uncompressed_size, &slot.bytes, error)) return false;
  slot.chunk = chunk;
  slot.last_use = uses_;
  *out = slot.bytes;
  return true;
}

bool IndexedMessages::Next(std::span<const uint8_t> file, BagMessage* message, std::string* error) {
  if (next_ >= entries_.size()) return false;
  const Entry& e = entries_[next_++];
  std::span<const uint8_t> source = file;
  if (e.chunk != kInFile && !ChunkBytes(file, e.chunk, &source, error)) return false;
  message->topic = e.channel;
  message->index = next_index_[e.channel]++;
  message->log_time_ns = e.log_time_ns;
  message->data = source.subspan(e.offset, e.size);
  return true;
}

}  // namespace swlio::drivers::bag
