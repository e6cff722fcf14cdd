#include "io/datasets/region_annotations.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/datasets/number_field.h"

namespace comic::io {
namespace {

// Splits a line on commas, tabs and spaces and parses every field as a number. Returns false
// (with the offending field in *bad_field) if a field is not a number.
bool ParseNumbers(const std::string& line, std::vector<double>* numbers, std::string* bad_field) {
  numbers->clear();
  std::string field;
  auto flush = [&]() -> bool {
    if (field.empty()) return true;
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(field.c_str(), &end);
    // The whole field: a NUL byte inside it is not the end of the number. Unlike the other
    // readers' ParseNumberField, NaN is a value here (VOT's frames without annotation).
    if (end != field.c_str() + field.size() || errno == ERANGE) {
      *bad_field = field;
      return false;
    }
    numbers->push_back(value);
    field.clear();
    return true;
  };
  for (char c : line) {
    if (c == ',' || c == '\t' || c == ' ' || c == '\r') {
      if (!flush()) return false;
    } else {
      field.push_back(c);
    }
  }
  return flush();
}

RegionPolygon BoxPolygon(double x, double y, double w, double h) {
  // The outer edges of the box's pixels, 1-based top-left pixel (see the header).
  const double x0 = x - 1.5;
  const double y0 = y - 1.5;
  return {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
}

bool AnyNan(const std::vector<double>& numbers) {
  for (double v : numbers) {
    if (std::isnan(v)) return true;
  }
  return false;
}

}  // namespace

RegionFileFormat ParseRegionFileFormat(const std::string& name) {
  if (name == "auto") return RegionFileFormat::kAuto;
  if (name == "vot") return RegionFileFormat::kVotPolygon;
  if (name == "otb") return RegionFileFormat::kOtbBox;
  throw Error(ErrorKind::kInvalidArgument,
              "unknown region format '" + name + "' (valid: auto, vot, otb)");
}

const char* RegionFileFormatName(RegionFileFormat format) {
  switch (format) {
    case RegionFileFormat::kAuto:
      return "auto";
    case RegionFileFormat::kVotPolygon:
      return "vot";
    case RegionFileFormat::kOtbBox:
      return "otb";
  }
  return "?";
}

RegionAnnotations ReadRegionFile(const std::string& path, RegionFileFormat format) {
  const std::string text = ReadFileToString(path);
  std::vector<std::string> lines;
  {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
  }
  // Blank trailing lines are not frames.
  auto is_blank = [](const std::string& line) {
    return line.find_first_not_of(" \t\r,") == std::string::npos;
  };
  while (!lines.empty() && is_blank(lines.back())) lines.pop_back();
  COMIC_CHECK(!lines.empty(), kInvalidData, path << ": holds no region");

  RegionAnnotations annotations;
  annotations.format = format;
  std::vector<double> numbers;
  for (size_t k = 0; k < lines.size(); ++k) {
    std::string bad_field;
    COMIC_CHECK(ParseNumbers(lines[k], &numbers, &bad_field), kInvalidData,
                path << ":" << k + 1 << ": " << QuotedField(bad_field) << " is not a number");
    if (annotations.format == RegionFileFormat::kAuto && !numbers.empty() && !AnyNan(numbers) &&
        !(numbers.size() == 1 && numbers[0] == 0.0)) {
      COMIC_CHECK(numbers.size() == 4 || numbers.size() >= 6, kInvalidData,
                  path << ":" << k + 1 << ": " << numbers.size()
                       << " numbers is neither an OTB box (4) nor a VOT polygon (8)");
      annotations.format =
          numbers.size() == 4 ? RegionFileFormat::kOtbBox : RegionFileFormat::kVotPolygon;
    }
    const RegionFileFormat line_format = annotations.format == RegionFileFormat::kAuto
                                             ? RegionFileFormat::kVotPolygon
                                             : annotations.format;
    // VOT marks frames without annotation by "0" or NaN coordinates.
    if (line_format == RegionFileFormat::kVotPolygon &&
        (AnyNan(numbers) || (numbers.size() == 1 && numbers[0] == 0.0))) {
      annotations.polygons.emplace_back();
      continue;
    }
    COMIC_CHECK(!numbers.empty(), kInvalidData, path << ":" << k + 1 << ": empty line");
    COMIC_CHECK(!AnyNan(numbers), kInvalidData, path << ":" << k + 1 << ": NaN in an OTB box");
    if (line_format == RegionFileFormat::kOtbBox) {
      COMIC_CHECK(numbers.size() == 4, kInvalidData,
                  path << ":" << k + 1 << ": expected an OTB box 'x y w h' (4 numbers), got "
                       << numbers.size());
    } else {
      COMIC_CHECK(numbers.size() == 4 || (numbers.size() >= 6 && numbers.size() % 2 == 0),
                  kInvalidData,
                  path << ":" << k + 1
                       << ": expected a VOT polygon 'x1,y1,...,x4,y4' or rectangle 'x,y,w,h', got "
                       << numbers.size() << " numbers");
    }
    if (numbers.size() == 4) {
      COMIC_CHECK(numbers[2] >= 0 && numbers[3] >= 0, kInvalidData,
                  path << ":" << k + 1 << ": box with negative width or height");
      annotations.polygons.push_back(BoxPolygon(numbers[0], numbers[1], numbers[2], numbers[3]));
    } else {
      RegionPolygon polygon;
      for (size_t i = 0; i + 1 < numbers.size(); i += 2) {
        polygon.emplace_back(numbers[i] - 1.0, numbers[i + 1] - 1.0);
      }
      annotations.polygons.push_back(std::move(polygon));
    }
  }
  if (annotations.format == RegionFileFormat::kAuto) {
    annotations.format = RegionFileFormat::kVotPolygon;  // every line unannotated
  }
  return annotations;
}

cv::Mat RasterizeRegion(const RegionPolygon& polygon, const cv::Size& source_size,
                        const cv::Size& target_size) {
  COMIC_CHECK(source_size.width > 0 && source_size.height > 0 && target_size.width > 0 &&
                  target_size.height > 0,
              kInvalidArgument, "RasterizeRegion: sizes must be positive");
  cv::Mat mask(target_size, CV_8UC1, cv::Scalar(0));
  if (polygon.size() < 3) return mask;
  const double sx = static_cast<double>(target_size.width) / source_size.width;
  const double sy = static_cast<double>(target_size.height) / source_size.height;
  std::vector<cv::Point2d> vertices;
  for (const cv::Point2d& p : polygon) {
    vertices.emplace_back((p.x + 0.5) * sx - 0.5, (p.y + 0.5) * sy - 0.5);
  }
  // Scanline fill at pixel centres: on row y, the polygon's edges crossing y (half-open in y, so
  // a vertex is counted once) cut the row into inside spans [x_a, x_b); pixel x is inside when
  // x_a <= x < x_b.
  std::vector<double> crossings;
  for (int y = 0; y < mask.rows; ++y) {
    crossings.clear();
    for (size_t i = 0; i < vertices.size(); ++i) {
      const cv::Point2d& p = vertices[i];
      const cv::Point2d& q = vertices[(i + 1) % vertices.size()];
      if ((p.y <= y && y < q.y) || (q.y <= y && y < p.y)) {
        crossings.push_back(p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    uint8_t* row = mask.ptr<uint8_t>(y);
    for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
      // Clamp in double first: a crossing far outside the image (a vertex at 1e10 in a region
      // file) does not fit an int, and converting it would be undefined behaviour.
      const double cols = mask.cols;
      const int x0 = static_cast<int>(std::clamp(std::ceil(crossings[k]), 0.0, cols));
      const int x1 = static_cast<int>(std::clamp(std::ceil(crossings[k + 1]), 0.0, cols));
      for (int x = x0; x < x1; ++x) row[x] = 255;
    }
  }
  return mask;
}

}  // namespace comic::io
