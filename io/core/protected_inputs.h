// Inputs are sacred: an output path that is one of a run's inputs, or lies inside an input
// folder, is refused before any work (issue 29: `comic_detect img.png --json img.png` replaced
// the image, `comic_sfm frames -o frames` left trajectory.png among the frames). Paths are
// compared as files, by device and inode after following symlinks and "..", not by name, so
// `./img.png`, a symlink to it and a hard link are all the same input.
//
//   io::CheckOutputsAvoidInputs({{"--json", json_path}, {"--overlay", overlay_path}},
//                               {{"IMAGE", input}});
#pragma once

#include <string>
#include <vector>

namespace comic::io {

// A path and what names it on the command line ("--json", "IMAGE", "FRAMES"); an empty path is
// an unset option and is skipped.
struct NamedPath {
  std::string name;
  std::string path;
};

// True if `path` is the file or folder `input` (same device and inode) or lies inside the
// folder `input`. Parts of `path` that do not exist yet are taken as written; a missing `input`
// holds nothing.
bool IsSameOrInside(const std::string& path, const std::string& input);

// Throws comic::Error(kInvalidArgument), naming the output, its option and the input, if an
// output is, or lies inside, one of the inputs.
void CheckOutputsAvoidInputs(const std::vector<NamedPath>& outputs,
                             const std::vector<NamedPath>& inputs);

// For an output folder the app fills with files of its own naming (comic_render's images/,
// scene.json, ...): throws comic::Error(kInvalidArgument) if an input is that folder or lies
// inside it, where a written file could replace it; then as CheckOutputsAvoidInputs.
void CheckOutputFolderAvoidsInputs(const NamedPath& output_folder,
                                   const std::vector<NamedPath>& inputs);

// For a run that writes chosen files and folders into an output folder (comic_sfm's models,
// reports, tracks.db): throws comic::Error(kInvalidArgument), naming the input and the written
// path, if an input is one of `written` (a file, or a folder whose files the run may replace),
// lies inside one, or holds one. An input elsewhere in the output folder (a COLMAP project's
// images/ as FRAMES with --output the project) is not touched and passes. `written` name the
// option that writes them ("--output"); empty paths are skipped.
void CheckWrittenPathsAvoidInputs(const std::vector<NamedPath>& written,
                                  const std::vector<NamedPath>& inputs);

}  // namespace comic::io
