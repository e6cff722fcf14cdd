// Fuzz target: image decoding (OpenCV's codecs through cv::imdecode, as cv::imread uses them) and
// our conversion to 8-bit grey, then every detector of the factory on the decoded image. Images
// are capped at 160x160 pixels after decoding so that one input takes milliseconds, not seconds.
#include <cstdio>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "frontend/detector_factory.h"
#include "io/core/error.h"
#include "io/image/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = [] {
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    return true;
  }();
  (void)quiet;
  if (size == 0) return 0;
  const std::vector<uint8_t> bytes(data, data + size);
  cv::Mat raw;
  try {
    raw = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    return 0;  // OpenCV refused the bytes: an answer, not a finding
  }
  if (raw.empty() || raw.total() > 4096u * 4096u) return 0;
  cv::Mat gray;
  try {
    gray = comic::io::ToGray8(raw);
  } catch (const comic::Error&) {
    return 0;  // unsupported depth or channels: reported as our error
  }
  if (gray.cols > 160 || gray.rows > 160) {
    gray = gray(cv::Rect(0, 0, std::min(gray.cols, 160), std::min(gray.rows, 160))).clone();
  }
  for (const std::string& name : comic::frontend::DetectorNames()) {
    try {
      const auto detector = comic::frontend::MakeDetector(name);
      const comic::frontend::FeatureSet features = detector->Detect(gray);
      for (const comic::frontend::Feature& f : features) {
        if (!(f.x >= -1 && f.x <= gray.cols && f.y >= -1 && f.y <= gray.rows)) {
          std::fprintf(stderr,
                       "fuzz_image_detectors: %s put a feature at (%g, %g) in a %dx%d image\n",
                       name.c_str(), f.x, f.y, gray.cols, gray.rows);
          __builtin_trap();
        }
      }
    } catch (const comic::Error&) {
    }
  }
  return 0;
}
