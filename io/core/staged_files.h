// All or nothing for a run's output files outside a staged folder (comic_detect's overlay and
// JSON, a COLMAP database): each is written to a hidden temporary file beside its target and the
// whole set is renamed into place only at Commit(), after every one was written, so a failed
// second output never leaves the first behind (issue 19).
//
//   io::StagedFiles outputs;
//   outputs.Stage(overlay_path);                 // checked now, before any work
//   outputs.Stage(json_path);
//   ...
//   outputs.WriteImage(overlay_path, overlay);   // to its temp file
//   outputs.WriteFile(json_path, json);
//   outputs.Commit();                            // both appear
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace cv {
class Mat;
}

namespace comic::io {

class ScopedTempPath;

class StagedFiles {
 public:
  StagedFiles();
  // Removes every staged file not committed.
  ~StagedFiles();
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;

  // Checks that `target` can be written (CheckWritableFile with `overwrite`) and returns the
  // temporary path to write it to (same folder and extension; registered for removal on
  // SIGINT/SIGTERM). Throws comic::Error(kIo) naming `target`.
  std::string Stage(const std::string& target, bool overwrite = true);

  // Write a staged target's temporary file (WriteFileAtomically / WriteImageAtomically, or
  // `write(temp_path)`); errors name `target`, never the temporary name. Throws
  // comic::Error(kInvalidArgument) for a target that was not staged.
  void WriteFile(const std::string& target, const std::string& contents);
  void WriteImage(const std::string& target, const cv::Mat& image);
  void Write(const std::string& target, const std::function<void(const std::string&)>& write);

  // Renames every staged file over its target, in the order staged. Throws comic::Error(kIo)
  // naming the target whose temporary file is missing or cannot be renamed.
  void Commit();

 private:
  struct Entry {
    std::string target;
    std::string temp;
    std::unique_ptr<ScopedTempPath> registered;
  };
  std::vector<Entry> entries_;
  bool committed_ = false;
};

}  // namespace comic::io
