#include "io/colmap/colmap_database.h"

#include <sqlite3.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <set>

#include "io/colmap/sqlite_file.h"
#include "io/core/error.h"

namespace comic::io {
namespace {

// COLMAP 3.8's tables, column for column what its Database::CreateTables() makes (checked
// against `colmap database_creator` output, see docs/colmap.md).
constexpr const char* kCreateTablesSql = R"sql(
CREATE TABLE IF NOT EXISTS cameras (
  camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  model INTEGER NOT NULL,
  width INTEGER NOT NULL,
  height INTEGER NOT NULL,
  params BLOB,
  prior_focal_length INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS images (
  image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  name TEXT NOT NULL UNIQUE,
  camera_id INTEGER NOT NULL,
  prior_qw REAL,
  prior_qx REAL,
  prior_qy REAL,
  prior_qz REAL,
  prior_tx REAL,
  prior_ty REAL,
  prior_tz REAL,
  CONSTRAINT image_id_check CHECK(image_id >= 0 and image_id < 2147483647),
  FOREIGN KEY(camera_id) REFERENCES cameras(camera_id));
CREATE UNIQUE INDEX IF NOT EXISTS index_name ON images(name);
CREATE TABLE IF NOT EXISTS keypoints (
  image_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL,
  cols INTEGER NOT NULL,
  data BLOB,
  FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE IF NOT EXISTS descriptors (
  image_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL,
  cols INTEGER NOT NULL,
  data BLOB,
  FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE IF NOT EXISTS matches (
  pair_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL,
  cols INTEGER NOT NULL,
  data BLOB);
CREATE TABLE IF NOT EXISTS two_view_geometries (
  pair_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL,
  cols INTEGER NOT NULL,
  data BLOB,
  config INTEGER NOT NULL,
  F BLOB,
  E BLOB,
  H BLOB,
  qvec BLOB,
  tvec BLOB);
)sql";

// What COLMAP 3.8 stores in PRAGMA user_version (its version number).
constexpr int kColmap38UserVersion = 3800;

struct ModelInfo {
  int id;
  const char* name;
  int num_params;
};
constexpr ModelInfo kModels[] = {
    {kColmapSimplePinhole, "SIMPLE_PINHOLE", 3},
    {kColmapPinhole, "PINHOLE", 4},
    {kColmapSimpleRadial, "SIMPLE_RADIAL", 4},
    {kColmapRadial, "RADIAL", 5},
    {kColmapOpenCV, "OPENCV", 8},
    {kColmapOpenCVFisheye, "OPENCV_FISHEYE", 8},
    {kColmapFullOpenCV, "FULL_OPENCV", 12},
    {kColmapFov, "FOV", 5},
    {kColmapSimpleRadialFisheye, "SIMPLE_RADIAL_FISHEYE", 4},
    {kColmapRadialFisheye, "RADIAL_FISHEYE", 5},
    {kColmapThinPrismFisheye, "THIN_PRISM_FISHEYE", 12},
};

// "PATH: SQLite: MESSAGE", with the system's reason when there is one ("database or disk is
// full: No space left on device"); for a lock that outlasted the busy timeout, who holds it.
std::string SqliteMessage(sqlite3* db, const std::string& path, int rc,
                          const std::string& message) {
  if ((rc & 0xff) != SQLITE_BUSY && (rc & 0xff) != SQLITE_LOCKED) {
    int system_errno = db != nullptr ? sqlite3_system_errno(db) : 0;
    // SQLite's unix VFS reports a full disk as SQLITE_FULL and clears the errno it got (ENOSPC);
    // we set no page limit, so that is the only way to SQLITE_FULL here.
    if ((rc & 0xff) == SQLITE_FULL && system_errno == 0) system_errno = ENOSPC;
    return path + ": SQLite: " + message +
           (system_errno != 0 ? std::string(": ") + std::strerror(system_errno) : "");
  }
  const std::string holders = DescribeOtherHolders(path);
  return path + ": the database is locked by another connection" +
         (holders.empty() ? "" : " (" + holders + ")") + " after waiting " +
         std::to_string(SqliteFileOptions().busy_timeout_ms) + " ms";
}

// COLMAP's feature_extractor writes descriptors for an image that has keypoints but none, and
// keeps the keypoints: 5064 SIFT descriptors beside 2000 of our keypoints, and its matchers then
// index keypoints that do not exist (exhaustive_matcher segfaults; issue 29). Such a database is
// refused, naming the first image.
void CheckDescriptorsMatchKeypoints(sqlite3* db, const std::string& path);

// A prepared statement, finalized on destruction. Errors name the database's path.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& path, const std::string& sql) : db_(db), path_(path) {
    COMIC_CHECK(db_ != nullptr, kInvalidArgument, "COLMAP database is closed");
    const int rc = sqlite3_prepare_v2(db_, sql.c_str(), -1, &stmt_, nullptr);
    if ((rc & 0xff) == SQLITE_BUSY || (rc & 0xff) == SQLITE_LOCKED) {
      throw Error(ErrorKind::kIo, SqliteMessage(db_, path_, rc, sqlite3_errmsg(db_)));
    }
    if (rc != SQLITE_OK) {
      throw Error(rc == SQLITE_NOTADB ? ErrorKind::kInvalidData : ErrorKind::kIo,
                  path_ + ": SQLite cannot prepare '" + sql + "': " + sqlite3_errmsg(db_));
    }
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  void BindInt64(int index, int64_t value) { Check(sqlite3_bind_int64(stmt_, index, value)); }
  void BindDouble(int index, double value) { Check(sqlite3_bind_double(stmt_, index, value)); }
  void BindNull(int index) { Check(sqlite3_bind_null(stmt_, index)); }
  void BindText(int index, const std::string& text) {
    Check(sqlite3_bind_text(stmt_, index, text.data(), static_cast<int>(text.size()),
                            SQLITE_TRANSIENT));
  }
  // A zero-length blob for num_bytes == 0 (not NULL), as COLMAP writes empty matrices.
  void BindBlob(int index, const void* data, size_t num_bytes) {
    COMIC_CHECK(num_bytes <= static_cast<size_t>(std::numeric_limits<int>::max()), kInvalidArgument,
                path_ << ": blob of " << num_bytes << " bytes is too large for SQLite");
    static const char kEmpty = 0;
    Check(sqlite3_bind_blob(stmt_, index, num_bytes == 0 ? &kEmpty : data,
                            static_cast<int>(num_bytes), SQLITE_TRANSIENT));
  }

  // True if a row is available, false when done.
  bool Step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw Error(rc == SQLITE_NOTADB ? ErrorKind::kInvalidData : ErrorKind::kIo,
                SqliteMessage(db_, path_, rc, sqlite3_errmsg(db_)));
  }
  void StepDone() {
    COMIC_CHECK(!Step(), kIo, path_ << ": SQLite statement returned an unexpected row");
  }

  int64_t Int64(int column) const { return sqlite3_column_int64(stmt_, column); }
  double Double(int column) const { return sqlite3_column_double(stmt_, column); }
  bool IsNull(int column) const { return sqlite3_column_type(stmt_, column) == SQLITE_NULL; }
  std::string Text(int column) const {
    const auto* text = sqlite3_column_text(stmt_, column);
    return text == nullptr ? std::string()
                           : std::string(reinterpret_cast<const char*>(text),
                                         static_cast<size_t>(sqlite3_column_bytes(stmt_, column)));
  }
  // Copies a blob column into `out` (resized to `num_bytes` elements of size `element`), checking
  // its size.
  template <typename T>
  void Blob(int column, size_t num_elements, T* out, const char* what) const {
    const void* data = sqlite3_column_blob(stmt_, column);
    const size_t num_bytes = static_cast<size_t>(sqlite3_column_bytes(stmt_, column));
    COMIC_CHECK(num_bytes == num_elements * sizeof(T), kInvalidData,
                path_ << ": " << what << " blob holds " << num_bytes << " bytes, expected "
                      << num_elements * sizeof(T));
    if (num_bytes > 0) std::memcpy(out, data, num_bytes);
  }
  size_t BlobBytes(int column) const {
    return static_cast<size_t>(sqlite3_column_bytes(stmt_, column));
  }

 private:
  void Check(int rc) const {
    COMIC_CHECK(rc == SQLITE_OK, kIo, path_ << ": SQLite bind failed: " << sqlite3_errmsg(db_));
  }

  sqlite3* db_;
  const std::string& path_;
  sqlite3_stmt* stmt_ = nullptr;
};

void CheckDescriptorsMatchKeypoints(sqlite3* db, const std::string& path) {
  Statement statement(db, path,
                      "SELECT keypoints.image_id, keypoints.rows, descriptors.rows FROM keypoints "
                      "JOIN descriptors ON keypoints.image_id = descriptors.image_id WHERE "
                      "keypoints.rows != descriptors.rows ORDER BY keypoints.image_id LIMIT 1");
  COMIC_CHECK(!statement.Step(), kInvalidData,
              path << ": image " << statement.Int64(0) << " has " << statement.Int64(1)
                   << " keypoints but " << statement.Int64(2)
                   << " descriptors (COLMAP's feature_extractor run on a database whose "
                      "keypoints had no descriptors?); COLMAP's matchers would read past its "
                      "keypoints (docs/colmap.md)");
}

void CheckImageId(int64_t image_id) {
  COMIC_CHECK(image_id >= 1 && image_id < kColmapMaxNumImages, kInvalidArgument,
              "COLMAP image id " << image_id << " is outside [1, " << kColmapMaxNumImages << ")");
}

// The blob of a row-major matrix with its rows and cols bound at `index`, `index + 1`, `index + 2`.
template <typename Matrix>
void BindMatrix(Statement* statement, int index, const Matrix& matrix) {
  statement->BindInt64(index, matrix.rows());
  statement->BindInt64(index + 1, matrix.cols());
  statement->BindBlob(index + 2, matrix.data(),
                      static_cast<size_t>(matrix.size()) * sizeof(typename Matrix::Scalar));
}

template <typename Matrix>
Matrix ReadMatrix(const Statement& statement, int index, const char* what) {
  const int64_t rows = statement.Int64(index);
  const int64_t cols = statement.Int64(index + 1);
  COMIC_CHECK(rows >= 0 && cols >= 0, kInvalidData,
              what << " has a negative size " << rows << "x" << cols);
  Matrix matrix(rows, cols);
  statement.Blob(index + 2, static_cast<size_t>(matrix.size()), matrix.data(), what);
  return matrix;
}

using MatchesBlob = Eigen::Matrix<uint32_t, Eigen::Dynamic, 2, Eigen::RowMajor>;

MatchesBlob MatchesToBlob(const ColmapFeatureMatches& matches, bool swap) {
  MatchesBlob blob(static_cast<Eigen::Index>(matches.size()), 2);
  for (size_t i = 0; i < matches.size(); ++i) {
    blob(i, swap ? 1 : 0) = matches[i].point2D_idx1;
    blob(i, swap ? 0 : 1) = matches[i].point2D_idx2;
  }
  return blob;
}

ColmapFeatureMatches MatchesFromStatement(const Statement& statement, int index, bool swap,
                                          const char* what) {
  const int64_t cols = statement.Int64(index + 1);
  COMIC_CHECK(cols == 2 || statement.Int64(index) == 0, kInvalidData,
              what << " have " << cols << " columns, expected 2");
  const Eigen::Matrix<uint32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> blob =
      ReadMatrix<Eigen::Matrix<uint32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          statement, index, what);
  ColmapFeatureMatches matches(static_cast<size_t>(blob.rows()));
  for (Eigen::Index i = 0; i < blob.rows(); ++i) {
    matches[i].point2D_idx1 = blob(i, swap ? 1 : 0);
    matches[i].point2D_idx2 = blob(i, swap ? 0 : 1);
  }
  return matches;
}

// A fixed-size float64 blob (F, E, H row-major; qvec; tvec). Empty or NULL -> `fallback`.
template <int Rows, int Cols>
Eigen::Matrix<double, Rows, Cols> ReadFixedBlob(const Statement& statement, int column,
                                                const Eigen::Matrix<double, Rows, Cols>& fallback,
                                                const char* what) {
  if (statement.IsNull(column) || statement.BlobBytes(column) == 0) return fallback;
  Eigen::Matrix<double, Rows, Cols, Rows == 1 || Cols == 1 ? 0 : Eigen::RowMajor> value;
  statement.Blob(column, Rows * Cols, value.data(), what);
  return value;
}

template <int Rows, int Cols>
void BindFixedBlob(Statement* statement, int index,
                   const Eigen::Matrix<double, Rows, Cols>& value) {
  const Eigen::Matrix<double, Rows, Cols, Rows == 1 || Cols == 1 ? 0 : Eigen::RowMajor> row_major =
      value;
  statement->BindBlob(index, row_major.data(), sizeof(double) * Rows * Cols);
}

ColmapTwoViewGeometry GeometryFromStatement(const Statement& statement, int index, bool invert) {
  ColmapTwoViewGeometry geometry;
  geometry.inlier_matches =
      MatchesFromStatement(statement, index, /*swap=*/false, "two-view geometry inlier matches");
  geometry.config = static_cast<int>(statement.Int64(index + 3));
  const ColmapTwoViewGeometry defaults;
  geometry.F = ReadFixedBlob<3, 3>(statement, index + 4, defaults.F, "two-view geometry F");
  geometry.E = ReadFixedBlob<3, 3>(statement, index + 5, defaults.E, "two-view geometry E");
  geometry.H = ReadFixedBlob<3, 3>(statement, index + 6, defaults.H, "two-view geometry H");
  geometry.qvec =
      ReadFixedBlob<4, 1>(statement, index + 7, defaults.qvec, "two-view geometry qvec");
  geometry.tvec =
      ReadFixedBlob<3, 1>(statement, index + 8, defaults.tvec, "two-view geometry tvec");
  return invert ? geometry.Inverted() : geometry;
}

ColmapDatabaseCamera CameraFromStatement(const Statement& statement) {
  ColmapDatabaseCamera camera;
  camera.camera_id = statement.Int64(0);
  camera.model_id = static_cast<int>(statement.Int64(1));
  camera.width = statement.Int64(2);
  camera.height = statement.Int64(3);
  const size_t num_bytes = statement.BlobBytes(4);
  COMIC_CHECK(num_bytes % sizeof(double) == 0, kInvalidData,
              "camera " << camera.camera_id << ": params blob of " << num_bytes << " bytes");
  camera.params.resize(num_bytes / sizeof(double));
  statement.Blob(4, camera.params.size(), camera.params.data(), "camera params");
  camera.prior_focal_length = statement.Int64(5) != 0;
  return camera;
}

}  // namespace

int64_t ColmapPairId(int64_t image_id1, int64_t image_id2) {
  CheckImageId(image_id1);
  CheckImageId(image_id2);
  const int64_t lo = std::min(image_id1, image_id2);
  const int64_t hi = std::max(image_id1, image_id2);
  return lo * kColmapMaxNumImages + hi;
}

std::pair<int64_t, int64_t> ColmapImagePairFromPairId(int64_t pair_id) {
  COMIC_CHECK(pair_id >= 0, kInvalidArgument, "COLMAP pair id must be >= 0, got " << pair_id);
  const int64_t image_id2 = pair_id % kColmapMaxNumImages;
  const int64_t image_id1 = (pair_id - image_id2) / kColmapMaxNumImages;
  return {image_id1, image_id2};
}

std::string ColmapCameraModelName(int model_id) {
  for (const ModelInfo& model : kModels) {
    if (model.id == model_id) return model.name;
  }
  return "";
}

int ColmapCameraModelIdFromName(const std::string& name) {
  for (const ModelInfo& model : kModels) {
    if (name == model.name) return model.id;
  }
  return -1;
}

int ColmapCameraModelNumParams(int model_id) {
  for (const ModelInfo& model : kModels) {
    if (model.id == model_id) return model.num_params;
  }
  return -1;
}

ColmapTwoViewGeometry ColmapTwoViewGeometry::Inverted() const {
  ColmapTwoViewGeometry inverted = *this;
  inverted.F = F.transpose();
  inverted.E = E.transpose();
  inverted.H = H.isZero() ? H : Eigen::Matrix3d(H.inverse());
  const Eigen::Quaterniond rotation(qvec(0), qvec(1), qvec(2), qvec(3));
  const Eigen::Quaterniond inverse = rotation.conjugate();
  inverted.qvec = Eigen::Vector4d(inverse.w(), inverse.x(), inverse.y(), inverse.z());
  inverted.tvec = -(inverse.normalized().toRotationMatrix() * tvec);
  for (ColmapFeatureMatch& match : inverted.inlier_matches) {
    std::swap(match.point2D_idx1, match.point2D_idx2);
  }
  return inverted;
}

// ---------------------------------------------------------------------------------------------
// ColmapDatabase

ColmapDatabase ColmapDatabase::Open(const std::string& path) {
  COMIC_CHECK(!path.empty(), kInvalidArgument, "COLMAP database path is empty");
  ColmapDatabase database;
  database.path_ = path;
  const int rc = sqlite3_open_v2(path.c_str(), &database.db_,
                                 SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message =
        database.db_ != nullptr ? sqlite3_errmsg(database.db_) : sqlite3_errstr(rc);
    throw Error(ErrorKind::kIo, path + ": SQLite cannot open the database: " + message);
  }
  // Another connection's lock is waited for, then named (io/colmap/sqlite_file.h).
  sqlite3_busy_timeout(database.db_, SqliteFileOptions().busy_timeout_ms);
  // Anything that is not an SQLite file fails here (SQLITE_NOTADB -> kInvalidData).
  int64_t num_tables = 0;
  {
    Statement count(database.db_, database.path_,
                    "SELECT COUNT(*) FROM sqlite_master WHERE type='table'");
    if (count.Step()) num_tables = count.Int64(0);
  }
  database.Execute("PRAGMA foreign_keys=ON");
  if (num_tables == 0) {
    database.CreateTables();
    database.Execute("PRAGMA user_version=" + std::to_string(kColmap38UserVersion));
  }
  database.CheckSchema();
  CheckDescriptorsMatchKeypoints(database.db_, database.path_);
  return database;
}

ColmapDatabase::ColmapDatabase(ColmapDatabase&& other) noexcept
    : db_(other.db_), path_(std::move(other.path_)), has_image_priors_(other.has_image_priors_) {
  other.db_ = nullptr;
}

ColmapDatabase& ColmapDatabase::operator=(ColmapDatabase&& other) noexcept {
  if (this != &other) {
    if (db_ != nullptr) sqlite3_close_v2(db_);
    db_ = other.db_;
    path_ = std::move(other.path_);
    has_image_priors_ = other.has_image_priors_;
    other.db_ = nullptr;
  }
  return *this;
}

ColmapDatabase::~ColmapDatabase() {
  if (db_ != nullptr) sqlite3_close_v2(db_);
}

void ColmapDatabase::Close() {
  if (db_ == nullptr) return;
  const int rc = sqlite3_close(db_);
  COMIC_CHECK(rc == SQLITE_OK, kIo,
              path_ << ": SQLite cannot close the database: " << sqlite3_errstr(rc));
  db_ = nullptr;
}

void ColmapDatabase::Execute(const std::string& sql) const {
  COMIC_CHECK(db_ != nullptr, kInvalidArgument, "COLMAP database is closed");
  char* error = nullptr;
  const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error);
  if (rc != SQLITE_OK) {
    const std::string message = error != nullptr ? error : sqlite3_errstr(rc);
    sqlite3_free(error);
    throw Error(rc == SQLITE_NOTADB ? ErrorKind::kInvalidData : ErrorKind::kIo,
                SqliteMessage(db_, path_, rc, message));
  }
}

void ColmapDatabase::CreateTables() const { Execute(kCreateTablesSql); }

void ColmapDatabase::CheckSchema() {
  const auto columns_of = [&](const std::string& table) {
    std::set<std::string> columns;
    Statement statement(db_, path_, "PRAGMA table_info(" + table + ")");
    while (statement.Step()) columns.insert(statement.Text(1));
    return columns;
  };
  const std::vector<std::pair<std::string, std::vector<std::string>>> required = {
      {"cameras", {"camera_id", "model", "width", "height", "params", "prior_focal_length"}},
      {"images", {"image_id", "name", "camera_id"}},
      {"keypoints", {"image_id", "rows", "cols", "data"}},
      {"descriptors", {"image_id", "rows", "cols", "data"}},
      {"matches", {"pair_id", "rows", "cols", "data"}},
      {"two_view_geometries",
       {"pair_id", "rows", "cols", "data", "config", "F", "E", "H", "qvec", "tvec"}},
  };
  for (const auto& [table, names] : required) {
    const std::set<std::string> columns = columns_of(table);
    COMIC_CHECK(!columns.empty(), kInvalidData,
                path_ << ": not a COLMAP database (no table '" << table << "')");
    for (const std::string& name : names) {
      COMIC_CHECK(columns.count(name) > 0, kInvalidData,
                  path_ << ": not a COLMAP 3.8 database (table '" << table << "' has no column '"
                        << name << "')");
    }
  }
  const std::set<std::string> image_columns = columns_of("images");
  has_image_priors_ = true;
  for (const char* name :
       {"prior_qw", "prior_qx", "prior_qy", "prior_qz", "prior_tx", "prior_ty", "prior_tz"}) {
    has_image_priors_ = has_image_priors_ && image_columns.count(name) > 0;
  }
}

ColmapDatabase::Transaction::Transaction(ColmapDatabase* database) : database_(database) {
  COMIC_CHECK(database_ != nullptr, kInvalidArgument, "Transaction needs a database");
  database_->Execute("BEGIN TRANSACTION");
  open_ = true;
}

ColmapDatabase::Transaction::~Transaction() {
  if (open_ && database_->db_ != nullptr) {
    sqlite3_exec(database_->db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
}

void ColmapDatabase::Transaction::Commit() {
  COMIC_CHECK(open_, kInvalidArgument, "transaction already committed");
  database_->Execute("COMMIT");
  open_ = false;
}

// --- Exists* / Num* ---------------------------------------------------------------------------

namespace {
bool ExistsRow(sqlite3* db, const std::string& path, const std::string& sql, int64_t id) {
  Statement statement(db, path, sql);
  statement.BindInt64(1, id);
  return statement.Step();
}
}  // namespace

bool ColmapDatabase::ExistsCamera(int64_t camera_id) const {
  return ExistsRow(db_, path_, "SELECT 1 FROM cameras WHERE camera_id = ?", camera_id);
}

bool ColmapDatabase::ExistsImage(int64_t image_id) const {
  return ExistsRow(db_, path_, "SELECT 1 FROM images WHERE image_id = ?", image_id);
}

bool ColmapDatabase::ExistsImageWithName(const std::string& name) const {
  Statement statement(db_, path_, "SELECT 1 FROM images WHERE name = ?");
  statement.BindText(1, name);
  return statement.Step();
}

bool ColmapDatabase::ExistsKeypoints(int64_t image_id) const {
  return ExistsRow(db_, path_, "SELECT 1 FROM keypoints WHERE image_id = ?", image_id);
}

bool ColmapDatabase::ExistsDescriptors(int64_t image_id) const {
  return ExistsRow(db_, path_, "SELECT 1 FROM descriptors WHERE image_id = ?", image_id);
}

bool ColmapDatabase::ExistsMatches(int64_t image_id1, int64_t image_id2) const {
  return ExistsRow(db_, path_, "SELECT 1 FROM matches WHERE pair_id = ?",
                   ColmapPairId(image_id1, image_id2));
}

bool ColmapDatabase::ExistsTwoViewGeometry(int64_t image_id1, int64_t image_id2) const {
  return ExistsRow(db_, path_, "SELECT 1 FROM two_view_geometries WHERE pair_id = ?",
                   ColmapPairId(image_id1, image_id2));
}

size_t ColmapDatabase::CountRows(const std::string& table) const {
  Statement statement(db_, path_, "SELECT COUNT(*) FROM " + table);
  return statement.Step() ? static_cast<size_t>(statement.Int64(0)) : 0;
}

size_t ColmapDatabase::SumRows(const std::string& table) const {
  Statement statement(db_, path_, "SELECT SUM(rows) FROM " + table);
  return statement.Step() && !statement.IsNull(0) ? static_cast<size_t>(statement.Int64(0)) : 0;
}

size_t ColmapDatabase::NumCameras() const { return CountRows("cameras"); }
size_t ColmapDatabase::NumImages() const { return CountRows("images"); }
size_t ColmapDatabase::NumKeypoints() const { return SumRows("keypoints"); }
size_t ColmapDatabase::NumDescriptors() const { return SumRows("descriptors"); }
size_t ColmapDatabase::NumMatches() const { return SumRows("matches"); }
size_t ColmapDatabase::NumMatchedImagePairs() const { return CountRows("matches"); }
size_t ColmapDatabase::NumInlierMatches() const { return SumRows("two_view_geometries"); }
size_t ColmapDatabase::NumVerifiedImagePairs() const { return CountRows("two_view_geometries"); }

size_t ColmapDatabase::NumKeypointsForImage(int64_t image_id) const {
  Statement statement(db_, path_, "SELECT rows FROM keypoints WHERE image_id = ?");
  statement.BindInt64(1, image_id);
  return statement.Step() ? static_cast<size_t>(statement.Int64(0)) : 0;
}

// --- Read* ------------------------------------------------------------------------------------

namespace {
constexpr const char* kSelectCameras =
    "SELECT camera_id, model, width, height, params, prior_focal_length FROM cameras";
constexpr const char* kSelectTwoViewGeometries =
    "SELECT pair_id, rows, cols, data, config, F, E, H, qvec, tvec FROM two_view_geometries";
}  // namespace

ColmapDatabaseCamera ColmapDatabase::ReadCamera(int64_t camera_id) const {
  Statement statement(db_, path_, std::string(kSelectCameras) + " WHERE camera_id = ?");
  statement.BindInt64(1, camera_id);
  COMIC_CHECK(statement.Step(), kNotFound, path_ << ": no camera with id " << camera_id);
  return CameraFromStatement(statement);
}

std::vector<ColmapDatabaseCamera> ColmapDatabase::ReadAllCameras() const {
  Statement statement(db_, path_, std::string(kSelectCameras) + " ORDER BY camera_id");
  std::vector<ColmapDatabaseCamera> cameras;
  while (statement.Step()) cameras.push_back(CameraFromStatement(statement));
  return cameras;
}

namespace {
std::string SelectImagesSql(bool has_priors) {
  return has_priors ? "SELECT image_id, name, camera_id, prior_qw, prior_qx, prior_qy, prior_qz, "
                      "prior_tx, prior_ty, prior_tz FROM images"
                    : "SELECT image_id, name, camera_id FROM images";
}

ColmapDatabaseImage ImageFromStatement(const Statement& statement, bool has_priors) {
  ColmapDatabaseImage image;
  image.image_id = statement.Int64(0);
  image.name = statement.Text(1);
  image.camera_id = statement.Int64(2);
  if (!has_priors) return image;
  // A prior is present only if all of its columns are (COLMAP writes NULL, or NaN which SQLite
  // stores as NULL, for an unknown prior).
  bool has_q = true;
  bool has_t = true;
  for (int c = 3; c < 7; ++c) has_q = has_q && !statement.IsNull(c);
  for (int c = 7; c < 10; ++c) has_t = has_t && !statement.IsNull(c);
  if (has_q) {
    image.prior_qvec = Eigen::Vector4d(statement.Double(3), statement.Double(4),
                                       statement.Double(5), statement.Double(6));
  }
  if (has_t) {
    image.prior_tvec =
        Eigen::Vector3d(statement.Double(7), statement.Double(8), statement.Double(9));
  }
  return image;
}
}  // namespace

ColmapDatabaseImage ColmapDatabase::ReadImage(int64_t image_id) const {
  Statement statement(db_, path_, SelectImagesSql(has_image_priors_) + " WHERE image_id = ?");
  statement.BindInt64(1, image_id);
  COMIC_CHECK(statement.Step(), kNotFound, path_ << ": no image with id " << image_id);
  return ImageFromStatement(statement, has_image_priors_);
}

std::vector<ColmapDatabaseImage> ColmapDatabase::ReadAllImages() const {
  Statement statement(db_, path_, SelectImagesSql(has_image_priors_) + " ORDER BY image_id");
  std::vector<ColmapDatabaseImage> images;
  while (statement.Step()) images.push_back(ImageFromStatement(statement, has_image_priors_));
  return images;
}

ColmapKeypoints ColmapDatabase::ReadKeypoints(int64_t image_id) const {
  Statement statement(db_, path_, "SELECT rows, cols, data FROM keypoints WHERE image_id = ?");
  statement.BindInt64(1, image_id);
  COMIC_CHECK(statement.Step(), kNotFound, path_ << ": no keypoints for image " << image_id);
  return ReadMatrix<ColmapKeypoints>(statement, 0, "keypoints");
}

ColmapDescriptors ColmapDatabase::ReadDescriptors(int64_t image_id) const {
  Statement statement(db_, path_, "SELECT rows, cols, data FROM descriptors WHERE image_id = ?");
  statement.BindInt64(1, image_id);
  COMIC_CHECK(statement.Step(), kNotFound, path_ << ": no descriptors for image " << image_id);
  return ReadMatrix<ColmapDescriptors>(statement, 0, "descriptors");
}

ColmapFeatureMatches ColmapDatabase::ReadMatches(int64_t image_id1, int64_t image_id2) const {
  Statement statement(db_, path_, "SELECT rows, cols, data FROM matches WHERE pair_id = ?");
  statement.BindInt64(1, ColmapPairId(image_id1, image_id2));
  COMIC_CHECK(statement.Step(), kNotFound,
              path_ << ": no matches for images " << image_id1 << " and " << image_id2);
  return MatchesFromStatement(statement, 0, /*swap=*/image_id1 > image_id2, "matches");
}

std::vector<std::pair<int64_t, ColmapFeatureMatches>> ColmapDatabase::ReadAllMatches() const {
  Statement statement(db_, path_, "SELECT pair_id, rows, cols, data FROM matches ORDER BY pair_id");
  std::vector<std::pair<int64_t, ColmapFeatureMatches>> all;
  while (statement.Step()) {
    all.emplace_back(statement.Int64(0), MatchesFromStatement(statement, 1, false, "matches"));
  }
  return all;
}

ColmapTwoViewGeometry ColmapDatabase::ReadTwoViewGeometry(int64_t image_id1,
                                                          int64_t image_id2) const {
  Statement statement(db_, path_, std::string(kSelectTwoViewGeometries) + " WHERE pair_id = ?");
  statement.BindInt64(1, ColmapPairId(image_id1, image_id2));
  COMIC_CHECK(statement.Step(), kNotFound,
              path_ << ": no two-view geometry for images " << image_id1 << " and " << image_id2);
  return GeometryFromStatement(statement, 1, /*invert=*/image_id1 > image_id2);
}

std::vector<std::pair<int64_t, ColmapTwoViewGeometry>> ColmapDatabase::ReadAllTwoViewGeometries()
    const {
  Statement statement(db_, path_, std::string(kSelectTwoViewGeometries) + " ORDER BY pair_id");
  std::vector<std::pair<int64_t, ColmapTwoViewGeometry>> all;
  while (statement.Step()) {
    all.emplace_back(statement.Int64(0), GeometryFromStatement(statement, 1, false));
  }
  return all;
}

// --- Write* -----------------------------------------------------------------------------------

int64_t ColmapDatabase::WriteCamera(const ColmapDatabaseCamera& camera) {
  const int num_params = ColmapCameraModelNumParams(camera.model_id);
  COMIC_CHECK(num_params >= 0, kInvalidArgument,
              "unknown COLMAP camera model id " << camera.model_id);
  COMIC_CHECK(static_cast<int>(camera.params.size()) == num_params, kInvalidArgument,
              "COLMAP camera model " << ColmapCameraModelName(camera.model_id) << " takes "
                                     << num_params << " parameters, got " << camera.params.size());
  COMIC_CHECK(camera.width > 0 && camera.height > 0, kInvalidArgument,
              "camera size must be positive, got " << camera.width << "x" << camera.height);
  COMIC_CHECK(camera.camera_id >= 0, kInvalidArgument,
              "camera id must be >= 1 (or 0 for the next free id), got " << camera.camera_id);
  COMIC_CHECK(camera.camera_id == 0 || !ExistsCamera(camera.camera_id), kInvalidArgument,
              path_ << ": camera " << camera.camera_id << " exists already");
  Statement statement(db_, path_,
                      "INSERT INTO cameras(camera_id, model, width, height, params, "
                      "prior_focal_length) VALUES(?, ?, ?, ?, ?, ?)");
  if (camera.camera_id == 0) {
    statement.BindNull(1);
  } else {
    statement.BindInt64(1, camera.camera_id);
  }
  statement.BindInt64(2, camera.model_id);
  statement.BindInt64(3, camera.width);
  statement.BindInt64(4, camera.height);
  statement.BindBlob(5, camera.params.data(), camera.params.size() * sizeof(double));
  statement.BindInt64(6, camera.prior_focal_length ? 1 : 0);
  statement.StepDone();
  return sqlite3_last_insert_rowid(db_);
}

int64_t ColmapDatabase::WriteImage(const ColmapDatabaseImage& image) {
  COMIC_CHECK(!image.name.empty(), kInvalidArgument, "COLMAP image name is empty");
  if (image.image_id != 0) CheckImageId(image.image_id);
  COMIC_CHECK(image.image_id == 0 || !ExistsImage(image.image_id), kInvalidArgument,
              path_ << ": image " << image.image_id << " exists already");
  COMIC_CHECK(!ExistsImageWithName(image.name), kInvalidArgument,
              path_ << ": an image named '" << image.name << "' exists already");
  COMIC_CHECK(ExistsCamera(image.camera_id), kInvalidArgument,
              path_ << ": image '" << image.name << "' names camera " << image.camera_id
                    << ", which does not exist");
  std::string sql = "INSERT INTO images(image_id, name, camera_id";
  sql += has_image_priors_
             ? ", prior_qw, prior_qx, prior_qy, prior_qz, prior_tx, prior_ty, prior_tz) "
               "VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?)"
             : ") VALUES(?, ?, ?)";
  Statement statement(db_, path_, sql);
  if (image.image_id == 0) {
    statement.BindNull(1);
  } else {
    statement.BindInt64(1, image.image_id);
  }
  statement.BindText(2, image.name);
  statement.BindInt64(3, image.camera_id);
  if (has_image_priors_) {
    for (int k = 0; k < 4; ++k) {
      if (image.prior_qvec) {
        statement.BindDouble(4 + k, (*image.prior_qvec)(k));
      } else {
        statement.BindNull(4 + k);
      }
    }
    for (int k = 0; k < 3; ++k) {
      if (image.prior_tvec) {
        statement.BindDouble(8 + k, (*image.prior_tvec)(k));
      } else {
        statement.BindNull(8 + k);
      }
    }
  }
  statement.StepDone();
  return sqlite3_last_insert_rowid(db_);
}

void ColmapDatabase::WriteKeypoints(int64_t image_id, const ColmapKeypoints& keypoints) {
  COMIC_CHECK(ExistsImage(image_id), kInvalidArgument,
              path_ << ": keypoints for image " << image_id << ", which does not exist");
  COMIC_CHECK(keypoints.cols() == 2 || keypoints.cols() == 4 || keypoints.cols() == 6,
              kInvalidArgument,
              "COLMAP keypoints have 2, 4 or 6 columns, got " << keypoints.cols());
  COMIC_CHECK(!ExistsKeypoints(image_id), kInvalidArgument,
              path_ << ": keypoints of image " << image_id << " exist already");
  Statement statement(db_, path_,
                      "INSERT INTO keypoints(image_id, rows, cols, data) "
                      "VALUES(?, ?, ?, ?)");
  statement.BindInt64(1, image_id);
  BindMatrix(&statement, 2, keypoints);
  statement.StepDone();
}

void ColmapDatabase::WriteDescriptors(int64_t image_id, const ColmapDescriptors& descriptors) {
  COMIC_CHECK(ExistsImage(image_id), kInvalidArgument,
              path_ << ": descriptors for image " << image_id << ", which does not exist");
  COMIC_CHECK(!ExistsDescriptors(image_id), kInvalidArgument,
              path_ << ": descriptors of image " << image_id << " exist already");
  COMIC_CHECK(!ExistsKeypoints(image_id) ||
                  NumKeypointsForImage(image_id) == static_cast<size_t>(descriptors.rows()),
              kInvalidArgument,
              path_ << ": image " << image_id << " has " << NumKeypointsForImage(image_id)
                    << " keypoints but " << descriptors.rows() << " descriptors");
  Statement statement(db_, path_,
                      "INSERT INTO descriptors(image_id, rows, cols, data) "
                      "VALUES(?, ?, ?, ?)");
  statement.BindInt64(1, image_id);
  BindMatrix(&statement, 2, descriptors);
  statement.StepDone();
}

void ColmapDatabase::CheckMatchIndices(int64_t image_id1, int64_t image_id2,
                                       const ColmapFeatureMatches& matches) const {
  COMIC_CHECK(image_id1 != image_id2, kInvalidArgument,
              "matches of image " << image_id1 << " with itself");
  for (const int64_t id : {image_id1, image_id2}) {
    COMIC_CHECK(ExistsImage(id), kInvalidArgument,
                path_ << ": matches name image " << id << ", which does not exist");
  }
  const auto check = [&](int64_t image_id, auto index_of) {
    if (!ExistsKeypoints(image_id)) return;
    const size_t num_keypoints = NumKeypointsForImage(image_id);
    for (const ColmapFeatureMatch& match : matches) {
      COMIC_CHECK(index_of(match) < num_keypoints, kInvalidArgument,
                  path_ << ": a match names keypoint " << index_of(match) << " of image "
                        << image_id << ", which has " << num_keypoints);
    }
  };
  check(image_id1, [](const ColmapFeatureMatch& m) { return size_t{m.point2D_idx1}; });
  check(image_id2, [](const ColmapFeatureMatch& m) { return size_t{m.point2D_idx2}; });
}

void ColmapDatabase::WriteMatches(int64_t image_id1, int64_t image_id2,
                                  const ColmapFeatureMatches& matches) {
  const int64_t pair_id = ColmapPairId(image_id1, image_id2);
  CheckMatchIndices(image_id1, image_id2, matches);
  COMIC_CHECK(
      !ExistsMatches(image_id1, image_id2), kInvalidArgument,
      path_ << ": matches of images " << image_id1 << " and " << image_id2 << " exist already");
  Statement statement(db_, path_,
                      "INSERT INTO matches(pair_id, rows, cols, data) "
                      "VALUES(?, ?, ?, ?)");
  statement.BindInt64(1, pair_id);
  BindMatrix(&statement, 2, MatchesToBlob(matches, /*swap=*/image_id1 > image_id2));
  statement.StepDone();
}

void ColmapDatabase::WriteTwoViewGeometry(int64_t image_id1, int64_t image_id2,
                                          const ColmapTwoViewGeometry& geometry) {
  const int64_t pair_id = ColmapPairId(image_id1, image_id2);
  CheckMatchIndices(image_id1, image_id2, geometry.inlier_matches);
  COMIC_CHECK(!ExistsTwoViewGeometry(image_id1, image_id2), kInvalidArgument,
              path_ << ": two-view geometry of images " << image_id1 << " and " << image_id2
                    << " exists already");
  // Stored from the smaller id to the larger, as COLMAP does.
  const ColmapTwoViewGeometry stored = image_id1 > image_id2 ? geometry.Inverted() : geometry;
  Statement statement(db_, path_,
                      "INSERT INTO two_view_geometries(pair_id, rows, cols, data, config, F, E, "
                      "H, qvec, tvec) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  statement.BindInt64(1, pair_id);
  BindMatrix(&statement, 2, MatchesToBlob(stored.inlier_matches, /*swap=*/false));
  statement.BindInt64(5, stored.config);
  BindFixedBlob<3, 3>(&statement, 6, stored.F);
  BindFixedBlob<3, 3>(&statement, 7, stored.E);
  BindFixedBlob<3, 3>(&statement, 8, stored.H);
  BindFixedBlob<4, 1>(&statement, 9, stored.qvec);
  BindFixedBlob<3, 1>(&statement, 10, stored.tvec);
  statement.StepDone();
}

}  // namespace comic::io
