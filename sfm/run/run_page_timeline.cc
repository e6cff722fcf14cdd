#include "sfm/run/run_page_timeline.h"

#include <algorithm>

#include "sfm/colmap/model_set_writer.h"

namespace comic::sfm {

namespace {

// Distinct on white and on the 3-D view's dark background; the ground truth is green.
const char* const kModelColors[] = {"#e0452b", "#2f7fd0", "#a05cc9", "#e8a317",
                                    "#8c5a3c", "#d957a8", "#19a9b8", "#7f8c1f"};

enum FrameState { kRegistered = 0, kUnregistered = 1, kKeyframe = 2 };

// Consecutive frames in `frames` (ascending) as [first, last] ranges.
std::vector<std::pair<int, int>> Ranges(const std::vector<int>& frames) {
  std::vector<std::pair<int, int>> ranges;
  for (int f : frames) {
    if (!ranges.empty() && ranges.back().second == f - 1) {
      ranges.back().second = f;
    } else {
      ranges.emplace_back(f, f);
    }
  }
  return ranges;
}

// Why frames are missing: the diagnosis of a failed run, else the mapper's word for each
// unregistered stretch.
std::vector<io::TimelineNote> UnregisteredNotes(const DetectorRun& run,
                                                const std::vector<int>& unregistered) {
  std::vector<io::TimelineNote> notes;
  if (run.diagnosis.failed) {
    if (!unregistered.empty()) {
      notes.push_back(
          {unregistered.front(), unregistered.back(), "no model: " + run.diagnosis.message});
    }
    return notes;
  }
  for (const auto& [first, last] : Ranges(unregistered)) {
    notes.push_back({first, last,
                     "not registered: the mapper found no pose for " +
                         std::string(first == last ? "this frame" : "these frames") +
                         " (too few tracked 3-D points or PnP inliers)"});
  }
  return notes;
}

}  // namespace

std::vector<const Reconstruction*> RunModels(const DetectorRun& run) {
  if (!run.success()) return {};
  // Every model, numbered as sparse/<k> is written: a page of the largest alone called the
  // frames of the others unregistered.
  return ModelsLargestFirst(run.run.mapping);
}

std::string ModelColor(int index) {
  const int n = static_cast<int>(sizeof(kModelColors) / sizeof(kModelColors[0]));
  return kModelColors[((index % n) + n) % n];
}

std::string ModelName(int index) {
  return "model " + std::to_string(index + 1) + " (sparse/" + std::to_string(index) + ")";
}

std::vector<int> RegisteredFramesOf(const Reconstruction& model) {
  std::vector<int> frames;
  for (const image_t id : model.RegisteredImageIds()) frames.push_back(static_cast<int>(id) - 1);
  return frames;
}

io::Timeline RunTimeline(const DetectorRun& run, const std::vector<std::string>& frame_names) {
  const int num_frames = static_cast<int>(frame_names.size());
  io::Timeline timeline;
  timeline.title = "Registration timeline";
  timeline.states = {{"registered", "registered (in the colour of its model)", "", "solid"},
                     {"unregistered", "not registered", "#c3c9cf", "solid"}};
  timeline.frame_states.assign(num_frames, kUnregistered);
  timeline.frame_groups.assign(num_frames, -1);
  timeline.frame_names = frame_names;
  const std::vector<const Reconstruction*> models = RunModels(run);
  for (size_t m = 0; m < models.size(); ++m) {
    const int index = static_cast<int>(m);
    timeline.groups.push_back({ModelName(index), ModelColor(index)});
    for (int f : RegisteredFramesOf(*models[m])) {
      if (f < 0 || f >= num_frames || timeline.frame_groups[f] >= 0) continue;
      timeline.frame_states[f] = kRegistered;
      timeline.frame_groups[f] = index;
    }
  }
  // --keyframes: the registered keyframes marked (the other frames were posed against the map).
  if (run.report.keyframes_only) {
    timeline.states.push_back(
        {"keyframe", "registered keyframe (adds points to the map)", "", "marked"});
    for (int f : run.report.keyframes) {
      if (f >= 0 && f < num_frames && timeline.frame_states[f] == kRegistered) {
        timeline.frame_states[f] = kKeyframe;
      }
    }
  }
  std::vector<int> unregistered;
  for (int f = 0; f < num_frames; ++f) {
    if (timeline.frame_states[f] == kUnregistered) unregistered.push_back(f);
  }
  timeline.notes = UnregisteredNotes(run, unregistered);
  timeline.note = std::to_string(num_frames - static_cast<int>(unregistered.size())) + " of " +
                  std::to_string(num_frames) + " frames registered in " +
                  std::to_string(models.size()) + (models.size() == 1 ? " model." : " models.");
  return timeline;
}

}  // namespace comic::sfm
