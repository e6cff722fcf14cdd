#include "io/core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "io/core/error.h"

namespace comic::io {
namespace {

bool StartsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

std::string KindOf(const struct stat& info) {
  if (S_ISFIFO(info.st_mode)) return "a FIFO";
  if (S_ISSOCK(info.st_mode)) return "a socket";
  if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode)) return "a device";
  return "not a regular file";
}

}  // namespace

bool IsStreamPath(const std::string& path) {
  return path == "/dev/stdin" || StartsWith(path, "/dev/fd/") || StartsWith(path, "/proc/self/fd/");
}

void CheckInputFile(const std::string& path) {
  struct stat info;
  COMIC_CHECK(::stat(path.c_str(), &info) == 0, kNotFound,
              path << ": no such file"
                   << (errno == ENOENT ? "" : std::string(" (") + std::strerror(errno) + ")"));
  COMIC_CHECK(!S_ISDIR(info.st_mode), kInvalidArgument, path << ": is a folder, expected a file");
  if (S_ISREG(info.st_mode) || (IsStreamPath(path) && !S_ISSOCK(info.st_mode))) return;
  throw Error(ErrorKind::kInvalidData, path + ": not a regular file (" + KindOf(info) +
                                           "); refusing to read it, which could block forever");
}

}  // namespace comic::io
