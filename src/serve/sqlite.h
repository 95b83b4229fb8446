#pragma once
// A thin RAII layer over SQLite's C interface: a connection and prepared statements whose errors
// become exceptions naming the database file.

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <string>

namespace countershade::serve {

class SqliteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Statement {
 public:
  Statement(sqlite3* db, const char* sql);
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  // Binds the parameters in order (1, 2, …) after a reset.
  Statement& bind(int index, const std::string& text);
  Statement& bind(int index, int64_t value);
  // One step: true while a row is there to read.
  bool step();
  std::string text(int column) const;
  int64_t integer(int column) const { return sqlite3_column_int64(statement_, column); }
  // Steps to the end, then resets for the next use.
  void run();
  void reset();

 private:
  sqlite3* db_;
  sqlite3_stmt* statement_ = nullptr;
};

class Connection {
 public:
  // read_only: never writes, even to recover a journal; else creates the file when missing.
  Connection(const std::filesystem::path& file, bool read_only);
  ~Connection() { close(); }
  void close() {
    sqlite3_close_v2(db_);
    db_ = nullptr;
  }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  void execute(const char* sql);
  sqlite3* get() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

}  // namespace countershade::serve
