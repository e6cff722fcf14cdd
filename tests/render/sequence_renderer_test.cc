// Rendering a sequence into files (render/sequence_renderer.h): same scene, photographs, seed and
// options give the same bytes in every file; the truth is written in the formats the apps read,
// and reads back as what was rendered.
#include "render/sequence_renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/datasets/ground_truth_cameras.h"
#include "io/image/depth_map.h"
#include "io/image/mask_folder.h"
#include "tests/test_support.h"

namespace comic::render {
namespace {

BuiltScene TestStreet(int frames) {
  SceneBuildOptions options;
  options.num_frames = frames;
  return BuildScene(
      test::SourceDir() + "/scenes/test_street.json",
      {test::ExampleDir() + "/image_l/000000.png", test::ExampleDir() + "/image_l/000005.png"}, 11,
      options);
}

std::vector<std::string> FilesUnder(const std::string& folder) {
  std::vector<std::string> files;
  for (const std::string& name : io::ListFiles(folder)) files.push_back(name);
  for (const char* sub : {"images", "depth", "ids", "boundaries", "masks", "colmap"}) {
    const std::string path = io::JoinPaths(folder, sub);
    if (!io::IsDirectory(path)) continue;
    for (const std::string& name : io::ListFiles(path))
      files.push_back(std::string(sub) + "/" + name);
  }
  return files;
}

TEST(SequenceRenderer, SameSeedAndOptionsGiveTheSameBytesInEveryFile) {
  const BuiltScene built = TestStreet(3);
  SequenceRenderOptions options;
  options.sensor.read_noise = 2.0;
  options.sensor.shot_noise = 0.3;
  options.sensor.exposure_drift = 0.2;
  options.sensor.shutter = 0.5;
  options.sensor.blur_samples = 3;
  test::ScopedTempDir a, b, c;
  RenderSequence(built, 11, options, a.path());
  RenderSequence(TestStreet(3), 11, options, b.path());
  RenderSequence(built, 12, options, c.path());  // another sensor seed: other noise
  const std::vector<std::string> files = FilesUnder(a.path());
  EXPECT_EQ(files, FilesUnder(b.path()));
  EXPECT_EQ(files.size(), 3u + 5 * 3 + 3);  // poses, calib, scene; 5 folders x 3; colmap
  for (const std::string& file : files) {
    EXPECT_EQ(io::ReadFileToString(io::JoinPaths(a.path(), file)),
              io::ReadFileToString(io::JoinPaths(b.path(), file)))
        << file;
  }
  EXPECT_NE(io::ReadFileToString(a.File("images/000001.png")),
            io::ReadFileToString(c.File("images/000001.png")));
  EXPECT_EQ(io::ReadFileToString(a.File("depth/000001.png")),
            io::ReadFileToString(c.File("depth/000001.png")));
}

TEST(SequenceRenderer, TheTruthReadsBackAsRendered) {
  const BuiltScene built = TestStreet(4);
  SequenceRenderOptions options;
  options.depth_format = "pfm";
  test::ScopedTempDir dir;
  const SequenceRenderSummary summary = RenderSequence(built, 11, options, dir.path());
  EXPECT_EQ(summary.num_frames, 4);
  EXPECT_GT(summary.render_cpu_s, 0.0);

  // KITTI poses + calib, as comic_sfm --gt reads them.
  const io::GroundTruthCameras truth =
      io::ReadKittiGroundTruth(dir.File("poses.txt"), dir.File("calib.txt"));
  ASSERT_EQ(truth.cameras.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const Pose pose = built.path.At(k);
    EXPECT_LT((truth.cameras[k].cam_from_world_rotation - pose.rotation).norm(), 1e-9);
    EXPECT_LT((truth.cameras[k].cam_from_world_translation - pose.translation).norm(), 1e-8);
    ASSERT_TRUE(truth.cameras[k].has_intrinsics);
    EXPECT_DOUBLE_EQ(truth.cameras[k].K(0, 0), built.lens.fx);
    EXPECT_DOUBLE_EQ(truth.cameras[k].K(0, 2), built.lens.cx);
  }
  // The COLMAP model of the true cameras.
  const io::ColmapTextModel model = io::ReadColmapTextModel(dir.File("colmap"));
  ASSERT_EQ(model.images.size(), 4u);
  EXPECT_EQ(model.cameras[0].model, "PINHOLE");
  EXPECT_DOUBLE_EQ(model.cameras[0].params[2], built.lens.cx + 0.5);
  EXPECT_EQ(model.images[2].name, "000002.png");
  EXPECT_TRUE(model.points3D.empty());
  // Depth, masks and ids as the frame's view.
  const Rasterizer rasterizer(built.lens, options.raster);
  const RenderedFrame frame = RenderFrame(built, rasterizer, 11, options.sensor, 2);
  EXPECT_EQ(
      cv::norm(io::ReadDepthMap(dir.File("depth/000002.pfm")), frame.view.depth, cv::NORM_INF),
      0.0);
  const io::MaskFolder masks = io::MaskFolder::Open(dir.File("masks"));
  masks.CheckCount(4);
  const cv::Mat mask = masks.Read(2, cv::Size(built.lens.width, built.lens.height));
  EXPECT_EQ(cv::norm(mask, ForegroundMask(built.scene, frame.view), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(mask), 1000);  // poles, trees, fences and boxes are seen
  const cv::Mat ids = cv::imread(dir.File("ids/000002.png"), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(ids.type(), CV_16UC1);
  EXPECT_EQ(cv::norm(ids, ObjectIds(built.scene, frame.view), cv::NORM_INF), 0.0);
  const cv::Mat boundaries = cv::imread(dir.File("boundaries/000002.png"), cv::IMREAD_UNCHANGED);
  EXPECT_GT(cv::countNonZero(boundaries), 2000);
  EXPECT_LT(cv::countNonZero(boundaries), built.lens.width * built.lens.height / 3);
  // scene.json: the scene as drawn and how.
  const nlohmann::json scene = nlohmann::json::parse(io::ReadFileToString(dir.File("scene.json")));
  EXPECT_EQ(scene["seed"], 11);
  EXPECT_EQ(scene["render_options"]["depth_format"], "pfm");
  EXPECT_EQ(scene["scene"]["pieces"].size(), built.scene.pieces.size());
}

TEST(SequenceRenderer, BlurEveryOtherFrameLeavesTheOthersAsSharpAsWithoutBlur) {
  const BuiltScene built = TestStreet(4);
  const Rasterizer rasterizer(built.lens, RasterOptions());
  SensorOptions sharp;
  sharp.read_noise = 1.0;  // the same noise on both: it is seeded by the frame
  SensorOptions alternate = sharp;
  alternate.shutter = 0.8;
  alternate.blur_samples = 4;
  alternate.blur_every = 2;
  for (int frame = 0; frame < 4; ++frame) {
    const RenderedFrame a = RenderFrame(built, rasterizer, 11, sharp, frame);
    const RenderedFrame b = RenderFrame(built, rasterizer, 11, alternate, frame);
    const double mean_difference = cv::norm(a.image, b.image, cv::NORM_L1) / a.image.total() / 3;
    if (frame % 2 == 0) {
      EXPECT_EQ(mean_difference, 0.0) << frame;
    } else {
      // A drive at 0.8 m per frame with the shutter open 80 % of the interval smears the view.
      EXPECT_GT(mean_difference, 2.0) << frame;
    }
    // The truth is the frame's geometry either way.
    EXPECT_EQ(cv::norm(a.view.depth, b.view.depth, cv::NORM_INF), 0.0) << frame;
  }
}

// The test street with a box (2 m wide, 2 m high, 1 m deep) whose centre is at `center` on the
// ground at time 0, moving at `velocity` metres per frame.
BuiltScene StreetWithBox(int frames, const Eigen::Vector3d& center,
                         const Eigen::Vector3d& velocity) {
  nlohmann::json spec =
      nlohmann::json::parse(io::ReadFileToString(test::SourceDir() + "/scenes/test_street.json"));
  nlohmann::json box = {
      {"type", "box"}, {"center", {center.x(), center.z()}}, {"size", {2.0, 2.0, 1.0}}};
  if (!velocity.isZero()) box["velocity"] = {velocity.x(), velocity.y(), velocity.z()};
  spec["elements"].push_back(box);
  std::vector<cv::Mat> photos;
  std::vector<std::string> names;
  for (const char* name : {"000000.png", "000005.png"}) {
    names.push_back(test::ExampleDir() + "/image_l/" + name);
    photos.push_back(cv::imread(names.back(), cv::IMREAD_COLOR));
  }
  SceneBuildOptions options;
  options.num_frames = frames;
  return BuildSceneFromJson(spec, "test_street.json", test::SourceDir() + "/scenes", photos, names,
                            11, options);
}

TEST(SequenceRenderer, AMovingObjectIsDrawnWhereItsVelocityPutsItAtEachFrame) {
  const Pose start = TestStreet(1).path.At(0);
  const Eigen::Vector3d forward = start.rotation.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d right = start.rotation.transpose() * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d center = start.Center() + 9.0 * forward + 1.0 * right;
  // Slower than the camera and drifting to the left: it stays in view, nearer at each frame.
  Eigen::Vector3d velocity = 0.4 * forward - 0.3 * right;
  velocity.y() = 0.0;  // along the ground
  const BuiltScene moving = StreetWithBox(6, center, velocity);
  const int box = static_cast<int>(moving.scene.objects.size());
  ASSERT_TRUE(moving.scene.objects.back().motion.Moves());
  const Rasterizer rasterizer(moving.lens, RasterOptions());
  std::vector<double> columns;
  for (int frame : {0, 3, 5}) {
    // The same box standing still where the moving one is at this frame.
    const BuiltScene placed = StreetWithBox(6, center + frame * velocity, Eigen::Vector3d::Zero());
    ASSERT_FALSE(placed.scene.HasMotion());
    const RenderedFrame a = RenderFrame(moving, rasterizer, 11, SensorOptions(), frame);
    const RenderedFrame b = RenderFrame(placed, rasterizer, 11, SensorOptions(), frame);
    const cv::Mat in_a = ObjectIds(a.scene, a.view) == box;
    const cv::Mat in_b = ObjectIds(placed.scene, b.view) == box;
    const int area = cv::countNonZero(in_b);
    EXPECT_GT(area, 5000) << frame;  // a good part of the view
    cv::Mat differ;
    cv::bitwise_xor(in_a, in_b, differ);
    EXPECT_LE(cv::countNonZero(differ), area / 200) << frame;  // rounding, on its outline
    EXPECT_LT(cv::norm(a.image, b.image, cv::NORM_L1) / a.image.total() / 3, 0.05) << frame;
    // It is foreground in the masks where it is now.
    cv::Mat outside;
    cv::bitwise_and(in_a, ~ForegroundMask(a.scene, a.view), outside);
    EXPECT_EQ(cv::countNonZero(outside), 0) << frame;
    const cv::Moments m = cv::moments(in_a, true);
    columns.push_back(m.m10 / m.m00);
  }
  // It crosses the view leftwards.
  ASSERT_EQ(columns.size(), 3u);
  EXPECT_GT(columns[0], columns[1] + 20);
  EXPECT_GT(columns[1], columns[2] + 10);
  // Built again from the same file and seed, blurred by its own motion too: the same bytes.
  SensorOptions blurred;
  blurred.shutter = 0.5;
  blurred.blur_samples = 3;
  const RenderedFrame once = RenderFrame(moving, rasterizer, 11, blurred, 4);
  const RenderedFrame again =
      RenderFrame(StreetWithBox(6, center, velocity), rasterizer, 11, blurred, 4);
  EXPECT_EQ(cv::norm(once.image, again.image, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(once.view.depth, again.view.depth, cv::NORM_INF), 0.0);
}

TEST(SequenceRenderer, BadOptionsFailBeforeAnythingIsWritten) {
  const BuiltScene built = TestStreet(2);
  SequenceRenderOptions options;
  options.depth_format = "exr";
  test::ScopedTempDir dir;
  EXPECT_THROW(RenderSequence(built, 1, options, dir.File("out")), Error);
  EXPECT_FALSE(io::PathExists(dir.File("out")));
  options = SequenceRenderOptions();
  options.sensor.shutter = 2.0;
  EXPECT_THROW(RenderSequence(built, 1, options, dir.File("out")), Error);
  options = SequenceRenderOptions();
  options.sensor.blur_every = 0;
  EXPECT_THROW(RenderSequence(built, 1, options, dir.File("out")), Error);
  options = SequenceRenderOptions();
  options.raster.supersampling = 9;
  EXPECT_THROW(RenderSequence(built, 1, options, dir.File("out")), Error);
  EXPECT_FALSE(io::PathExists(dir.File("out")));
}

}  // namespace
}  // namespace comic::render
