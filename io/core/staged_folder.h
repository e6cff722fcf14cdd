// All or nothing for an output folder: a run writes its outputs into a hidden staging folder
// beside the target and moves them into place only when the whole run has succeeded, so that a
// failed or interrupted run leaves the file system as it was (issue 19). The target folder and
// its missing parents are created only at Commit().
//
//   io::StagedFolder out(flags.out);            // checks flags.out, creates only the staging
//   io::WriteFileAtomically(io::JoinPaths(out.path(), "report.json"), json);
//   out.Commit();                               // now flags.out/report.json exists
#pragma once

#include <functional>
#include <memory>
#include <string>

namespace comic::io {

class ScopedTempPath;

class StagedFolder {
 public:
  // Checks that `target` is, or can be created as, a writable folder (CheckCreatableFolder),
  // then creates the staging folder ".<name>.staging-<pid>-XXXXXX" in the nearest existing
  // ancestor of `target`, registered for removal on SIGINT/SIGTERM. Throws comic::Error(kIo).
  explicit StagedFolder(const std::string& target);
  // Without Commit(), removes the staging folder and everything in it.
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  // Where to write: the staging folder, standing for `target`.
  const std::string& path() const { return staging_; }
  const std::string& target() const { return target_; }
  // `text` with the staging folder's path replaced by the target's (paths in reports and logs).
  std::string ToTargetPaths(const std::string& text) const;

  // Runs `body`, which writes into path(); a comic::Error it throws is rethrown with the staging
  // folder's path replaced by the target's, so a failure (a full disk) names the user's path,
  // never the hidden staging folder (issue 29).
  void NamingTarget(const std::function<void()>& body) const;

  // Moves everything staged into `target` (created if missing; files of the same name replaced,
  // subfolders merged) and removes the staging folder. Throws comic::Error(kIo) naming target.
  void Commit();

 private:
  std::string target_;
  std::string staging_;
  std::unique_ptr<ScopedTempPath> registered_;
  bool committed_ = false;
};

}  // namespace comic::io
