#include "io/core/staged_files.h"

#include <unistd.h>

#include <filesystem>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"

namespace comic::io {

namespace fs = std::filesystem;

StagedFiles::StagedFiles() = default;

StagedFiles::~StagedFiles() {
  if (committed_) return;
  for (const Entry& entry : entries_) {
    std::error_code ec;
    fs::remove(entry.temp, ec);
    fs::remove(entry.temp + "-journal", ec);
  }
}

std::string StagedFiles::Stage(const std::string& target, bool overwrite) {
  CheckWritableFile(target, overwrite);
  const fs::path path(target);
  Entry entry;
  entry.target = target;
  entry.temp =
      (path.parent_path() / ("." + path.stem().string() + ".staged" + std::to_string(::getpid()) +
                             "-" + std::to_string(entries_.size()) + path.extension().string()))
          .string();
  entry.registered = std::make_unique<ScopedTempPath>(entry.temp);
  entries_.push_back(std::move(entry));
  return entries_.back().temp;
}

void StagedFiles::Write(const std::string& target,
                        const std::function<void(const std::string&)>& write) {
  const Entry* staged = nullptr;
  for (const Entry& entry : entries_) {
    if (entry.target == target) staged = &entry;
  }
  COMIC_CHECK(staged != nullptr, kInvalidArgument, target << ": not staged");
  try {
    write(staged->temp);
  } catch (const Error& e) {
    std::string message = e.what();
    const std::string& temp = staged->temp;
    for (size_t at = message.find(temp); at != std::string::npos; at = message.find(temp, at)) {
      message.replace(at, temp.size(), target);
      at += target.size();
    }
    throw Error(e.kind(), message);
  }
}

void StagedFiles::WriteFile(const std::string& target, const std::string& contents) {
  Write(target, [&](const std::string& temp) { WriteFileAtomically(temp, contents); });
}

void StagedFiles::WriteImage(const std::string& target, const cv::Mat& image) {
  Write(target, [&](const std::string& temp) { WriteImageAtomically(temp, image); });
}

void StagedFiles::Commit() {
  COMIC_CHECK(!committed_, kInvalidArgument, "staged files already committed");
  for (const Entry& entry : entries_) {
    COMIC_CHECK(IsRegularFile(entry.temp), kIo, entry.target << ": writing failed");
  }
  for (const Entry& entry : entries_) {
    std::error_code ec;
    fs::rename(entry.temp, entry.target, ec);
    COMIC_CHECK(!ec, kIo, entry.target << ": cannot rename into place: " << ec.message());
  }
  committed_ = true;
}

}  // namespace comic::io
