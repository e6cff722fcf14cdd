// The option vocabulary shared by the apps: each option several apps take is defined here once,
// with one name, one one-line meaning and one value name, so that `--output`, `--threads`,
// `--search-radius`... mean the same in every app (tests/apps/option_vocabulary_test.cc reads
// every app's --help and fails on a name with two meanings or two names for one meaning). The
// default is the variable's value when the option is added, normally the library's default.
#pragma once

#include <string>

#include "apps/common/arg_parser.h"

namespace comic::apps {

// --output DIR, -o: the folder the app writes its results into (created if needed).
void AddOutputFolderFlag(ArgParser& parser, std::string* folder);
// --threads N: the worker count for all the work of the app (detection, matching, verification,
// evaluation); 0 = one per core. No app's output depends on it (see docs/apps.md).
void AddThreadsFlag(ArgParser& parser, int* threads);
// --quiet, -q: no progress messages.
void AddQuietFlag(ArgParser& parser, bool* quiet);
// --json FILE: also write the results as JSON.
void AddJsonFlag(ArgParser& parser, std::string* path);
// --resize-height H: resize the image(s) to height H first, keeping the aspect ratio.
void AddResizeHeightFlag(ArgParser& parser, int* height);
// --detector NAME: one of frontend::DetectorNames() (listed in the meaning).
void AddDetectorFlag(ArgParser& parser, std::string* name);
// --scale-levels N: every detector on N levels of an image pyramid, each half the size of the
// one before (frontend/scale_space_detector.h); 1 = the image as given only.
void AddScaleLevelsFlag(ArgParser& parser, int* levels);
// --detectors LIST: comma-separated detector names, one run each.
void AddDetectorListFlag(ArgParser& parser, std::string* list);
// --max-features N: the N strongest features kept per frame (0 = all).
void AddMaxFeaturesFlag(ArgParser& parser, int* count);
// --search-radius PX: the matcher's radius gate r around a feature's (predicted) position
// (paper §4: 20 px).
void AddSearchRadiusFlag(ArgParser& parser, double* radius);
// --max-cost T: the SSD threshold T of a match (mean squared grey-level difference).
void AddMaxCostFlag(ArgParser& parser, double* cost);
// --min-side-overlap PX: split matching (paper Algorithm 2), fewest shared pixels of a side pair.
void AddMinSideOverlapFlag(ArgParser& parser, int* pixels);
// --min-side-fraction F, --side-noise-sigma S and --side-noise-from-pair: the calibrated
// side-aware cost's smallest side share of the patch, its noise σ, and σ taken from each pair's
// full-patch matches instead (frontend/matching/patch_matcher.h, issue 15).
void AddCalibratedCostFlags(ArgParser& parser, double* min_side_fraction, double* noise_sigma,
                            bool* noise_from_pair);
// --intrinsics FILE: the frames' intrinsics as stored (see sfm/run/camera_resolution.h).
void AddIntrinsicsFlag(ArgParser& parser, std::string* path);
// --camera-model NAME: COLMAP's model name (sfm/camera_model.h) for the camera, checked by
// sfm/run/camera_resolution.h's ParseCameraModel.
void AddCameraModelFlag(ArgParser& parser, std::string* name);

// The object region of a sequence (paper §5.1: boundary vs interior features): --masks DIR or
// --regions FILE, and the --boundary-band width.
struct ObjectRegionFlags {
  std::string masks;     // folder of per-frame masks, non-zero = object
  std::string regions;   // region file, line k = frame k (VOT polygons or OTB boxes)
  double boundary_band;  // px on each side of the region's edge
};
void AddObjectRegionFlags(ArgParser& parser, ObjectRegionFlags* flags);

}  // namespace comic::apps
