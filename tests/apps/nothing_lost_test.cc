// Issue 29, the cases a table cannot hold: a database another process holds, a journal left by a
// killed writer, a full disk (a small tmpfs, mounted in a private mount namespace where the test
// may make one; skipped cleanly otherwise), and the peak memory of a refused huge image. Each
// checks the one stderr line, the exit code and that nothing of the user's was lost.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sqlite3.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/colmap/colmap_database.h"
#include "io/core/file_utils.h"
#include "tests/sqlite_other_process.h"
#include "tests/test_support.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using comic::test::AppPath;
using comic::test::CountLines;
using comic::test::ExampleDir;
using comic::test::FileInode;
using comic::test::OtherSqliteProcess;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

// A quick export: the bundled example's first 4 frames, FAST.
std::string ExportArgs(const std::string& database) {
  return ExampleDir() + "/image_l --last 3 --detector fast --threads 1 -q --colmap-db " + database;
}

// The arguments of `app` (comic_export_colmap or comic_sfm) writing the same frames' tracks to
// `database`; comic_sfm also writes its model to `output`.
std::string AppArgs(const std::string& app, const std::string& database,
                    const std::string& output) {
  if (app == "comic_sfm") return ExportArgs(database) + " --output " + output;
  return ExportArgs(database);
}

int64_t Rows(const std::string& path, const std::string& table) {
  sqlite3* db = nullptr;
  int64_t rows = -1;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db, ("SELECT COUNT(*) FROM " + table).c_str(), -1, &statement,
                           nullptr) == SQLITE_OK &&
        sqlite3_step(statement) == SQLITE_ROW) {
      rows = sqlite3_column_int64(statement, 0);
    }
    sqlite3_finalize(statement);
  }
  sqlite3_close(db);
  return rows;
}

void MakeTable(const std::string& path) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "CREATE TABLE t(x TEXT); WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL "
                         "SELECT i + 1 FROM n WHERE i < 50) INSERT INTO t SELECT "
                         "printf('%01000d', i) FROM n;",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
}

// Issue 29: a writer killed mid-transaction leaves hot.db-journal; `--overwrite` printed success
// and the next open replayed the journal into the new database ("database disk image is
// malformed"). Now the journal is rolled back first, and the new database is whole.
TEST(NothingLost, OverwriteBesideAHotJournalLeavesAWholeDatabase) {
  ScopedTempDir dir;
  for (const std::string app : {"comic_export_colmap", "comic_sfm"}) {
    SCOPED_TRACE(app);
    const std::string database = dir.File(app + "_hot.db");
    MakeTable(database);
    {
      OtherSqliteProcess writer(
          database,
          "PRAGMA cache_size=2; BEGIN; WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL "
          "SELECT i + 1 FROM n WHERE i < 300) INSERT INTO t SELECT "
          "printf('%03000d', i) FROM n;");
      ASSERT_TRUE(writer.ok());
      writer.Kill();
    }
    ASSERT_TRUE(fs::exists(database + "-journal"));
    const auto result =
        RunCommand(AppPath(app) + " " + AppArgs(app, database, dir.File(app)) + " --overwrite");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_FALSE(fs::exists(database + "-journal"));
    comic::io::ColmapDatabase opened = comic::io::ColmapDatabase::Open(database);
    EXPECT_EQ(opened.NumImages(), 4u);
    EXPECT_GT(opened.NumVerifiedImagePairs(), 0u);
  }
}

// Issue 29: with another process in BEGIN EXCLUSIVE, `--overwrite` replaced the file (new inode)
// and exited 0; the other process's commit went into the unlinked file. Now: one line naming the
// holder after the busy timeout, the file untouched, their commit kept.
TEST(NothingLost, OverwriteRefusesADatabaseAnotherProcessHolds) {
  ScopedTempDir dir;
  for (const std::string app : {"comic_export_colmap", "comic_sfm"}) {
    SCOPED_TRACE(app);
    const std::string database = dir.File(app + "_held.db");
    MakeTable(database);
    const ino_t inode = FileInode(database);
    OtherSqliteProcess other(database, "BEGIN EXCLUSIVE; INSERT INTO t VALUES('theirs');");
    ASSERT_TRUE(other.ok());
    const auto result =
        RunCommand(AppPath(app) + " " + AppArgs(app, database, dir.File(app)) + " --overwrite");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_EQ(CountLines(result.output), 1) << result.output;
    EXPECT_EQ(result.output.rfind(app + ": error: " + database +
                                      ": the database is held by another connection (process " +
                                      std::to_string(other.pid()),
                                  0),
              0u)
        << result.output;
    EXPECT_EQ(FileInode(database), inode);
    other.Release();
    EXPECT_EQ(Rows(database, "t"), 51);  // their row landed in the file
    EXPECT_FALSE(fs::exists(dir.File(app))) << "comic_sfm worked before it refused";
  }
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << entry.path() << " left behind";
  }
}

// Runs `command` with a tmpfs of `kib` KiB mounted at `mount` in a private mount namespace
// (unshare -rm: it vanishes with the command). Returns false when no namespace can be made here.
// `listing` receives what the tmpfs held afterwards (hidden files too).
bool RunOnSmallDisk(const std::string& mount, int kib, const std::string& command,
                    comic::test::CommandResult* result, std::string* listing) {
  const auto probe = RunCommand("unshare -rm sh -c 'mount -t tmpfs -o size=16k tmpfs " + mount +
                                " && umount " + mount + "'");
  if (probe.exit_code != 0) return false;
  const std::string listing_file = mount + ".listing";
  *result = RunCommand("unshare -rm sh -c 'mount -t tmpfs -o size=" + std::to_string(kib) +
                       "k tmpfs " + mount + " && { " + command + " >/dev/null; status=$?; ls -A " +
                       mount + " > " + listing_file + "; exit $status; }'");
  *listing = comic::io::ReadFileToString(listing_file);
  fs::remove(listing_file);
  return true;
}

// Issue 29: disk-full errors named the hidden staging path, and libpng's "Write Error" leaked as
// a second line. comic_detect stages files beside the target, comic_export_colmap writes an
// SQLite database, comic_sfm and comic_stereo_eval stage folders.
TEST(NothingLost, AFullDiskIsOneLineNamingTheUsersPath) {
  ScopedTempDir dir;
  const std::string disk = dir.File("disk");
  fs::create_directories(disk);
  const std::string image = ExampleDir() + "/image_l/000000.png";
  struct Case {
    std::string app;
    std::string args;
    std::string named;  // the path the line must name
  };
  const std::vector<Case> cases = {
      {"comic_detect",
       image + " --detector comic-paper --overlay " + disk + "/o.png --json " + disk + "/f.json",
       disk + "/o.png"},
      {"comic_export_colmap", ExportArgs(disk + "/a.db"), disk + "/a.db"},
      {"comic_sfm",
       ExampleDir() + "/image_l --last 5 --detector fast --threads 1 -q --output " + disk + "/out",
       disk + "/out/"},
      {"comic_stereo_eval",
       image + " " + image + " --disparity " + image + " --disparity-scale 4 --methods harris -q " +
           "--output " + disk + "/stereo",
       disk + "/stereo"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.app);
    comic::test::CommandResult result;
    std::string listing;
    if (!RunOnSmallDisk(disk, 48, AppPath(c.app) + " " + c.args, &result, &listing)) {
      GTEST_SKIP() << "no private tmpfs can be mounted here (unshare -rm): disk-full cases skipped";
    }
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_EQ(CountLines(result.output), 1) << result.output;
    EXPECT_EQ(result.output.rfind(c.app + ": error: " + c.named, 0), 0u) << result.output;
    EXPECT_NE(result.output.find("No space left on device"), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find("staging"), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find(".tmp"), std::string::npos) << result.output;
    EXPECT_EQ(listing, "") << "left on the full disk: " << listing;
  }
}

// Issue 29: an 875 kB PNG declaring 30000x30000 peaked at 937 MB before --max-pixels refused it.
// The header is read first now: refused at the size of a small process.
TEST(NothingLost, AHugeDeclaredImageIsRefusedBeforeItIsDecoded) {
  ScopedTempDir dir;
  const auto big_endian = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  // A real 30000x30000 grey PNG's start: signature, IHDR, then an IDAT chunk of zlib data.
  std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + big_endian(13) + "IHDR" +
                    big_endian(30000) + big_endian(30000) + std::string("\x08\x00\x00\x00\x00", 5) +
                    big_endian(0) + big_endian(200000) + "IDAT" + std::string(200000, '\0');
  comic::io::WriteFileAtomically(dir.File("huge.png"), png);
  const std::string app = AppPath("comic_detect");
  std::vector<std::string> args = {app, dir.File("huge.png")};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, dir.File("stderr").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, app.c_str(), &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  struct rusage usage;
  ASSERT_EQ(::wait4(pid, &status, 0, &usage), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = comic::io::ReadFileToString(dir.File("stderr"));
  EXPECT_NE(err.find("30000x30000 = 900000000 pixels exceeds the budget"), std::string::npos)
      << err;
  // ru_maxrss is in kB; the decode alone would take 900 MB.
  EXPECT_LT(usage.ru_maxrss, 200 * 1024) << "peak RSS " << usage.ru_maxrss << " kB";
}

}  // namespace
