// Detects CoMIC features on a synthetic image with a known answer (a bright square on a dark
// background has four corners) through the installed package, and checks that bad input comes
// back as comic::Error. Exits non-zero, with one line on stderr, on any wrong result.
#include <comic/frontend/detector_factory.h>
#include <comic/io/core/error.h>
#include <comic/render/rasterizer.h>
#include <comic/sfm/rigid3d.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "io/core/error.h"  // the consumer's own, see io/core/error.h

namespace {

int Fail(const std::string& message) {
  std::cerr << "comic_consumer: " << message << "\n";
  return 1;
}

}  // namespace

int main() {
  if (std::strcmp(consumer::io::kWhichErrorHeader, "consumer") != 0) {
    return Fail("the consumer's own io/core/error.h was shadowed");
  }
  // Pixels [60, 110) x [70, 120) at 200 on 50, lightly blurred: the square's corners lie at the
  // pixel edges, (59.5, 69.5) ... (109.5, 119.5) with pixel centres at integers.
  cv::Mat image(160, 180, CV_8UC1, cv::Scalar(50));
  cv::rectangle(image, cv::Rect(60, 70, 50, 50), cv::Scalar(200), cv::FILLED);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.0);

  const std::unique_ptr<comic::frontend::Detector> detector =
      comic::frontend::MakeDetector("comic");
  const comic::frontend::FeatureSet features = detector->Detect(image);
  const cv::Point2f corners[4] = {
      {59.5f, 69.5f}, {109.5f, 69.5f}, {59.5f, 119.5f}, {109.5f, 119.5f}};
  for (const cv::Point2f& corner : corners) {
    double nearest = 1e9;
    for (const comic::frontend::Feature& f : features) {
      nearest = std::min(nearest, std::hypot(double{f.x} - corner.x, double{f.y} - corner.y));
    }
    if (nearest > 2.0) {
      return Fail("no feature within 2 px of the corner (" + std::to_string(corner.x) + ", " +
                  std::to_string(corner.y) + "); nearest " + std::to_string(nearest) + " px");
    }
  }

  // A colour image is invalid input for Detect: comic::Error with kInvalidArgument.
  try {
    detector->Detect(cv::Mat(20, 20, CV_8UC3, cv::Scalar(0, 0, 0)));
    return Fail("Detect accepted a colour image");
  } catch (const comic::Error& e) {
    if (e.kind() != comic::ErrorKind::kInvalidArgument) return Fail("wrong error kind");
  }

  // Something from comic::sfm, so that linking comic::sfm (and its Ceres dependency) is exercised.
  // x_cam = x_world + (0, 0, 2): the camera centre is the world point (0, 0, -2).
  const comic::sfm::Rigid3d cam_from_world(Eigen::Quaterniond::Identity(),
                                           Eigen::Vector3d(0, 0, 2));
  if ((comic::sfm::ProjectionCenter(cam_from_world) - Eigen::Vector3d(0, 0, -2)).norm() > 1e-12) {
    return Fail("wrong projection centre");
  }
  // And comic::render: a grey card filling the view renders as its grey.
  comic::render::Scene scene;
  scene.textures.push_back(comic::render::Texture::Solid({90.0f, 90.0f, 90.0f}, "grey"));
  comic::render::Piece card;
  card.origin = {-10.0, -10.0, 5.0};
  card.s_axis = {20.0, 0.0, 0.0};
  card.t_axis = {0.0, 20.0, 0.0};
  card.object_id = scene.AddObject("card", true);
  scene.pieces.push_back(card);
  comic::render::Lens lens;
  lens.width = 40;
  lens.height = 30;
  const comic::render::RenderedView view =
      comic::render::Rasterizer(lens, comic::render::RasterOptions())
          .Render(scene, comic::render::Pose());
  if (std::abs(view.color.at<cv::Vec3f>(15, 20)[0] - 90.0f) > 1e-3f ||
      std::abs(view.depth.at<float>(15, 20) - 5.0f) > 1e-5f) {
    return Fail("comic::render drew the card wrong");
  }
  std::cout << "comic_consumer: " << features.size() << " CoMIC features, the square's 4 corners "
            << "found within 2 px\n";
  return 0;
}
