#include "io/colmap/sqlite_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/sqlite_other_process.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

namespace fs = std::filesystem;
using comic::test::FileInode;
using comic::test::OtherSqliteProcess;
using comic::test::ScopedTempDir;

// A database with one table `t` of `rows` rows of 1 kB text.
void MakeDatabase(const std::string& path, int rows, const std::string& journal_mode = "DELETE") {
  fs::remove(path);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  const std::string sql = "PRAGMA journal_mode=" + journal_mode +
                          "; CREATE TABLE t(x TEXT); WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL "
                          "SELECT i + 1 FROM n WHERE i < " +
                          std::to_string(rows) +
                          ") INSERT INTO t SELECT printf('%01000d', i) FROM n;";
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
}

// Rows of `t`, or -1 if the database cannot be read or fails its integrity check.
int64_t CheckedRows(const std::string& path) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) return -1;
  int64_t rows = -1;
  sqlite3_stmt* check = nullptr;
  if (sqlite3_prepare_v2(db, "PRAGMA integrity_check", -1, &check, nullptr) == SQLITE_OK &&
      sqlite3_step(check) == SQLITE_ROW &&
      std::string(reinterpret_cast<const char*>(sqlite3_column_text(check, 0))) == "ok") {
    sqlite3_stmt* count = nullptr;
    if (sqlite3_prepare_v2(db, "SELECT COUNT(*) FROM t", -1, &count, nullptr) == SQLITE_OK &&
        sqlite3_step(count) == SQLITE_ROW) {
      rows = sqlite3_column_int64(count, 0);
    }
    sqlite3_finalize(count);
  }
  sqlite3_finalize(check);
  sqlite3_close(db);
  return rows;
}

SqliteFileOptions ShortWait() {
  SqliteFileOptions options;
  options.busy_timeout_ms = 200;
  return options;
}

TEST(SqliteFile, ReplacesAnIdleDatabaseWithACheckedNewOne) {
  ScopedTempDir dir;
  MakeDatabase(dir.File("t.db"), 3);
  MakeDatabase(dir.File("new.db"), 5);
  ReplaceSqliteFile(dir.File("new.db"), dir.File("t.db"), ShortWait());
  EXPECT_EQ(CheckedRows(dir.File("t.db")), 5);
  EXPECT_FALSE(PathExists(dir.File("new.db")));
  EXPECT_FALSE(PathExists(dir.File("t.db-journal")));
  // A missing target, and a target that is not an SQLite file, are simply replaced.
  MakeDatabase(dir.File("new.db"), 2);
  ReplaceSqliteFile(dir.File("new.db"), dir.File("fresh.db"), ShortWait());
  EXPECT_EQ(CheckedRows(dir.File("fresh.db")), 2);
  WriteFileAtomically(dir.File("text.db"), "not a database\n");
  MakeDatabase(dir.File("new.db"), 2);
  ReplaceSqliteFile(dir.File("new.db"), dir.File("text.db"), ShortWait());
  EXPECT_EQ(CheckedRows(dir.File("text.db")), 2);
}

// Issue 29: with another process in BEGIN EXCLUSIVE, the old export replaced the file in 0.6 s;
// the other process's commit then went into the unlinked file.
TEST(SqliteFile, RefusesADatabaseAnotherProcessHoldsAndNamesIt) {
  ScopedTempDir dir;
  const std::string target = dir.File("held.db");
  MakeDatabase(target, 3);
  const ino_t inode = FileInode(target);
  OtherSqliteProcess other(target, "BEGIN EXCLUSIVE; INSERT INTO t VALUES('theirs');");
  ASSERT_TRUE(other.ok());
  MakeDatabase(dir.File("new.db"), 5);
  for (const bool replace : {false, true}) {
    try {
      if (replace) {
        ReplaceSqliteFile(dir.File("new.db"), target, ShortWait());
      } else {
        CheckSqliteFileReplaceable(target, ShortWait());
      }
      FAIL() << "a held database was replaced";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(e.kind(), ErrorKind::kIo);
      EXPECT_EQ(message.rfind(target + ": the database is held by another connection", 0), 0u)
          << message;
      EXPECT_NE(message.find("process " + std::to_string(other.pid())), std::string::npos)
          << message;
      EXPECT_NE(message.find("refusing to replace it"), std::string::npos) << message;
    }
  }
  EXPECT_EQ(FileInode(target), inode);
  EXPECT_TRUE(PathExists(dir.File("new.db")));  // the caller's temporary file, not renamed
  other.Release();                              // their commit lands in the file, not lost
  EXPECT_EQ(CheckedRows(target), 4);
}

TEST(SqliteFile, RefusesADatabaseOpenInAnotherProcessWithoutALock) {
  ScopedTempDir dir;
  const std::string target = dir.File("open.db");
  MakeDatabase(target, 3);
  OtherSqliteProcess other(target, "SELECT COUNT(*) FROM t");  // open, idle: no lock held
  ASSERT_TRUE(other.ok());
  MakeDatabase(dir.File("new.db"), 5);
  try {
    ReplaceSqliteFile(dir.File("new.db"), target, ShortWait());
    FAIL() << "an open database was replaced";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("open in another program (process " + std::to_string(other.pid())),
              std::string::npos)
        << message;
  }
  EXPECT_EQ(CheckedRows(target), 3);
  other.Release();
  ReplaceSqliteFile(dir.File("new.db"), target, ShortWait());
  EXPECT_EQ(CheckedRows(target), 5);
}

// Issue 29: a writer killed mid-transaction leaves t.db-journal; renaming a new database over
// t.db made SQLite replay that journal into it ("database disk image is malformed").
TEST(SqliteFile, RollsAHotJournalBackBeforeReplacing) {
  ScopedTempDir dir;
  const std::string target = dir.File("hot.db");
  MakeDatabase(target, 50);
  {
    // A small page cache, so the uncommitted rows spill into the database file itself.
    OtherSqliteProcess writer(
        target,
        "PRAGMA cache_size=2; BEGIN; DELETE FROM t; INSERT INTO t SELECT "
        "printf('%02000d', rowid) FROM (SELECT 1 AS rowid UNION SELECT 2);"
        "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE "
        "i < 300) INSERT INTO t SELECT printf('%03000d', i) FROM n;");
    ASSERT_TRUE(writer.ok());
    writer.Kill();
  }
  ASSERT_TRUE(PathExists(target + "-journal")) << "no hot journal was left";
  // Checking rolls it back: the committed 50 rows are what the file holds.
  CheckSqliteFileReplaceable(target, ShortWait());
  EXPECT_FALSE(PathExists(target + "-journal"));
  EXPECT_EQ(CheckedRows(target), 50);
  // And a replacement over a fresh hot journal leaves the new database whole, journal gone.
  {
    OtherSqliteProcess writer(
        target,
        "PRAGMA cache_size=2; BEGIN; WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL "
        "SELECT i + 1 FROM n WHERE i < 300) INSERT INTO t SELECT "
        "printf('%03000d', i) FROM n;");
    ASSERT_TRUE(writer.ok());
    writer.Kill();
  }
  ASSERT_TRUE(PathExists(target + "-journal"));
  MakeDatabase(dir.File("new.db"), 7);
  ReplaceSqliteFile(dir.File("new.db"), target, ShortWait());
  EXPECT_FALSE(PathExists(target + "-journal"));
  EXPECT_EQ(CheckedRows(target), 7);
}

TEST(SqliteFile, RefusesAJournalWhoseDatabaseIsGone) {
  ScopedTempDir dir;
  for (const std::string suffix : {"-journal", "-wal"}) {
    const std::string target = dir.File("gone" + suffix + ".db");
    WriteFileAtomically(target + suffix, std::string(600, 'j'));
    MakeDatabase(dir.File("new.db"), 2);
    try {
      ReplaceSqliteFile(dir.File("new.db"), target, ShortWait());
      FAIL() << "written beside a stale " << suffix;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(target + suffix + ": a journal is left beside", 0), 0u)
          << e.what();
    }
    EXPECT_FALSE(PathExists(target));
  }
}

TEST(SqliteFile, ReplacesAWalDatabaseOnlyWhenNobodyHoldsIt) {
  ScopedTempDir dir;
  const std::string target = dir.File("wal.db");
  MakeDatabase(target, 3, "WAL");
  MakeDatabase(dir.File("new.db"), 6);
  {
    OtherSqliteProcess reader(target, "SELECT COUNT(*) FROM t");
    ASSERT_TRUE(reader.ok());
    EXPECT_THROW(ReplaceSqliteFile(dir.File("new.db"), target, ShortWait()), Error);
    EXPECT_EQ(CheckedRows(target), 3);
  }
  ReplaceSqliteFile(dir.File("new.db"), target, ShortWait());
  EXPECT_EQ(CheckedRows(target), 6);
  EXPECT_FALSE(PathExists(target + "-wal"));
}

TEST(SqliteFile, ANewDatabaseFailingItsIntegrityCheckReplacesNothing) {
  ScopedTempDir dir;
  const std::string target = dir.File("t.db");
  MakeDatabase(target, 3);
  const std::string corrupt = dir.File("new.db");
  MakeDatabase(corrupt, 40);
  // Scribble over the middle of the file: a b-tree page of table t.
  std::string bytes = ReadFileToString(corrupt);
  ASSERT_GT(bytes.size(), 20000u);
  for (size_t k = 8192; k < 8192 + 600; ++k) bytes[k] = static_cast<char>(k * 7);
  WriteFileAtomically(corrupt, bytes);
  try {
    ReplaceSqliteFile(corrupt, target, ShortWait());
    FAIL() << "a corrupt database replaced the target";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("integrity check"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nothing was replaced"), std::string::npos) << e.what();
  }
  EXPECT_EQ(CheckedRows(target), 3);
}

TEST(SqliteFile, OptionsAreChecked) {
  SqliteFileOptions options;
  EXPECT_NO_THROW(options.Check());
  options.busy_timeout_ms = -1;
  EXPECT_THROW(options.Check(), Error);
  options.busy_timeout_ms = 600001;
  EXPECT_THROW(options.Check(), Error);
}

}  // namespace
}  // namespace comic::io
