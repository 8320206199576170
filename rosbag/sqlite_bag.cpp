#include "rosbag/sqlite_bag.hpp"

#include <sqlite3.h>

#include <memory>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

class Database {
 public:
  explicit Database(const std::filesystem::path& path) : path_(path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      throw Error(path.string() + ": no such file (a rosbag2 .db3 file was expected)");
    }
    // immutable=1: no locking, no journal; the file must not change while we read (a bag).
    std::string uri = "file:";
    for (const char c : path.string()) {  // a URI: '%', '?' and '#' in the path are escaped
      if (c == '%' || c == '?' || c == '#') {
        static const char kHex[] = "0123456789ABCDEF";
        uri += {'%', kHex[static_cast<unsigned char>(c) >> 4], kHex[c & 15]};
      } else {
        uri += c;
      }
    }
    uri += "?immutable=1";
    sqlite3* db = nullptr;
    const int rc =
        sqlite3_open_v2(uri.c_str(), &db, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
    db_.reset(db);
    if (rc != SQLITE_OK) Fail("cannot open as SQLite");
  }

  [[noreturn]] void Fail(const std::string& what) const {
    throw Error(path_.string() + ": " + what + " (" +
                (db_ ? sqlite3_errmsg(db_.get()) : "out of memory") +
                "; expected a rosbag2 SQLite 3 bag)");
  }

  sqlite3_stmt* Prepare(const char* sql) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql, -1, &statement, nullptr) != SQLITE_OK) {
      Fail(std::string("cannot query it: ") + sql);
    }
    return statement;
  }

 private:
  struct Close {
    void operator()(sqlite3* db) const { sqlite3_close(db); }
  };
  std::filesystem::path path_;
  std::unique_ptr<sqlite3, Close> db_;
};

struct Finalize {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Statement = std::unique_ptr<sqlite3_stmt, Finalize>;

std::string Text(sqlite3_stmt* s, int column) {
  const unsigned char* text = sqlite3_column_text(s, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

std::vector<BagTopic> SqliteBagTopics(const std::filesystem::path& db3) {
  Database db(db3);
  Statement s(
      db.Prepare("SELECT t.name, t.type, (SELECT COUNT(*) FROM messages m WHERE m.topic_id = t.id) "
                 "FROM topics t ORDER BY t.name"));
  std::vector<BagTopic> topics;
  int rc;
  while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
    topics.push_back({Text(s.get(), 0), Text(s.get(), 1),
                      static_cast<std::uint64_t>(sqlite3_column_int64(s.get(), 2))});
  }
  if (rc != SQLITE_DONE) db.Fail("cannot read its topics");
  return topics;
}

std::optional<BagMessage> SqliteBagLastMessage(const std::filesystem::path& db3,
                                               const std::string& topic) {
  Database db(db3);
  Statement s(db.Prepare(
      "SELECT m.timestamp, m.data, t.serialization_format FROM messages m JOIN topics t ON "
      "m.topic_id = t.id WHERE t.name = ?1 ORDER BY m.timestamp DESC, m.id DESC LIMIT 1"));
  sqlite3_bind_text(s.get(), 1, topic.c_str(), -1, SQLITE_TRANSIENT);
  const int rc = sqlite3_step(s.get());
  if (rc == SQLITE_DONE) return std::nullopt;
  if (rc != SQLITE_ROW) db.Fail("cannot read the messages of " + topic);
  const std::string format = Text(s.get(), 2);
  if (format != "cdr") {
    throw Error(db3.string() + ": topic " + topic + " has serialization_format '" + format +
                "', expected 'cdr'");
  }
  BagMessage message;
  message.log_time_ns = sqlite3_column_int64(s.get(), 0);
  const void* blob = sqlite3_column_blob(s.get(), 1);
  const int size = sqlite3_column_bytes(s.get(), 1);
  if (blob && size > 0) message.data.assign(static_cast<const char*>(blob), size);
  return message;
}

}  // namespace fleetmerge
