#pragma once
/// @file
/// Writes small rosbag2 SQLite3 files for tests, in each database schema version (tables as
/// rosbag2's sqlite_storage.cpp creates them; research/bags.md §1.1): 1 topics + messages,
/// 2 adds topics.offered_qos_profiles, 3 adds the schema and metadata tables, 4 adds
/// topics.type_description_hash and message_definitions.

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace swlio::test {

struct Db3Topic {
  int64_t id = 1;
  std::string name;
  std::string type;
  std::string format = "cdr";
  std::string definition;  ///< stored in message_definitions (version 4) when not empty
};

struct Db3Message {
  int64_t topic_id = 1;
  int64_t t_ns = 0;
  std::vector<uint8_t> data;
};

inline void Db3Exec(sqlite3* db, const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    ADD_FAILURE() << sql << ": " << (err != nullptr ? err : "?");
    sqlite3_free(err);
  }
}

inline std::string Db3TopicsTable(int version) {
  std::string sql =
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
      "serialization_format TEXT NOT NULL";
  if (version >= 2) sql += ", offered_qos_profiles TEXT NOT NULL";
  if (version >= 4) sql += ", type_description_hash TEXT NOT NULL";
  return sql + ")";
}

inline void Db3CreateTables(sqlite3* db, int version) {
  Db3Exec(db, Db3TopicsTable(version));
  Db3Exec(db,
          "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
          "timestamp INTEGER NOT NULL, data BLOB NOT NULL)");
  Db3Exec(db, "CREATE INDEX timestamp_idx ON messages (timestamp ASC)");
  if (version >= 3) {
    Db3Exec(db,
            "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL)");
    Db3Exec(db, "INSERT INTO schema VALUES(" + std::to_string(version) + ", 'humble')");
    Db3Exec(db,
            "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, "
            "metadata TEXT NOT NULL)");
  }
  if (version >= 4) {
    Db3Exec(db,
            "CREATE TABLE message_definitions(id INTEGER PRIMARY KEY, topic_type TEXT NOT NULL, "
            "encoding TEXT NOT NULL, encoded_message_definition TEXT NOT NULL, "
            "type_description_hash TEXT NOT NULL)");
  }
}

inline void Db3InsertTopic(sqlite3* db, int version, const Db3Topic& t) {
  sqlite3_stmt* s = nullptr;
  std::string sql = "INSERT INTO topics VALUES(?, ?, ?, ?";
  if (version >= 2) sql += ", ''";
  if (version >= 4) sql += ", ''";
  sqlite3_prepare_v2(db, (sql + ")").c_str(), -1, &s, nullptr);
  sqlite3_bind_int64(s, 1, t.id);
  sqlite3_bind_text(s, 2, t.name.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 3, t.type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 4, t.format.c_str(), -1, SQLITE_TRANSIENT);
  EXPECT_EQ(sqlite3_step(s), SQLITE_DONE);
  sqlite3_finalize(s);
  if (version >= 4 && !t.definition.empty()) {
    sqlite3_prepare_v2(db, "INSERT INTO message_definitions VALUES(NULL, ?, 'ros2msg', ?, '')", -1,
                       &s, nullptr);
    sqlite3_bind_text(s, 1, t.type.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(s, 2, t.definition.c_str(), -1, SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(s), SQLITE_DONE);
    sqlite3_finalize(s);
  }
}

inline void Db3InsertMessage(sqlite3* db, const Db3Message& m) {
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", -1, &s,
                     nullptr);
  sqlite3_bind_int64(s, 1, m.topic_id);
  sqlite3_bind_int64(s, 2, m.t_ns);
  sqlite3_bind_blob(s, 3, m.data.data(), static_cast<int>(m.data.size()), SQLITE_TRANSIENT);
  EXPECT_EQ(sqlite3_step(s), SQLITE_DONE);
  sqlite3_finalize(s);
}

/// Writes `path` (replacing it) with the tables of `version` and the given rows.
inline void WriteDb3(const std::filesystem::path& path,
                     int version,
                     const std::vector<Db3Topic>& topics,
                     const std::vector<Db3Message>& messages) {
  std::filesystem::remove(path);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  Db3CreateTables(db, version);
  for (const Db3Topic& t : topics) Db3InsertTopic(db, version, t);
  Db3Exec(db, "BEGIN");
  for (const Db3Message& m : messages) Db3InsertMessage(db, m);
  Db3Exec(db, "COMMIT");
  sqlite3_close(db);
}

}  // namespace swlio::test
