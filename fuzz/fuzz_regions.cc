// Fuzz target: the region/box parsers (VOT polygons, OTB boxes, auto-detected) and the
// rasterisation of what they return into a small mask.
#include "fuzz/fuzz_input.h"
#include "io/core/error.h"
#include "io/datasets/region_annotations.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace comic::io;
  const std::string path = comic::fuzz::WriteInput("regions.txt", data, size);
  for (const RegionFileFormat format :
       {RegionFileFormat::kAuto, RegionFileFormat::kVotPolygon, RegionFileFormat::kOtbBox}) {
    try {
      const RegionAnnotations regions = ReadRegionFile(path, format);
      for (size_t i = 0; i < regions.polygons.size() && i < 4; ++i) {
        const cv::Mat mask = RasterizeRegion(regions.polygons[i], {64, 48}, {32, 24});
        if (mask.rows != 24 || mask.cols != 32) __builtin_trap();
      }
    } catch (const comic::Error&) {
    }
  }
  return 0;
}
