#include "render/truth_files.h"

#include <cstdio>
#include <sstream>

#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"

namespace comic::render {

std::string KittiPoseLine(const Pose& cam_from_world) {
  const Eigen::Matrix3d r = cam_from_world.rotation.transpose();
  const Eigen::Vector3d c = cam_from_world.Center();
  std::ostringstream line;
  line.precision(12);
  for (int i = 0; i < 3; ++i) {
    line << (i ? " " : "") << r(i, 0) << " " << r(i, 1) << " " << r(i, 2) << " " << c(i);
  }
  return line.str();
}

void WriteTrueCameras(const std::string& folder, const Lens& lens, const std::vector<Pose>& poses,
                      const std::vector<std::string>& image_names) {
  COMIC_CHECK(
      poses.size() == image_names.size(), kInvalidArgument,
      "true cameras: " << poses.size() << " poses for " << image_names.size() << " image names");
  std::string kitti;
  for (const Pose& pose : poses) kitti += KittiPoseLine(pose) + "\n";
  io::WriteFileAtomically(io::JoinPaths(folder, "poses.txt"), kitti);
  std::ostringstream calib;
  calib.precision(17);
  calib << "P0: " << lens.fx << " 0 " << lens.cx << " 0 0 " << lens.fy << " " << lens.cy
        << " 0 0 0 1 0\n";
  io::WriteFileAtomically(io::JoinPaths(folder, "calib.txt"), calib.str());

  io::ColmapTextModel model;
  model.cameras.push_back(
      {1, lens.ColmapModelName(), lens.width, lens.height, lens.ColmapParams()});
  for (size_t k = 0; k < poses.size(); ++k) {
    io::ColmapImage image;
    image.image_id = static_cast<uint32_t>(k + 1);
    image.cam_from_world_rotation = Eigen::Quaterniond(poses[k].rotation).normalized();
    image.cam_from_world_translation = poses[k].translation;
    image.camera_id = 1;
    image.name = image_names[k];
    model.images.push_back(image);
  }
  io::WriteColmapTextModel(model, io::JoinPaths(folder, "colmap"));
}

}  // namespace comic::render
