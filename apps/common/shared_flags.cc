#include "apps/common/shared_flags.h"

#include "frontend/detector_factory.h"
#include "sfm/run/tracker_option_table.h"

namespace comic::apps {

void AddOutputFolderFlag(ArgParser& parser, std::string* folder) {
  parser.AddOption("output", "DIR", "output folder (created if needed)", folder);
  parser.AddShortName('o', "output");
  parser.AddDeprecatedAlias("out", "output");
}

void AddThreadsFlag(ArgParser& parser, int* threads) {
  parser.AddOption("threads", "N",
                   "worker threads for all the work (0 = one per core); the output does not "
                   "depend on it",
                   threads);
}

void AddQuietFlag(ArgParser& parser, bool* quiet) {
  parser.AddFlag("quiet", "no progress messages", quiet);
  parser.AddShortName('q', "quiet");
}

void AddJsonFlag(ArgParser& parser, std::string* path) {
  parser.AddOption("json", "FILE", "also write the results as JSON", path);
}

void AddResizeHeightFlag(ArgParser& parser, int* height) {
  parser.AddOption("resize-height", "H",
                   "resize to height H first, keeping the aspect ratio (0 = original size)",
                   height);
}

void AddDetectorFlag(ArgParser& parser, std::string* name) {
  std::string names;
  for (const std::string& detector : frontend::DetectorNames()) {
    names += (names.empty() ? "" : ", ") + detector;
  }
  parser.AddOption("detector", "NAME",
                   "feature detector: " + names +
                       ", or several joined by '+' (e.g. comic+hessian: each detector's features "
                       "tracked on their own, the tracks used together)",
                   name);
}

void AddScaleLevelsFlag(ArgParser& parser, int* levels) {
  parser.AddOption("scale-levels", "N",
                   "detect on N levels of an image pyramid, each half the size of the one before "
                   "(1 = the image as given only); features keep their level's scale",
                   levels);
}

void AddDetectorListFlag(ArgParser& parser, std::string* list) {
  parser.AddOption("detectors", "LIST", "comma-separated detectors, one run each (empty = all)",
                   list);
}

namespace {

// The tracker table's flag, bound to another app's field (the meaning is written once).
template <typename T>
void AddTrackerTableFlag(ArgParser& parser, const std::string& flag, T* value) {
  const sfm::TrackerOption entry = sfm::FindTrackerOption(flag);
  parser.AddOption(entry.flag, entry.metavar, entry.help, value);
}

}  // namespace

void AddMaxFeaturesFlag(ArgParser& parser, int* count) {
  AddTrackerTableFlag(parser, "max-features", count);
}

void AddSearchRadiusFlag(ArgParser& parser, double* radius) {
  AddTrackerTableFlag(parser, "search-radius", radius);
}

void AddMaxCostFlag(ArgParser& parser, double* cost) {
  AddTrackerTableFlag(parser, "max-cost", cost);
}

void AddMinSideOverlapFlag(ArgParser& parser, int* pixels) {
  parser.AddOption("min-side-overlap", "PX",
                   "split matching: fewest shared pixels for a side pairing to count (of 529)",
                   pixels);
}

void AddCalibratedCostFlags(ArgParser& parser, double* min_side_fraction, double* noise_sigma,
                            bool* noise_from_pair) {
  parser.AddOption("min-side-fraction", "F",
                   "calibrated cost: smallest share of the patch a side pairing must cover",
                   min_side_fraction);
  parser.AddOption("side-noise-sigma", "S",
                   "calibrated cost: noise sigma (grey levels) that calibrates side costs",
                   noise_sigma);
  parser.AddFlag("side-noise-from-pair",
                 "calibrated cost: sigma from each pair instead (2 sigma^2 = median full-patch "
                 "cost of its mutual-best matches)",
                 noise_from_pair);
}

void AddIntrinsicsFlag(ArgParser& parser, std::string* path) {
  parser.AddOption("intrinsics", "FILE",
                   "intrinsics of the frames as stored: 'fx fy cx cy [k1 k2 p1 p2]', a 3x3 K or a "
                   "3x4 P (KITTI calib.txt), an OpenCV calibration .yml/.xml (camera_matrix, "
                   "distortion_coefficients) or a COLMAP cameras.txt (its first camera)",
                   path);
}

void AddCameraModelFlag(ArgParser& parser, std::string* name) {
  parser.AddOption("camera-model", "NAME",
                   "camera model: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL or OPENCV "
                   "(COLMAP's names; default SIMPLE_RADIAL without --intrinsics, else the file's "
                   "model, converted where that loses nothing)",
                   name);
}

void AddObjectRegionFlags(ArgParser& parser, ObjectRegionFlags* flags) {
  parser.AddOption("masks", "DIR", "object region: a folder of per-frame masks (non-zero = object)",
                   &flags->masks);
  parser.AddOption("regions", "FILE",
                   "object region: a region file, line k = frame k (VOT polygons or OTB boxes)",
                   &flags->regions);
  parser.AddOption("boundary-band", "PX",
                   "boundary features: within PX pixels of the region's edge (either side)",
                   &flags->boundary_band);
}

}  // namespace comic::apps
