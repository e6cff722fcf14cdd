#include "io/colmap/colmap_database.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <Eigen/Geometry>
#include <cstring>
#include <map>
#include <random>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::RunCommand;
using comic::test::ScopedTempDir;

bool ColmapOnPath() { return RunCommand("command -v colmap").exit_code == 0; }

// Runs `sql` on the database file at `path` with plain SQLite and returns the first column of
// every row as text (blobs as raw bytes).
std::vector<std::string> QueryColumn(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* stmt = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr), SQLITE_OK) << sql;
  std::vector<std::string> values;
  while (stmt != nullptr && sqlite3_step(stmt) == SQLITE_ROW) {
    const char* data = static_cast<const char*>(sqlite3_column_blob(stmt, 0));
    values.emplace_back(data == nullptr ? "" : std::string(data, sqlite3_column_bytes(stmt, 0)));
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return values;
}

// PRAGMA table_info of every COLMAP table as "table.column type notnull pk" lines.
std::vector<std::string> SchemaOf(const std::string& path) {
  std::vector<std::string> lines;
  for (const char* table :
       {"cameras", "images", "keypoints", "descriptors", "matches", "two_view_geometries"}) {
    const std::string sql = std::string("SELECT '") + table +
                            ".' || name || ' ' || type || ' ' || \"notnull\" || ' ' || pk FROM "
                            "pragma_table_info('" +
                            table + "')";
    for (const std::string& line : QueryColumn(path, sql)) lines.push_back(line);
  }
  return lines;
}

TEST(ColmapPairId, IsMinTimesMaxNumImagesPlusMax) {
  EXPECT_EQ(kColmapMaxNumImages, 2147483647);
  EXPECT_EQ(ColmapPairId(1, 2), int64_t{2147483647} + 2);
  EXPECT_EQ(ColmapPairId(2, 1), int64_t{2147483647} + 2);
  EXPECT_EQ(ColmapPairId(3, 7), 3 * int64_t{2147483647} + 7);
  EXPECT_EQ(ColmapPairId(2147483646, 2147483645), int64_t{2147483645} * 2147483647 + 2147483646);
  EXPECT_THROW(ColmapPairId(0, 1), Error);
  EXPECT_THROW(ColmapPairId(1, 2147483647), Error);
}

TEST(ColmapPairId, InverseGivesSmallerIdFirst) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int64_t> id(1, kColmapMaxNumImages - 1);
  for (int i = 0; i < 1000; ++i) {
    const int64_t a = id(rng);
    const int64_t b = id(rng);
    const auto [first, second] = ColmapImagePairFromPairId(ColmapPairId(a, b));
    EXPECT_EQ(first, std::min(a, b));
    EXPECT_EQ(second, std::max(a, b));
  }
  EXPECT_EQ(ColmapImagePairFromPairId(int64_t{2147483647} + 2),
            std::make_pair(int64_t{1}, int64_t{2}));
}

TEST(ColmapPixel, TopLeftPixelCentreIsHalfAPixelIn) {
  EXPECT_DOUBLE_EQ(ToColmapPixel(0.0), 0.5);
  EXPECT_DOUBLE_EQ(ToColmapPixel(601.8873), 602.3873);
  EXPECT_DOUBLE_EQ(FromColmapPixel(ToColmapPixel(12.25)), 12.25);
}

TEST(ColmapCameraModels, IdsNamesAndParameterCountsAsCameraModelsH) {
  EXPECT_EQ(ColmapCameraModelName(0), "SIMPLE_PINHOLE");
  EXPECT_EQ(ColmapCameraModelName(1), "PINHOLE");
  EXPECT_EQ(ColmapCameraModelName(2), "SIMPLE_RADIAL");
  EXPECT_EQ(ColmapCameraModelName(4), "OPENCV");
  EXPECT_EQ(ColmapCameraModelName(10), "THIN_PRISM_FISHEYE");
  EXPECT_EQ(ColmapCameraModelName(11), "");
  EXPECT_EQ(ColmapCameraModelIdFromName("PINHOLE"), 1);
  EXPECT_EQ(ColmapCameraModelIdFromName("SIMPLE_RADIAL"), 2);
  EXPECT_EQ(ColmapCameraModelIdFromName("nonsense"), -1);
  EXPECT_EQ(ColmapCameraModelNumParams(kColmapPinhole), 4);
  EXPECT_EQ(ColmapCameraModelNumParams(kColmapSimpleRadial), 4);
  EXPECT_EQ(ColmapCameraModelNumParams(kColmapFullOpenCV), 12);
  EXPECT_EQ(ColmapCameraModelNumParams(-3), -1);
  EXPECT_EQ(kColmapCalibrated, 2);
  EXPECT_EQ(kColmapUncalibrated, 3);
}

// A small database with every kind of row, written in ways that exercise the id order rules.
struct Fixture {
  std::vector<ColmapDatabaseCamera> cameras;
  std::vector<ColmapDatabaseImage> images;
  std::map<int64_t, ColmapKeypoints> keypoints;
  std::map<int64_t, ColmapDescriptors> descriptors;
};

Fixture MakeFixture() {
  Fixture f;
  f.cameras.push_back(
      {1, kColmapPinhole, 1226, 370, {707.0912, 707.0912, 602.3873, 183.6104}, true});
  f.cameras.push_back({0, kColmapSimpleRadial, 640, 480, {768.0, 320.0, 240.0, 0.0}, false});
  f.images.push_back({0, "image_l/000000.png", 1, std::nullopt, std::nullopt});
  f.images.push_back({0, "image_l/000001.png", 1, Eigen::Vector4d(0.5, 0.5, -0.5, 0.5),
                      Eigen::Vector3d(1.0, -2.0, 3.5)});
  f.images.push_back({7, "other/frame 7.jpg", 2, std::nullopt, std::nullopt});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(0.5f, 600.0f);
  const std::map<int64_t, std::pair<int, int>> sizes = {{1, {40, 2}}, {2, {35, 4}}, {7, {0, 2}}};
  for (const auto& [image_id, size] : sizes) {
    ColmapKeypoints kp(size.first, size.second);
    for (Eigen::Index i = 0; i < kp.size(); ++i) kp.data()[i] = coordinate(rng);
    f.keypoints[image_id] = kp;
  }
  ColmapDescriptors d(40, 128);
  for (Eigen::Index i = 0; i < d.size(); ++i) d.data()[i] = static_cast<uint8_t>(rng() % 256);
  f.descriptors[1] = d;
  return f;
}

ColmapTwoViewGeometry MakeGeometry() {
  ColmapTwoViewGeometry geometry;
  geometry.config = kColmapCalibrated;
  geometry.inlier_matches = {{0, 3}, {5, 1}, {39, 34}};
  geometry.F << 1, 2, 3, 4, 5, 6, 7, 8, 9.5;
  geometry.E << 0, -1, 0.25, 1, 0, -2, -0.25, 2, 0;
  geometry.H << 2, 0.1, 3, 0, 1.5, -4, 0.001, 0, 1;
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized();
  geometry.qvec = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  geometry.tvec = Eigen::Vector3d(0.1, -0.2, 0.97);
  return geometry;
}

void WriteFixture(const Fixture& f, ColmapDatabase* database) {
  ColmapDatabase::Transaction transaction(database);
  EXPECT_EQ(database->WriteCamera(f.cameras[0]), 1);
  EXPECT_EQ(database->WriteCamera(f.cameras[1]), 2);  // next free id
  EXPECT_EQ(database->WriteImage(f.images[0]), 1);
  EXPECT_EQ(database->WriteImage(f.images[1]), 2);
  EXPECT_EQ(database->WriteImage(f.images[2]), 7);
  for (const auto& [id, kp] : f.keypoints) database->WriteKeypoints(id, kp);
  for (const auto& [id, d] : f.descriptors) database->WriteDescriptors(id, d);
  // Pair (1, 2) written with the larger id first: stored swapped.
  database->WriteMatches(2, 1, {{3, 0}, {1, 5}, {34, 39}, {0, 0}});
  database->WriteTwoViewGeometry(2, 1, MakeGeometry().Inverted());
  database->WriteMatches(1, 7, {});
  transaction.Commit();
}

void ExpectSameGeometry(const ColmapTwoViewGeometry& a, const ColmapTwoViewGeometry& b,
                        double tolerance) {
  EXPECT_EQ(a.config, b.config);
  EXPECT_EQ(a.inlier_matches, b.inlier_matches);
  EXPECT_TRUE(a.F.isApprox(b.F, tolerance)) << a.F << "\n" << b.F;
  EXPECT_TRUE(a.E.isApprox(b.E, tolerance)) << a.E << "\n" << b.E;
  EXPECT_TRUE(a.H.isApprox(b.H, tolerance)) << a.H << "\n" << b.H;
  EXPECT_TRUE(a.qvec.isApprox(b.qvec, tolerance))
      << a.qvec.transpose() << " " << b.qvec.transpose();
  EXPECT_TRUE(a.tvec.isApprox(b.tvec, tolerance))
      << a.tvec.transpose() << " " << b.tvec.transpose();
}

void ExpectFixture(const Fixture& f, const ColmapDatabase& database) {
  EXPECT_EQ(database.NumCameras(), 2u);
  EXPECT_EQ(database.NumImages(), 3u);
  EXPECT_EQ(database.NumKeypoints(), 75u);
  EXPECT_EQ(database.NumKeypointsForImage(2), 35u);
  EXPECT_EQ(database.NumDescriptors(), 40u);
  EXPECT_EQ(database.NumMatchedImagePairs(), 2u);
  EXPECT_EQ(database.NumMatches(), 4u);
  EXPECT_EQ(database.NumVerifiedImagePairs(), 1u);
  EXPECT_EQ(database.NumInlierMatches(), 3u);

  const auto cameras = database.ReadAllCameras();
  ASSERT_EQ(cameras.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(cameras[i].camera_id, static_cast<int64_t>(i + 1));
    EXPECT_EQ(cameras[i].model_id, f.cameras[i].model_id);
    EXPECT_EQ(cameras[i].width, f.cameras[i].width);
    EXPECT_EQ(cameras[i].height, f.cameras[i].height);
    EXPECT_EQ(cameras[i].params, f.cameras[i].params);  // exact
    EXPECT_EQ(cameras[i].prior_focal_length, f.cameras[i].prior_focal_length);
  }
  EXPECT_EQ(database.ReadCamera(2).params, f.cameras[1].params);

  const auto images = database.ReadAllImages();
  ASSERT_EQ(images.size(), 3u);
  const int64_t ids[] = {1, 2, 7};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(images[i].image_id, ids[i]);
    EXPECT_EQ(images[i].name, f.images[i].name);
    EXPECT_EQ(images[i].camera_id, f.images[i].camera_id);
    EXPECT_EQ(images[i].prior_qvec.has_value(), f.images[i].prior_qvec.has_value());
    EXPECT_EQ(images[i].prior_tvec.has_value(), f.images[i].prior_tvec.has_value());
    if (images[i].prior_qvec && f.images[i].prior_qvec) {
      EXPECT_EQ(*images[i].prior_qvec, *f.images[i].prior_qvec);
    }
    if (images[i].prior_tvec && f.images[i].prior_tvec) {
      EXPECT_EQ(*images[i].prior_tvec, *f.images[i].prior_tvec);
    }
  }
  EXPECT_EQ(database.ReadImage(7).name, "other/frame 7.jpg");

  for (const auto& [id, kp] : f.keypoints) {
    const ColmapKeypoints read = database.ReadKeypoints(id);
    EXPECT_EQ(read.rows(), kp.rows()) << id;
    EXPECT_EQ(read.cols(), kp.cols()) << id;
    EXPECT_TRUE(read == kp) << id;
  }
  EXPECT_TRUE(database.ReadDescriptors(1) == f.descriptors.at(1));

  // Whatever order the ids are given in, point2D_idx1 indexes the first image given.
  const ColmapFeatureMatches forward = {{0, 3}, {5, 1}, {39, 34}, {0, 0}};
  EXPECT_EQ(database.ReadMatches(1, 2), forward);
  const ColmapFeatureMatches backward = {{3, 0}, {1, 5}, {34, 39}, {0, 0}};
  EXPECT_EQ(database.ReadMatches(2, 1), backward);
  EXPECT_TRUE(database.ReadMatches(7, 1).empty());
  const auto all_matches = database.ReadAllMatches();
  ASSERT_EQ(all_matches.size(), 2u);
  EXPECT_EQ(all_matches[0].first, ColmapPairId(1, 2));
  EXPECT_EQ(all_matches[0].second, forward);
  EXPECT_EQ(all_matches[1].first, ColmapPairId(1, 7));

  ExpectSameGeometry(database.ReadTwoViewGeometry(1, 2), MakeGeometry(), 1e-12);
  ExpectSameGeometry(database.ReadTwoViewGeometry(2, 1), MakeGeometry().Inverted(), 1e-12);
  const auto all_geometries = database.ReadAllTwoViewGeometries();
  ASSERT_EQ(all_geometries.size(), 1u);
  EXPECT_EQ(all_geometries[0].first, ColmapPairId(1, 2));
  ExpectSameGeometry(all_geometries[0].second, MakeGeometry(), 1e-12);

  EXPECT_TRUE(database.ExistsCamera(2));
  EXPECT_FALSE(database.ExistsCamera(3));
  EXPECT_TRUE(database.ExistsImage(7));
  EXPECT_FALSE(database.ExistsImage(3));
  EXPECT_TRUE(database.ExistsImageWithName("image_l/000001.png"));
  EXPECT_FALSE(database.ExistsImageWithName("image_l/000002.png"));
  EXPECT_TRUE(database.ExistsKeypoints(7));
  EXPECT_TRUE(database.ExistsDescriptors(1));
  EXPECT_FALSE(database.ExistsDescriptors(2));
  EXPECT_TRUE(database.ExistsMatches(2, 1));
  EXPECT_FALSE(database.ExistsMatches(2, 7));
  EXPECT_TRUE(database.ExistsTwoViewGeometry(1, 2));
  EXPECT_FALSE(database.ExistsTwoViewGeometry(1, 7));
}

TEST(ColmapDatabase, RoundTripInMemoryKeepsEveryField) {
  const Fixture fixture = MakeFixture();
  ColmapDatabase database = ColmapDatabase::Open(":memory:");
  WriteFixture(fixture, &database);
  ExpectFixture(fixture, database);
}

TEST(ColmapDatabase, RoundTripThroughAFileKeepsEveryField) {
  ScopedTempDir dir;
  const Fixture fixture = MakeFixture();
  {
    ColmapDatabase database = ColmapDatabase::Open(dir.File("db.db"));
    WriteFixture(fixture, &database);
    database.Close();
  }
  ColmapDatabase database = ColmapDatabase::Open(dir.File("db.db"));
  ExpectFixture(fixture, database);
}

TEST(ColmapDatabase, StoresBlobsInColmapsLayout) {
  ScopedTempDir dir;
  const std::string path = dir.File("db.db");
  {
    ColmapDatabase database = ColmapDatabase::Open(path);
    WriteFixture(MakeFixture(), &database);
  }
  // Keypoints: float32, row-major (x0, y0, x1, y1, ...), rows and cols in their own columns.
  const Fixture fixture = MakeFixture();
  const std::string blob = QueryColumn(path, "SELECT data FROM keypoints WHERE image_id=1").at(0);
  ASSERT_EQ(blob.size(), 40u * 2u * sizeof(float));
  float xy[4];
  std::memcpy(xy, blob.data(), sizeof(xy));
  EXPECT_EQ(xy[0], fixture.keypoints.at(1)(0, 0));
  EXPECT_EQ(xy[1], fixture.keypoints.at(1)(0, 1));
  EXPECT_EQ(xy[2], fixture.keypoints.at(1)(1, 0));
  EXPECT_EQ(QueryColumn(path, "SELECT rows || 'x' || cols FROM keypoints WHERE image_id=2").at(0),
            "35x4");
  // Matches written as (2, 1) are stored under pair (1, 2) with image 1's indices first, uint32.
  const std::string pair = std::to_string(ColmapPairId(1, 2));
  const std::string matches =
      QueryColumn(path, "SELECT data FROM matches WHERE pair_id=" + pair).at(0);
  ASSERT_EQ(matches.size(), 4u * 2u * sizeof(uint32_t));
  uint32_t first_rows[4];
  std::memcpy(first_rows, matches.data(), sizeof(first_rows));
  EXPECT_EQ(first_rows[0], 0u);
  EXPECT_EQ(first_rows[1], 3u);
  EXPECT_EQ(first_rows[2], 5u);
  EXPECT_EQ(first_rows[3], 1u);
  // F row-major float64, config as written, qvec (w, x, y, z), tvec.
  const std::string f_blob =
      QueryColumn(path, "SELECT F FROM two_view_geometries WHERE pair_id=" + pair).at(0);
  ASSERT_EQ(f_blob.size(), 9u * sizeof(double));
  double f[9];
  std::memcpy(f, f_blob.data(), sizeof(f));
  EXPECT_DOUBLE_EQ(f[1], 2.0);  // F(0, 1)
  EXPECT_DOUBLE_EQ(f[3], 4.0);  // F(1, 0)
  EXPECT_EQ(QueryColumn(path, "SELECT config FROM two_view_geometries").at(0), "2");
  const std::string q_blob =
      QueryColumn(path, "SELECT qvec FROM two_view_geometries WHERE pair_id=" + pair).at(0);
  ASSERT_EQ(q_blob.size(), 4u * sizeof(double));
  double q[4];
  std::memcpy(q, q_blob.data(), sizeof(q));
  EXPECT_NEAR(q[0], MakeGeometry().qvec(0), 1e-12);
  // Camera params float64 in model order; prior flag as an integer.
  const std::string params =
      QueryColumn(path, "SELECT params FROM cameras WHERE camera_id=1").at(0);
  ASSERT_EQ(params.size(), 4u * sizeof(double));
  double p[4];
  std::memcpy(p, params.data(), sizeof(p));
  EXPECT_EQ(p[2], 602.3873);
  EXPECT_EQ(QueryColumn(path, "SELECT prior_focal_length FROM cameras ORDER BY camera_id"),
            (std::vector<std::string>{"1", "0"}));
  // COLMAP 3.8 stamps its databases with user_version 3800.
  EXPECT_EQ(QueryColumn(path, "PRAGMA user_version").at(0), "3800");
}

TEST(ColmapDatabase, TransactionWithoutCommitWritesNothing) {
  ColmapDatabase database = ColmapDatabase::Open(":memory:");
  {
    ColmapDatabase::Transaction transaction(&database);
    database.WriteCamera({0, kColmapPinhole, 10, 10, {1, 1, 5, 5}, false});
  }
  EXPECT_EQ(database.NumCameras(), 0u);
  ColmapDatabase::Transaction transaction(&database);
  database.WriteCamera({0, kColmapPinhole, 10, 10, {1, 1, 5, 5}, false});
  transaction.Commit();
  EXPECT_EQ(database.NumCameras(), 1u);
}

TEST(ColmapDatabase, RejectsInvalidWrites) {
  ColmapDatabase database = ColmapDatabase::Open(":memory:");
  const auto expect_invalid = [](const std::function<void()>& write, const std::string& message) {
    try {
      write();
      ADD_FAILURE() << "no error, expected: " << message;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument) << e.what();
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  expect_invalid(
      [&] {
        database.WriteCamera({0, kColmapPinhole, 10, 10, {1, 5, 5}, false});
      },
      "takes 4 parameters, got 3");
  expect_invalid([&] { database.WriteCamera({0, 42, 10, 10, {}, false}); }, "unknown COLMAP");
  ASSERT_EQ(database.WriteCamera({0, kColmapPinhole, 10, 10, {1, 1, 5, 5}, false}), 1);
  expect_invalid(
      [&] {
        database.WriteCamera({1, kColmapPinhole, 10, 10, {1, 1, 5, 5}, false});
      },
      "exists already");
  expect_invalid(
      [&] {
        database.WriteImage({0, "a.png", 9, std::nullopt, std::nullopt});
      },
      "does not exist");
  ASSERT_EQ(database.WriteImage({0, "a.png", 1, std::nullopt, std::nullopt}), 1);
  ASSERT_EQ(database.WriteImage({0, "b.png", 1, std::nullopt, std::nullopt}), 2);
  expect_invalid(
      [&] {
        database.WriteImage({0, "a.png", 1, std::nullopt, std::nullopt});
      },
      "exists already");
  expect_invalid([&] { database.WriteKeypoints(1, ColmapKeypoints(3, 3)); }, "2, 4 or 6 columns");
  database.WriteKeypoints(1, ColmapKeypoints::Zero(3, 2));
  database.WriteKeypoints(2, ColmapKeypoints::Zero(2, 2));
  expect_invalid([&] { database.WriteKeypoints(1, ColmapKeypoints::Zero(3, 2)); }, "exist already");
  expect_invalid([&] { database.WriteMatches(1, 2, {{0, 2}}); }, "keypoint 2 of image 2");
  expect_invalid([&] { database.WriteMatches(2, 1, {{0, 3}}); }, "keypoint 3 of image 1");
  expect_invalid([&] { database.WriteMatches(1, 1, {}); }, "with itself");
  expect_invalid([&] { database.WriteMatches(1, 3, {}); }, "does not exist");
  database.WriteMatches(1, 2, {{2, 1}});
  expect_invalid([&] { database.WriteMatches(2, 1, {{1, 2}}); }, "exist already");
  expect_invalid([&] { database.WriteDescriptors(1, ColmapDescriptors::Zero(2, 128)); },
                 "3 keypoints but 2 descriptors");
  EXPECT_THROW(database.ReadCamera(5), Error);
  EXPECT_THROW(database.ReadMatches(1, 3), Error);
}

TEST(ColmapDatabase, RefusesFilesThatAreNotColmapDatabases) {
  ScopedTempDir dir;
  WriteFileAtomically(dir.File("text.db"), "this is not an SQLite database, just some text\n");
  try {
    ColmapDatabase::Open(dir.File("text.db"));
    ADD_FAILURE() << "opened a text file";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData) << e.what();
  }
  // An SQLite database with other tables.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(dir.File("other.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "CREATE TABLE cameras (id INTEGER)", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  try {
    ColmapDatabase::Open(dir.File("other.db"));
    ADD_FAILURE() << "opened a foreign database";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a COLMAP"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ColmapDatabase::Open("/nonexistent/folder/x.db"), Error);
}

// The schema we create is COLMAP 3.8's own: compared column by column (name, type, NOT NULL,
// primary key) with what `colmap database_creator` makes.
TEST(ColmapDatabase, SchemaEqualsColmapDatabaseCreators) {
  if (!ColmapOnPath()) GTEST_SKIP() << "colmap is not installed";
  ScopedTempDir dir;
  const auto created = RunCommand(
      "QT_QPA_PLATFORM=offscreen colmap database_creator "
      "--database_path " +
      dir.File("colmap.db"));
  ASSERT_EQ(created.exit_code, 0) << created.output;
  ColmapDatabase::Open(dir.File("ours.db")).Close();
  const std::vector<std::string> colmap_schema = SchemaOf(dir.File("colmap.db"));
  EXPECT_EQ(colmap_schema.size(), 6u + 10u + 4u + 4u + 4u + 10u);
  EXPECT_EQ(SchemaOf(dir.File("ours.db")), colmap_schema);
  EXPECT_EQ(QueryColumn(dir.File("ours.db"), "PRAGMA user_version"),
            QueryColumn(dir.File("colmap.db"), "PRAGMA user_version"));
  // The same indices (the unique index on image names).
  const std::string indices = "SELECT name FROM sqlite_master WHERE type='index' ORDER BY name";
  EXPECT_EQ(QueryColumn(dir.File("ours.db"), indices), QueryColumn(dir.File("colmap.db"), indices));
}

TEST(ColmapDatabase, WritesIntoADatabaseMadeByColmapsDatabaseCreator) {
  if (!ColmapOnPath()) GTEST_SKIP() << "colmap is not installed";
  ScopedTempDir dir;
  const std::string path = dir.File("colmap.db");
  const auto created =
      RunCommand("QT_QPA_PLATFORM=offscreen colmap database_creator --database_path " + path);
  ASSERT_EQ(created.exit_code, 0) << created.output;
  const Fixture fixture = MakeFixture();
  {
    ColmapDatabase database = ColmapDatabase::Open(path);
    WriteFixture(fixture, &database);
    database.Close();
  }
  ColmapDatabase database = ColmapDatabase::Open(path);
  ExpectFixture(fixture, database);
}

}  // namespace
}  // namespace comic::io
