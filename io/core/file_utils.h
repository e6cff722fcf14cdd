// Files and folders: existence checks with clear errors, and atomic writes, so that a failed or
// interrupted run never leaves a half-written output behind (write a temporary file in the same
// folder, then rename it over the target).
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace cv {
class Mat;
}

namespace comic::io {

bool PathExists(const std::string& path);
bool IsDirectory(const std::string& path);
bool IsRegularFile(const std::string& path);

// Lower-case extension without the dot ("PNG" -> "png"); empty if none.
std::string FileExtension(const std::string& path);
std::string FileName(const std::string& path);    // last path component
std::string ParentPath(const std::string& path);  // "" for a bare file name
std::string JoinPaths(const std::string& a, const std::string& b);

// An entry of a folder that is not a regular file (nor a symlink to one), and what it is:
// "a folder", "a FIFO", "a socket", "a device", "a dangling symlink", "a symlink loop", ...
struct SkippedEntry {
  std::string name;
  std::string kind;
};

// Regular files directly inside `folder` (names only, not paths), naturally sorted; symlinks to
// regular files count as files. The other entries go to `skipped` (if given), naturally sorted.
// Throws comic::Error (kNotFound / kInvalidArgument) if `folder` is missing or not a folder.
std::vector<std::string> ListFiles(const std::string& folder,
                                   std::vector<SkippedEntry>* skipped = nullptr);

// One line for entries a reader skipped (empty if none): "skipped 3 entries that are not regular
// files, the first 'a.png' (a FIFO)".
std::string DescribeSkippedEntries(const std::vector<SkippedEntry>& skipped);

// Creates `folder` and its parents if needed and checks that a file can be created in it.
// Throws comic::Error(kIo) naming the folder otherwise.
void EnsureWritableDirectory(const std::string& folder);

// Checks, without creating anything, that `folder` could be a folder: it is not a file, and its
// nearest existing ancestor is a folder (writable or not). Returns that ancestor. Throws
// comic::Error(kIo) naming the path ("X is not a folder" when X is a file). For a folder that is
// only written if it can be (a cache): a read-only one is still read.
std::string CheckFolderPath(const std::string& folder);

// Checks, without creating anything, that `folder` is a writable folder or could be created:
// it is not a file, and its nearest existing ancestor is a writable folder. Returns that
// ancestor. Throws comic::Error(kIo) naming the path ("X is not a folder" when X is a file).
std::string CheckCreatableFolder(const std::string& folder);

// Checks, before any work is done, that a file can later be written at `path`: its folder exists
// and is writable and `path` is not a folder (nor, unless `overwrite`, an existing file). Apps call
// this up front so a bad output path fails in a second, not after a long run. Throws
// comic::Error(kIo) naming the path.
void CheckWritableFile(const std::string& path, bool overwrite = true);

// Reads a whole text or binary file. Throws comic::Error(kNotFound / kIo).
std::string ReadFileToString(const std::string& path);

// Reads the regular file at `path` (or the one a symlink names), never more than the size it has
// when opened, so that a device, a stream or a growing file cannot make the read endless. Throws
// comic::Error: kNotFound, kInvalidData for anything but a regular file (a FIFO is not waited
// for, a stream path such as /dev/stdin is refused too), kIo for an open or read error.
std::string ReadRegularFile(const std::string& path);

// How a finished temporary file takes the place of the target: (temp_path, path). Empty:
// rename(2). io/colmap/sqlite_file.h checks and locks an old database around the rename.
using MoveIntoPlace = std::function<void(const std::string&, const std::string&)>;

// Calls `write(temp_path)`, which must create the file at temp_path, then moves it to `path`
// (`move`, by default a rename). On any exception the temporary file is removed and the
// exception is rethrown with the temporary name replaced by `path`, so `path` is either the
// complete new file or untouched. If `overwrite` is false and `path` exists, throws
// comic::Error(kIo) before writing anything.
void WriteAtomically(const std::string& path, const std::function<void(const std::string&)>& write,
                     bool overwrite = true, const MoveIntoPlace& move = {});

// Atomic write of bytes to `path` (see WriteAtomically).
void WriteFileAtomically(const std::string& path, const std::string& contents,
                         bool overwrite = true);

// A file written by streaming into it: where it goes and what writes its contents.
struct StreamedFile {
  std::string path;
  std::function<void(std::ostream&)> write;
};

// Streams every file into its own temporary file, then moves them all into place (the last
// first), so a file never needs to be held in memory whole (a 5000-frame model's images.txt is
// 369 MB), and anything thrown while writing (a full disk, a model that cannot be serialised)
// leaves every old file whole and no temporary file behind. Only a failed rename, after the disk
// has taken every byte, can leave some files new and others old.
void WriteFilesAtomically(const std::vector<StreamedFile>& files);

// Throws comic::Error(kInvalidArgument) naming `what` (the option) and `path` unless OpenCV can
// encode an image in the format `path`'s extension names (cv::haveImageWriter); apps call it
// before any work, so "--overlay out.xyz" fails in a second with our words, not after the work
// with OpenCV's "could not find a writer for the specified extension".
void CheckImageOutputFormat(const std::string& path, const std::string& what);

// Atomic cv::imwrite; the format follows the extension of `path`. Throws comic::Error(kIo)
// naming `path`, with what the codec library printed (libpng's "Write Error" on a full disk)
// inside the one message instead of on stderr.
void WriteImageAtomically(const std::string& path, const cv::Mat& image);

}  // namespace comic::io
