#include "render/nerf_composite.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"
#include "render/random.h"
#include "render/truth_files.h"

namespace comic::render {
namespace {

enum CompositeStream : uint64_t { kCompositeSensor = 2 };

// Blender's camera axes (x right, y up, z backwards) to OpenCV's (x right, y down, z forward),
// and Blender's world (z up) to the scene's (y up): x stays, y = z, z = -y.
const Eigen::Matrix3d kCameraFlip = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
Eigen::Matrix3d WorldToScene() {
  Eigen::Matrix3d m;
  m << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return m;
}

// The band around the object's outline: pixels within `band` of a pixel whose 4-neighbour is on
// the other side of alpha = 1/2.
cv::Mat SilhouetteBand(const cv::Mat& object, double band) {
  cv::Mat far_from_edge(object.size(), CV_8UC1, cv::Scalar(255));
  for (int y = 0; y < object.rows; ++y) {
    for (int x = 0; x < object.cols; ++x) {
      const bool in = object.at<uint8_t>(y, x) != 0;
      if (x + 1 < object.cols && in != (object.at<uint8_t>(y, x + 1) != 0)) {
        far_from_edge.at<uint8_t>(y, x) = far_from_edge.at<uint8_t>(y, x + 1) = 0;
      }
      if (y + 1 < object.rows && in != (object.at<uint8_t>(y + 1, x) != 0)) {
        far_from_edge.at<uint8_t>(y, x) = far_from_edge.at<uint8_t>(y + 1, x) = 0;
      }
    }
  }
  cv::Mat distance;
  cv::distanceTransform(far_from_edge, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance <= band;
}

}  // namespace

NerfSet ReadNerfSet(const std::string& folder, const std::string& split, double lift) {
  const std::string path = io::JoinPaths(folder, "transforms_" + split + ".json");
  COMIC_CHECK(io::PathExists(path), kNotFound, path << ": no such file (a NeRF synthetic set)");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(io::ReadFileToString(path));
  } catch (const nlohmann::json::exception& e) {
    throw Error(ErrorKind::kInvalidData, path + ": not valid JSON: " + e.what());
  }
  COMIC_CHECK(json.contains("camera_angle_x") && json["camera_angle_x"].is_number() &&
                  json.contains("frames") && json["frames"].is_array() && !json["frames"].empty(),
              kInvalidData, path << ": expected camera_angle_x and a list of frames");
  NerfSet set;
  for (const nlohmann::json& frame : json["frames"]) {
    COMIC_CHECK(frame.contains("file_path") && frame.contains("transform_matrix"), kInvalidData,
                path << ": a frame without file_path or transform_matrix");
    std::string file = frame["file_path"].get<std::string>();
    if (file.rfind("./", 0) == 0) file = file.substr(2);
    if (io::FileExtension(file).empty()) file += ".png";
    const nlohmann::json& m = frame["transform_matrix"];
    COMIC_CHECK(m.is_array() && m.size() >= 3, kInvalidData, path << ": bad transform_matrix");
    Eigen::Matrix3d rotation;
    Eigen::Vector3d center;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) rotation(i, j) = m[i][j].get<double>();
      center(i) = m[i][3].get<double>();
    }
    const Eigen::Matrix3d world_from_cam = WorldToScene() * rotation * kCameraFlip;
    NerfView view;
    view.image_path = io::JoinPaths(folder, file);
    view.cam_from_world.rotation = world_from_cam.transpose();
    view.cam_from_world.translation =
        -view.cam_from_world.rotation * (WorldToScene() * center + Eigen::Vector3d(0, lift, 0));
    set.views.push_back(view);
  }
  const cv::Mat first = io::ReadImageUnchanged(set.views.front().image_path);
  set.lens.width = first.cols;
  set.lens.height = first.rows;
  set.lens.fx = set.lens.fy =
      0.5 * first.cols / std::tan(0.5 * json["camera_angle_x"].get<double>());
  set.lens.cx = (first.cols - 1) / 2.0;
  set.lens.cy = (first.rows - 1) / 2.0;
  set.lens.Check();
  return set;
}

SequenceRenderSummary RenderNerfComposite(const NerfSet& set, const BuiltScene& background,
                                          uint64_t seed, const SequenceRenderOptions& options,
                                          const std::string& folder, int max_views,
                                          const RenderProgress& progress) {
  options.Check();
  const Rasterizer rasterizer(set.lens, options.raster);
  PrepareOutputFolder(folder, options);
  const int num_views = max_views > 0 ? std::min<int>(max_views, set.views.size())
                                      : static_cast<int>(set.views.size());
  const uint16_t object_id = static_cast<uint16_t>(background.scene.objects.size() + 1);
  SequenceRenderSummary summary;
  std::vector<Pose> poses;
  std::vector<std::string> names;
  for (int k = 0; k < num_views; ++k) {
    const NerfView& view = set.views[k];
    const cv::Mat rgba = io::ReadImageUnchanged(view.image_path);
    COMIC_CHECK(
        rgba.type() == CV_8UC4 && rgba.cols == set.lens.width && rgba.rows == set.lens.height,
        kInvalidData,
        view.image_path << ": expected an 8-bit RGBA image of " << set.lens.width << "x"
                        << set.lens.height);
    const double start = ThreadCpuSeconds();
    const RenderedView seen = rasterizer.Render(background.scene, view.cam_from_world);
    cv::Mat color = seen.color.clone();
    cv::Mat object(rgba.size(), CV_8UC1);
    for (int y = 0; y < rgba.rows; ++y) {
      for (int x = 0; x < rgba.cols; ++x) {
        const cv::Vec4b& p = rgba.at<cv::Vec4b>(y, x);
        const float a = p[3] / 255.0f;
        cv::Vec3f& c = color.at<cv::Vec3f>(y, x);
        for (int i = 0; i < 3; ++i) c[i] = a * p[i] + (1.0f - a) * c[i];
        object.at<uint8_t>(y, x) = p[3] >= 128 ? 255 : 0;
      }
    }
    FrameOutputs outputs;
    outputs.image = ExposeFrame(color, options.sensor, MixSeed(seed, kCompositeSensor), k);
    // Unknown on the object: NaN (a PFM keeps it; a 16-bit PNG has no such value and stores 0).
    outputs.depth = seen.depth.clone();
    outputs.depth.setTo(std::numeric_limits<float>::quiet_NaN(), object);
    outputs.ids = ObjectIds(background.scene, seen);
    outputs.ids.setTo(object_id, object);
    outputs.masks = object;
    const cv::Mat hidden_behind = object & ~SilhouetteBand(object, options.boundary.band_px);
    outputs.boundaries = OcclusionBoundaryMask(background.scene, view.cam_from_world, rasterizer,
                                               seen, options.boundary);
    outputs.boundaries.setTo(0, hidden_behind);
    outputs.boundaries |= SilhouetteBand(object, options.boundary.band_px);
    const double rendered_at = ThreadCpuSeconds();
    summary.render_cpu_s += rendered_at - start;
    WriteFrameOutputs(folder, k, outputs, options);
    summary.write_cpu_s += ThreadCpuSeconds() - rendered_at;
    poses.push_back(view.cam_from_world);
    names.push_back(FrameFileName(k, "png"));
    ++summary.num_frames;
    if (progress) progress(summary.num_frames, num_views);
  }
  WriteTrueCameras(folder, set.lens, poses, names);
  nlohmann::json scene = background.resolved;
  scene["render_options"] = RenderOptionsToJson(options);
  scene["composite"] = {{"views", num_views},
                        {"object_id", object_id},
                        {"first_view", set.views.front().image_path},
                        {"depth_on_object", "unknown (NaN in PFM, 0 in PNG)"}};
  io::WriteFileAtomically(io::JoinPaths(folder, "scene.json"), scene.dump(1) + "\n");
  return summary;
}

}  // namespace comic::render
