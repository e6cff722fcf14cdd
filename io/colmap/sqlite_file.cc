#include "io/colmap/sqlite_file.h"

#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <vector>

#include "io/core/error.h"

namespace comic::io {
namespace {

namespace fs = std::filesystem;

// The journals SQLite keeps beside a database: a rollback journal, or a write-ahead log.
const char* const kJournalSuffixes[] = {"-journal", "-wal"};

std::string ProcessName(pid_t pid) {
  std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
  std::string name;
  std::getline(comm, name);
  return name.empty() ? "?" : name;
}

// Processes other than this one holding a POSIX or flock lock on the file (dev, ino), from
// /proc/locks: "1: POSIX  ADVISORY  WRITE 4242 08:01:1234 1073741824 1073742335".
std::set<pid_t> LockHolders(dev_t dev, ino_t ino) {
  std::set<pid_t> holders;
  std::ifstream locks("/proc/locks");
  std::string line;
  while (std::getline(locks, line)) {
    std::istringstream fields(line);
    std::string number, type, mode, access, file;
    long pid = 0;
    if (!(fields >> number >> type)) continue;
    if (type == "->") fields >> type;  // a waiting lock: "1: -> POSIX ..."
    if (!(fields >> mode >> access >> pid >> file)) continue;
    unsigned major_id = 0, minor_id = 0;
    unsigned long long inode = 0;
    if (std::sscanf(file.c_str(), "%x:%x:%llu", &major_id, &minor_id, &inode) != 3) continue;
    if (major_id == major(dev) && minor_id == minor(dev) && inode == ino && pid > 0 &&
        pid != ::getpid()) {
      holders.insert(static_cast<pid_t>(pid));
    }
  }
  return holders;
}

// Processes other than this one with the file (dev, ino) open, from /proc/*/fd (those this user
// may inspect).
std::set<pid_t> OpenHolders(dev_t dev, ino_t ino) {
  std::set<pid_t> holders;
  std::error_code ec;
  for (const auto& process : fs::directory_iterator("/proc", ec)) {
    const std::string name = process.path().filename().string();
    if (name.empty() || !std::isdigit(static_cast<unsigned char>(name[0]))) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(name));
    if (pid == ::getpid()) continue;
    std::error_code fd_ec;
    for (const auto& fd : fs::directory_iterator(process.path() / "fd", fd_ec)) {
      struct stat info;
      if (::stat(fd.path().c_str(), &info) == 0 && info.st_dev == dev && info.st_ino == ino) {
        holders.insert(pid);
        break;
      }
    }
  }
  return holders;
}

// An open connection to an existing database, closed on destruction.
class Connection {
 public:
  Connection(const std::string& path, int busy_timeout_ms) {
    if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
      error_ = db_ != nullptr ? sqlite3_errmsg(db_) : "cannot open";
      Close();
      return;
    }
    sqlite3_busy_timeout(db_, busy_timeout_ms);
  }
  ~Connection() { Close(); }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  bool ok() const { return db_ != nullptr; }
  const std::string& error() const { return error_; }
  // Runs `sql`; returns SQLite's result code and keeps its message in error().
  int Execute(const std::string& sql) {
    char* message = nullptr;
    const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message);
    error_ = message != nullptr ? message : sqlite3_errstr(rc);
    sqlite3_free(message);
    return rc;
  }
  // The first column of every row `sql` returns.
  std::vector<std::string> Column(const std::string& sql, int* rc) {
    std::vector<std::string> values;
    sqlite3_stmt* statement = nullptr;
    *rc = sqlite3_prepare_v2(db_, sql.c_str(), -1, &statement, nullptr);
    while (*rc == SQLITE_OK || *rc == SQLITE_ROW) {
      *rc = sqlite3_step(statement);
      if (*rc != SQLITE_ROW) break;
      const unsigned char* text = sqlite3_column_text(statement, 0);
      values.emplace_back(text != nullptr ? reinterpret_cast<const char*>(text) : "");
    }
    error_ = sqlite3_errmsg(db_);
    sqlite3_finalize(statement);
    if (*rc == SQLITE_DONE) *rc = SQLITE_OK;
    return values;
  }
  void Close() {
    if (db_ != nullptr) sqlite3_close_v2(db_);
    db_ = nullptr;
  }

 private:
  sqlite3* db_ = nullptr;
  std::string error_;
};

bool IsBusy(int rc) { return (rc & 0xff) == SQLITE_BUSY || (rc & 0xff) == SQLITE_LOCKED; }

// A journal beside `path` (which must not be replaced while it lies there), or "".
std::string JournalBeside(const std::string& path) {
  for (const char* suffix : kJournalSuffixes) {
    std::error_code ec;
    if (fs::exists(path + suffix, ec)) return path + suffix;
  }
  return "";
}

[[noreturn]] void ThrowHeld(const std::string& path, const SqliteFileOptions& options,
                            const std::string& holders) {
  std::ostringstream message;
  message << path << ": the database is held by another connection";
  if (!holders.empty()) message << " (" << holders << ")";
  message << " and stayed locked for " << options.busy_timeout_ms
          << " ms; refusing to replace it (close that program and run again)";
  throw Error(ErrorKind::kIo, message.str());
}

// The old database at `path` with its EXCLUSIVE lock taken, or not an SQLite database; kept
// until the replacement has been renamed over it.
class OldDatabaseLock {
 public:
  OldDatabaseLock(const std::string& path, const SqliteFileOptions& options)
      : connection_(path, options.busy_timeout_ms) {
    COMIC_CHECK(connection_.ok(), kIo,
                path << ": SQLite cannot open the existing database to replace it: "
                     << connection_.error());
    int rc = SQLITE_OK;
    const std::vector<std::string> mode = connection_.Column("PRAGMA journal_mode", &rc);
    if ((rc & 0xff) == SQLITE_NOTADB) return;  // not a database: nothing to lock or roll back
    if (IsBusy(rc)) Held(path, options);
    COMIC_CHECK(rc == SQLITE_OK, kIo,
                path << ": SQLite cannot read the existing database: " << connection_.error());
    // A WAL database back to a rollback journal: it checkpoints the log, removes it, and needs
    // every other connection gone.
    if (!mode.empty() && mode.front() == "wal") {
      connection_.Column("PRAGMA journal_mode=DELETE", &rc);
      if (IsBusy(rc)) Held(path, options);
      COMIC_CHECK(rc == SQLITE_OK, kIo,
                  path << ": cannot checkpoint the existing database's write-ahead log: "
                       << connection_.error());
    }
    // Taking the lock rolls a hot journal back first (SQLite's recovery).
    rc = connection_.Execute("BEGIN EXCLUSIVE");
    if (IsBusy(rc)) Held(path, options);
    if ((rc & 0xff) == SQLITE_NOTADB) return;
    COMIC_CHECK(rc == SQLITE_OK, kIo,
                path << ": cannot lock the existing database (" << connection_.error()
                     << "); refusing to replace it");
    locked_ = true;
  }
  ~OldDatabaseLock() {
    if (locked_) connection_.Execute("ROLLBACK");
  }
  OldDatabaseLock(const OldDatabaseLock&) = delete;
  OldDatabaseLock& operator=(const OldDatabaseLock&) = delete;

 private:
  [[noreturn]] void Held(const std::string& path, const SqliteFileOptions& options) {
    connection_.Close();  // our own locks go before /proc/locks is read
    ThrowHeld(path, options, DescribeOtherHolders(path));
  }

  Connection connection_;
  bool locked_ = false;
};

// Steps 2 and 3 (see the header) up to the point of the rename; the returned lock (null when
// `path` does not exist) must be kept until then.
std::unique_ptr<OldDatabaseLock> GuardTarget(const std::string& path,
                                             const SqliteFileOptions& options) {
  options.Check();
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    const std::string journal = JournalBeside(path);
    COMIC_CHECK(journal.empty(), kIo,
                journal << ": a journal is left beside " << path
                        << ", whose database is gone; SQLite would replay it into the new "
                           "database (move it away and run again)");
    return nullptr;
  }
  auto lock = std::make_unique<OldDatabaseLock>(path, options);
  // Locked now: whoever else still has the file open could write into it after the rename.
  const std::string holders = DescribeOtherHolders(path);
  COMIC_CHECK(holders.empty(), kIo,
              path << ": the database is open in another program (" << holders
                   << "); refusing to replace it (close that program and run again)");
  const std::string journal = JournalBeside(path);
  COMIC_CHECK(journal.empty(), kIo,
              journal << ": a journal is left beside " << path
                      << " that SQLite could not roll back; refusing to replace the database");
  return lock;
}

void CheckIntegrity(const std::string& new_path, const std::string& path) {
  Connection connection(new_path, 0);
  COMIC_CHECK(connection.ok(), kIo,
              path << ": SQLite cannot open the new database: " << connection.error());
  int rc = SQLITE_OK;
  const std::vector<std::string> result = connection.Column("PRAGMA integrity_check", &rc);
  COMIC_CHECK(rc == SQLITE_OK, kInvalidData,
              path << ": SQLite's integrity check of the new database failed: "
                   << connection.error() << "; nothing was replaced");
  COMIC_CHECK(result.size() == 1 && result.front() == "ok", kInvalidData,
              path << ": the new database fails SQLite's integrity check ("
                   << (result.empty() ? "no answer" : result.front()) << "); nothing was replaced");
}

}  // namespace

void SqliteFileOptions::Check() const {
  COMIC_CHECK(busy_timeout_ms >= 0 && busy_timeout_ms <= 600000, kInvalidArgument,
              "SQLite busy timeout must be in [0, 600000] ms, got " << busy_timeout_ms);
}

std::string DescribeOtherHolders(const std::string& path) {
  struct stat info;
  if (::stat(path.c_str(), &info) != 0) return "";
  const std::set<pid_t> locking = LockHolders(info.st_dev, info.st_ino);
  std::set<pid_t> opening = OpenHolders(info.st_dev, info.st_ino);
  std::string text;
  const auto add = [&](pid_t pid, const char* what) {
    text += (text.empty() ? "" : ", ") + std::string("process ") + std::to_string(pid) + " (" +
            ProcessName(pid) + ") " + what;
  };
  for (const pid_t pid : locking) add(pid, "holds a lock on it");
  for (const pid_t pid : opening) {
    if (locking.count(pid) == 0) add(pid, "has it open");
  }
  return text;
}

void CheckSqliteFileReplaceable(const std::string& path, const SqliteFileOptions& options) {
  GuardTarget(path, options);
}

void ReplaceSqliteFile(const std::string& new_path, const std::string& path,
                       const SqliteFileOptions& options) {
  CheckIntegrity(new_path, path);
  const std::unique_ptr<OldDatabaseLock> lock = GuardTarget(path, options);
  std::error_code ec;
  fs::rename(new_path, path, ec);
  COMIC_CHECK(!ec, kIo, path << ": cannot rename the new database into place: " << ec.message());
}

MoveIntoPlace SqliteReplacement(const SqliteFileOptions& options) {
  return [options](const std::string& temp_path, const std::string& path) {
    ReplaceSqliteFile(temp_path, path, options);
  };
}

}  // namespace comic::io
