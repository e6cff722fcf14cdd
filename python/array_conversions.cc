#include "python/array_conversions.h"

#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"

namespace comic::python {
namespace {

using frontend::Feature;
using frontend::FeatureSet;
using frontend::kPatchSize;

template <typename T>
py::array_t<T> Column(const FeatureSet& features, T (*get)(const Feature&)) {
  py::array_t<T> column(static_cast<py::ssize_t>(features.size()));
  T* out = column.mutable_data();
  for (size_t i = 0; i < features.size(); ++i) out[i] = get(features[i]);
  return column;
}

template <typename T>
py::array_t<T, py::array::c_style | py::array::forcecast> ColumnOf(const py::dict& columns,
                                                                   const char* name, size_t size,
                                                                   const std::string& what) {
  COMIC_CHECK(columns.contains(name), kInvalidArgument, what << ": no field '" << name << "'");
  auto column = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(columns[name]);
  COMIC_CHECK(column && column.ndim() == 1 && static_cast<size_t>(column.shape(0)) == size,
              kInvalidArgument, what << ": field '" << name << "' must hold " << size << " values");
  return column;
}

}  // namespace

cv::Mat GrayFromArray(const py::array& image, const std::string& what, int64_t max_pixels) {
  COMIC_CHECK(image.dtype().is(py::dtype::of<uint8_t>()), kInvalidArgument,
              what << ": expected a uint8 image, got dtype "
                   << py::cast<std::string>(py::str(image.dtype())));
  COMIC_CHECK(image.ndim() == 2 || (image.ndim() == 3 && image.shape(2) == 3), kInvalidArgument,
              what << ": expected an H x W (grey) or H x W x 3 (BGR) image, got " << image.ndim()
                   << " dimensions");
  COMIC_CHECK(image.shape(0) > 0 && image.shape(1) > 0, kInvalidArgument, what << ": empty image");
  io::CheckPixelBudget(what, image.shape(1), image.shape(0), max_pixels);
  const auto contiguous =
      py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(image);
  const int rows = static_cast<int>(image.shape(0));
  const int cols = static_cast<int>(image.shape(1));
  if (image.ndim() == 2) {
    return cv::Mat(rows, cols, CV_8UC1, const_cast<uint8_t*>(contiguous.data())).clone();
  }
  const cv::Mat bgr(rows, cols, CV_8UC3, const_cast<uint8_t*>(contiguous.data()));
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

py::array_t<uint8_t> ArrayFromImage(const cv::Mat& mat) {
  std::vector<py::ssize_t> shape = {mat.rows, mat.cols};
  if (mat.channels() == 3) shape.push_back(3);
  py::array_t<uint8_t> array(shape);
  const size_t row_bytes = static_cast<size_t>(mat.cols) * mat.channels();
  for (int r = 0; r < mat.rows; ++r) {
    std::memcpy(array.mutable_data() + r * row_bytes, mat.ptr<uint8_t>(r), row_bytes);
  }
  return array;
}

py::dict FeaturesToColumns(const FeatureSet& features) {
  py::dict columns;
  columns["x"] = Column<float>(features, [](const Feature& f) { return f.x; });
  columns["y"] = Column<float>(features, [](const Feature& f) { return f.y; });
  columns["scale"] = Column<float>(features, [](const Feature& f) { return f.scale; });
  columns["response"] = Column<float>(features, [](const Feature& f) { return f.response; });
  columns["cornerness"] = Column<float>(features, [](const Feature& f) { return f.cornerness; });
  columns["level"] = Column<int32_t>(features, [](const Feature& f) { return int32_t{f.level}; });
  columns["polarity"] =
      Column<int8_t>(features, [](const Feature& f) { return static_cast<int8_t>(f.polarity); });
  columns["has_side_mask"] =
      Column<bool>(features, [](const Feature& f) { return f.HasSideMask(); });
  py::array_t<uint8_t> masks({static_cast<py::ssize_t>(features.size()),
                              static_cast<py::ssize_t>(kPatchSize),
                              static_cast<py::ssize_t>(kPatchSize)});
  uint8_t* out = masks.mutable_data();
  std::memset(out, 0, features.size() * kPatchSize * kPatchSize);
  for (size_t i = 0; i < features.size(); ++i) {
    if (!features[i].HasSideMask()) continue;
    for (int k = 0; k < kPatchSize * kPatchSize; ++k) {
      out[i * kPatchSize * kPatchSize + k] = static_cast<uint8_t>(features[i].side_mask[k]);
    }
  }
  columns["side_masks"] = masks;
  return columns;
}

FeatureSet FeaturesFromColumns(const py::dict& columns, const py::object& side_masks,
                               const std::string& what) {
  COMIC_CHECK(columns.contains("x"), kInvalidArgument, what << ": no field 'x'");
  const size_t n = static_cast<size_t>(py::len(columns["x"]));
  const auto x = ColumnOf<float>(columns, "x", n, what);
  const auto y = ColumnOf<float>(columns, "y", n, what);
  const auto scale = ColumnOf<float>(columns, "scale", n, what);
  const auto response = ColumnOf<float>(columns, "response", n, what);
  const auto cornerness = ColumnOf<float>(columns, "cornerness", n, what);
  const auto level = ColumnOf<int32_t>(columns, "level", n, what);
  const auto polarity = ColumnOf<int8_t>(columns, "polarity", n, what);
  FeatureSet features(n);
  for (size_t i = 0; i < n; ++i) {
    Feature& f = features[i];
    f.x = x.at(i);
    f.y = y.at(i);
    COMIC_CHECK(std::isfinite(f.x) && std::isfinite(f.y), kInvalidArgument,
                what << ": feature " << i << " has a non-finite position");
    f.scale = scale.at(i);
    f.response = response.at(i);
    f.cornerness = cornerness.at(i);
    f.level = level.at(i);
    COMIC_CHECK(polarity.at(i) >= -1 && polarity.at(i) <= 1, kInvalidArgument,
                what << ": feature " << i << " has polarity " << int{polarity.at(i)});
    f.polarity = static_cast<frontend::Polarity>(polarity.at(i));
  }
  if (!side_masks.is_none()) {
    const auto masks =
        py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(side_masks);
    COMIC_CHECK(masks && masks.ndim() == 3 && static_cast<size_t>(masks.shape(0)) == n &&
                    masks.shape(1) == kPatchSize && masks.shape(2) == kPatchSize,
                kInvalidArgument,
                what << ": side masks must be an array of shape (" << n << ", 23, 23)");
    const uint8_t* data = masks.data();
    for (size_t i = 0; i < n; ++i) {
      const uint8_t* mask = data + i * kPatchSize * kPatchSize;
      bool any = false;
      for (int k = 0; k < kPatchSize * kPatchSize; ++k) {
        COMIC_CHECK(mask[k] <= 2, kInvalidArgument,
                    what << ": side mask values are 0, 1 or 2, got " << int{mask[k]});
        any = any || mask[k] != 0;
      }
      if (!any) continue;  // all 0: no side information for this feature
      features[i].side_mask.assign(
          reinterpret_cast<const frontend::PatchSide*>(mask),
          reinterpret_cast<const frontend::PatchSide*>(mask) + kPatchSize * kPatchSize);
    }
  }
  return features;
}

py::dict MatchesToColumns(const std::vector<frontend::PatchMatch>& matches) {
  py::array_t<int32_t> index1(static_cast<py::ssize_t>(matches.size()));
  py::array_t<int32_t> index2(static_cast<py::ssize_t>(matches.size()));
  py::array_t<float> cost(static_cast<py::ssize_t>(matches.size()));
  for (size_t i = 0; i < matches.size(); ++i) {
    index1.mutable_at(i) = matches[i].index1;
    index2.mutable_at(i) = matches[i].index2;
    cost.mutable_at(i) = matches[i].cost;
  }
  py::dict columns;
  columns["index1"] = index1;
  columns["index2"] = index2;
  columns["cost"] = cost;
  return columns;
}

py::dict TracksToPython(const frontend::FeatureTracks& tracks) {
  py::list features;
  for (const FeatureSet& frame : tracks.features) features.append(FeaturesToColumns(frame));
  size_t num_observations = 0;
  for (const frontend::Track& track : tracks.tracks) num_observations += track.Length();
  py::array_t<int32_t> track_ids(static_cast<py::ssize_t>(num_observations));
  py::array_t<int32_t> frames(static_cast<py::ssize_t>(num_observations));
  py::array_t<int32_t> feature_ids(static_cast<py::ssize_t>(num_observations));
  size_t k = 0;
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : tracks.tracks[t].observations) {
      track_ids.mutable_at(k) = static_cast<int32_t>(t);
      frames.mutable_at(k) = obs.frame;
      feature_ids.mutable_at(k) = obs.feature;
      ++k;
    }
  }
  py::dict result;
  result["detector"] = tracks.detector_name;
  result["image_size"] = py::make_tuple(tracks.image_size.width, tracks.image_size.height);
  result["frame_names"] = tracks.frame_names;
  result["features"] = features;
  result["track"] = track_ids;
  result["frame"] = frames;
  result["feature"] = feature_ids;
  return result;
}

}  // namespace comic::python
