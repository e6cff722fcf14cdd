#include "io/core/protected_inputs.h"

#include <sys/stat.h>

#include <filesystem>

#include "io/core/error.h"

namespace comic::io {
namespace {

namespace fs = std::filesystem;

bool SameFile(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

}  // namespace

bool IsSameOrInside(const std::string& path, const std::string& input) {
  if (path.empty() || input.empty()) return false;
  struct stat input_stat;
  if (::stat(input.c_str(), &input_stat) != 0) return false;
  // The existing part resolved (symlinks, ".."), the rest as written; then every ancestor.
  std::error_code ec;
  fs::path candidate = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) candidate = fs::absolute(path).lexically_normal();
  while (true) {
    struct stat candidate_stat;
    if (::stat(candidate.c_str(), &candidate_stat) == 0 && SameFile(candidate_stat, input_stat)) {
      return true;
    }
    if (!candidate.has_relative_path()) return false;  // reached the root
    candidate = candidate.parent_path();
  }
}

void CheckOutputsAvoidInputs(const std::vector<NamedPath>& outputs,
                             const std::vector<NamedPath>& inputs) {
  for (const NamedPath& output : outputs) {
    for (const NamedPath& input : inputs) {
      if (!IsSameOrInside(output.path, input.path)) continue;
      struct stat input_stat;
      const bool input_is_folder =
          ::stat(input.path.c_str(), &input_stat) == 0 && S_ISDIR(input_stat.st_mode);
      struct stat output_stat;
      const bool same =
          ::stat(output.path.c_str(), &output_stat) == 0 && SameFile(output_stat, input_stat);
      if (same) {
        throw Error(ErrorKind::kInvalidArgument,
                    output.path + ": " + output.name + " is the input " + input.name +
                        (output.path == input.path ? "" : " (" + input.path + ")") +
                        "; refusing to write over an input");
      }
      throw Error(ErrorKind::kInvalidArgument, output.path + ": " + output.name +
                                                   " lies inside the input " + input.name + " " +
                                                   (input_is_folder ? "folder " : "") + input.path +
                                                   "; refusing to write among the inputs");
    }
  }
}

void CheckOutputFolderAvoidsInputs(const NamedPath& output_folder,
                                   const std::vector<NamedPath>& inputs) {
  CheckOutputsAvoidInputs({output_folder}, inputs);
  for (const NamedPath& input : inputs) {
    if (input.path.empty() || !IsSameOrInside(input.path, output_folder.path)) continue;
    throw Error(ErrorKind::kInvalidArgument,
                output_folder.path + ": " + output_folder.name + " holds the input " + input.name +
                    " " + input.path + "; refusing to write where it could be replaced");
  }
}

void CheckWrittenPathsAvoidInputs(const std::vector<NamedPath>& written,
                                  const std::vector<NamedPath>& inputs) {
  for (const NamedPath& output : written) {
    for (const NamedPath& input : inputs) {
      if (output.path.empty() || input.path.empty()) continue;
      if (IsSameOrInside(input.path, output.path)) {
        throw Error(ErrorKind::kInvalidArgument,
                    input.path + ": the input " + input.name +
                        " would be replaced: " + output.name + " writes " + output.path +
                        "; refusing (choose another " + output.name + ")");
      }
      if (IsSameOrInside(output.path, input.path)) {
        throw Error(ErrorKind::kInvalidArgument,
                    output.path + ": " + output.name + " writes it inside the input " + input.name +
                        " " + input.path + "; refusing to write among the inputs");
      }
    }
  }
}

}  // namespace comic::io
