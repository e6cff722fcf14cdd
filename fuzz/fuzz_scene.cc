// Fuzz target: comic_render's scene file (JSON) read, checked and built into a scene with one
// small photograph, as comic_render does before it renders: the nesting limit, every key's
// bounds, the camera path (a poses file it names is looked up beside the scene), the lens; then
// the camera's first and last poses and the resolved description written back as JSON. A scene
// the checks accept must give finite poses (a non-finite one is a finding: a bound is missing).
#include <opencv2/imgcodecs.hpp>

#include "fuzz/fuzz_input.h"
#include "io/core/error.h"
#include "render/scene_builder.h"

namespace {

// One textured photograph, written once: the scenes' surfaces are cut from it.
const std::string& PhotoPath() {
  static const std::string path = [] {
    cv::Mat photo(48, 64, CV_8UC3);
    cv::randu(photo, 0, 255);
    const std::string file = comic::fuzz::ScratchDir() + "/photo.png";
    cv::imwrite(file, photo);
    return file;
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string photo = PhotoPath();
  const std::string path = comic::fuzz::WriteInput("scene.json", data, size);
  comic::render::SceneBuildOptions options;
  options.max_texture_size = 64;
  options.num_frames = 2;  // the path is built for two frames: its checks, not its length
  try {
    const comic::render::BuiltScene built = comic::render::BuildScene(path, {photo}, 1, options);
    for (const double time : {0.0, static_cast<double>(built.num_frames - 1)}) {
      const comic::render::Pose pose = built.path.At(time);
      if (!pose.rotation.allFinite() || !pose.translation.allFinite()) __builtin_trap();
    }
    const std::string resolved = built.resolved.dump();
    if (resolved.empty()) __builtin_trap();
  } catch (const comic::Error&) {
  }
  return 0;
}
