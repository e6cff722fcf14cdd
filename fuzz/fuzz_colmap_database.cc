// Fuzz target: the COLMAP database reader on arbitrary bytes as the database file (SQLite's own
// checks plus ours on the schema and the blobs: keypoints, descriptors, matches, geometries).
#include <filesystem>

#include "fuzz/fuzz_input.h"
#include "io/colmap/colmap_database.h"
#include "io/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace comic::io;
  const std::string path = comic::fuzz::WriteInput("fuzz.db", data, size);
  std::error_code ec;
  std::filesystem::remove(path + "-journal", ec);
  try {
    ColmapDatabase database = ColmapDatabase::Open(path);
    database.NumCameras();
    database.NumImages();
    database.NumKeypoints();
    database.NumMatches();
    database.NumInlierMatches();
    database.ReadAllCameras();
    for (const ColmapDatabaseImage& image : database.ReadAllImages()) {
      try {
        database.ReadKeypoints(image.image_id);
      } catch (const comic::Error&) {
      }
      try {
        database.ReadDescriptors(image.image_id);
      } catch (const comic::Error&) {
      }
    }
    database.ReadAllMatches();
    database.ReadAllTwoViewGeometries();
  } catch (const comic::Error&) {
  }
  return 0;
}
