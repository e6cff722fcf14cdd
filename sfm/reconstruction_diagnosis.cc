#include "sfm/reconstruction_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace comic::sfm {

namespace {

std::string FrameName(const std::vector<std::string>& names, image_t image_id) {
  const size_t frame = static_cast<size_t>(image_id) - 1;
  return image_id > 0 && frame < names.size() ? names[frame] : "frame " + std::to_string(frame);
}

using Stage = IncrementalMapper::InitialPairSearch::Stage;

void DescribeTooFewFrames(const IncrementalReconstruction& reconstruction,
                          ReconstructionDiagnosis& diagnosis, std::ostringstream& message,
                          std::ostringstream& suggestion) {
  diagnosis.stage = diagnosis.check = "frames";
  diagnosis.value = static_cast<double>(reconstruction.unregistered_frames.size());
  diagnosis.needed = 2;
  message << "too few frames: " << diagnosis.value << " of the 2 needed";
  suggestion << "a longer --first/--last range or a smaller --stride";
}

void DescribeTooFewPoints(const IncrementalReconstruction& reconstruction,
                          const IncrementalPipelineOptions& options,
                          const std::vector<std::string>& frame_names,
                          ReconstructionDiagnosis& diagnosis, std::ostringstream& message,
                          std::ostringstream& suggestion) {
  diagnosis.stage = "initial_points";
  diagnosis.check = "initial_points";
  diagnosis.frame1 = FrameName(frame_names, reconstruction.initial_frame1 + 1);
  diagnosis.frame2 = FrameName(frame_names, reconstruction.initial_frame2 + 1);
  diagnosis.value = static_cast<double>(reconstruction.initial_pair_num_points);
  diagnosis.needed = options.min_num_initial_points;
  message << "initial pair " << diagnosis.frame1 << "-" << diagnosis.frame2 << " kept "
          << reconstruction.initial_pair_num_points << " 3-D points, needs "
          << options.min_num_initial_points;
  suggestion << "more tracked features (--max-features, another --detector) or correct "
                "--intrinsics";
}

// The best pair's two-view geometry failed: a homography explains it (no parallax) or no relative
// pose was found.
void DescribeGeometryFailure(const IncrementalMapper::InitialPairSearch& search,
                             const IncrementalMapper::Options& mapper, bool gap_can_grow,
                             int larger_gap, ReconstructionDiagnosis& diagnosis,
                             std::ostringstream& message, std::ostringstream& suggestion) {
  diagnosis.check = "two_view_geometry";
  if (search.configuration == TwoViewConfiguration::kPlanarOrPanoramic) {
    // The homography check of two_view_geometry: more than max_homography_inlier_ratio of
    // the essential-matrix inliers fit one homography.
    const double ratio = static_cast<double>(search.num_homography_inliers) /
                         std::max(search.num_essential_inliers, 1);
    diagnosis.rotation_only = true;
    diagnosis.value = ratio;
    diagnosis.needed = mapper.two_view.max_homography_inlier_ratio;
    message << ", but a homography explains " << std::setprecision(0) << 100.0 * ratio
            << " % of its " << search.num_essential_inliers << " inliers (at most "
            << 100.0 * diagnosis.needed
            << " %): the camera only turns (panning) or the scene is flat, no parallax";
    if (gap_can_grow) {
      suggestion << "--init-max-gap " << larger_gap << " if the camera moves at all, else ";
    }
    suggestion << "footage where the camera moves sideways or around the scene (turning on "
                  "the spot gives no depth)";
  } else {
    diagnosis.value = search.num_essential_inliers;
    diagnosis.needed = mapper.two_view.min_num_inliers;
    message << ", no relative pose (" << search.num_essential_inliers
            << " essential-matrix inliers, needs " << mapper.two_view.min_num_inliers << ")";
    suggestion << "correct --intrinsics, or steadier tracks (a smaller --max-cost, another "
                  "--detector)";
  }
}

// The best pair had a pose but too little parallax: what would let it pass.
void DescribeParallaxFailure(const IncrementalMapper::InitialPairSearch& search,
                             const IncrementalMapper::Options& mapper, bool gap_can_grow,
                             int larger_gap, ReconstructionDiagnosis& diagnosis,
                             std::ostringstream& message, std::ostringstream& suggestion) {
  diagnosis.check = "parallax";
  diagnosis.value = search.score;
  diagnosis.needed = mapper.init_min_score;
  message << ", " << search.num_inliers << " inliers, median triangulation angle "
          << std::setprecision(2) << search.median_triangulation_angle_deg << " deg"
          << std::setprecision(1) << ", parallax score " << search.score << ", needs "
          << mapper.init_min_score << " (an inlier counts fully at --init-angle "
          << mapper.init_tri_angle_deg << " deg)";
  // Below --init-angle every inlier counts angle / init_angle, so the score grows as the
  // angle shrinks: about this --init-angle lets this pair pass.
  const double angle =
      std::floor(10.0 * mapper.init_tri_angle_deg * search.score / mapper.init_min_score) / 10.0;
  if (gap_can_grow) suggestion << "frames farther apart (--init-max-gap " << larger_gap << ")";
  if (angle >= 0.1) {
    suggestion << (gap_can_grow ? " or " : "") << "accepting less parallax (--init-angle " << angle
               << ", a less accurate start)";
  } else if (!gap_can_grow) {
    suggestion << "footage where the camera moves more between frames";
  }
}

// kNoInitialPair: the pair that came closest, and the check it failed.
void DescribeNoInitialPair(const IncrementalReconstruction& reconstruction,
                           const IncrementalMapper::Options& mapper,
                           const std::vector<std::string>& frame_names,
                           ReconstructionDiagnosis& diagnosis, std::ostringstream& message,
                           std::ostringstream& suggestion) {
  const IncrementalMapper::InitialPairSearch& search = reconstruction.initial_pair_search;
  diagnosis.stage = "initial_pair";
  if (search.stage == Stage::kNone) {
    diagnosis.check = "shared_tracks";
    diagnosis.needed = mapper.init_min_num_matches;
    message << "no initial pair: no two frames share a tracked feature";
    suggestion << "another --detector, more features (--max-features 0 keeps all) or a larger "
                  "--search-radius";
    return;
  }
  // A larger --init-max-gap can only help while it reaches frames the search has not paired
  // (0: no limit, the search already grows each anchor's gap as far as its tracks reach).
  const int num_frames = static_cast<int>(frame_names.size());
  const bool gap_can_grow =
      mapper.init_max_frame_gap > 0 && mapper.init_max_frame_gap + 1 < num_frames;
  const int larger_gap = std::min(2 * mapper.init_max_frame_gap, std::max(num_frames - 1, 1));
  diagnosis.frame1 = FrameName(frame_names, search.image_id1);
  diagnosis.frame2 = FrameName(frame_names, search.image_id2);
  message << "no initial pair: best pair " << diagnosis.frame1 << "-" << diagnosis.frame2 << ": "
          << search.num_shared_tracks << " shared tracks";
  switch (search.stage) {
    case Stage::kNone:
    case Stage::kSharedTracks:
      diagnosis.check = "shared_tracks";
      diagnosis.value = search.num_shared_tracks;
      diagnosis.needed = mapper.init_min_num_matches;
      message << ", needs " << mapper.init_min_num_matches;
      suggestion << "more features tracked through more frames: --max-features, a larger "
                    "--search-radius, another --detector, or a smaller --stride";
      break;
    case Stage::kGeometry:
      DescribeGeometryFailure(search, mapper, gap_can_grow, larger_gap, diagnosis, message,
                              suggestion);
      break;
    case Stage::kInliers:
      diagnosis.check = "inliers";
      diagnosis.value = search.num_inliers;
      diagnosis.needed = mapper.init_min_num_inliers;
      message << ", " << search.num_inliers << " inliers of the relative pose, needs "
              << mapper.init_min_num_inliers;
      suggestion << "correct --intrinsics, or more features tracked (--max-features, another "
                    "--detector)";
      break;
    case Stage::kParallax:
    case Stage::kQualified:
      DescribeParallaxFailure(search, mapper, gap_can_grow, larger_gap, diagnosis, message,
                              suggestion);
      break;
  }
}

}  // namespace

ReconstructionDiagnosis DiagnoseReconstruction(const IncrementalReconstruction& reconstruction,
                                               const IncrementalPipelineOptions& options,
                                               const std::vector<std::string>& frame_names) {
  ReconstructionDiagnosis diagnosis;
  if (HasModel(reconstruction.status)) return diagnosis;
  diagnosis.failed = true;
  std::ostringstream message;
  std::ostringstream suggestion;
  message << std::fixed << std::setprecision(1);
  suggestion << std::fixed << std::setprecision(1);
  if (reconstruction.status == ReconstructionStatus::kTooFewFrames) {
    DescribeTooFewFrames(reconstruction, diagnosis, message, suggestion);
  } else if (reconstruction.status == ReconstructionStatus::kTooFewPoints) {
    DescribeTooFewPoints(reconstruction, options, frame_names, diagnosis, message, suggestion);
  } else {
    DescribeNoInitialPair(reconstruction, options.mapper, frame_names, diagnosis, message,
                          suggestion);
  }
  diagnosis.message = message.str();
  diagnosis.suggestion = suggestion.str();
  return diagnosis;
}

}  // namespace comic::sfm
