// Fuzz target: the COLMAP text-model reader. The input is split at the first two bytes 0x00 into
// cameras.txt, images.txt and points3D.txt of one model folder (the seeds are real models joined
// that way by scripts/fuzz.sh).
#include <filesystem>
#include <string>

#include "fuzz/fuzz_input.h"
#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const size_t first = bytes.find('\0');
  const size_t second = first == std::string::npos ? first : bytes.find('\0', first + 1);
  const std::string cameras = bytes.substr(0, first);
  const std::string images =
      first == std::string::npos ? "" : bytes.substr(first + 1, second - first - 1);
  const std::string points = second == std::string::npos ? "" : bytes.substr(second + 1);
  const std::string folder = comic::fuzz::ScratchDir() + "/model";
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  auto write = [&](const char* name, const std::string& text) {
    comic::fuzz::WriteInput(std::string("model/") + name,
                            reinterpret_cast<const uint8_t*>(text.data()), text.size());
  };
  write("cameras.txt", cameras);
  write("images.txt", images);
  write("points3D.txt", points);
  try {
    const comic::io::ColmapTextModel model = comic::io::ReadColmapTextModel(folder);
    // What was read must write back: the writer's own checks may refuse it, never crash.
    comic::io::ColmapCamerasText(model);
    comic::io::ColmapImagesText(model);
    comic::io::ColmapPoints3DText(model);
  } catch (const comic::Error&) {
  }
  return 0;
}
