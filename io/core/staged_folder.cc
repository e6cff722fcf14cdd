#include "io/core/staged_folder.h"

#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/interrupt_cleanup.h"

namespace comic::io {
namespace {

namespace fs = std::filesystem;

// Moves the contents of `from` into the folder `to` (which exists): entries missing in `to` are
// renamed whole, files replace files, folders are merged.
void MergeInto(const fs::path& from, const fs::path& to, const std::string& target) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(from, ec)) {
    const fs::path destination = to / entry.path().filename();
    std::error_code type_ec;
    if (entry.is_directory(type_ec) && fs::is_directory(destination, type_ec)) {
      MergeInto(entry.path(), destination, target);
      continue;
    }
    COMIC_CHECK(!fs::is_directory(destination, type_ec) || entry.is_directory(type_ec), kIo,
                target << ": cannot replace the folder " << destination.string() << " with a file");
    std::error_code rename_ec;
    fs::rename(entry.path(), destination, rename_ec);
    COMIC_CHECK(!rename_ec, kIo,
                target << ": cannot move " << destination.filename().string()
                       << " into place: " << rename_ec.message());
  }
  COMIC_CHECK(!ec, kIo, target << ": cannot list the staged outputs: " << ec.message());
}

}  // namespace

StagedFolder::StagedFolder(const std::string& target) : target_(target) {
  const std::string ancestor = CheckCreatableFolder(target);
  const std::string name = fs::path(target).lexically_normal().filename().string();
  std::string pattern =
      (fs::path(ancestor) / ("." + (name.empty() ? std::string("out") : name) + ".staging-" +
                             std::to_string(::getpid()) + "-XXXXXX"))
          .string();
  COMIC_CHECK(::mkdtemp(pattern.data()) != nullptr, kIo,
              target << ": cannot create a staging folder in " << ancestor);
  staging_ = pattern;
  // mkdtemp makes it 0700; renamed into place it becomes the user's folder: the usual mode.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(staging_.c_str(), 0777 & ~mask);
  registered_ = std::make_unique<ScopedTempPath>(staging_);
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

std::string StagedFolder::ToTargetPaths(const std::string& text) const {
  std::string out = text;
  for (size_t at = out.find(staging_); at != std::string::npos; at = out.find(staging_, at)) {
    out.replace(at, staging_.size(), target_);
    at += target_.size();
  }
  return out;
}

void StagedFolder::NamingTarget(const std::function<void()>& body) const {
  try {
    body();
  } catch (const Error& e) {
    throw Error(e.kind(), ToTargetPaths(e.what()));
  }
}

void StagedFolder::Commit() {
  COMIC_CHECK(!committed_, kInvalidArgument, target_ << ": staged outputs already committed");
  std::error_code ec;
  if (!PathExists(target_)) {
    const fs::path parent = fs::path(target_).lexically_normal().parent_path();
    if (!parent.empty()) fs::create_directories(parent, ec);
    COMIC_CHECK(!ec, kIo, target_ << ": cannot create folder: " << ec.message());
    fs::rename(staging_, target_, ec);
    COMIC_CHECK(!ec, kIo, target_ << ": cannot move the outputs into place: " << ec.message());
  } else {
    COMIC_CHECK(IsDirectory(target_), kIo, target_ << ": exists and is not a folder");
    MergeInto(staging_, target_, target_);
    fs::remove_all(staging_, ec);
  }
  committed_ = true;
}

}  // namespace comic::io
