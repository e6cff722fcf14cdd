// The compiled half of the Python module `comic` (python/comic/__init__.py is the other half):
// thin wrappers that turn numpy arrays and keyword dicts into the libraries' Options and types,
// release the GIL around the heavy calls, and hand results back as plain numpy columns, which
// __init__.py packs into structured arrays. reconstruct and export_colmap are doors onto the runs
// comic_sfm and comic_export_colmap call (sfm/run/), with their options named as the flags
// (--max-features -> max_features). comic::Error becomes ValueError (kInvalidArgument) or
// RuntimeError (every other kind), with the C++ message, which is the command line's.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "frontend/detector_factory.h"
#include "frontend/matching/patch_matcher.h"
#include "frontend/matching/tracker.h"
#include "io/colmap/colmap_binary_model.h"
#include "io/colmap/colmap_model_folder.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/pixel_budget.h"
#include "io/core/printable_text.h"
#include "io/core/protected_inputs.h"
#include "io/core/thread_count.h"
#include "io/core/version.h"
#include "io/image/image_io.h"
#include "io/image/image_sequence.h"
#include "io/report/json_text.h"
#include "io/report/ply.h"
#include "python/distributed_binding.h"
#include "sfm/colmap/colmap_model_conversion.h"
#include "sfm/option_vocabulary.h"
#include "sfm/run/colmap_export_run.h"
#include "sfm/run/reconstruction_run.h"
#include "sfm/run/run_messages.h"
#include "sfm/run/run_option_table.h"
#include "sfm/run/run_outputs.h"

namespace py = pybind11;

namespace comic::python {
namespace {

using frontend::Feature;
using frontend::FeatureSet;
using frontend::kPatchSize;

// ---- keyword options -> Options fields ---------------------------------------------------------

using Setter = std::function<void(py::handle)>;
using OptionTable = std::map<std::string, Setter>;

// A Python int `value` holds a T exactly.
template <typename T>
bool FitsIn(py::handle value) {
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if constexpr (std::is_unsigned_v<T>) {
    if (overflow > 0) {  // above long long: an unsigned long long may still hold it
      const unsigned long long u = PyLong_AsUnsignedLongLong(value.ptr());
      if (PyErr_Occurred()) {
        PyErr_Clear();
        return false;
      }
      return u <= std::numeric_limits<T>::max();
    }
  }
  if (overflow != 0 || (v == -1 && PyErr_Occurred())) {
    PyErr_Clear();
    return false;
  }
  if constexpr (std::is_signed_v<T>) {
    return v >= std::numeric_limits<T>::min() && v <= std::numeric_limits<T>::max();
  } else {
    return v >= 0 && static_cast<unsigned long long>(v) <= std::numeric_limits<T>::max();
  }
}

template <typename T>
Setter Field(T* field) {
  return [field](py::handle value) {
    // A bool is an int to Python: refuse it for numbers, and numbers for a bool, so that a
    // swapped argument is an error rather than a silent 1 or true.
    if constexpr (std::is_same_v<T, bool>) {
      if (!py::isinstance<py::bool_>(value)) throw py::type_error("expects a bool");
    } else if constexpr (std::is_arithmetic_v<T>) {
      if (py::isinstance<py::bool_>(value)) throw py::type_error("expects a number, not a bool");
      // An int beyond the field's range is a bad value, not a wrong type (threads=10**20).
      if constexpr (std::is_integral_v<T>) {
        if (py::isinstance<py::int_>(value) && !FitsIn<T>(value)) {
          throw py::value_error("= " + py::cast<std::string>(py::str(value)) +
                                " is beyond the range of a " + std::to_string(8 * sizeof(T)) +
                                "-bit integer");
        }
      }
    } else if constexpr (std::is_same_v<T, std::string>) {
      // A path or a name: str (os.PathLike is turned into str by comic/__init__.py).
      if (!py::isinstance<py::str>(value)) throw py::type_error("expects a str");
    }
    *field = py::cast<T>(value);
  };
}

template <typename Parse, typename T>
Setter Parsed(T* field, Parse parse) {
  return [field, parse](py::handle value) { *field = parse(py::cast<std::string>(value)); };
}

// A field whose being given matters (sfm::TrackerSettings: a given value wins over the pairing's).
template <typename T>
Setter Given(std::optional<T>* field) {
  return [field](py::handle value) {
    T given{};
    Field (&given)(value);
    *field = given;
  };
}

// Sets every (name, value) of `options` through `table`; unknown names raise ValueError listing the
// valid ones, values of the wrong type TypeError, both naming `context` and the option.
void ApplyOptions(const py::dict& options, const OptionTable& table, const std::string& context) {
  for (const auto& [key, value] : options) {
    const std::string name = py::cast<std::string>(key);
    const auto it = table.find(name);
    if (it == table.end()) {
      std::string valid;
      for (const auto& entry : table) valid += (valid.empty() ? "" : ", ") + entry.first;
      throw Error(ErrorKind::kInvalidArgument,
                  context + ": unknown option '" + name + "' (valid: " + valid + ")");
    }
    try {
      it->second(value);
    } catch (const py::cast_error&) {
      throw py::type_error(context + ": option '" + name + "' has the wrong type (" +
                           py::cast<std::string>(py::str(value.get_type())) + ")");
    } catch (const py::type_error& e) {
      throw py::type_error(context + ": option '" + name + "' " + e.what());
    } catch (const py::value_error& e) {
      throw Error(ErrorKind::kInvalidArgument, context + ": option '" + name + "' " + e.what());
    }
  }
}

OptionTable DetectorOptionTable(frontend::DetectorOptions* o) {
  if (o->name == "comic") {
    frontend::ComicDirectDetectorOptions* c = &o->comic;
    return {{"scale", Field(&c->scale)},
            {"delta", Field(&c->delta)},
            {"half_length", Field(&c->half_length)},
            {"min_cornerness", Field(&c->min_cornerness)},
            {"level_radius", Field(&c->level_radius)},
            {"bridge_levels", Field(&c->bridge_levels)},
            {"link_radius", Field(&c->link_radius)},
            {"consensus_fraction", Field(&c->consensus_fraction)},
            {"presmoothing_sigma", Field(&c->presmoothing_sigma)},
            {"merge_radius", Field(&c->merge_radius)},
            {"min_stability", Field(&c->min_stability)},
            {"threads", Field(&c->num_threads)}};
  }
  if (o->name == "comic-paper") {
    frontend::ComicDetectorOptions* c = &o->comic_paper;
    return {{"scale", Field(&c->scale)},
            {"block_size", Field(&c->block_size)},
            {"delta", Field(&c->delta)},
            {"half_length", Field(&c->half_length)},
            {"max_iterations", Field(&c->max_iterations)},
            {"convergence_tolerance", Field(&c->convergence_tolerance)},
            {"stop_tolerance", Field(&c->stop_tolerance)},
            {"merge_radius", Field(&c->merge_radius)},
            {"min_stability", Field(&c->min_stability)},
            {"threads", Field(&c->num_threads)},
            {"min_cornerness", Field(&c->min_cornerness)},
            {"coarse_initialisation", Field(&c->coarse_initialisation)},
            {"seed_neighbouring_corners", Field(&c->seed_neighbouring_corners)},
            {"skip_duplicate_paths", Field(&c->skip_duplicate_paths)}};
  }
  if (o->name == "harris") {
    frontend::HarrisDetectorOptions* h = &o->harris;
    return {{"derivative_sigma", Field(&h->derivative_sigma)},
            {"integration_sigma", Field(&h->integration_sigma)},
            {"k", Field(&h->k)},
            {"nms_radius", Field(&h->nms_radius)},
            {"border", Field(&h->border)},
            {"min_response", Field(&h->min_response)}};
  }
  if (o->name == "hessian") {
    frontend::HessianDetectorOptions* h = &o->hessian;
    return {{"sigma", Field(&h->sigma)},
            {"nms_radius", Field(&h->nms_radius)},
            {"border", Field(&h->border)},
            {"min_response", Field(&h->min_response)}};
  }
  if (o->name == "mser") {
    frontend::MserDetectorOptions* m = &o->mser;
    return {{"delta", Field(&m->delta)},
            {"min_area", Field(&m->min_area)},
            {"max_area", Field(&m->max_area)},
            {"max_variation", Field(&m->max_variation)},
            {"merge_radius", Field(&m->merge_radius)}};
  }
  frontend::FastDetectorOptions* f = &o->fast;
  return {{"min_threshold", Field(&f->min_threshold)},
          {"nonmax_suppression", Field(&f->nonmax_suppression)}};
}

// `options` for the detector `name` (one of comic.DETECTORS, or several joined by '+' when
// `options` is empty). `threads` says whether "threads" is one of them (detect; the runs take
// their threads= instead, as the flags do).
frontend::DetectorOptions MakeDetectorOptions(const std::string& name, const py::dict& options,
                                              bool threads = true) {
  frontend::DetectorOptions detector_options;
  detector_options.name = name;
  frontend::CheckDetectorName(name);  // the command line's message, listing the names
  if (options.empty()) return detector_options;
  COMIC_CHECK(name.find('+') == std::string::npos, kInvalidArgument,
              "detector_options are one detector's; '" << name << "' names several");
  OptionTable table = DetectorOptionTable(&detector_options);
  table.emplace("scale_levels", Field(&detector_options.scale_space.num_levels));
  if (!threads) table.erase("threads");
  ApplyOptions(options, table, "detector '" + name + "'");
  detector_options.Check();
  // The apps' bound on threads (issue 29: threads=10**6 aborted the interpreter).
  io::CheckThreadCount("--threads", detector_options.comic.num_threads);
  io::CheckThreadCount("--threads", detector_options.comic_paper.num_threads);
  return detector_options;
}

void AddMatcherOptions(frontend::PatchMatcherOptions* m, OptionTable* table) {
  // The apps' names (apps/common/shared_flags.h): --search-radius, --max-cost, ...
  table->insert({{"search_radius", Field(&m->radius)},
                 {"cost", Parsed(&m->cost, frontend::ParseMatchCost)},
                 {"min_side_overlap", Field(&m->min_side_overlap)},
                 {"max_cost", Field(&m->max_cost)}});
}

// comic.track's tracker options named as the apps' tracker flags (apps/common/tracker_flags.h).
void AddSfmTrackerOptions(frontend::TrackerOptions* t, OptionTable* table) {
  table->insert({{"max_features", Field(&t->max_features)},
                 {"search_radius", Field(&t->matcher.radius)},
                 {"unpredicted_radius", Field(&t->unpredicted_radius)},
                 {"prediction", Parsed(&t->prediction, frontend::ParseMotionPrediction)},
                 {"coarse_radius", Field(&t->coarse_radius)},
                 {"match_window", Field(&t->match_window)},
                 {"track_conflicts", Parsed(&t->conflict_rule, frontend::ParseTrackConflictRule)},
                 {"verify_min_gap", Field(&t->verify_min_gap)},
                 {"match_turned", Field(&t->match_turned_180)},
                 {"max_cost", Field(&t->matcher.max_cost)}});
}

// comic.track: the shared tracker options, the matcher's cost, and the tracker's finer fields.
void AddTrackerOptions(frontend::TrackerOptions* t, OptionTable* table) {
  AddMatcherOptions(&t->matcher, table);
  AddSfmTrackerOptions(t, table);
  table->insert({{"min_response", Field(&t->min_response)},
                 {"velocity_neighbours", Field(&t->velocity_neighbours)},
                 {"velocity_neighbour_radius", Field(&t->velocity_neighbour_radius)},
                 {"coarse_factor", Field(&t->coarse_factor)},
                 {"coarse_features", Field(&t->coarse_features)}});
}

void AddSequenceOptions(io::ImageSequenceOptions* s, OptionTable* table) {
  table->insert({{"resize_height", Field(&s->resize_height)},
                 {"first", Field(&s->first_frame)},
                 {"last", Field(&s->last_frame)},
                 {"stride", Field(&s->stride)}});
}

// ---- images and features ----------------------------------------------------------------------

// An 8-bit numpy image, H x W (grey) or H x W x 3 (BGR, as cv2 reads it), copied into a grey
// cv::Mat; more than `max_pixels` pixels are refused before the copy (the apps' budget).
cv::Mat GrayFromArray(const py::array& image, const std::string& what,
                      int64_t max_pixels = io::kDefaultMaxPixels) {
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

template <typename T>
py::array_t<T> Column(const FeatureSet& features, T (*get)(const Feature&)) {
  py::array_t<T> column(static_cast<py::ssize_t>(features.size()));
  T* out = column.mutable_data();
  for (size_t i = 0; i < features.size(); ++i) out[i] = get(features[i]);
  return column;
}

// The features as columns (x, y, scale, response, cornerness, level, polarity), the side masks
// as an N x 23 x 23 uint8 array (0: neither side, 1: ic+, 2: ic−; all 0 without side information)
// and has_side_mask.
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

// The inverse of FeaturesToColumns (the masks may be None: no side information).
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

// A Python progress callback called from C++ code running without the GIL: it takes the GIL for
// the call. It captures a pointer to the caller's py::object (alive for the whole call), so that
// copying the std::function inside the libraries touches no Python reference count without the
// GIL.
frontend::TrackingProgress TrackingCallback(const py::object& callback) {
  if (callback.is_none()) return {};
  const py::object* function = &callback;
  return [function](size_t done, size_t total) {
    py::gil_scoped_acquire gil;
    (*function)(done, total);
  };
}

// The run's progress for Python: `callback(event)` after each registered frame (a dict), and the
// command line's lines printed (sys.stdout) unless `quiet`; a truncated video's warning and an
// unusable --cache file's as a RuntimeWarning. Each takes the GIL, as TrackingCallback does.
sfm::RunCallbacks RunCallbacksFor(const py::object& callback, bool quiet,
                                  const std::string& program) {
  sfm::RunCallbacks callbacks;
  const py::object* function = &callback;
  callbacks.inputs_resolved = [quiet, program](const sfm::RunInputs& inputs) {
    py::gil_scoped_acquire gil;
    if (!inputs.sequence->warning().empty() &&
        PyErr_WarnEx(PyExc_RuntimeWarning, inputs.sequence->warning().c_str(), 1) != 0) {
      throw py::error_already_set();
    }
    if (quiet) return;
    for (const std::string& line : sfm::RunInputsLines(inputs, program)) py::print(line);
  };
  // A cache file that could not be used (recomputed and replaced), as the truncated video's.
  callbacks.warning = [](const std::string& message) {
    py::gil_scoped_acquire gil;
    if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw py::error_already_set();
  };
  // A choice the run made as it went (a second matcher tried), printed as the command line does.
  callbacks.note = [quiet, program](const std::string& message) {
    if (quiet) return;
    py::gil_scoped_acquire gil;
    py::print(program + ": " + message);
  };
  callbacks.frame_registered = [function, quiet](const std::string& detector,
                                                 const sfm::MapperProgress& p) {
    if (function->is_none() && quiet) return;
    py::gil_scoped_acquire gil;
    if (!quiet) py::print(sfm::FrameRegisteredLine(detector, p));
    if (function->is_none()) return;
    py::dict event;
    event["detector"] = detector;
    event["frame"] = p.frame;
    event["frame_name"] = p.frame_name;
    event["model"] = p.attempt;
    event["initial_pair"] = p.initial_pair;
    event["merged"] = p.merged;
    event["num_registered"] = p.num_registered;
    event["num_frames"] = p.num_frames;
    event["num_points3D"] = p.num_points3D;
    (*function)(event);
  };
  if (!quiet) {
    callbacks.detector_finished = [](const sfm::DetectorRun& run) {
      py::gil_scoped_acquire gil;
      py::print(sfm::DetectorSummaryLine(run));
    };
  }
  return callbacks;
}

// ---- the functions ----------------------------------------------------------------------------

// A keyword argument as an option of `context` (a T, an int beyond T's range a ValueError).
template <typename T>
T Argument(const py::object& value, const std::string& name, const std::string& context) {
  T result{};
  py::dict options;
  options[py::str(name)] = value;
  ApplyOptions(options, {{name, Field(&result)}}, context);
  return result;
}

py::array_t<uint8_t> ImRead(const std::string& path, const py::object& resize_height_argument,
                            bool color, const py::object& max_pixels_argument) {
  const int resize_height = Argument<int>(resize_height_argument, "resize_height", "imread");
  const int64_t max_pixels = Argument<int64_t>(max_pixels_argument, "max_pixels", "imread");
  io::CheckResizeHeight(resize_height, "resize_height");
  io::CheckMaxPixels(max_pixels);
  const io::LoadedImage image = io::LoadImage(path, resize_height, max_pixels);
  const cv::Mat& mat = color ? image.color : image.gray;
  std::vector<py::ssize_t> shape = {mat.rows, mat.cols};
  if (color) shape.push_back(3);
  py::array_t<uint8_t> array(shape);
  const size_t row_bytes = static_cast<size_t>(mat.cols) * mat.channels();
  for (int r = 0; r < mat.rows; ++r) {
    std::memcpy(array.mutable_data() + r * row_bytes, mat.ptr<uint8_t>(r), row_bytes);
  }
  return array;
}

py::dict Detect(const py::array& image, const std::string& detector_name, const py::dict& options,
                const py::object& max_pixels_argument) {
  const frontend::DetectorOptions detector_options = MakeDetectorOptions(detector_name, options);
  const int64_t max_pixels = Argument<int64_t>(max_pixels_argument, "max_pixels", "detect");
  io::CheckMaxPixels(max_pixels);
  const cv::Mat gray = GrayFromArray(image, "detect", max_pixels);
  FeatureSet features;
  {
    py::gil_scoped_release release;
    features = frontend::MakeDetector(detector_options)->Detect(gray);
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
  const frontend::DetectorOptions made = MakeDetectorOptions(detector_name, detector_options);
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

// A reconstruction for Python: the COLMAP model and, for a run's, its report.json and status.
struct PyReconstruction {
  io::ColmapTextModel model;  // a run's largest model, in the input's pixels as comic_sfm writes it
  // A run's: every model (the largest first), in the input's pixels; and the run itself with its
  // options, kept so that writing it is comic_sfm's own writer on the same run (WriteOutputs).
  std::vector<io::ColmapTextModel> models;
  std::shared_ptr<const sfm::ReconstructionRunResult> run_result;
  size_t run_index = 0;
  sfm::ReconstructionRunOptions run_options;
  std::string status;       // ReconstructionStatusName; "" for a model read without a report
  std::string report_json;  // report.json's text ("" without one)
  std::string failure;      // a single detector's run without a model: the command line's error
  std::string path;         // where the model is on disk ("" for a run without --output)
};

py::dict ModelToColumns(const io::ColmapTextModel& model) {
  py::dict result;
  {
    const size_t n = model.cameras.size();
    py::array_t<uint32_t> id(n);
    py::array_t<int32_t> width(n), height(n);
    py::list names, params;
    for (size_t i = 0; i < n; ++i) {
      const io::ColmapCamera& c = model.cameras[i];
      id.mutable_at(i) = c.camera_id;
      width.mutable_at(i) = c.width;
      height.mutable_at(i) = c.height;
      names.append(c.model);
      params.append(py::array_t<double>(c.params.size(), c.params.data()));
    }
    py::dict cameras;
    cameras["camera_id"] = id;
    cameras["model"] = names;
    cameras["width"] = width;
    cameras["height"] = height;
    cameras["params"] = params;
    result["cameras"] = cameras;
  }
  {
    const size_t n = model.images.size();
    py::array_t<uint32_t> id(n), camera_id(n), num_points2D(n);
    py::array_t<double> qvec({static_cast<py::ssize_t>(n), py::ssize_t{4}});
    py::array_t<double> tvec({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    py::list names;
    size_t num_observations = 0;
    for (const io::ColmapImage& image : model.images) num_observations += image.points2D.size();
    py::array_t<uint32_t> obs_image(num_observations);
    py::array_t<double> obs_x(num_observations), obs_y(num_observations);
    py::array_t<int64_t> obs_point(num_observations);
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
      const io::ColmapImage& image = model.images[i];
      id.mutable_at(i) = image.image_id;
      camera_id.mutable_at(i) = image.camera_id;
      num_points2D.mutable_at(i) = static_cast<uint32_t>(image.points2D.size());
      const Eigen::Quaterniond& q = image.cam_from_world_rotation;
      qvec.mutable_at(i, 0) = q.w();
      qvec.mutable_at(i, 1) = q.x();
      qvec.mutable_at(i, 2) = q.y();
      qvec.mutable_at(i, 3) = q.z();
      for (int c = 0; c < 3; ++c) tvec.mutable_at(i, c) = image.cam_from_world_translation[c];
      names.append(image.name);
      for (const io::ColmapPoint2D& point : image.points2D) {
        obs_image.mutable_at(k) = image.image_id;
        obs_x.mutable_at(k) = point.x;
        obs_y.mutable_at(k) = point.y;
        obs_point.mutable_at(k) = point.point3D_id;
        ++k;
      }
    }
    py::dict images;
    images["image_id"] = id;
    images["camera_id"] = camera_id;
    images["qvec"] = qvec;
    images["tvec"] = tvec;
    images["name"] = names;
    images["num_points2D"] = num_points2D;
    result["images"] = images;
    py::dict points2D;
    points2D["image_id"] = obs_image;
    points2D["x"] = obs_x;
    points2D["y"] = obs_y;
    points2D["point3D_id"] = obs_point;
    result["points2D"] = points2D;
  }
  {
    const size_t n = model.points3D.size();
    py::array_t<uint64_t> id(n);
    py::array_t<double> xyz({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    py::array_t<uint8_t> rgb({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    py::array_t<double> error(n);
    py::array_t<uint32_t> track_length(n);
    for (size_t i = 0; i < n; ++i) {
      const io::ColmapPoint3D& p = model.points3D[i];
      id.mutable_at(i) = p.point3D_id;
      for (int c = 0; c < 3; ++c) {
        xyz.mutable_at(i, c) = p.xyz[c];
        rgb.mutable_at(i, c) = p.rgb[c];
      }
      error.mutable_at(i) = p.error;
      track_length.mutable_at(i) = static_cast<uint32_t>(p.track.size());
    }
    py::dict points;
    points["point3D_id"] = id;
    points["xyz"] = xyz;
    points["rgb"] = rgb;
    points["error"] = error;
    points["track_length"] = track_length;
    result["points3D"] = points;
  }
  return result;
}

// ---- the runs ---------------------------------------------------------------------------------

// The tracker flags of comic_sfm and comic_export_colmap (apps/common/tracker_flags.h), given.
// A field of an optional struct: the struct is engaged with its defaults first, as the CLI takes
// the whole struct once any of its flags is given (apps/common/tracker_flags.cc).
template <typename S, typename Access>
Setter InOptional(std::optional<S>* holder, Access access) {
  return [holder, access](py::handle value) {
    S given = holder->value_or(S());
    Field (&access(given))(value);
    *holder = given;
  };
}

void AddRunTrackerSettings(sfm::TrackerSettings* t, OptionTable* table) {
  table->insert({{"max_features", Given(&t->max_features)},
                 {"search_radius", Given(&t->search_radius)},
                 {"unpredicted_radius", Given(&t->unpredicted_radius)},
                 {"prediction", Given(&t->prediction)},
                 {"coarse_radius", Given(&t->coarse_radius)},
                 {"match_window", Given(&t->match_window)},
                 {"track_conflicts", Given(&t->track_conflicts)},
                 {"verify_min_gap", Given(&t->verify_min_gap)},
                 {"match_turned", Given(&t->match_turned)},
                 {"max_cost", Given(&t->max_cost)},
                 {"align_patches", Given(&t->align_patches)},
                 {"min_window_eigenvalue", Given(&t->min_window_eigenvalue)}});
  using Continuation = frontend::TrackContinuationOptions;
  std::optional<Continuation>* c = &t->continuation;
  table->insert(
      {{"max_continued_frames",
        InOptional(c, [](Continuation& o) -> int& { return o.max_continued_frames; })},
       {"max_alignment_residual",
        InOptional(c, [](Continuation& o) -> double& { return o.max_residual; })},
       {"aligned_radius",
        InOptional(c, [](Continuation& o) -> double& { return o.aligned_radius; })},
       {"min_alignment_correlation",
        InOptional(c, [](Continuation& o) -> double& { return o.min_correlation; })},
       {"alignment_min_eigenvalue",
        InOptional(c, [](Continuation& o) -> double& { return o.alignment.min_eigenvalue; })},
       {"bridge_frames", InOptional(c, [](Continuation& o) -> int& { return o.bridge_frames; })},
       {"alignment_max_fb",
        InOptional(c,
                   [](Continuation& o) -> double& { return o.alignment.max_forward_backward_px; })},
       {"alignment_iterations",
        InOptional(c, [](Continuation& o) -> int& { return o.alignment.max_iterations; })},
       {"alignment_levels",
        InOptional(c, [](Continuation& o) -> int& { return o.alignment.levels; })}});
}

// --first, --last, --stride, --resize-height, --max-pixels.
void AddRunSequenceOptions(io::ImageSequenceOptions* s, OptionTable* table) {
  AddSequenceOptions(s, table);
  (*table)["max_pixels"] = Field(&s->max_pixels);
}

// --colmap-db and its flags (apps/common/colmap_db_flags.h).
void AddColmapDatabaseOptions(sfm::ColmapDatabaseOptions* c, OptionTable* table) {
  table->insert({{"colmap_db", Field(&c->colmap_db)},
                 {"overwrite", Field(&c->overwrite)},
                 {"window", Field(&c->export_options.pair_window)},
                 {"max_error", Field(&c->export_options.two_view.max_error_px)},
                 {"min_inliers", Field(&c->export_options.two_view.min_num_inliers)},
                 {"colmap_threads", Field(&c->colmap_threads)}});
}

// A flag that turns a field off (--mask-keeps-nonzero: mask_drops_nonzero = false); the keyword
// is the flag's name, as every other.
Setter Negated(bool* field) {
  return [field](py::handle value) {
    if (!py::isinstance<py::bool_>(value)) throw py::type_error("expects a bool");
    *field = !py::cast<bool>(value);
  };
}

// --write-frames: True for the default folder (`implicit`), a path, or False / "" for none.
Setter WriteFrames(std::string* field, const char* implicit) {
  return [field, implicit](py::handle value) {
    if (py::isinstance<py::bool_>(value)) {
      *field = py::cast<bool>(value) ? implicit : "";
    } else {
      *field = py::cast<std::string>(value);
    }
  };
}

// comic_sfm's options by their flags' names (apps/comic_sfm.cc and sfm/run/run_option_table.h),
// into the run's options.
OptionTable ReconstructOptionTable(sfm::ReconstructionRunOptions* o, bool* quiet) {
  OptionTable table = {{"detector", Field(&o->detector)},
                       {"scale_levels", Field(&o->detector_options.scale_space.num_levels)},
                       {"detectors", Field(&o->detectors)},
                       {"intrinsics", Field(&o->camera.intrinsics)},
                       {"camera_model", Field(&o->camera.camera_model)},
                       {"allow_truncated", Field(&o->sequence.allow_truncated)},
                       {"matching", Field(&o->matching)},
                       {"matcher", Field(&o->matcher)},
                       {"threads", Field(&o->threads)},
                       {"masks", Field(&o->masks)},
                       {"mask_keeps_nonzero", Negated(&o->mask_drops_nonzero)},
                       {"regions", Field(&o->regions)},
                       {"boundary_band", Field(&o->boundary_band)},
                       {"output", Field(&o->output)},
                       {"write_frames", WriteFrames(&o->write_frames, sfm::kFramesInOutput)},
                       {"quiet", Field(quiet)}};
  // The plain options: a keyword per entry of the library's table, typed as its field. A keyword
  // also set up by hand above would leave one of the two setters unused.
  for (const sfm::RunOption& entry : sfm::RunOptionTable()) {
    Setter setter = std::visit([o](auto field) { return Field(&field(*o)); }, entry.field);
    const bool added = table.emplace(entry.keyword, std::move(setter)).second;
    COMIC_CHECK(added, kInvalidArgument, "reconstruct: two setters for '" << entry.keyword << "'");
  }
  AddRunSequenceOptions(&o->sequence, &table);
  AddRunTrackerSettings(&o->tracker, &table);
  AddColmapDatabaseOptions(&o->colmap, &table);
  return table;
}

// The `index`th run of `run_result`, its models in the input's pixels (as comic_sfm writes them).
PyReconstruction FromDetectorRun(
    const std::shared_ptr<const sfm::ReconstructionRunResult>& run_result, size_t index,
    const sfm::ReconstructionRunOptions& options, const std::string& path) {
  const sfm::DetectorRun& run = run_result->runs[index];
  PyReconstruction result;
  result.run_result = run_result;
  result.run_index = index;
  result.run_options = options;
  if (run.success()) {
    const sfm::ModelSetWriteOptions in_input_pixels = sfm::ModelWriteOptions(run, options);
    for (const sfm::Reconstruction* model : sfm::ModelsLargestFirst(run.run.mapping)) {
      result.models.push_back(sfm::ColmapModelForImages(*model, in_input_pixels));
    }
    result.model = result.models.front();
  }
  result.status = sfm::ReconstructionStatusName(run.run.mapping.status);
  result.report_json = io::JsonText(run.report_json, 2);
  result.path = run.success() ? path : "";
  return result;
}

// comic.reconstruct: comic_sfm's run (sfm/run/reconstruction_run.h). Returns {"runs": [one
// Reconstruction per detector], "failure", "comparison" (the --compare table), "lines" (what
// comic_sfm prints after the run)}.
py::dict Reconstruct(const std::string& frames, const py::dict& options,
                     const py::dict& detector_options, const py::object& callback) {
  sfm::ReconstructionRunOptions run;
  run.frames = frames;
  run.output.clear();  // nothing written unless output= is given
  bool quiet = true;
  ApplyOptions(options, ReconstructOptionTable(&run, &quiet), "reconstruct");
  run.Check();
  if (!detector_options.empty()) {
    COMIC_CHECK(!run.compare, kInvalidArgument,
                "detector_options are one detector's, not --compare's");
    const int scale_levels = run.detector_options.scale_space.num_levels;  // scale_levels=
    run.detector_options =
        MakeDetectorOptions(run.DetectorList().front(), detector_options, /*threads=*/false);
    // detector_options' own scale_levels wins over the keyword's only when it is given.
    if (!detector_options.contains("scale_levels")) {
      run.detector_options.scale_space.num_levels = scale_levels;
    }
  }
  const sfm::RunCallbacks callbacks = RunCallbacksFor(callback, quiet, "comic.reconstruct");
  sfm::ReconstructionRunResult result;
  {
    py::gil_scoped_release release;
    result = sfm::RunReconstruction(run, callbacks);
  }
  const auto shared = std::make_shared<const sfm::ReconstructionRunResult>(std::move(result));
  py::list runs;
  for (size_t i = 0; i < shared->runs.size(); ++i) {
    const std::string& detector = shared->runs[i].detector;
    const std::string folder = run.output.empty() ? ""
                               : run.compare      ? io::JoinPaths(run.output, detector)
                                                  : run.output;
    PyReconstruction reconstruction = FromDetectorRun(shared, i, run, folder);
    if (!run.compare) reconstruction.failure = shared->failure;
    runs.append(py::cast(std::move(reconstruction)));
  }
  py::dict out;
  out["runs"] = runs;
  out["failure"] = shared->failure;
  out["comparison"] =
      shared->comparison ? py::object(py::str(shared->comparison->ToMarkdown())) : py::none();
  out["lines"] = sfm::RunOutcomeLines(*shared, run.output, "comic.reconstruct", quiet);
  return out;
}

// comic.Reconstruction(path): a model in a folder (io/colmap/colmap_model_folder.h), with the
// report.json beside it when comic_sfm wrote one.
PyReconstruction ReadReconstruction(const std::string& path) {
  PyReconstruction result;
  result.model = io::ReadColmapModel(path);
  result.models = {result.model};
  result.path = path;
  const std::string report = io::JoinPaths(path, "report.json");
  if (io::PathExists(report)) {
    result.report_json = io::ReadFileToString(report);
    const nlohmann::json json = nlohmann::json::parse(result.report_json, nullptr, false);
    COMIC_CHECK(!json.is_discarded() && json.is_object(), kInvalidData,
                report << ": not a JSON object");
    if (json.contains("status") && json["status"].is_string()) result.status = json["status"];
  }
  return result;
}

// Reconstructions.write: a run's outputs written by comic_sfm's writer (sfm/run/run_outputs.h) into
// `folder`, as `comic_sfm FRAMES --output folder --model-format ... --ply-format ...` writes them
// for one detector.
void WriteOutputs(const PyReconstruction& r, const std::string& folder,
                  const std::string& model_format, const std::string& ply_format) {
  COMIC_CHECK(r.run_result != nullptr, kInvalidArgument,
              "write: only a run's reconstruction (comic.reconstruct) writes a run's outputs");
  sfm::ReconstructionRunOptions options = r.run_options;
  options.output = folder;
  options.compare = false;
  options.model_format = model_format;
  options.ply_format = ply_format;
  io::ParsePlyFormat(ply_format);  // its message names the PLY formats
  options.Check();
  // As comic_sfm's --output: no written file may replace an input (a folder of frames written
  // into would receive trajectory.png and the reports).
  io::CheckOutputsAvoidInputs({{"write", folder}}, sfm::RunInputPaths(options));
  io::CheckWrittenPathsAvoidInputs(sfm::RunWrittenPaths(options), sfm::RunInputPaths(options));
  py::gil_scoped_release release;
  sfm::WriteDetectorOutputs(r.run_result->runs[r.run_index], options, r.run_result->inputs, folder);
}

// One model of a run's reconstruction (0: the largest), alone, with the run's report.
PyReconstruction ModelOf(const PyReconstruction& r, size_t index) {
  COMIC_CHECK(index < r.models.size(), kInvalidArgument,
              "model " << index << ": the reconstruction holds " << r.models.size() << " models");
  PyReconstruction model;
  model.model = r.models[index];
  model.models = {r.models[index]};
  model.status = r.status;
  model.report_json = r.report_json;
  model.failure = r.failure;
  model.path = r.path;
  return model;
}

// comic_export_colmap's options by their flags' names (apps/comic_export_colmap.cc).
OptionTable ExportOptionTable(sfm::ColmapExportRunOptions* o, bool* quiet) {
  OptionTable table = {{"intrinsics", Field(&o->camera.intrinsics)},
                       {"camera_model", Field(&o->camera.camera_model)},
                       {"detector", Field(&o->detector)},
                       {"matching", Field(&o->matching)},
                       {"matcher", Field(&o->matcher)},
                       {"threads", Field(&o->threads)},
                       {"image_path", Field(&o->image_path)},
                       {"sparse", Field(&o->sparse)},
                       {"write_frames", WriteFrames(&o->write_frames, sfm::kFramesBesideDatabase)},
                       {"quiet", Field(quiet)}};
  AddColmapDatabaseOptions(&o->colmap, &table);
  table.erase("colmap_db");  // the second argument
  AddRunSequenceOptions(&o->sequence, &table);
  AddRunTrackerSettings(&o->tracker, &table);
  return table;
}

// comic.export_colmap: comic_export_colmap's run (sfm/run/colmap_export_run.h).
py::dict ExportColmap(const std::string& frames, const std::string& colmap_db,
                      const py::dict& options, const py::dict& detector_options) {
  sfm::ColmapExportRunOptions run;
  run.frames = frames;
  run.colmap.colmap_db = colmap_db;
  bool quiet = true;
  ApplyOptions(options, ExportOptionTable(&run, &quiet), "export_colmap");
  run.Check();
  if (!detector_options.empty()) {
    run.detector_options = MakeDetectorOptions(run.detector, detector_options, /*threads=*/false);
  }
  sfm::ColmapExportRunResult result;
  {
    py::gil_scoped_release release;
    result = sfm::RunColmapExport(run);
  }
  if (!quiet) {
    for (const std::string& line : sfm::ColmapExportReportLines(run, result)) py::print(line);
  }
  const sfm::ColmapExportSummary& summary = result.summary;
  py::dict out;
  out["num_images"] = summary.num_images;
  out["num_keypoints"] = summary.num_keypoints;
  out["num_matched_pairs"] = summary.num_matched_pairs;
  out["num_verified_pairs"] = summary.num_verified_pairs;
  out["num_matches"] = summary.num_matches;
  out["num_inlier_matches"] = summary.num_inlier_matches;
  out["known_intrinsics"] = summary.known_intrinsics;
  out["num_tracks"] = result.num_tracks;
  out["num_observations"] = result.num_observations;
  out["matching"] = frontend::PairingName(result.pairing.chosen);
  out["frames_folder"] = result.frames_folder;
  out["image_path"] = result.image_path;
  out["mapper_command"] = result.mapper_command;
  return out;
}

}  // namespace
}  // namespace comic::python

PYBIND11_MODULE(_core, m) {
  using namespace comic::python;
  m.doc() = "comic-sfm's compiled core; use the package `comic` (python/comic/__init__.py).";
  m.attr("__version__") = comic::Version();  // project(VERSION), through io/core/version.cc
  m.attr("detector_names") = comic::frontend::DetectorNames();
  m.attr("patch_size") = comic::frontend::kPatchSize;

  // Every C++ error is a Python exception with the command line's one line (RunMain's): the
  // option named as the flag, printable, never an abort and never a raw multi-line library text.
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const comic::Error& e) {
      const std::string message =
          comic::io::PrintableMessage(comic::sfm::WithUserOptionNames(e.what()));
      if (e.kind() == comic::ErrorKind::kInvalidArgument) {
        PyErr_SetString(PyExc_ValueError, message.c_str());
      } else {
        PyErr_SetString(PyExc_RuntimeError, message.c_str());
      }
    } catch (const cv::Exception& e) {
      PyErr_SetString(
          PyExc_RuntimeError,
          ("OpenCV: " + comic::io::PrintableOneLine(e.err) + " (" + e.func + ")").c_str());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "out of memory");
    }
  });

  m.attr("default_max_pixels") = comic::io::kDefaultMaxPixels;
  m.def("imread", &ImRead, py::arg("path"), py::arg("resize_height"), py::arg("color"),
        py::arg("max_pixels"));
  m.def("detect", &Detect, py::arg("image"), py::arg("detector"), py::arg("options"),
        py::arg("max_pixels"));
  m.def("match", &Match, py::arg("image1"), py::arg("features1"), py::arg("side_masks1"),
        py::arg("image2"), py::arg("features2"), py::arg("side_masks2"), py::arg("options"));
  m.def("track", &Track, py::arg("frames"), py::arg("detector"), py::arg("detector_options"),
        py::arg("options"), py::arg("callback"));
  m.def("reconstruct", &Reconstruct, py::arg("frames"), py::arg("options"),
        py::arg("detector_options"), py::arg("callback"));
  m.def("export_colmap", &ExportColmap, py::arg("frames"), py::arg("colmap_db"), py::arg("options"),
        py::arg("detector_options"));
  m.def("read_reconstruction", &ReadReconstruction, py::arg("path"));
  BindDistributed(m);
  m.def("reconstruct_option_names", [] {
    comic::sfm::ReconstructionRunOptions options;
    bool quiet = true;
    std::vector<std::string> names;
    for (const auto& entry : ReconstructOptionTable(&options, &quiet)) names.push_back(entry.first);
    return names;
  });
  // The library's table of plain run options (sfm/run/run_option_table.h), for the docstring of
  // reconstruct() and the tests that every entry is a flag and a keyword.
  m.def("run_option_table", [] {
    py::list entries;
    comic::sfm::ReconstructionRunOptions defaults;
    for (const comic::sfm::RunOption& entry : comic::sfm::RunOptionTable()) {
      py::dict d;
      d["flag"] = entry.flag;
      d["keyword"] = entry.keyword;
      d["metavar"] = entry.metavar;
      d["help"] = entry.help;
      d["default"] = std::visit([&](auto field) { return py::cast(field(defaults)); }, entry.field);
      entries.append(d);
    }
    return entries;
  });
  m.def("export_colmap_option_names", [] {
    comic::sfm::ColmapExportRunOptions options;
    bool quiet = true;
    std::vector<std::string> names;
    for (const auto& entry : ExportOptionTable(&options, &quiet)) names.push_back(entry.first);
    return names;
  });

  py::class_<PyReconstruction>(m, "Reconstruction")
      .def_readonly("status", &PyReconstruction::status)
      .def_readonly("report_json", &PyReconstruction::report_json)
      .def_readonly("failure", &PyReconstruction::failure)
      .def_readonly("path", &PyReconstruction::path)
      .def("columns", [](const PyReconstruction& r) { return ModelToColumns(r.model); })
      .def("num_models", [](const PyReconstruction& r) { return r.models.size(); })
      .def("has_run", [](const PyReconstruction& r) { return r.run_result != nullptr; })
      .def("model", &ModelOf, py::arg("index"))
      .def("write_outputs", &WriteOutputs, py::arg("folder"), py::arg("model_format"),
           py::arg("ply_format"))
      .def("write_text",
           [](const PyReconstruction& r, const std::string& folder) {
             comic::io::WriteColmapTextModel(r.model, folder);
           })
      .def("write_binary",
           [](const PyReconstruction& r, const std::string& folder) {
             comic::io::WriteColmapBinaryModel(r.model, folder);
           })
      .def("write_ply",
           [](const PyReconstruction& r, const std::string& path, const std::string& format) {
             std::vector<comic::io::PlyPoint> cloud;
             for (const comic::io::ColmapPoint3D& point : r.model.points3D) {
               cloud.push_back({point.xyz, point.rgb});
             }
             comic::io::WritePly(path, cloud, comic::io::ParsePlyFormat(format));
           });
}
