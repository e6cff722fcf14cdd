// Running the real `colmap` program (COLMAP 3.8, headless) from the library: the mapper on an
// exported database, the model analyzer and the model converter, with every run's output kept in
// a log file. Used by the COLMAP comparison and by the tests that check our exports with COLMAP.
//
//   const auto model = comic::sfm::RunColmapMapper("out.db", "frames/", "sparse/",
//                                                  mapper_options, "colmap.log");
//   if (model) {
//     const comic::sfm::ColmapModelStats stats = AnalyzeColmapModel(*model, "colmap.log");
//   }
//
// Every function that runs COLMAP throws comic::Error(kExternal) naming the command, its exit
// status, the last line it printed and the log file when the program cannot be started or fails.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sfm/colmap/colmap_export.h"

namespace comic::sfm {

// True if `executable` (a name looked up on PATH, or a path) exists and can be executed.
bool IsColmapAvailable(const std::string& executable = "colmap");

// `args` as one shell command line, each argument quoted where the shell would split or expand
// it, for printing commands users can paste.
std::string ShellCommandLine(const std::vector<std::string>& args);

// User and system CPU time, in seconds, of every child process this process has waited for
// (RunColmap waits for each), all threads: the CPU column of the COLMAP comparisons.
double ChildrenCpuSeconds();

// Runs `executable args...` with QT_QPA_PLATFORM=offscreen (no display needed) and stdin from
// /dev/null, appending a line "$ <command>" and then the program's stdout and stderr to
// `log_path`. Returns when the program has exited; throws comic::Error(kExternal) unless it exited
// with status 0.
void RunColmap(const std::vector<std::string>& args, const std::string& log_path,
               const std::string& executable = "colmap");

struct ColmapMapperOptions {
  // --Mapper.num_threads (-1: COLMAP's default, every core).
  int num_threads = -1;
  // --Mapper.init_max_forward_motion: COLMAP starts only from a pair whose unit translation has
  // |t_z| below this. COLMAP's default 0.95 rejects every pair of a forward-moving video; 1.0
  // accepts them.
  double init_max_forward_motion = 0.95;
  // --Mapper.init_min_tri_angle, degrees: COLMAP starts only from a pair whose inliers' median
  // triangulation angle exceeds this (it halves it once when no pair is found). COLMAP's default
  // 16 is far above what forward motion over a few frames gives.
  double init_min_tri_angle = 16.0;
  // --Mapper.ba_refine_focal_length, _principal_point, _extra_params (COLMAP's defaults: refine
  // the focal length and the distortion, keep the principal point).
  bool ba_refine_focal_length = true;
  bool ba_refine_principal_point = false;
  bool ba_refine_extra_params = true;
  // --Mapper.min_model_size: COLMAP discards models with fewer registered images (default 10,
  // which is most of a short sequence).
  int min_model_size = 10;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// The options an exported sequence needs: init_max_forward_motion 1.0 when no verified pair
// allows COLMAP's default initialisation (summary.num_pairs_allowing_default_init == 0);
// init_min_tri_angle half the largest median triangulation angle of a pair with 100 inliers
// (rounded down to 0.1 degree, at least 0.1) when that is below COLMAP's default; and the
// intrinsics held fixed (no focal length, principal point or distortion refinement) when known;
// min_model_size a quarter of the frames (at least 3) when that is below COLMAP's default 10, so a
// partial model of a short sequence is kept rather than silently dropped. num_threads stays -1.
ColmapMapperOptions RecommendedColmapMapperOptions(const ColmapExportSummary& summary);

// The arguments of `colmap mapper` (without the program name): the three paths, then
// --Mapper.num_threads (unless -1) and every other option of ColmapMapperOptions, explicitly.
std::vector<std::string> ColmapMapperArguments(const std::string& database_path,
                                               const std::string& image_path,
                                               const std::string& output_path,
                                               const ColmapMapperOptions& options);

// Where the printed `colmap mapper` command for the database at `database_path` writes its
// models: colmap/sparse beside the database, a folder of COLMAP's own, never comic_sfm's sparse/0
// when the database lies in its --output (issue 29: the printed command replaced images.bin and
// points3D.bin there).
std::string ColmapMapperOutputBeside(const std::string& database_path);

// The exact commands to run the mapper by hand: "mkdir -p OUT && colmap mapper ...".
std::string ColmapMapperCommandLine(const std::string& database_path, const std::string& image_path,
                                    const std::string& output_path,
                                    const ColmapMapperOptions& options);

// Creates `output_path` (which must not hold models already: comic::Error(kIo)), runs
// `colmap mapper` and returns the largest model it wrote (see FindLargestColmapModel), or
// std::nullopt if it wrote none because it found no initial pair (COLMAP 3.8 then exits with
// status 1; any other failure throws comic::Error(kExternal)).
std::optional<std::string> RunColmapMapper(const std::string& database_path,
                                           const std::string& image_path,
                                           const std::string& output_path,
                                           const ColmapMapperOptions& options,
                                           const std::string& log_path,
                                           const std::string& executable = "colmap");

// Registered images of the model in `model_path` (images.bin or images.txt). Throws
// comic::Error(kNotFound / kInvalidData).
int64_t NumRegisteredImagesOfColmapModel(const std::string& model_path);

// The model with the most registered images among the numbered sub-folders (0, 1, ...) of a
// mapper output folder; ties go to the lower number. COLMAP numbers models in the order it
// finishes them, so sparse/0 is not always the largest. std::nullopt if there is none.
std::optional<std::string> FindLargestColmapModel(const std::string& output_path);

// The time COLMAP's mapper spent in bundle adjustment, from its log: the sum of the "Time : x [s]"
// lines of its bundle adjustment reports, those under the heading "Global bundle adjustment" as
// global and the others (printed after each image registration) as local. `log_text` is the output
// of one `colmap mapper` run (for a log holding several runs, the part after its last
// "$ ... mapper" line is used). Zero when the log holds no report.
struct ColmapBundleAdjustmentTimes {
  double local_s = 0.0;
  double global_s = 0.0;
  int num_local = 0;
  int num_global = 0;
};
ColmapBundleAdjustmentTimes ParseColmapBundleAdjustmentTimes(const std::string& log_text);

// What `colmap model_analyzer` reports.
struct ColmapModelStats {
  int64_t num_cameras = 0;
  int64_t num_images = 0;
  int64_t num_registered_images = 0;
  int64_t num_points3D = 0;
  int64_t num_observations = 0;
  double mean_track_length = 0.0;
  double mean_observations_per_image = 0.0;
  double mean_reprojection_error = 0.0;  // pixels
};

// Parses model_analyzer's report ("Registered images: 12", "Mean reprojection error: 0.51px",
// ...; glog prefixes are ignored). Throws comic::Error(kInvalidData) if a field is missing.
ColmapModelStats ParseColmapModelAnalyzerOutput(const std::string& text);

// Runs `colmap model_analyzer --path MODEL` and parses its report.
ColmapModelStats AnalyzeColmapModel(const std::string& model_path, const std::string& log_path,
                                    const std::string& executable = "colmap");

// Runs `colmap model_converter` from `input_path` into `output_path` (created if needed);
// `output_type` is "TXT" or "BIN".
void ConvertColmapModel(const std::string& input_path, const std::string& output_path,
                        const std::string& output_type, const std::string& log_path,
                        const std::string& executable = "colmap");

}  // namespace comic::sfm
