#include "sfm/working_resolution.h"

#include <algorithm>
#include <cmath>

#include "io/core/error.h"

namespace comic::sfm {

double WorkingScale(int width, int height, int max_size) {
  const int larger = std::max(width, height);
  if (max_size <= 0 || larger <= max_size) return 1.0;
  return static_cast<double>(max_size) / static_cast<double>(larger);
}

int WorkingResizeHeight(cv::Size source_size, int max_size) {
  const double scale = WorkingScale(source_size.width, source_size.height, max_size);
  if (scale == 1.0) return 0;
  return std::max(8, static_cast<int>(std::floor(source_size.height * scale)));
}

frontend::FeatureTracks ScaleTracks(const frontend::FeatureTracks& tracks, double factor) {
  COMIC_CHECK(factor > 0, kInvalidArgument, "track scale factor must be > 0, got " << factor);
  frontend::FeatureTracks scaled = tracks;
  scaled.image_size = cv::Size(static_cast<int>(std::lround(tracks.image_size.width * factor)),
                               static_cast<int>(std::lround(tracks.image_size.height * factor)));
  const float f = static_cast<float>(factor);
  for (frontend::FeatureSet& features : scaled.features) {
    for (frontend::Feature& feature : features) {
      feature.x = (feature.x + 0.5f) * f - 0.5f;
      feature.y = (feature.y + 0.5f) * f - 0.5f;
      feature.scale *= f;
      for (cv::Point2f& point : feature.curve) point = (point + cv::Point2f(0.5f, 0.5f)) * f;
      for (cv::Point2f& point : feature.curve) point -= cv::Point2f(0.5f, 0.5f);
    }
  }
  return scaled;
}

void ScaleReconstruction(double factor, int width, int height, Reconstruction* reconstruction) {
  COMIC_CHECK(factor > 0, kInvalidArgument,
              "reconstruction scale factor must be > 0, got " << factor);
  if (factor == 1.0) return;
  std::vector<camera_t> camera_ids;
  for (const auto& [camera_id, camera] : reconstruction->cameras()) camera_ids.push_back(camera_id);
  for (camera_t camera_id : camera_ids) {
    Camera& camera = reconstruction->camera(camera_id);
    camera = camera.Scaled(factor);
    camera.width = width;
    camera.height = height;
  }
  std::vector<image_t> image_ids;
  for (const auto& [image_id, image] : reconstruction->images()) image_ids.push_back(image_id);
  for (image_t image_id : image_ids) {
    for (Point2D& point2D : reconstruction->image(image_id).points2D) {
      point2D.xy = (point2D.xy.array() + 0.5) * factor - 0.5;
    }
  }
}

Camera ResizedCamera(const Camera& camera, int width, int height) {
  if (camera.width == width && camera.height == height) return camera;
  Camera resized = camera.Scaled(static_cast<double>(height) / static_cast<double>(camera.height));
  resized.width = width;
  resized.height = height;
  return resized;
}

std::optional<Reconstruction> ResizedReconstruction(const Reconstruction& reconstruction, int width,
                                                    int height) {
  if (reconstruction.cameras().empty()) return std::nullopt;
  const Camera& camera = reconstruction.cameras().begin()->second;
  if (camera.width == width && camera.height == height) return std::nullopt;
  std::optional<Reconstruction> resized = reconstruction;
  ScaleReconstruction(static_cast<double>(height) / static_cast<double>(camera.height), width,
                      height, &*resized);
  return resized;
}

}  // namespace comic::sfm
