// rosbag2 SQLite3 storage reader; the layout and its versions are in rosbag2_sqlite_reader.h.

#include "swlio/drivers/bag/rosbag2_sqlite_reader.h"

#include "swlio/drivers/bag/decompress.h"

#include <sqlite3.h>
#include <zstd.h>

#include <cctype>
#include <cstring>
#include <set>
#include <utility>

namespace swlio::drivers::bag {
namespace {

/// One prepared statement, finalized on scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql) {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK) stmt_ = nullptr;
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  sqlite3_stmt* get() const { return stmt_; }
  bool ok() const { return stmt_ != nullptr; }
  bool Row() { return sqlite3_step(stmt_) == SQLITE_ROW; }
  std::string Text(int column) const {
    const unsigned char* t = sqlite3_column_text(stmt_, column);
    const int n = sqlite3_column_bytes(stmt_, column);
    return t == nullptr ? std::string()
                        : std::string(reinterpret_cast<const char*>(t), static_cast<size_t>(n));
  }
  int64_t Int(int column) const { return sqlite3_column_int64(stmt_, column); }

 private:
  sqlite3_stmt* stmt_ = nullptr;
};

/// `path` as an SQLite URI filename (https://www.sqlite.org/uri.html: "%HH" escapes for
/// characters other than unreserved ones and '/'), read-only and immutable.
std::string ImmutableUri(const std::string& path) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string uri = "file:";
  for (const char c : path) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) != 0 || std::strchr("/-._~", c) != nullptr) {
      uri += c;
    } else {
      uri += '%';
      uri += kHex[u >> 4];
      uri += kHex[u & 15];
    }
  }
  return uri + "?mode=ro&immutable=1";
}

/// Hardening for a file that may be crafted (https://www.sqlite.org/security.html).
void Harden(sqlite3* db) {
  sqlite3_db_config(db, SQLITE_DBCONFIG_DEFENSIVE, 1, nullptr);
  sqlite3_db_config(db, SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, nullptr);
  sqlite3_exec(db, "PRAGMA cell_size_check=ON", nullptr, nullptr, nullptr);
}

std::set<std::string> Tables(sqlite3* db) {
  std::set<std::string> tables;
  Statement s(db, "SELECT name FROM sqlite_master WHERE type='table'");
  while (s.ok() && s.Row()) tables.insert(s.Text(0));
  return tables;
}

bool HasColumn(sqlite3* db, const char* table, const char* column) {
  Statement s(db, (std::string("PRAGMA table_info(") + table + ")").c_str());
  while (s.ok() && s.Row()) {
    if (s.Text(1) == column) return true;
  }
  return false;
}

}  // namespace

Rosbag2SqliteReader::Rosbag2SqliteReader(sqlite3* db,
                                         std::string path,
                                         const Rosbag2SqliteOptions& options)
    : db_(db), path_(std::move(path)), options_(options) {}

Rosbag2SqliteReader::~Rosbag2SqliteReader() {
  sqlite3_finalize(rows_);
  sqlite3_close(db_);
}

std::unique_ptr<Rosbag2SqliteReader> Rosbag2SqliteReader::Open(const std::string& path,
                                                               const Rosbag2SqliteOptions& options,
                                                               std::string* error) {
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(ImmutableUri(path).c_str(), &db,
                                 SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
  std::unique_ptr<Rosbag2SqliteReader> reader(new Rosbag2SqliteReader(db, path, options));
  if (rc != SQLITE_OK) {
    *error = path + ": cannot open as SQLite3: " + reader->SqliteError();
    return nullptr;
  }
  if (!reader->Load(error)) return nullptr;
  return reader;
}

std::unique_ptr<Rosbag2SqliteReader> Rosbag2SqliteReader::OpenBytes(
    std::span<const uint8_t> bytes,
    const std::string& name,
    const Rosbag2SqliteOptions& options,
    std::string* error) {
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(":memory:", &db, SQLITE_OPEN_READWRITE, nullptr);
  std::unique_ptr<Rosbag2SqliteReader> reader(new Rosbag2SqliteReader(db, name, options));
  if (rc != SQLITE_OK) {
    *error = name + ": cannot open an in-memory database";
    return nullptr;
  }
  auto* image = static_cast<unsigned char*>(sqlite3_malloc64(bytes.size() + 1));
  if (image == nullptr) {
    *error = name + ": out of memory";
    return nullptr;
  }
  if (!bytes.empty()) std::memcpy(image, bytes.data(), bytes.size());
  const auto n = static_cast<sqlite3_int64>(bytes.size());
  if (sqlite3_deserialize(db, "main", image, n, n,
                          SQLITE_DESERIALIZE_FREEONCLOSE | SQLITE_DESERIALIZE_READONLY) !=
      SQLITE_OK) {
    *error = name + ": not an SQLite3 image: " + reader->SqliteError();
    return nullptr;
  }
  if (!reader->Load(error)) return nullptr;
  return reader;
}

std::string Rosbag2SqliteReader::SqliteError() const {
  return db_ == nullptr ? "out of memory" : sqlite3_errmsg(db_);
}

bool Rosbag2SqliteReader::Load(std::string* error) {
  Harden(db_);
  return LoadSchemaVersion(error) && LoadTopics(error) && LoadCounts(error) && Prepare(error);
}

bool Rosbag2SqliteReader::LoadSchemaVersion(std::string* error) {
  // Reading the schema is the first access to the file: a non-database fails here.
  const std::set<std::string> tables = Tables(db_);
  if (sqlite3_errcode(db_) != SQLITE_OK && sqlite3_errcode(db_) != SQLITE_DONE) {
    *error = path_ + ": not a readable SQLite3 database: " + SqliteError();
    return false;
  }
  if (tables.count("topics") == 0 || tables.count("messages") == 0) {
    *error = path_ + ": not a rosbag2 database (no 'topics' and 'messages' tables)";
    return false;
  }
  if (tables.count("schema") != 0) {
    Statement s(db_, "SELECT schema_version, ros_distro FROM schema ORDER BY schema_version DESC");
    if (s.ok() && s.Row()) {
      db_schema_version_ = static_cast<int>(s.Int(0));
      ros_distro_ = s.Text(1);
    }
  } else {
    db_schema_version_ = HasColumn(db_, "topics", "offered_qos_profiles") ? 2 : 1;
  }
  return true;
}

bool Rosbag2SqliteReader::LoadTopics(std::string* error) {
  Statement s(db_, "SELECT id, name, type, serialization_format FROM topics ORDER BY id");
  if (!s.ok()) {
    *error = path_ + ": unreadable 'topics' table: " + SqliteError();
    return false;
  }
  while (s.Row()) {
    BagTopic t;
    t.name = s.Text(1);
    t.type = s.Text(2);
    t.encoding_name = s.Text(3);
    t.encoding = EncodingFromName(t.encoding_name);
    if (!topic_by_id_.emplace(s.Int(0), static_cast<uint32_t>(topics_.size())).second) {
      warnings_.Add(path_ + ": topics row id " + std::to_string(s.Int(0)) + " repeated; ignored");
      continue;
    }
    topics_.push_back(std::move(t));
  }
  next_index_.assign(topics_.size(), 0);
  LoadDefinitions();
  return true;
}

void Rosbag2SqliteReader::LoadDefinitions() {
  if (!HasColumn(db_, "message_definitions", "encoded_message_definition")) return;
  Statement s(db_,
              "SELECT topic_type, encoding, encoded_message_definition FROM message_definitions");
  while (s.ok() && s.Row()) {
    for (BagTopic& t : topics_) {
      if (t.type != s.Text(0)) continue;
      t.definition_encoding = s.Text(1);
      t.definition = s.Text(2);
    }
  }
}

bool Rosbag2SqliteReader::LoadCounts(std::string* error) {
  Statement s(db_,
              "SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages "
              "GROUP BY topic_id");
  if (!s.ok()) {
    *error = path_ + ": unreadable 'messages' table: " + SqliteError();
    return false;
  }
  while (s.Row()) {
    const auto it = topic_by_id_.find(s.Int(0));
    if (it == topic_by_id_.end()) continue;  // warned per row while reading
    BagTopic& t = topics_[it->second];
    t.message_count = static_cast<uint64_t>(s.Int(1));
    t.first_log_time_ns = s.Int(2);
    t.last_log_time_ns = s.Int(3);
  }
  return true;
}

bool Rosbag2SqliteReader::Prepare(std::string* error) {
  const char* sql =
      "SELECT rowid, topic_id, timestamp, data FROM messages ORDER BY timestamp, rowid";
  if (sqlite3_prepare_v2(db_, sql, -1, &rows_, nullptr) != SQLITE_OK) {
    *error = path_ + ": cannot read 'messages': " + SqliteError();
    return false;
  }
  return true;
}

std::string Rosbag2SqliteReader::StorageDescription() const {
  std::string d = "rosbag2 sqlite3 (db schema " + std::to_string(db_schema_version_);
  if (!ros_distro_.empty()) d += ", " + ros_distro_;
  return d + ")";
}

bool Rosbag2SqliteReader::Next(BagMessage* message) {
  if (rows_ == nullptr || !error_.empty()) return false;
  for (;;) {
    const int rc = sqlite3_step(rows_);
    if (rc == SQLITE_DONE) return false;
    if (rc != SQLITE_ROW) {
      error_ = path_ + ": reading 'messages' failed after " +
               std::to_string(stats_.messages_returned) + " messages: " + SqliteError();
      return false;
    }
    if (TakeRow(message)) return true;
    ++stats_.messages_skipped;
  }
}

bool Rosbag2SqliteReader::TakeRow(BagMessage* message) {
  const int64_t topic_id = sqlite3_column_int64(rows_, 1);
  const auto it = topic_by_id_.find(topic_id);
  const auto where = [&] {
    std::string w = path_ + ": messages row " + std::to_string(sqlite3_column_int64(rows_, 0));
    if (it == topic_by_id_.end()) return w;
    return w + " (" + topics_[it->second].name + " #" +
           std::to_string(next_index_[it->second] - 1) + ")";
  };
  if (it == topic_by_id_.end()) {
    warnings_.Add(where() + ": unknown topic_id " + std::to_string(topic_id) + "; skipped");
    return false;
  }
  const uint64_t index = next_index_[it->second]++;  // skipped rows keep their place
  const int64_t t_ns = sqlite3_column_int64(rows_, 2);
  if (sqlite3_column_type(rows_, 2) != SQLITE_INTEGER) {
    warnings_.Add(where() + ": timestamp is not an integer; skipped");
    return false;
  }
  if (t_ns < last_time_ns_) {  // ORDER BY over a damaged index
    warnings_.Add(where() + ": timestamp before the previous row's (damaged index?); skipped");
    return false;
  }
  if (sqlite3_column_type(rows_, 3) != SQLITE_BLOB) {
    warnings_.Add(where() + ": data is not a BLOB; skipped");
    return false;
  }
  const auto* blob = static_cast<const uint8_t*>(sqlite3_column_blob(rows_, 3));
  const auto size = static_cast<size_t>(sqlite3_column_bytes(rows_, 3));
  std::span<const uint8_t> data(blob, blob == nullptr ? 0 : size);
  if (data.size() > options_.limits.max_message_bytes) {
    warnings_.Add(where() + ": " + std::to_string(data.size()) + " bytes, over the limit; skipped");
    return false;
  }
  if (options_.zstd_per_message) {
    std::string why;
    if (!Inflate(data, &why)) {
      warnings_.Add(where() + ": " + why + "; skipped");
      return false;
    }
    data = decompressed_;
  }
  message->topic = it->second;
  message->index = index;
  message->log_time_ns = t_ns;
  last_time_ns_ = t_ns;
  message->data = data;
  ++stats_.messages_returned;
  stats_.bytes_returned += data.size();
  return true;
}

bool Rosbag2SqliteReader::Inflate(std::span<const uint8_t> blob, std::string* why) {
  // rosbag2's zstd compressor writes the content size into each frame (ZSTD_compress).
  const unsigned long long n = ZSTD_getFrameContentSize(blob.data(), blob.size());
  if (n == ZSTD_CONTENTSIZE_ERROR || n == ZSTD_CONTENTSIZE_UNKNOWN) {
    *why = "not a zstd frame of known size";
    return false;
  }
  if (n > options_.limits.max_message_bytes) {
    *why = "decompresses to " + std::to_string(n) + " bytes, over the limit";
    return false;
  }
  return Decompress(Compression::kZstd, blob, n, &decompressed_, why);
}

}  // namespace swlio::drivers::bag
