// COLMAP 3.8's SQLite database (tables cameras, images, keypoints, descriptors, matches,
// two_view_geometries), written and read with plain structs in COLMAP's own conventions, so that
// `colmap mapper` can reconstruct from our features and tracks.
//
//   comic::io::ColmapDatabase database = comic::io::ColmapDatabase::Open("out.db");
//   comic::io::ColmapDatabase::Transaction transaction(&database);
//   const int64_t camera_id = database.WriteCamera(camera);
//   const int64_t image_id = database.WriteImage(image);
//   database.WriteKeypoints(image_id, keypoints);
//   database.WriteMatches(image_id1, image_id2, matches);
//   database.WriteTwoViewGeometry(image_id1, image_id2, geometry);
//   transaction.Commit();
//
// Conventions, as COLMAP's:
// - image coordinates put the centre of the top-left pixel at (0.5, 0.5): add 0.5 to OpenCV
//   coordinates (keypoints and principal points alike; ToColmapPixel);
// - ids start at 1 and image ids are below kColmapMaxNumImages;
// - a pair of images is stored once, under ColmapPairId(min id, max id), and the first column of
//   its matches indexes the keypoints of the image with the smaller id; Write*/Read* take the two
//   ids in any order and swap columns (and invert the two-view geometry) as needed;
// - matrices are stored as blobs of row-major data with their rows and cols in separate columns
//   (keypoints float32, descriptors uint8, matches uint32); F, E, H are 3x3 row-major float64,
//   qvec (w, x, y, z) and tvec float64.
// The schema is exactly COLMAP 3.8's (what `colmap database_creator` makes); every INSERT names
// its columns, so a database made by another COLMAP version with extra columns is written too.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

struct sqlite3;

namespace comic::io {

// COLMAP's kMaxNumImages (INT32_MAX): image ids lie in [1, kColmapMaxNumImages) and pair ids are
// id1 · kColmapMaxNumImages + id2.
inline constexpr int64_t kColmapMaxNumImages = 2147483647;

// The pair id of two images, whatever their order: min · kColmapMaxNumImages + max. Throws
// comic::Error(kInvalidArgument) for ids outside [1, kColmapMaxNumImages).
int64_t ColmapPairId(int64_t image_id1, int64_t image_id2);
// The inverse of ColmapPairId: (smaller id, larger id).
std::pair<int64_t, int64_t> ColmapImagePairFromPairId(int64_t pair_id);

// OpenCV pixel coordinate (pixel centres at integers) -> COLMAP's (pixel centres at +0.5).
inline double ToColmapPixel(double opencv_coordinate) { return opencv_coordinate + 0.5; }
inline double FromColmapPixel(double colmap_coordinate) { return colmap_coordinate - 0.5; }

// Camera model ids of COLMAP's camera_models.h, with their parameter order.
enum ColmapCameraModelId : int {
  kColmapSimplePinhole = 0,        // f, cx, cy
  kColmapPinhole = 1,              // fx, fy, cx, cy
  kColmapSimpleRadial = 2,         // f, cx, cy, k
  kColmapRadial = 3,               // f, cx, cy, k1, k2
  kColmapOpenCV = 4,               // fx, fy, cx, cy, k1, k2, p1, p2
  kColmapOpenCVFisheye = 5,        // fx, fy, cx, cy, k1, k2, k3, k4
  kColmapFullOpenCV = 6,           // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6
  kColmapFov = 7,                  // fx, fy, cx, cy, omega
  kColmapSimpleRadialFisheye = 8,  // f, cx, cy, k
  kColmapRadialFisheye = 9,        // f, cx, cy, k1, k2
  kColmapThinPrismFisheye = 10,    // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, sx1, sy1
};
// "PINHOLE" for 1 etc. (the names of the text format); "" for an unknown id.
std::string ColmapCameraModelName(int model_id);
// The id of a model name; -1 if unknown.
int ColmapCameraModelIdFromName(const std::string& name);
// Number of parameters of a model; -1 for an unknown id.
int ColmapCameraModelNumParams(int model_id);

// TwoViewGeometry::ConfigurationType of COLMAP.
enum ColmapTwoViewConfig : int {
  kColmapUndefined = 0,
  kColmapDegenerate = 1,         // no overlap or too few inliers
  kColmapCalibrated = 2,         // essential matrix
  kColmapUncalibrated = 3,       // fundamental matrix
  kColmapPlanar = 4,             // homography, planar scene with baseline
  kColmapPanoramic = 5,          // homography, pure rotation
  kColmapPlanarOrPanoramic = 6,  // homography, planar or panoramic
  kColmapWatermark = 7,          // pure 2-D translation in the image borders
  kColmapMultiple = 8,           // inliers of several non-degenerate models
};

// A row of `cameras`.
struct ColmapDatabaseCamera {
  int64_t camera_id = 0;  // 0 when writing: let the database pick the next id
  int model_id = kColmapPinhole;
  int64_t width = 0;                // pixels
  int64_t height = 0;               // pixels
  std::vector<double> params;       // in the model's parameter order, COLMAP pixel convention
  bool prior_focal_length = false;  // true: the focal length is known (not a guess)
};

// A row of `images`. The pose prior (cam_from_world) is optional; NULL columns when absent.
struct ColmapDatabaseImage {
  int64_t image_id = 0;  // 0 when writing: let the database pick the next id
  std::string name;      // path relative to the image folder, unique
  int64_t camera_id = 0;
  std::optional<Eigen::Vector4d> prior_qvec;  // rotation quaternion (w, x, y, z)
  std::optional<Eigen::Vector3d> prior_tvec;
};

// Keypoints: one row per keypoint, 2 columns (x, y), 4 (x, y, scale, orientation) or 6 (x, y,
// a11, a12, a21, a22); COLMAP pixel convention.
using ColmapKeypoints = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
// Descriptors: one row per keypoint.
using ColmapDescriptors = Eigen::Matrix<uint8_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct ColmapFeatureMatch {
  uint32_t point2D_idx1 = 0;  // keypoint index in the first image
  uint32_t point2D_idx2 = 0;  // keypoint index in the second image
  bool operator==(const ColmapFeatureMatch& other) const {
    return point2D_idx1 == other.point2D_idx1 && point2D_idx2 == other.point2D_idx2;
  }
};
using ColmapFeatureMatches = std::vector<ColmapFeatureMatch>;

// A row of `two_view_geometries`: the verified (inlier) matches of a pair and its geometry, from
// the first image to the second (x2ᵀ F x1 = 0, cam2_from_cam1 = (qvec, tvec)).
struct ColmapTwoViewGeometry {
  int config = kColmapUndefined;  // a ColmapTwoViewConfig
  ColmapFeatureMatches inlier_matches;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector4d qvec = Eigen::Vector4d(1, 0, 0, 0);  // cam2_from_cam1 rotation (w, x, y, z)
  Eigen::Vector3d tvec = Eigen::Vector3d::Zero();      // cam2_from_cam1 translation

  // The same geometry seen from the second image: F, E transposed, H inverted, the pose
  // inverted and the match columns swapped.
  ColmapTwoViewGeometry Inverted() const;
};

class ColmapDatabase {
 public:
  // Opens the database at `path`, creating the file and COLMAP 3.8's tables where missing
  // (":memory:" gives an in-memory database). An existing database must hold COLMAP's tables
  // with at least COLMAP 3.8's columns (minus images' pose prior columns, which newer COLMAP
  // versions dropped), and as many descriptors as keypoints for every image that has both.
  // Another connection's lock is waited for (SqliteFileOptions' busy timeout), then named in the
  // error. Throws comic::Error: kIo if SQLite cannot open it or it stays locked, kInvalidData if
  // it is not a (consistent) COLMAP database.
  static ColmapDatabase Open(const std::string& path);

  ColmapDatabase(ColmapDatabase&& other) noexcept;
  ColmapDatabase& operator=(ColmapDatabase&& other) noexcept;
  ColmapDatabase(const ColmapDatabase&) = delete;
  ColmapDatabase& operator=(const ColmapDatabase&) = delete;
  ~ColmapDatabase();

  // Closes the database (also done by the destructor). Throws comic::Error(kIo) if SQLite
  // reports an error on closing.
  void Close();

  // Groups writes: everything written between construction and Commit() is stored at once, and
  // nothing of it if the transaction is destroyed without Commit() (e.g. by an exception).
  class Transaction {
   public:
    explicit Transaction(ColmapDatabase* database);
    ~Transaction();
    Transaction(const Transaction&) = delete;
    Transaction& operator=(const Transaction&) = delete;
    void Commit();

   private:
    ColmapDatabase* database_;
    bool open_ = false;
  };

  bool ExistsCamera(int64_t camera_id) const;
  bool ExistsImage(int64_t image_id) const;
  bool ExistsImageWithName(const std::string& name) const;
  bool ExistsKeypoints(int64_t image_id) const;
  bool ExistsDescriptors(int64_t image_id) const;
  bool ExistsMatches(int64_t image_id1, int64_t image_id2) const;
  bool ExistsTwoViewGeometry(int64_t image_id1, int64_t image_id2) const;

  size_t NumCameras() const;
  size_t NumImages() const;
  size_t NumKeypoints() const;                          // over all images
  size_t NumKeypointsForImage(int64_t image_id) const;  // 0 if none
  size_t NumDescriptors() const;
  size_t NumMatches() const;             // raw matches over all pairs
  size_t NumMatchedImagePairs() const;   // rows of `matches`
  size_t NumInlierMatches() const;       // verified matches over all pairs
  size_t NumVerifiedImagePairs() const;  // rows of `two_view_geometries`

  // Single-row reads throw comic::Error(kNotFound) if the row does not exist (see Exists*), and
  // kInvalidData if a blob's size does not match its rows and cols.
  ColmapDatabaseCamera ReadCamera(int64_t camera_id) const;
  std::vector<ColmapDatabaseCamera> ReadAllCameras() const;  // by camera_id
  ColmapDatabaseImage ReadImage(int64_t image_id) const;
  std::vector<ColmapDatabaseImage> ReadAllImages() const;  // by image_id
  ColmapKeypoints ReadKeypoints(int64_t image_id) const;
  ColmapDescriptors ReadDescriptors(int64_t image_id) const;
  // Matches with point2D_idx1 in image_id1, whatever the stored order.
  ColmapFeatureMatches ReadMatches(int64_t image_id1, int64_t image_id2) const;
  // Every stored pair as (pair_id, matches with the smaller id first), by pair_id.
  std::vector<std::pair<int64_t, ColmapFeatureMatches>> ReadAllMatches() const;
  // The geometry from image_id1 to image_id2, whatever the stored order.
  ColmapTwoViewGeometry ReadTwoViewGeometry(int64_t image_id1, int64_t image_id2) const;
  std::vector<std::pair<int64_t, ColmapTwoViewGeometry>> ReadAllTwoViewGeometries() const;

  // Writes return the row's id. A camera or image with id 0 gets the next free id. Writing a row
  // that exists (same id, same image name, same pair) throws comic::Error(kInvalidArgument), as
  // do parameters that do not fit the camera model, keypoints with other than 2, 4 or 6
  // columns, descriptors with a row count other than the image's keypoints, and matches whose
  // indices exceed the images' keypoints (when those are written).
  int64_t WriteCamera(const ColmapDatabaseCamera& camera);
  int64_t WriteImage(const ColmapDatabaseImage& image);
  void WriteKeypoints(int64_t image_id, const ColmapKeypoints& keypoints);
  void WriteDescriptors(int64_t image_id, const ColmapDescriptors& descriptors);
  void WriteMatches(int64_t image_id1, int64_t image_id2, const ColmapFeatureMatches& matches);
  void WriteTwoViewGeometry(int64_t image_id1, int64_t image_id2,
                            const ColmapTwoViewGeometry& geometry);

  const std::string& path() const { return path_; }

 private:
  ColmapDatabase() = default;
  void Execute(const std::string& sql) const;
  void CreateTables() const;
  void CheckSchema();
  void CheckMatchIndices(int64_t image_id1, int64_t image_id2,
                         const ColmapFeatureMatches& matches) const;
  size_t CountRows(const std::string& table) const;
  size_t SumRows(const std::string& table) const;

  sqlite3* db_ = nullptr;
  std::string path_;
  bool has_image_priors_ = true;  // images has prior_q*/prior_t* columns (COLMAP <= 3.8)
};

}  // namespace comic::io
