// Another process with an SQLite database open, for the tests that check what happens to a
// database somebody else holds (tests/io/colmap/sqlite_file_test.cc,
// tests/apps/nothing_lost_test.cc).
#pragma once

#include <signal.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

namespace comic::test {

// The inode of `path` (0 when missing): a replaced file has a new one.
inline ino_t FileInode(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 ? info.st_ino : 0;
}

// A forked process that opens the database, runs `sql` (e.g. BEGIN EXCLUSIVE and an INSERT), says
// so, and keeps the connection and the locks the SQL took until Release() (then commits), or
// dies mid-transaction by Kill(), as a killed writer: its journal stays behind.
class OtherSqliteProcess {
 public:
  OtherSqliteProcess(const std::string& path, const std::string& sql) {
    int ready[2], release[2];
    if (::pipe(ready) != 0 || ::pipe(release) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(ready[0]);
      ::close(release[1]);
      sqlite3* db = nullptr;
      const bool ok = sqlite3_open(path.c_str(), &db) == SQLITE_OK &&
                      sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK;
      const char answer = ok ? 'y' : 'n';
      if (::write(ready[1], &answer, 1) != 1) ::_exit(3);
      char byte;
      while (::read(release[0], &byte, 1) > 0) {
      }
      sqlite3_exec(db, "COMMIT", nullptr, nullptr, nullptr);
      sqlite3_close(db);
      ::_exit(0);
    }
    ::close(ready[1]);
    ::close(release[0]);
    release_ = release[1];
    char answer = 'n';
    ok_ = ::read(ready[0], &answer, 1) == 1 && answer == 'y';
    ::close(ready[0]);
  }
  OtherSqliteProcess(const OtherSqliteProcess&) = delete;
  OtherSqliteProcess& operator=(const OtherSqliteProcess&) = delete;
  ~OtherSqliteProcess() { Release(); }

  // The SQL ran and the process holds the connection.
  bool ok() const { return ok_; }
  pid_t pid() const { return pid_; }
  // Lets the process commit and close; waits for it.
  void Release() {
    if (release_ >= 0) ::close(release_);
    release_ = -1;
    Wait();
  }
  // Kills the process mid-transaction and waits for it.
  void Kill() {
    if (pid_ > 0) ::kill(pid_, SIGKILL);
    Wait();
    if (release_ >= 0) ::close(release_);
    release_ = -1;
  }

 private:
  void Wait() {
    if (pid_ > 0) ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  pid_t pid_ = -1;
  int release_ = -1;
  bool ok_ = false;
};

}  // namespace comic::test
