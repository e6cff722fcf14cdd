#include "io/core/file_utils.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "io/core/error.h"
#include "io/core/input_file.h"
#include "io/core/interrupt_cleanup.h"
#include "io/core/library_messages.h"
#include "io/core/natural_sort.h"

namespace comic::io {
namespace fs = std::filesystem;

bool PathExists(const std::string& path) {
  std::error_code ec;
  return fs::exists(path, ec);
}

bool IsDirectory(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

bool IsRegularFile(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string FileExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string FileName(const std::string& path) { return fs::path(path).filename().string(); }

std::string ParentPath(const std::string& path) { return fs::path(path).parent_path().string(); }

std::string JoinPaths(const std::string& a, const std::string& b) {
  if (a.empty()) return b;
  return (fs::path(a) / b).string();
}

namespace {

// What a folder entry that is not a regular file is, following symlinks.
std::string EntryKind(const fs::path& path) {
  struct stat info;
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ELOOP) return "a symlink loop";
    struct stat link;
    if (::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) return "a dangling symlink";
    return std::string("unreadable: ") + std::strerror(errno);
  }
  if (S_ISDIR(info.st_mode)) return "a folder";
  if (S_ISFIFO(info.st_mode)) return "a FIFO";
  if (S_ISSOCK(info.st_mode)) return "a socket";
  if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode)) return "a device";
  return "not a regular file";
}

}  // namespace

std::vector<std::string> ListFiles(const std::string& folder, std::vector<SkippedEntry>* skipped) {
  COMIC_CHECK(PathExists(folder), kNotFound, folder << ": no such file or folder");
  COMIC_CHECK(IsDirectory(folder), kInvalidArgument, folder << ": not a folder");
  std::vector<std::string> names;
  std::vector<std::string> skipped_names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    std::error_code type_ec;
    if (entry.is_regular_file(type_ec)) {
      names.push_back(entry.path().filename().string());
    } else {
      skipped_names.push_back(entry.path().filename().string());
    }
  }
  COMIC_CHECK(!ec, kIo, folder << ": cannot list folder: " << ec.message());
  NaturalSort(&names);
  if (skipped != nullptr) {
    NaturalSort(&skipped_names);
    skipped->clear();
    for (const std::string& name : skipped_names) {
      skipped->push_back({name, EntryKind(fs::path(folder) / name)});
    }
  }
  return names;
}

std::string DescribeSkippedEntries(const std::vector<SkippedEntry>& skipped) {
  if (skipped.empty()) return "";
  const bool one = skipped.size() == 1;
  return "skipped " + std::to_string(skipped.size()) +
         (one ? " entry that is not a regular file: '"
              : " entries that are not regular files, the first '") +
         skipped.front().name + "' (" + skipped.front().kind + ")";
}

void EnsureWritableDirectory(const std::string& folder) {
  COMIC_CHECK(!folder.empty(), kInvalidArgument, "output folder name is empty");
  std::error_code ec;
  if (PathExists(folder)) {
    COMIC_CHECK(IsDirectory(folder), kIo, folder << ": exists and is not a folder");
  } else {
    CheckCreatableFolder(folder);
    fs::create_directories(folder, ec);
    COMIC_CHECK(!ec, kIo, folder << ": cannot create folder: " << ec.message());
  }
  COMIC_CHECK(::access(folder.c_str(), W_OK | X_OK) == 0, kIo,
              folder << ": folder is not writable");
}

std::string CheckFolderPath(const std::string& folder) {
  COMIC_CHECK(!folder.empty(), kInvalidArgument, "output folder name is empty");
  COMIC_CHECK(!PathExists(folder) || IsDirectory(folder), kIo,
              folder << ": exists and is not a folder");
  // The nearest existing ancestor must be a folder (a file there: "X is not a folder").
  fs::path existing = fs::path(folder);
  std::error_code ec;
  while (!existing.empty() && !fs::exists(existing, ec)) existing = existing.parent_path();
  const std::string ancestor = existing.empty() ? "." : existing.string();
  COMIC_CHECK(IsDirectory(ancestor), kIo,
              folder << ": cannot create it, " << ancestor << " is not a folder");
  return ancestor;
}

std::string CheckCreatableFolder(const std::string& folder) {
  const std::string ancestor = CheckFolderPath(folder);
  COMIC_CHECK(::access(ancestor.c_str(), W_OK | X_OK) == 0, kIo,
              folder << ": folder " << ancestor << " is not writable");
  return ancestor;
}

void CheckWritableFile(const std::string& path, bool overwrite) {
  COMIC_CHECK(!path.empty(), kInvalidArgument, "output file name is empty");
  COMIC_CHECK(!IsDirectory(path), kIo, path << ": is a folder, cannot write a file there");
  COMIC_CHECK(overwrite || !PathExists(path), kIo,
              path << ": already exists (refusing to overwrite)");
  const std::string parent = ParentPath(path).empty() ? "." : ParentPath(path);
  COMIC_CHECK(!PathExists(parent) || IsDirectory(parent), kIo,
              path << ": " << parent << " is not a folder");
  COMIC_CHECK(IsDirectory(parent), kIo, path << ": folder " << parent << " does not exist");
  COMIC_CHECK(::access(parent.c_str(), W_OK | X_OK) == 0, kIo,
              path << ": folder " << parent << " is not writable");
}

std::string ReadFileToString(const std::string& path) {
  CheckInputFile(path);
  std::ifstream in(path, std::ios::binary);
  COMIC_CHECK(in.good(), kIo, path << ": cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  COMIC_CHECK(!in.bad(), kIo, path << ": read failed");
  return buffer.str();
}

std::string ReadRegularFile(const std::string& path) {
  CheckInputFile(path);
  // Non-blocking, and checked on the open descriptor: a FIFO put in the file's place after the
  // check above is refused, not waited for.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  COMIC_CHECK(fd >= 0, kIo, path << ": cannot open for reading: " << std::strerror(errno));
  struct stat info;
  const bool regular = ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode);
  if (!regular) ::close(fd);
  COMIC_CHECK(regular, kInvalidData, path << ": not a regular file; refusing to read it");
  // The size as opened bounds the read: a file that keeps growing is not followed.
  std::string bytes(static_cast<size_t>(info.st_size), '\0');
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t got = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    done += static_cast<size_t>(got);
  }
  const int read_errno = errno;
  ::close(fd);
  COMIC_CHECK(done == bytes.size(), kIo,
              path << ": read failed after " << done << " of " << bytes.size() << " bytes"
                   << (done < bytes.size() && read_errno != 0
                           ? std::string(" (") + std::strerror(read_errno) + ")"
                           : std::string()));
  return bytes;
}

void WriteAtomically(const std::string& path, const std::function<void(const std::string&)>& write,
                     bool overwrite, const MoveIntoPlace& move) {
  CheckWritableFile(path, overwrite);
  // The temporary name keeps the extension, so writers that pick the format from it still work.
  const fs::path target(path);
  const std::string temp =
      (target.parent_path() / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) +
                               target.extension().string()))
          .string();
  // Removed on SIGINT/SIGTERM too, with an SQLite -journal beside it.
  const ScopedTempPath registered(temp);
  auto remove_temp = [&] {
    std::error_code ec;
    fs::remove(temp, ec);
    fs::remove(temp + "-journal", ec);
  };
  try {
    write(temp);
    COMIC_CHECK(IsRegularFile(temp), kIo, path << ": writing failed");
    if (move) {
      move(temp, path);
    } else {
      std::error_code ec;
      fs::rename(temp, path, ec);
      COMIC_CHECK(!ec, kIo, path << ": cannot rename temporary file into place: " << ec.message());
    }
  } catch (const Error& e) {
    remove_temp();
    // The user knows the path they gave, not our hidden temporary name.
    std::string message = e.what();
    for (size_t at = message.find(temp); at != std::string::npos; at = message.find(temp, at)) {
      message.replace(at, temp.size(), path);
      at += path.size();
    }
    throw Error(e.kind(), message);
  } catch (...) {
    remove_temp();
    throw;
  }
}

namespace {

// Writes `size` bytes to the new file `temp`; errors name `path` and say why (errno: "No space
// left on device"), checked up to the close, where a full disk often shows first.
void WriteBytes(const std::string& temp, const char* data, size_t size, const std::string& path) {
  std::FILE* file = std::fopen(temp.c_str(), "wb");
  COMIC_CHECK(file != nullptr, kIo, path << ": cannot open for writing: " << std::strerror(errno));
  const bool written = std::fwrite(data, 1, size, file) == size && std::fflush(file) == 0;
  const int write_errno = errno;
  const bool closed = std::fclose(file) == 0;
  COMIC_CHECK(written && closed, kIo,
              path << ": write failed: " << std::strerror(written ? errno : write_errno));
}

// Streams `write` into the new file `temp`; errors name `path` and say why, as WriteBytes.
void WriteStream(const std::string& temp, const std::function<void(std::ostream&)>& write,
                 const std::string& path) {
  std::ofstream out(temp, std::ios::binary);
  COMIC_CHECK(out.is_open(), kIo, path << ": cannot open for writing: " << std::strerror(errno));
  write(out);
  out.flush();
  const bool written = out.good();
  const int write_errno = errno;
  out.close();
  COMIC_CHECK(written && !out.fail(), kIo,
              path << ": write failed: " << std::strerror(written ? errno : write_errno));
}

// Writes files[first..] each into its temporary file, the next inside the previous one's
// WriteAtomically, so every byte is on disk before the first rename.
void WriteFilesAtomicallyFrom(const std::vector<StreamedFile>& files, size_t first) {
  if (first == files.size()) return;
  const StreamedFile& file = files[first];
  WriteAtomically(file.path, [&](const std::string& temp) {
    WriteStream(temp, file.write, file.path);
    WriteFilesAtomicallyFrom(files, first + 1);
  });
}

}  // namespace

void WriteFileAtomically(const std::string& path, const std::string& contents, bool overwrite) {
  WriteAtomically(
      path,
      [&](const std::string& temp) { WriteBytes(temp, contents.data(), contents.size(), path); },
      overwrite);
}

void WriteFilesAtomically(const std::vector<StreamedFile>& files) {
  WriteFilesAtomicallyFrom(files, 0);
}

void CheckImageOutputFormat(const std::string& path, const std::string& what) {
  bool writable = false;
  try {
    writable = !FileExtension(path).empty() && cv::haveImageWriter(path);
  } catch (const cv::Exception&) {
  }
  COMIC_CHECK(writable, kInvalidArgument,
              path << ": " << what
                   << " needs an image file name OpenCV can write (.png, .jpg, .bmp, .tif, .ppm, "
                      "...), got the extension '"
                   << FileExtension(path) << "'");
}

void WriteImageAtomically(const std::string& path, const cv::Mat& image) {
  COMIC_CHECK(!image.empty(), kInvalidArgument, path << ": refusing to write an empty image");
  // Encoded in memory, then written by us: a full disk is our one line naming `path`, never
  // libpng's "Write Error" on stderr, and never a truncated file the encoder did not notice.
  const std::string extension = "." + FileExtension(path);
  std::vector<uchar> encoded;
  bool ok = false;
  std::string opencv_error;
  const std::string library_message = CaptureLibraryMessages([&] {
    try {
      ok = cv::imencode(extension, image, encoded);
    } catch (const cv::Exception& e) {
      opencv_error = e.err;
    }
  });
  const std::string detail = !library_message.empty() ? library_message : opencv_error;
  COMIC_CHECK(ok && !encoded.empty(), kIo,
              path << ": cannot encode the image as '" << extension << "'"
                   << (detail.empty() ? "" : " (" + detail + ")"));
  WriteAtomically(path, [&](const std::string& temp) {
    WriteBytes(temp, reinterpret_cast<const char*>(encoded.data()), encoded.size(), path);
  });
}

}  // namespace comic::io
