// An SQLite database file on disk and the other programs that may hold it (issue 29). Replacing a
// database is where data gets lost: a database another connection holds (its commit would go into
// the unlinked file), or a stale journal left beside it by a killed writer (SQLite would replay
// it into the new file: "database disk image is malformed"). So a replacement
//   1. is written beside the target and passes `PRAGMA integrity_check` first;
//   2. takes the old database's EXCLUSIVE lock, waiting up to a busy timeout for the connections
//      that hold it (SQLite rolls a hot journal back as the lock is taken; a WAL database is
//      checkpointed back to a rollback journal); a database still locked, or open in another
//      process, is refused with one line naming that process;
//   3. refuses a journal (-journal, -wal) left beside a target whose database is gone;
//   4. is renamed over the target while the old database's lock is held.
//
//   io::WriteAtomically(path, write_database, overwrite, io::SqliteReplacement(options));
#pragma once

#include <string>

#include "io/core/file_utils.h"

namespace comic::io {

struct SqliteFileOptions {
  // How long to wait for another connection's lock before giving up, milliseconds.
  int busy_timeout_ms = 5000;

  // Throws comic::Error(kInvalidArgument) unless busy_timeout_ms is in [0, 600000].
  void Check() const;
};

// The other processes that hold the file at `path` locked (/proc/locks) or open (/proc/*/fd),
// as "process 4242 (python3) holds a lock on it"; "" if none is seen (or not on Linux). Reads
// /proc only: opening the file would drop this process's own POSIX locks on it.
std::string DescribeOtherHolders(const std::string& path);

// Checks, before any work, that the database at `path` could be replaced now (steps 2 and 3
// above), and rolls back a hot journal beside it. A file that is not an SQLite database is
// replaceable unless a journal lies beside it. Throws comic::Error(kIo) naming `path`.
void CheckSqliteFileReplaceable(const std::string& path, const SqliteFileOptions& options = {});

// Moves the finished database `new_path` to `path` (steps 1 to 4). Throws comic::Error(kIo or
// kInvalidData) naming `path`; `path` is then untouched.
void ReplaceSqliteFile(const std::string& new_path, const std::string& path,
                       const SqliteFileOptions& options = {});

// ReplaceSqliteFile as the last step of WriteAtomically.
MoveIntoPlace SqliteReplacement(const SqliteFileOptions& options = {});

}  // namespace comic::io
