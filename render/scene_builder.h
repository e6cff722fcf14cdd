// A scene file (JSON, kept in the repository) plus photographs plus a seed -> the Scene, its camera
// path and lens. The file says what stands where in words ("poles every 12-25 m on the right, 5 m
// from the track"); the seed draws the exact positions, sizes and texture regions, so one file
// gives a family of scenes and one (file, photographs, seed) exactly one. docs/rendering.md lists
// every key.
//
//   SceneBuildOptions options;
//   BuiltScene built = BuildScene("scenes/street_drive_500.json", {"a.png", "b.jpg"}, 7, options);
//   Rasterizer rasterizer(built.lens, RasterOptions());
//   RenderedView view = rasterizer.Render(built.scene, built.path.At(0));
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/camera_path.h"
#include "render/lens.h"
#include "render/scene.h"

namespace comic::render {

struct SceneBuildOptions {
  // Photographs larger than this (pixels, longer side) are shrunk before use: textures are cut
  // at about texels_per_metre, so more would only cost memory.
  int max_texture_size = 2048;
  // Frames to render (0: the file's "frames").
  int num_frames = 0;

  void Check() const;
};

struct BuiltScene {
  std::string name;
  int num_frames = 0;
  Lens lens;
  Scene scene;
  CameraPath path;
  // Everything drawn and why: the file as read, the seed, the photographs, and every object and
  // piece as placed (the scene.json an output folder holds).
  nlohmann::json resolved;
};

// Throws comic::Error: kNotFound for a missing scene file or photograph, kInvalidData for a file
// that is not JSON or a photograph that cannot be decoded, kInvalidArgument naming the key for
// anything else wrong in the file (unknown keys included).
BuiltScene BuildScene(const std::string& scene_file, const std::vector<std::string>& photos,
                      uint64_t seed, const SceneBuildOptions& options);

// The same from a JSON value (`where` names it in messages; relative paths resolve against
// `base_dir`) and photographs already loaded (8-bit, any channel count).
BuiltScene BuildSceneFromJson(const nlohmann::json& spec, const std::string& where,
                              const std::string& base_dir, const std::vector<cv::Mat>& photos,
                              const std::vector<std::string>& photo_names, uint64_t seed,
                              const SceneBuildOptions& options);

// The resolved description of `scene` (objects and pieces) as written into scene.json.
nlohmann::json DescribeScene(const Scene& scene);

}  // namespace comic::render
