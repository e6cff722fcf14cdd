#include "python/frontend_bindings.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "io/core/error.h"
#include "io/core/pixel_budget.h"
#include "io/image/image_io.h"
#include "io/image/image_sequence.h"
#include "python/array_conversions.h"
#include "python/detector_keywords.h"
#include "python/keyword_options.h"
#include "python/run_callbacks.h"
#include "python/run_keywords.h"

namespace comic::python {
namespace {

using frontend::FeatureSet;

py::array_t<uint8_t> ImRead(const std::string& path, const py::object& resize_height_argument,
                            bool color, const py::object& max_pixels_argument) {
  const int resize_height = Argument<int>(resize_height_argument, "resize_height", "imread");
  const int64_t max_pixels = Argument<int64_t>(max_pixels_argument, "max_pixels", "imread");
  io::CheckResizeHeight(resize_height, "resize_height");
  io::CheckMaxPixels(max_pixels);
  const io::LoadedImage image = io::LoadImage(path, resize_height, max_pixels);
  return ArrayFromImage(color ? image.color : image.gray);
}

// comic_detect's run (sfm/run/detect_run.h) on an image given as an array.
py::dict Detect(const py::array& image, const std::string& detector_name, const py::dict& options,
                const py::object& max_pixels_argument) {
  const sfm::DetectRunOptions run =
      DetectRunFromKeywords(detector_name, options, DetectorDoor::kDetect);
  const int64_t max_pixels = Argument<int64_t>(max_pixels_argument, "max_pixels", "detect");
  io::CheckMaxPixels(max_pixels);
  const cv::Mat gray = GrayFromArray(image, "detect", max_pixels);
  FeatureSet features;
  {
    py::gil_scoped_release release;
    features = sfm::RunDetect(run, gray).features;
  }
  return FeaturesToColumns(features);
}

py::dict Match(const py::array& image1, const py::dict& features1, const py::object& masks1,
               const py::array& image2, const py::dict& features2, const py::object& masks2,
               const py::dict& options) {
  frontend::PatchMatcherOptions matcher;
  OptionTable table;
  AddMatcherOptions(&matcher, &table);
  ApplyOptions(options, table, "match");
  matcher.Check();
  const cv::Mat gray1 = GrayFromArray(image1, "match: image1");
  const cv::Mat gray2 = GrayFromArray(image2, "match: image2");
  const FeatureSet set1 = FeaturesFromColumns(features1, masks1, "match: features1");
  const FeatureSet set2 = FeaturesFromColumns(features2, masks2, "match: features2");
  std::vector<frontend::PatchMatch> matches;
  {
    py::gil_scoped_release release;
    matches = frontend::MatchFeatures(gray1, set1, gray2, set2, matcher);
  }
  return MatchesToColumns(matches);
}

py::dict Track(const py::object& frames, const std::string& detector_name,
               const py::dict& detector_options, const py::dict& options,
               const py::object& callback) {
  const frontend::DetectorOptions made =
      MakeDetectorOptions(detector_name, detector_options, DetectorDoor::kTrack);
  frontend::TrackerOptions tracker;
  io::ImageSequenceOptions sequence_options;
  OptionTable table;
  AddTrackerOptions(&tracker, &table);
  const bool from_path = py::isinstance<py::str>(frames);
  if (from_path) AddSequenceOptions(&sequence_options, &table);
  table["max_pixels"] = Field(&sequence_options.max_pixels);  // paths and arrays alike
  ApplyOptions(options, table, "track");
  tracker.Check();
  sequence_options.Check();
  const frontend::TrackingProgress progress = TrackingCallback(callback);
  const std::unique_ptr<frontend::Detector> detector = frontend::MakeDetector(made);
  frontend::TrackingResult result;
  if (from_path) {
    const io::ImageSequence sequence =
        io::ImageSequence::Open(py::cast<std::string>(frames), sequence_options);
    py::gil_scoped_release release;
    result = frontend::TrackSequence(sequence, *detector, tracker, progress);
  } else {
    std::vector<cv::Mat> grays;
    for (const py::handle frame : frames) {
      COMIC_CHECK(py::isinstance<py::array>(frame), kInvalidArgument,
                  "track: frames must be a path or a sequence of uint8 numpy images");
      grays.push_back(GrayFromArray(py::reinterpret_borrow<py::array>(frame),
                                    "track: frame " + std::to_string(grays.size()),
                                    sequence_options.max_pixels));
      COMIC_CHECK(grays.back().size() == grays.front().size(), kInvalidArgument,
                  "track: frame " << grays.size() - 1 << " differs in size from frame 0");
    }
    COMIC_CHECK(!grays.empty(), kInvalidArgument, "track: no frames");
    py::gil_scoped_release release;
    result = frontend::TrackFrames(grays, *detector, tracker, {}, progress);
  }
  return TracksToPython(result.tracks);
}

}  // namespace

void BindFrontend(py::module_& m) {
  m.def("imread", &ImRead, py::arg("path"), py::arg("resize_height"), py::arg("color"),
        py::arg("max_pixels"));
  m.def("detect", &Detect, py::arg("image"), py::arg("detector"), py::arg("options"),
        py::arg("max_pixels"));
  m.def("match", &Match, py::arg("image1"), py::arg("features1"), py::arg("side_masks1"),
        py::arg("image2"), py::arg("features2"), py::arg("side_masks2"), py::arg("options"));
  m.def("track", &Track, py::arg("frames"), py::arg("detector"), py::arg("detector_options"),
        py::arg("options"), py::arg("callback"));
  // The library's detector option table (sfm/run/detector_option_table.h), for the docstring of
  // detect() and the tests that every entry is a flag of comic_detect and a keyword of detect().
  m.def("detector_option_table", &DetectorOptionEntries);
}

}  // namespace comic::python
