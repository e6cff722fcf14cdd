#include "sfm/colmap/colmap_export.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <random>
#include <set>

#include "frontend/detector_factory.h"
#include "frontend/matching/image_set_matching.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/datasets/kitti_odometry.h"
#include "io/image/image_io.h"
#include "sfm/colmap/colmap_runner.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

using comic::test::ScopedTempDir;

// A synthetic video: a camera moving forward (and a little sideways) through random points,
// every point visible in a frame is a feature, consecutive visible frames of a point form its
// track. Some extra features belong to no track, and a few tracks carry one wrong observation.
struct Scene {
  Camera camera;
  std::vector<Rigid3d> cams_from_world;
  frontend::FeatureTracks tracks;
  std::set<std::pair<int, int>> corrupted;  // (frame, feature) of wrong observations
};

Scene MakeScene(int num_frames, uint32_t seed) {
  Scene scene;
  scene.camera.width = 640;
  scene.camera.height = 480;
  scene.camera.fx = 500.0;
  scene.camera.fy = 510.0;
  scene.camera.cx = 319.5;
  scene.camera.cy = 241.0;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int i = 0; i < num_frames; ++i) {
    const Eigen::Vector3d center(0.2 * i, 0.005 * i * i, 1.0 * i);
    const Eigen::Quaterniond rotation(Eigen::AngleAxisd(0.005 * i, Eigen::Vector3d::UnitY()));
    // cam_from_world: x_cam = R (x_world - c).
    scene.cams_from_world.push_back(Rigid3d(rotation, -(rotation * center)));
  }
  auto& tracks = scene.tracks;
  tracks.detector_name = "synthetic";
  tracks.image_size = cv::Size(scene.camera.width, scene.camera.height);
  tracks.features.resize(num_frames);
  for (int i = 0; i < num_frames; ++i) {
    tracks.frame_names.push_back("frame_" + std::to_string(100 + i) + ".png");
  }
  for (int p = 0; p < 600; ++p) {
    const Eigen::Vector3d point(8.0 * uniform(rng), 4.0 * uniform(rng), 14.0 + 10.0 * uniform(rng));
    frontend::Track track;
    for (int i = 0; i < num_frames; ++i) {
      const Eigen::Vector3d in_camera = scene.cams_from_world[i] * point;
      const Eigen::Vector3d projected = scene.camera.K() * in_camera;
      const std::optional<Eigen::Vector2d> pixel =
          in_camera.z() > 0.1 ? std::optional<Eigen::Vector2d>(projected.hnormalized())
                              : std::nullopt;
      const bool visible = pixel && pixel->x() >= 0 && pixel->y() >= 0 &&
                           pixel->x() <= scene.camera.width - 1 &&
                           pixel->y() <= scene.camera.height - 1;
      if (!visible) {
        if (!track.observations.empty()) break;  // tracks are contiguous
        continue;
      }
      frontend::Feature feature;
      feature.x = static_cast<float>(pixel->x());
      feature.y = static_cast<float>(pixel->y());
      feature.response = 1.0f;
      const int index = static_cast<int>(tracks.features[i].size());
      if (p % 40 == 7 && i == 2) {  // a wrong observation, far off the epipolar line
        feature.x = static_cast<float>(std::fmod(feature.x + 157.0, 600.0));
        feature.y = static_cast<float>(std::fmod(feature.y + 211.0, 460.0));
        scene.corrupted.insert({i, index});
      }
      tracks.features[i].push_back(feature);
      track.observations.push_back({i, index});
    }
    if (track.observations.size() >= 2) tracks.tracks.push_back(track);
  }
  for (int i = 0; i < num_frames; ++i) {  // features that belong to no track
    for (int k = 0; k < 10; ++k) {
      frontend::Feature feature;
      feature.x = static_cast<float>(320 + 300 * uniform(rng));
      feature.y = static_cast<float>(240 + 230 * uniform(rng));
      tracks.features[i].push_back(feature);
    }
  }
  tracks.Check();
  return scene;
}

// Pairs (i, j), i < j, sharing a track within `window`, with the number of shared tracks.
std::map<std::pair<int, int>, int> ExpectedPairs(const frontend::FeatureTracks& tracks,
                                                 int window) {
  std::map<std::pair<int, int>, int> pairs;
  for (const auto& track : tracks.tracks) {
    for (const auto& a : track.observations) {
      for (const auto& b : track.observations) {
        if (a.frame < b.frame && b.frame - a.frame <= window) ++pairs[{a.frame, b.frame}];
      }
    }
  }
  return pairs;
}

Eigen::Vector3d Homogeneous(const Eigen::Ref<const io::ColmapKeypoints>& keypoints, uint32_t i) {
  return Eigen::Vector3d(keypoints(i, 0), keypoints(i, 1), 1.0);
}

TEST(ColmapExport, WritesImagesKeypointsWithHalfPixelShiftAndPinholeCamera) {
  const Scene scene = MakeScene(8, 1);
  ColmapExportOptions options;
  options.image_name_prefix = "image_l/";
  io::ColmapDatabase database = io::ColmapDatabase::Open(":memory:");
  const auto summary = WriteTracksToColmapDatabase(scene.tracks, scene.camera, options, &database);
  EXPECT_EQ(summary.num_images, 8);
  EXPECT_TRUE(summary.known_intrinsics);

  const auto cameras = database.ReadAllCameras();
  ASSERT_EQ(cameras.size(), 1u);
  EXPECT_EQ(cameras[0].model_id, io::kColmapPinhole);
  EXPECT_EQ(cameras[0].width, 640);
  EXPECT_EQ(cameras[0].height, 480);
  EXPECT_EQ(cameras[0].params, (std::vector<double>{500.0, 510.0, 320.0, 241.5}));
  EXPECT_TRUE(cameras[0].prior_focal_length);

  const auto images = database.ReadAllImages();
  ASSERT_EQ(images.size(), 8u);
  int64_t total = 0;
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(images[i].image_id, i + 1);
    EXPECT_EQ(images[i].name, "image_l/frame_" + std::to_string(100 + i) + ".png");
    EXPECT_EQ(images[i].camera_id, cameras[0].camera_id);
    const io::ColmapKeypoints keypoints = database.ReadKeypoints(i + 1);
    const auto& features = scene.tracks.features[i];
    ASSERT_EQ(keypoints.rows(), static_cast<Eigen::Index>(features.size()));
    ASSERT_EQ(keypoints.cols(), 2);
    for (size_t k = 0; k < features.size(); ++k) {
      EXPECT_EQ(keypoints(k, 0), features[k].x + 0.5f) << i << " " << k;
      EXPECT_EQ(keypoints(k, 1), features[k].y + 0.5f) << i << " " << k;
    }
    total += keypoints.rows();
  }
  EXPECT_EQ(summary.num_keypoints, total);
}

TEST(ColmapExport, PairsEveryFrameSharingTracksWithinTheWindowOneToOne) {
  const Scene scene = MakeScene(9, 2);
  for (const int window : {1, 5}) {
    ColmapExportOptions options;
    options.pair_window = window;
    io::ColmapDatabase database = io::ColmapDatabase::Open(":memory:");
    const auto summary =
        WriteTracksToColmapDatabase(scene.tracks, scene.camera, options, &database);
    const auto expected = ExpectedPairs(scene.tracks, window);
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(summary.num_matched_pairs, static_cast<int>(expected.size()));
    const auto all = database.ReadAllMatches();
    ASSERT_EQ(all.size(), expected.size()) << "window " << window;
    int64_t num_matches = 0;
    for (const auto& [pair_id, matches] : all) {
      const auto [id1, id2] = io::ColmapImagePairFromPairId(pair_id);
      const std::pair<int, int> frames(static_cast<int>(id1 - 1), static_cast<int>(id2 - 1));
      ASSERT_TRUE(expected.count(frames)) << id1 << " " << id2;
      EXPECT_LE(frames.second - frames.first, window);
      EXPECT_EQ(static_cast<int>(matches.size()), expected.at(frames));
      std::set<uint32_t> used1, used2;
      for (const auto& match : matches) {
        EXPECT_TRUE(used1.insert(match.point2D_idx1).second) << "feature matched twice";
        EXPECT_TRUE(used2.insert(match.point2D_idx2).second) << "feature matched twice";
        // The first column indexes the image with the smaller id: the pair's earlier frame.
        bool found = false;
        for (const auto& track : scene.tracks.tracks) {
          bool has1 = false;
          bool has2 = false;
          for (const auto& obs : track.observations) {
            has1 |= obs.frame == frames.first && obs.feature == int(match.point2D_idx1);
            has2 |= obs.frame == frames.second && obs.feature == int(match.point2D_idx2);
          }
          found |= has1 && has2;
        }
        EXPECT_TRUE(found) << "match not on one track";
      }
      num_matches += static_cast<int64_t>(matches.size());
    }
    EXPECT_EQ(summary.num_matches, num_matches);
  }
}

TEST(ColmapExport, VerifiedMatchesAreCalibratedInliersConsistentWithTheTruePose) {
  const Scene scene = MakeScene(8, 3);
  io::ColmapDatabase database = io::ColmapDatabase::Open(":memory:");
  const auto summary =
      WriteTracksToColmapDatabase(scene.tracks, scene.camera, ColmapExportOptions(), &database);
  EXPECT_EQ(summary.num_verified_pairs, summary.num_matched_pairs);
  EXPECT_GT(summary.num_verified_pairs, 20);
  const auto geometries = database.ReadAllTwoViewGeometries();
  ASSERT_EQ(static_cast<int>(geometries.size()), summary.num_matched_pairs);
  int corrupted_rejected = 0;
  for (const auto& [pair_id, geometry] : geometries) {
    const auto [id1, id2] = io::ColmapImagePairFromPairId(pair_id);
    EXPECT_EQ(geometry.config, io::kColmapCalibrated) << id1 << " " << id2;
    const io::ColmapFeatureMatches raw = database.ReadMatches(id1, id2);
    const std::set<std::pair<uint32_t, uint32_t>> raw_set = [&] {
      std::set<std::pair<uint32_t, uint32_t>> s;
      for (const auto& m : raw) s.insert({m.point2D_idx1, m.point2D_idx2});
      return s;
    }();
    std::set<std::pair<uint32_t, uint32_t>> inliers;
    for (const auto& m : geometry.inlier_matches) inliers.insert({m.point2D_idx1, m.point2D_idx2});
    EXPECT_GE(inliers.size(), raw.size() * 9 / 10);
    for (const auto& m : inliers) EXPECT_TRUE(raw_set.count(m)) << "inlier not among raw matches";
    for (const auto& m : raw) {
      const bool bad = scene.corrupted.count({int(id1 - 1), int(m.point2D_idx1)}) ||
                       scene.corrupted.count({int(id2 - 1), int(m.point2D_idx2)});
      if (bad) {
        EXPECT_FALSE(inliers.count({m.point2D_idx1, m.point2D_idx2})) << "wrong match kept";
        ++corrupted_rejected;
      }
    }
    // E = [t]× R of the stored pose, and F = K⁻ᵀ E K⁻¹ with K of the stored camera row, i.e. in
    // COLMAP's pixel convention (with OpenCV's principal point F would differ): exact identities.
    const Eigen::Quaterniond q(geometry.qvec(0), geometry.qvec(1), geometry.qvec(2),
                               geometry.qvec(3));
    Eigen::Matrix3d t_cross;
    t_cross << 0, -geometry.tvec.z(), geometry.tvec.y(), geometry.tvec.z(), 0, -geometry.tvec.x(),
        -geometry.tvec.y(), geometry.tvec.x(), 0;
    const Eigen::Matrix3d essential = t_cross * q.toRotationMatrix();
    EXPECT_LT((geometry.E - essential).norm(), 1e-9 * essential.norm()) << id1 << " " << id2;
    const std::vector<double> p = database.ReadCamera(1).params;
    Eigen::Matrix3d k;
    k << p[0], 0, p[2], 0, p[1], p[3], 0, 0, 1;
    const Eigen::Matrix3d fundamental = k.inverse().transpose() * essential * k.inverse();
    EXPECT_LT((geometry.F - fundamental).norm(), 1e-9 * fundamental.norm()) << id1 << " " << id2;
    // So the stored inliers, as stored (COLMAP coordinates), lie within the RANSAC threshold of
    // their epipolar lines x2ᵀ F x1 = 0.
    const io::ColmapKeypoints k1 = database.ReadKeypoints(id1);
    const io::ColmapKeypoints k2 = database.ReadKeypoints(id2);
    for (const auto& m : geometry.inlier_matches) {
      const Eigen::Vector3d x1 = Homogeneous(k1, m.point2D_idx1);
      const Eigen::Vector3d x2 = Homogeneous(k2, m.point2D_idx2);
      const Eigen::Vector3d line = geometry.F * x1;
      EXPECT_LT(std::abs(x2.dot(line)) / line.head<2>().norm(),
                ColmapExportOptions().two_view.max_error_px)
          << id1 << " " << id2;
    }
    // qvec, tvec: cam2_from_cam1 of the true poses (translation up to scale).
    const Rigid3d truth = scene.cams_from_world[id2 - 1] * scene.cams_from_world[id1 - 1].Inverse();
    EXPECT_LT(RotationAngleDeg(q, truth.rotation), 0.05) << id1 << " " << id2;
    EXPECT_GT(geometry.tvec.normalized().dot(truth.translation.normalized()), 0.9999);
  }
  EXPECT_GT(corrupted_rejected, 0);
  // Forward motion: |t_z| of every pair is above COLMAP's default 0.95.
  EXPECT_EQ(summary.num_pairs_allowing_default_init, 0);
}

TEST(ColmapExport, UnknownIntrinsicsGiveColmapsDefaultCameraAndUncalibratedPairs) {
  const Scene scene = MakeScene(6, 4);
  io::ColmapDatabase database = io::ColmapDatabase::Open(":memory:");
  const auto summary =
      WriteTracksToColmapDatabase(scene.tracks, std::nullopt, ColmapExportOptions(), &database);
  EXPECT_FALSE(summary.known_intrinsics);
  const auto camera = database.ReadCamera(1);
  EXPECT_EQ(camera.model_id, io::kColmapSimpleRadial);
  EXPECT_EQ(camera.params, (std::vector<double>{768.0, 320.0, 240.0, 0.0}));
  EXPECT_FALSE(camera.prior_focal_length);
  EXPECT_GT(summary.num_verified_pairs, 5);
  for (const auto& [pair_id, geometry] : database.ReadAllTwoViewGeometries()) {
    const auto [id1, id2] = io::ColmapImagePairFromPairId(pair_id);
    ASSERT_EQ(geometry.config, io::kColmapUncalibrated);
    const io::ColmapKeypoints k1 = database.ReadKeypoints(id1);
    const io::ColmapKeypoints k2 = database.ReadKeypoints(id2);
    for (const auto& m : geometry.inlier_matches) {
      const Eigen::Vector3d line = geometry.F * Homogeneous(k1, m.point2D_idx1);
      EXPECT_LT(std::abs(Homogeneous(k2, m.point2D_idx2).dot(line)) / line.head<2>().norm(), 1.0);
    }
  }
}

// Every table, read back, as one comparable value.
std::string DatabaseContent(const std::string& path) {
  io::ColmapDatabase database = io::ColmapDatabase::Open(path);
  std::ostringstream out;
  out.precision(17);
  for (const auto& c : database.ReadAllCameras()) {
    out << c.camera_id << " " << c.model_id << " " << c.width << " " << c.height << " "
        << c.prior_focal_length;
    for (double p : c.params) out << " " << p;
    out << "\n";
  }
  for (const auto& i : database.ReadAllImages()) {
    out << i.image_id << " " << i.name << " " << i.camera_id << "\n";
    out << database.ReadKeypoints(i.image_id) << "\n";
  }
  for (const auto& [pair_id, matches] : database.ReadAllMatches()) {
    out << pair_id;
    for (const auto& m : matches) out << " " << m.point2D_idx1 << ":" << m.point2D_idx2;
    out << "\n";
  }
  for (const auto& [pair_id, g] : database.ReadAllTwoViewGeometries()) {
    out << pair_id << " " << g.config << "\n"
        << g.F << "\n"
        << g.E << "\n"
        << g.qvec << "\n"
        << g.tvec;
    for (const auto& m : g.inlier_matches) out << " " << m.point2D_idx1 << ":" << m.point2D_idx2;
    out << "\n";
  }
  return out.str();
}

TEST(ColmapExport, SameTracksGiveTheSameDatabaseWhateverTheThreadCount) {
  const Scene scene = MakeScene(7, 5);
  ScopedTempDir dir;
  ColmapExportOptions one_thread;
  one_thread.num_threads = 1;
  ColmapExportOptions four_threads;
  four_threads.num_threads = 4;
  ExportTracksToColmapDatabase(scene.tracks, scene.camera, one_thread, dir.File("a.db"), false);
  ExportTracksToColmapDatabase(scene.tracks, scene.camera, four_threads, dir.File("b.db"), false);
  const std::string a = DatabaseContent(dir.File("a.db"));
  EXPECT_GT(a.size(), 10000u);
  EXPECT_EQ(a, DatabaseContent(dir.File("b.db")));
}

TEST(ColmapExport, RefusesToOverwriteAnExistingDatabaseUnlessAsked) {
  const Scene scene = MakeScene(5, 6);
  ScopedTempDir dir;
  const std::string path = dir.File("out.db");
  io::WriteFileAtomically(path, "precious\n");
  try {
    ExportTracksToColmapDatabase(scene.tracks, scene.camera, {}, path, /*overwrite=*/false);
    ADD_FAILURE() << "overwrote an existing file";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kIo);
    EXPECT_NE(std::string(e.what()).find("already exists"), std::string::npos) << e.what();
  }
  EXPECT_EQ(io::ReadFileToString(path), "precious\n");
  // A real database is not modified either.
  ExportTracksToColmapDatabase(scene.tracks, std::nullopt, {}, dir.File("colmap.db"), false);
  const std::string before = io::ReadFileToString(dir.File("colmap.db"));
  EXPECT_THROW(
      ExportTracksToColmapDatabase(scene.tracks, scene.camera, {}, dir.File("colmap.db"), false),
      Error);
  EXPECT_EQ(io::ReadFileToString(dir.File("colmap.db")), before);

  const auto summary =
      ExportTracksToColmapDatabase(scene.tracks, scene.camera, {}, path, /*overwrite=*/true);
  EXPECT_EQ(summary.num_images, 5);
  EXPECT_EQ(io::ColmapDatabase::Open(path).NumImages(), 5u);
}

TEST(ColmapExport, AFailedExportLeavesNoFileBehind) {
  Scene scene = MakeScene(5, 7);
  ScopedTempDir dir;
  const std::string path = dir.File("out.db");
  scene.tracks.frame_names.clear();  // COLMAP needs image names
  EXPECT_THROW(ExportTracksToColmapDatabase(scene.tracks, scene.camera, {}, path, false), Error);
  Camera wrong_size = scene.camera;
  wrong_size.width = 1000;
  scene.tracks.frame_names.assign(5, "x.png");  // duplicate names fail half-way through writing
  EXPECT_THROW(ExportTracksToColmapDatabase(scene.tracks, scene.camera, {}, path, false), Error);
  scene.tracks.frame_names = {"a", "b", "c", "d", "e"};
  EXPECT_THROW(ExportTracksToColmapDatabase(scene.tracks, wrong_size, {}, path, false), Error);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "left files behind";
}

TEST(ColmapExport, RejectsBadOptionsAndNonEmptyDatabases) {
  const Scene scene = MakeScene(4, 8);
  ColmapExportOptions options;
  options.pair_window = 0;
  EXPECT_THROW(options.Check(), Error);
  options = ColmapExportOptions();
  options.num_threads = -1;
  EXPECT_THROW(options.Check(), Error);
  io::ColmapDatabase database = io::ColmapDatabase::Open(":memory:");
  WriteTracksToColmapDatabase(scene.tracks, scene.camera, {}, &database);
  EXPECT_THROW(WriteTracksToColmapDatabase(scene.tracks, scene.camera, {}, &database), Error);
}

TEST(ColmapExport, WritesOneDescriptorPerKeypointInTheKeypointsOrder) {
  Scene scene = MakeScene(5, 9);
  // Tell-tale descriptors: feature k of frame i has byte (i * 7 + k) % 251 everywhere.
  for (size_t i = 0; i < scene.tracks.NumFrames(); ++i) {
    cv::Mat rows(static_cast<int>(scene.tracks.features[i].size()), 128, CV_8UC1);
    for (int k = 0; k < rows.rows; ++k) rows.row(k).setTo((i * 7 + k) % 251);
    scene.tracks.descriptors.push_back(rows);
  }
  io::ColmapDatabase database = io::ColmapDatabase::Open(":memory:");
  const ColmapExportSummary summary =
      WriteTracksToColmapDatabase(scene.tracks, scene.camera, {}, &database);
  EXPECT_EQ(summary.num_descriptors, summary.num_keypoints);
  for (size_t i = 0; i < scene.tracks.NumFrames(); ++i) {
    const io::ColmapDescriptors d = database.ReadDescriptors(static_cast<int64_t>(i) + 1);
    ASSERT_EQ(d.rows(), static_cast<Eigen::Index>(database.NumKeypointsForImage(i + 1)));
    ASSERT_EQ(d.cols(), 128);
    for (int k = 0; k < d.rows(); ++k) {
      EXPECT_EQ(d(k, 0), (i * 7 + k) % 251);
      EXPECT_EQ(d(k, 127), (i * 7 + k) % 251);
    }
  }
  // Asked not to, or tracks without descriptors: no descriptors table rows.
  ColmapExportOptions without;
  without.write_descriptors = false;
  io::ColmapDatabase second = io::ColmapDatabase::Open(":memory:");
  EXPECT_EQ(
      WriteTracksToColmapDatabase(scene.tracks, scene.camera, without, &second).num_descriptors, 0);
  EXPECT_EQ(second.NumDescriptors(), 0u);
  scene.tracks.descriptors.clear();
  io::ColmapDatabase third = io::ColmapDatabase::Open(":memory:");
  WriteTracksToColmapDatabase(scene.tracks, scene.camera, {}, &third);
  EXPECT_EQ(third.NumDescriptors(), 0u);
}

// The real COLMAP on an exported database of six KITTI frames whose tracks come from the
// consecutive pairs only. With our descriptors COLMAP's exhaustive matcher adds the other pairs
// and its mapper registers every frame; its feature extractor leaves our features alone (the
// images are complete), so that its matchers do not crash on keypoints without their
// descriptors; hierarchical_mapper and point_triangulator run on it too.
TEST(ColmapExport, ColmapsMatchersAndMappersExtendADatabaseWithDescriptors) {
  if (!IsColmapAvailable()) GTEST_SKIP() << "colmap is not installed";
  const std::string frames = test::ExampleDir() + "/image_l";
  std::vector<cv::Mat> grays;
  std::vector<std::string> names;
  for (int i = 0; i < 6; ++i) {
    names.push_back("00000" + std::to_string(i) + ".png");
    grays.push_back(io::LoadImage(frames + "/" + names.back(), 0, 1 << 30).gray);
  }
  frontend::ImageSetMatchingOptions matching;
  matching.window = 1;
  matching.max_features = 1500;
  const auto detector = frontend::MakeDetector("harris");
  const frontend::FeatureTracks tracks =
      frontend::MatchImageFrames(grays, *detector, matching, names).tracks;
  const cv::Matx33d k = io::ReadKittiIntrinsics(test::ExampleDir() + "/calib.txt", 0);
  const Camera camera = Camera::FromParams(CameraModelId::kPinhole, grays[0].cols, grays[0].rows,
                                           {k(0, 0), k(1, 1), k(0, 2), k(1, 2)});
  ScopedTempDir dir;
  ColmapExportOptions options;
  options.pair_window = 1;
  const std::string with = dir.File("with.db"), without = dir.File("without.db");
  const ColmapExportSummary summary =
      ExportTracksToColmapDatabase(tracks, camera, options, with, false);
  EXPECT_EQ(summary.num_verified_pairs, 5);
  options.write_descriptors = false;
  ExportTracksToColmapDatabase(tracks, camera, options, without, false);
  const std::string log = dir.File("colmap.log");
  const auto verified_pairs = [](const std::string& path) {
    int verified = 0;
    for (const auto& [pair_id, geometry] :
         io::ColmapDatabase::Open(path).ReadAllTwoViewGeometries()) {
      verified += geometry.inlier_matches.size() >= 15;
    }
    return verified;
  };
  for (const std::string& db : {with, without}) {
    RunColmap({"exhaustive_matcher", "--database_path", db, "--SiftMatching.use_gpu", "0",
               "--SiftMatching.num_threads", "2"},
              log);
  }
  EXPECT_GE(verified_pairs(with), 12) << "of 15";  // frames 0 and 5 are 6 m apart
  EXPECT_EQ(verified_pairs(without), 5);
  ColmapMapperOptions mapper = RecommendedColmapMapperOptions(summary);
  mapper.num_threads = 2;
  std::map<std::string, int64_t> registered;
  for (const std::string& db : {with, without}) {
    const auto model = RunColmapMapper(db, frames, db + ".sparse", mapper, log);
    registered[db] = model ? NumRegisteredImagesOfColmapModel(*model) : 0;
  }
  EXPECT_EQ(registered[with], 6) << io::ReadFileToString(log);
  EXPECT_GE(registered[with], registered[without]);

  // feature_extractor over the same images changes nothing; the matcher runs again without error.
  io::WriteFileAtomically(dir.File("list.txt"), [&] {
    std::string list;
    for (const std::string& name : names) list += name + "\n";
    return list;
  }());
  const io::ColmapDescriptors before = io::ColmapDatabase::Open(with).ReadDescriptors(3);
  // COLMAP 3.8's extractor can hang once it is done when it skipped every image (seen once in
  // many runs, under load: all six images reported, then every thread waiting on its job queues
  // with no CPU used): the step gets two minutes, and one more try if they run out.
  const std::vector<std::string> args = {"feature_extractor",
                                         "--database_path",
                                         with,
                                         "--image_path",
                                         frames,
                                         "--image_list_path",
                                         dir.File("list.txt"),
                                         "--SiftExtraction.use_gpu",
                                         "0",
                                         "--SiftExtraction.num_threads",
                                         "2"};
  std::vector<std::string> extract = {"--kill-after=5", "120", "colmap"};
  extract.insert(extract.end(), args.begin(), args.end());
  try {
    RunColmap(extract, log, "timeout");
  } catch (const Error&) {
    RunColmap(extract, log, "timeout");
  }
  {
    const io::ColmapDatabase database = io::ColmapDatabase::Open(with);
    EXPECT_EQ(database.NumImages(), 6u);
    EXPECT_TRUE(database.ReadDescriptors(3) == before);
  }
  RunColmap({"exhaustive_matcher", "--database_path", with, "--SiftMatching.use_gpu", "0"}, log);
  std::filesystem::create_directories(dir.File("hierarchical"));
  RunColmap({"hierarchical_mapper", "--database_path", with, "--image_path", frames,
             "--output_path", dir.File("hierarchical"), "--Mapper.init_max_forward_motion", "1",
             "--Mapper.init_min_tri_angle", "1", "--Mapper.min_model_size", "3",
             "--Mapper.ba_refine_focal_length", "0", "--Mapper.ba_refine_extra_params", "0",
             "--num_workers", "2"},
            log);
  const auto hierarchical = FindLargestColmapModel(dir.File("hierarchical"));
  ASSERT_TRUE(hierarchical) << io::ReadFileToString(log);
  EXPECT_EQ(NumRegisteredImagesOfColmapModel(*hierarchical), 6);
  std::filesystem::create_directories(dir.File("triangulated"));
  RunColmap({"point_triangulator", "--database_path", with, "--image_path", frames, "--input_path",
             *hierarchical, "--output_path", dir.File("triangulated")},
            log);
  EXPECT_EQ(NumRegisteredImagesOfColmapModel(dir.File("triangulated")), 6);
}

// The database's camera row carries the model's id and parameters (+0.5 on the principal point);
// without intrinsics COLMAP's default guess in the chosen model.
TEST(ColmapExport, DatabaseCameraRowHasTheModelsIdAndParameters) {
  const Camera opencv = Camera::FromParams(CameraModelId::kOpenCV, 640, 480,
                                           {500, 510, 319.5, 239.5, -0.1, 0.02, 0.001, -0.002});
  io::ColmapDatabaseCamera row = ToColmapDatabaseCamera(opencv, cv::Size(640, 480));
  EXPECT_EQ(row.model_id, 4);
  EXPECT_EQ(row.params, (std::vector<double>{500, 510, 320, 240, -0.1, 0.02, 0.001, -0.002}));
  EXPECT_TRUE(row.prior_focal_length);
  row = ToColmapDatabaseCamera(std::nullopt, cv::Size(640, 480));
  EXPECT_EQ(row.model_id, 2);
  EXPECT_EQ(row.params, (std::vector<double>{768, 320, 240, 0}));
  EXPECT_FALSE(row.prior_focal_length);
  row = ToColmapDatabaseCamera(std::nullopt, cv::Size(640, 480), CameraModelId::kRadial);
  EXPECT_EQ(row.model_id, 3);
  EXPECT_EQ(row.params, (std::vector<double>{768, 320, 240, 0, 0}));
}

}  // namespace
}  // namespace comic::sfm
