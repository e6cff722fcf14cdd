#include "sfm/run/run_page_frames.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <set>

#include "frontend/evaluation/region_labels.h"
#include "frontend/evaluation/track_drawing.h"
#include "io/report/data_uri.h"
#include "sfm/run/run_page_timeline.h"

namespace comic::sfm {

namespace {

// `count` frames spread evenly over [first, last].
std::vector<int> Spread(int first, int last, int count) {
  std::vector<int> frames;
  if (count <= 0 || last < first) return frames;
  if (count == 1) return {first};
  for (int k = 0; k < count; ++k) {
    frames.push_back(first +
                     static_cast<int>(static_cast<long long>(k) * (last - first) / (count - 1)));
  }
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

// `image` scaled by `scale`, at least one pixel each way (a very wide frame would round to none).
cv::Mat Scaled(const cv::Mat& image, double scale) {
  const cv::Size size(std::max(1, static_cast<int>(std::lround(image.cols * scale))),
                      std::max(1, static_cast<int>(std::lround(image.rows * scale))));
  cv::Mat scaled;
  cv::resize(image, scaled, size, 0, 0, cv::INTER_AREA);
  return scaled;
}

cv::Mat ShrinkToWidth(const cv::Mat& image, int width) {
  if (image.cols <= width) return image;
  return Scaled(image, static_cast<double>(width) / image.cols);
}

// The frame with the tracks through it, in the size the tracks live in.
cv::Mat DrawFrameTracks(const cv::Mat& color, const DetectorRun& run, const RunInputs& inputs,
                        int frame) {
  const frontend::FeatureTracks& tracks = run.run.tracks;
  cv::Mat image = color;
  if (image.size() != tracks.image_size) cv::resize(color, image, tracks.image_size);
  std::vector<frontend::RegionLabel> labels;
  cv::Mat region;
  if (!inputs.region_labels.empty() && inputs.region_labels[frame].size() == tracks.image_size) {
    region = inputs.region_labels[frame];
    labels = frontend::LabelFeatures(region, tracks.features[frame]);
  }
  return frontend::DrawTracks(image, tracks, frame, labels, region);
}

std::string Caption(const RunInputs& inputs, int frame, bool registered) {
  return "frame " + std::to_string(frame) + " · " + inputs.sequence->FrameNames()[frame] +
         (registered ? "" : " · not registered");
}

}  // namespace

std::vector<int> TrackFramesToDraw(int num_frames, int count,
                                   const std::vector<int>& unregistered) {
  if (num_frames <= 0 || count <= 0) return {};
  // Late enough in the clip for each drawn track to show a few frames of history.
  std::vector<int> frames = Spread(std::min(5, num_frames - 1), num_frames - 1, count);
  if (!unregistered.empty() &&
      std::find(frames.begin(), frames.end(), unregistered.front()) == frames.end()) {
    // Where it went wrong replaces the nearest spread frame.
    const int first_missing = unregistered.front();
    auto nearest = std::min_element(frames.begin(), frames.end(), [&](int a, int b) {
      return std::abs(a - first_missing) < std::abs(b - first_missing);
    });
    *nearest = first_missing;
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  }
  return frames;
}

std::vector<int> ThumbnailFrames(int num_frames, int count) {
  return Spread(0, num_frames - 1, std::min(num_frames, count));
}

RunFramePictures RunFramePicturesOf(const DetectorRun& run, const RunInputs& inputs,
                                    const RunPageOptions& options) {
  const int num_frames = static_cast<int>(inputs.sequence->NumFrames());
  std::vector<bool> registered(num_frames, false);
  for (const Reconstruction* model : RunModels(run)) {
    for (int f : RegisteredFramesOf(*model)) {
      if (f >= 0 && f < num_frames) registered[f] = true;
    }
  }
  std::vector<int> unregistered;
  for (int f = 0; f < num_frames; ++f) {
    if (!registered[f]) unregistered.push_back(f);
  }
  const bool has_tracks = static_cast<int>(run.run.tracks.NumFrames()) == num_frames;
  const std::vector<int> track_frames =
      has_tracks ? TrackFramesToDraw(num_frames, options.num_track_frames, unregistered)
                 : std::vector<int>();
  const std::vector<int> thumbnail_frames = ThumbnailFrames(num_frames, options.max_thumbnails);
  std::set<int> to_read(track_frames.begin(), track_frames.end());
  to_read.insert(thumbnail_frames.begin(), thumbnail_frames.end());

  RunFramePictures pictures;
  const std::set<int> drawn(track_frames.begin(), track_frames.end());
  const std::set<int> thumbnailed(thumbnail_frames.begin(), thumbnail_frames.end());
  for (int frame : to_read) {  // ascending: a video is read forward once
    const io::Frame image = inputs.sequence->ReadFrame(frame);
    const std::string tone = registered[frame] ? "" : "bad";
    if (drawn.count(frame)) {
      const cv::Mat picture = ShrinkToWidth(DrawFrameTracks(image.color, run, inputs, frame),
                                            options.track_frame_width);
      pictures.tracks.push_back({io::ImageDataUri(picture, options.jpeg_quality),
                                 Caption(inputs, frame, registered[frame]), tone});
    }
    if (thumbnailed.count(frame)) {
      // The thumbnail's height, or at most 8 times that wide.
      const double scale =
          std::min(static_cast<double>(options.thumbnail_height) / image.color.rows,
                   8.0 * options.thumbnail_height / image.color.cols);
      const cv::Mat thumbnail = Scaled(image.color, scale);
      pictures.thumbnails.push_back({io::ImageDataUri(thumbnail, options.jpeg_quality),
                                     Caption(inputs, frame, registered[frame]), tone});
    }
  }
  pictures.legend = frontend::TrackDrawingLegend(!inputs.region_labels.empty());
  pictures.thumbnails_note =
      (static_cast<int>(thumbnail_frames.size()) < num_frames
           ? std::to_string(thumbnail_frames.size()) + " of " + std::to_string(num_frames) +
                 " frames, spread evenly over the clip. "
           : std::string()) +
      "Frames no model holds are framed in red.";
  return pictures;
}

}  // namespace comic::sfm
