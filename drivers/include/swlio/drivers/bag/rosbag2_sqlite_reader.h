#pragma once
/// @file
/// rosbag2's SQLite3 storage (`.db3`), all four database schema versions, through SQLite's C API.
///
/// Layout (ros2/rosbag2 rosbag2_storage_sqlite3 sqlite_storage.cpp, read at humble d256a5b and
/// rolling 25304dd; summary in research/bags.md §1):
/// - `topics(id, name, type, serialization_format[, offered_qos_profiles][,
/// type_description_hash])`
/// - `messages(id INTEGER PRIMARY KEY, topic_id, timestamp INTEGER (receive time, ns), data BLOB)`
///   with an index on `timestamp`; `data` is the serialized message as the RMW delivered it.
/// - Schema version: the `schema` table's `schema_version` when present (3 Humble, 4 Iron and
///   later); without it, 2 when `topics` has `offered_qos_profiles` (Foxy, Galactic), else 1.
/// - Version 4 adds `message_definitions(topic_type, encoding, encoded_message_definition, …)`.
///
/// The file is opened read-only and immutable (no locks, no journal: the data folder may be
/// read-only) in SQLite's defensive mode; `topics` and `messages` must be tables, not views,
/// so a crafted file cannot make a query run forever. Messages come `ORDER BY timestamp, rowid`;
/// a row whose timestamp is no integer, or earlier than the one returned before it (a damaged
/// index), is skipped with a warning, so the order holds whatever the file says.
///
/// rosbag2's per-message compression (metadata.yaml `compression_mode: message`, zstd) is
/// undone when the caller says so (`Rosbag2SqliteOptions`); a blob that fails is skipped.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/warning_log.h"

struct sqlite3;
struct sqlite3_stmt;

namespace swlio::drivers::bag {

struct Rosbag2SqliteOptions {
  bool zstd_per_message =
      false;  ///< every `data` blob is one zstd frame (compression_mode message)
  BagReadLimits limits;
};

class Rosbag2SqliteReader final : public BagReader {
 public:
  /// Opens a `.db3` file. Returns nullptr and sets `error` (naming the file) when it is not an
  /// SQLite database or lacks rosbag2's tables.
  static std::unique_ptr<Rosbag2SqliteReader> Open(const std::string& path,
                                                   const Rosbag2SqliteOptions& options,
                                                   std::string* error);
  /// The same from an in-memory image of a `.db3` file (copied); `name` stands for the path in
  /// messages. For tests and fuzzing.
  static std::unique_ptr<Rosbag2SqliteReader> OpenBytes(std::span<const uint8_t> bytes,
                                                        const std::string& name,
                                                        const Rosbag2SqliteOptions& options,
                                                        std::string* error);
  ~Rosbag2SqliteReader() override;
  Rosbag2SqliteReader(const Rosbag2SqliteReader&) = delete;
  Rosbag2SqliteReader& operator=(const Rosbag2SqliteReader&) = delete;

  std::string StorageDescription() const override;
  const std::vector<BagTopic>& topics() const override { return topics_; }
  bool Next(BagMessage* message) override;
  const std::string& error() const override { return error_; }
  const std::vector<std::string>& warnings() const override { return warnings_.lines(); }
  uint64_t warnings_dropped() const override { return warnings_.dropped(); }
  const BagReadStats& stats() const override { return stats_; }
  const std::string& path() const override { return path_; }

  int db_schema_version() const { return db_schema_version_; }
  const std::string& ros_distro() const { return ros_distro_; }

 private:
  Rosbag2SqliteReader(sqlite3* db, std::string path, const Rosbag2SqliteOptions& options);
  bool Load(std::string* error);
  bool LoadSchemaVersion(std::string* error);
  bool LoadTopics(std::string* error);
  void LoadDefinitions();
  bool LoadCounts(std::string* error);
  bool Prepare(std::string* error);
  /// Fills `message` from the current row; false (with a warning) when the row is skipped.
  bool TakeRow(BagMessage* message);
  /// Undoes rosbag2's per-message zstd into decompressed_.
  bool Inflate(std::span<const uint8_t> blob, std::string* why);
  std::string SqliteError() const;

  sqlite3* db_ = nullptr;
  sqlite3_stmt* rows_ = nullptr;
  std::string path_;
  Rosbag2SqliteOptions options_;
  int db_schema_version_ = 0;
  std::string ros_distro_;
  std::vector<BagTopic> topics_;
  std::unordered_map<int64_t, uint32_t> topic_by_id_;
  std::vector<uint64_t> next_index_;
  std::vector<uint8_t> decompressed_;
  int64_t last_time_ns_ = INT64_MIN;  ///< of the last message returned
  std::string error_;
  WarningLog warnings_{kMaxWarnings};
  BagReadStats stats_;
};

}  // namespace swlio::drivers::bag
