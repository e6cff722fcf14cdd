#include "sfm/run/run_inputs.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "frontend/evaluation/region_labels.h"
#include "io/core/error.h"
#include "io/datasets/region_annotations.h"
#include "io/image/mask_folder.h"
#include "sfm/run/run_outputs.h"
#include "sfm/working_resolution.h"

namespace comic::sfm {

namespace {

// The frames, at the working size when they are larger and --resize-height does not say otherwise
// (sfm/working_resolution.h).
void OpenFrames(const ReconstructionRunOptions& options, RunInputs* inputs) {
  inputs->sequence = std::make_unique<io::ImageSequence>(
      io::ImageSequence::Open(options.frames, options.sequence));
  const int working_height =
      WorkingResizeHeight(inputs->sequence->SourceFrameSize(), options.max_working_size);
  if (options.sequence.resize_height == 0 && working_height > 0) {
    io::ImageSequenceOptions working = options.sequence;
    working.resize_height = working_height;
    inputs->sequence =
        std::make_unique<io::ImageSequence>(io::ImageSequence::Open(options.frames, working));
    inputs->at_working_size = true;
  }
  for (size_t k = 0; k < inputs->sequence->NumFrames(); ++k) {
    inputs->source_indices.push_back(options.sequence.first_frame +
                                     static_cast<int>(k) * options.sequence.stride);
  }
}

void ReadGroundTruth(const ReconstructionRunOptions& options, RunInputs* inputs) {
  if (options.gt.empty()) return;
  const io::ImageSequence& sequence = *inputs->sequence;
  const io::GroundTruthCameras truth =
      io::ReadGroundTruthCameras(options.gt, io::ParseGroundTruthFormat(options.gt_format));
  inputs->gt_format = truth.format;
  inputs->ground_truth =
      MatchGroundTruthToFrames(truth, sequence.FrameNames(), inputs->source_indices,
                               sequence.SourceFrameSize(), sequence.FrameSize());
  CheckGroundTruthCoverage(*inputs->ground_truth, sequence.FrameNames(), options.gt,
                           options.gt_partial);
}

// --regions / --masks: per frame, the object region labelled (boundary band, interior); --masks
// also remove the features they cover (frontend/feature_masks.h).
void LabelRegions(const ReconstructionRunOptions& options, RunInputs* inputs) {
  if (options.regions.empty() && options.masks.empty()) return;
  const cv::Size source_size = inputs->sequence->SourceFrameSize();
  const cv::Size frame_size = inputs->sequence->FrameSize();
  std::optional<io::RegionAnnotations> regions;
  std::optional<io::MaskFolder> masks;
  if (!options.regions.empty()) {
    regions = io::ReadRegionFile(options.regions);
  } else {
    masks = io::MaskFolder::Open(options.masks);
  }
  std::vector<cv::Mat> object_masks;
  for (int source_index : inputs->source_indices) {
    cv::Mat mask;
    if (regions) {
      COMIC_CHECK(source_index < static_cast<int>(regions->polygons.size()), kInvalidData,
                  options.regions << ": no region for frame " << source_index);
      mask = io::RasterizeRegion(regions->polygons[source_index], source_size, frame_size);
    } else {
      COMIC_CHECK(source_index < static_cast<int>(masks->NumMasks()), kInvalidData,
                  options.masks << ": no mask for frame " << source_index);
      mask = masks->Read(source_index, source_size);
      if (mask.size() != frame_size) cv::resize(mask, mask, frame_size, 0, 0, cv::INTER_NEAREST);
      object_masks.push_back(mask);
    }
    inputs->region_labels.push_back(frontend::LabelRegion(mask, options.boundary_band));
  }
  if (masks) {
    frontend::FeatureMaskOptions mask_options;
    mask_options.drop_nonzero = options.mask_drops_nonzero;
    inputs->feature_masks =
        std::make_shared<const frontend::FeatureMasks>(object_masks, mask_options);
  }
}

void ChoosePlotPlane(const ReconstructionRunOptions& options, RunInputs* inputs) {
  if (options.plot_plane != "auto") {
    inputs->plot_plane = ParsePlotPlane(options.plot_plane);
  } else if (inputs->gt_format == io::GroundTruthFormat::kKitti) {
    inputs->plot_plane = PlotPlaneFromAxes(0, 2);  // KITTI: y points down, x–z is the ground
  } else if (inputs->ground_truth) {
    std::vector<Eigen::Vector3d> centers;
    for (const auto& pose : inputs->ground_truth->cams_from_world) {
      if (pose) centers.push_back(ProjectionCenter(*pose));
    }
    inputs->plot_plane = PlotPlaneFromCenters(centers);
  } else {
    inputs->plot_plane_from_estimate = true;
  }
}

}  // namespace

RunInputs ResolveRunInputs(const ReconstructionRunOptions& options) {
  RunInputs inputs;
  OpenFrames(options, &inputs);
  ReadGroundTruth(options, &inputs);
  // The photos' EXIF focal matters only without a calibration file.
  const ExifFocalPrior exif =
      options.camera.intrinsics.empty() ? FindExifFocalPrior(*inputs.sequence) : ExifFocalPrior();
  inputs.camera =
      ResolveCamera(options.camera, inputs.sequence->SourceFrameSize(),
                    inputs.sequence->FrameSize(), inputs.ground_truth, options.gt, exif);
  LabelRegions(options, &inputs);
  ChoosePlotPlane(options, &inputs);
  inputs.pairing = ChooseRunPairing(options.matching, options.tracker, *inputs.sequence);
  inputs.tracker = TrackerOptionsForRun(options.tracker, inputs.pairing,
                                        static_cast<int>(inputs.sequence->NumFrames()));
  inputs.image_set =
      ImageSetMatchingForRun(options.matcher, inputs.pairing, inputs.tracker, options.threads);
  inputs.matchers = ResolveMatchers(options, inputs);
  return inputs;
}

std::vector<MatcherAttempt> ResolveMatchers(const ReconstructionRunOptions& options,
                                            const RunInputs& inputs) {
  const MatcherAttempt as_given{inputs.tracker, inputs.image_set};
  if (frontend::ParseFeatureMatcher(options.matcher) != frontend::FeatureMatcher::kAuto ||
      options.tracker.Given("match-window")) {
    return {as_given};
  }
  if (frontend::IsVideo(inputs.pairing)) {
    if (!inputs.image_set) return {as_given};
    MatcherAttempt verified_patches{inputs.tracker, std::nullopt};
    if (!options.tracker.Given("verify-min-gap")) verified_patches.tracker.verify_min_gap = 1;
    return {verified_patches, as_given};
  }
  if (inputs.image_set) return {as_given};
  return {as_given,
          MatcherAttempt{inputs.tracker, ImageSetMatchingForRun("descriptors", inputs.pairing,
                                                                inputs.tracker, options.threads)}};
}

RegionLabelFn RegionLabelsOf(const RunInputs& inputs) {
  if (inputs.region_labels.empty()) return {};
  return [&inputs](const Image& image, const Eigen::Vector2d& xy) {
    const cv::Mat& labels = inputs.region_labels.at(image.image_id - 1);
    const int x = static_cast<int>(std::lround(xy.x()));
    const int y = static_cast<int>(std::lround(xy.y()));
    if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows) {
      return frontend::RegionLabel::kOutside;
    }
    return static_cast<frontend::RegionLabel>(labels.at<uint8_t>(y, x));
  };
}

}  // namespace comic::sfm
