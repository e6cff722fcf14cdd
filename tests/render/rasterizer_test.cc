// Exactness of render/rasterizer.h: the corners of a rendered card, found from where its
// anti-aliased edges cross, lie within 0.05 px of the projections of its 3-D corners (pinhole,
// and through a distorted lens projected by sfm's camera model); depth at every pixel equals the
// plane's analytic depth; the view is the same on every call.
#include "render/rasterizer.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <iostream>

#include "sfm/camera_model.h"

namespace comic::render {
namespace {

constexpr float kCard = 230.0f;     // the card's grey level
constexpr float kBackdrop = 20.0f;  // the backdrop's

// A bright card tilted in front of a dark backdrop, seen by a camera at the origin looking along
// +z (the identity pose; camera y down is world y here).
Scene CardScene(const Eigen::Vector3d& origin, const Eigen::Vector3d& s_axis,
                const Eigen::Vector3d& t_axis) {
  Scene scene;
  scene.textures.push_back(Texture::Solid({kCard, kCard, kCard}, "card"));
  scene.textures.push_back(Texture::Solid({kBackdrop, kBackdrop, kBackdrop}, "backdrop"));
  Piece backdrop;
  backdrop.origin = {-60.0, -60.0, 30.0};
  backdrop.s_axis = {120.0, 0.0, 0.0};
  backdrop.t_axis = {0.0, 120.0, 0.0};
  backdrop.texture = 1;
  backdrop.object_id = scene.AddObject("background", false);
  Piece card;
  card.origin = origin;
  card.s_axis = s_axis;
  card.t_axis = t_axis;
  card.texture = 0;
  card.object_id = scene.AddObject("card", true);
  scene.pieces = {backdrop, card};
  return scene;
}

Scene TiltedCard() { return CardScene({-1.2, -0.8, 6.0}, {2.3, 0.25, 0.8}, {0.15, 1.6, -0.5}); }

std::array<Eigen::Vector3d, 4> Corners(const Piece& piece) {
  return {piece.PointAt(0, 0), piece.PointAt(1, 0), piece.PointAt(1, 1), piece.PointAt(0, 1)};
}

double Coverage(const cv::Mat& color, int x, int y) {
  return (color.at<cv::Vec3f>(y, x)[0] - kBackdrop) / (kCard - kBackdrop);
}

// Where the edge crosses row y (vertical = true) or column x, from the sum of coverage across a
// window of +-5 px around `guess`: the card's area in that row equals the distance from the edge
// to the window's far end, whatever the edge's slope.
double Crossing(const cv::Mat& color, bool vertical, int line, double guess) {
  const int lo = static_cast<int>(std::lround(guess)) - 5;
  const int hi = lo + 10;
  double sum = 0.0;
  for (int k = lo; k <= hi; ++k)
    sum += vertical ? Coverage(color, k, line) : Coverage(color, line, k);
  const double at_hi = vertical ? Coverage(color, hi, line) : Coverage(color, line, hi);
  return at_hi > 0.5 ? hi + 0.5 - sum : lo - 0.5 + sum;
}

// Polynomial fit (degree 1 or 2) of the crossing along an edge: coordinate = p(other).
struct EdgeFit {
  bool vertical = true;  // x as a function of y
  Eigen::Vector3d coefficients = Eigen::Vector3d::Zero();
  double At(double t) const {
    return coefficients[0] + coefficients[1] * t + coefficients[2] * t * t;
  }
};

// Measures the edge through `points` (the predicted edge, sampled densely, first point at the
// corner): crossings at every row or column between fractions `from` and `to` of its length.
EdgeFit MeasureEdge(const cv::Mat& color, const std::vector<Eigen::Vector2d>& points, double from,
                    double to, int degree) {
  const Eigen::Vector2d d = points.back() - points.front();
  EdgeFit fit;
  fit.vertical = std::abs(d.y()) > std::abs(d.x());
  std::vector<double> ts, values;
  const int n = static_cast<int>(points.size());
  for (int k = static_cast<int>(from * (n - 1)); k <= static_cast<int>(to * (n - 1)); ++k) {
    // One measurement per row (or column) the predicted edge passes.
    const double line_coordinate = fit.vertical ? points[k].y() : points[k].x();
    const int line = static_cast<int>(std::lround(line_coordinate));
    if (!ts.empty() && std::lround(ts.back()) == line) continue;
    const double guess = fit.vertical ? points[k].x() : points[k].y();
    ts.push_back(line);
    values.push_back(Crossing(color, fit.vertical, line, guess));
  }
  Eigen::MatrixXd a(ts.size(), degree + 1);
  Eigen::VectorXd b(ts.size());
  for (size_t i = 0; i < ts.size(); ++i) {
    for (int p = 0; p <= degree; ++p) a(i, p) = std::pow(ts[i], p);
    b(i) = values[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  for (int p = 0; p <= degree; ++p) fit.coefficients[p] = c[p];
  return fit;
}

// Where a near-vertical and a near-horizontal fit cross (fixed-point iteration).
Eigen::Vector2d Intersect(const EdgeFit& a, const EdgeFit& b, const Eigen::Vector2d& start) {
  EXPECT_NE(a.vertical, b.vertical);
  const EdgeFit& vertical = a.vertical ? a : b;
  const EdgeFit& horizontal = a.vertical ? b : a;
  Eigen::Vector2d p = start;
  for (int i = 0; i < 50; ++i) {
    p.y() = horizontal.At(p.x());
    p.x() = vertical.At(p.y());
  }
  return p;
}

// The projected edge from corner a to corner b, sampled every 0.25 px or so.
std::vector<Eigen::Vector2d> ProjectEdge(const Lens& lens, const Eigen::Vector3d& a,
                                         const Eigen::Vector3d& b) {
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k <= 2000; ++k) {
    const Eigen::Vector3d p = a + (b - a) * (k / 2000.0);
    points.push_back(lens.PixelFromNormalized({p.x() / p.z(), p.y() / p.z()}));
  }
  return points;
}

// Measures the card's four corners in `color` and returns the largest distance to `expected`.
double WorstCornerError(const Lens& lens, const cv::Mat& color, const Piece& card,
                        const std::array<Eigen::Vector2d, 4>& expected, double from, double to,
                        int degree) {
  const std::array<Eigen::Vector3d, 4> corners = Corners(card);
  double worst = 0.0;
  for (int k = 0; k < 4; ++k) {
    // The two edges leaving corner k, each measured from near the corner outwards.
    const EdgeFit next =
        MeasureEdge(color, ProjectEdge(lens, corners[k], corners[(k + 1) % 4]), from, to, degree);
    const EdgeFit previous =
        MeasureEdge(color, ProjectEdge(lens, corners[k], corners[(k + 3) % 4]), from, to, degree);
    const Eigen::Vector2d measured = Intersect(next, previous, expected[k]);
    worst = std::max(worst, (measured - expected[k]).norm());
  }
  return worst;
}

TEST(Rasterizer, CornersOfAPinholeRenderLieWithinFiveHundredthsOfAPixel) {
  const Scene scene = TiltedCard();
  Lens lens;
  for (int supersampling : {3, 4}) {
    RasterOptions options;
    options.supersampling = supersampling;
    const RenderedView view = Rasterizer(lens, options).Render(scene, Pose());
    std::array<Eigen::Vector2d, 4> expected;
    const std::array<Eigen::Vector3d, 4> corners = Corners(scene.pieces[1]);
    for (int k = 0; k < 4; ++k) {
      expected[k] = {lens.fx * corners[k].x() / corners[k].z() + lens.cx,
                     lens.fy * corners[k].y() / corners[k].z() + lens.cy};
    }
    // Straight edges: lines fitted over the middle of each edge (15 % to 85 %).
    const double worst =
        WorstCornerError(lens, view.color, scene.pieces[1], expected, 0.15, 0.85, 1);
    EXPECT_LT(worst, 0.05) << "supersampling " << supersampling;
    RecordProperty("worst_corner_error_px_ss" + std::to_string(supersampling),
                   std::to_string(worst));
    std::cout << "pinhole, supersampling " << supersampling << ": worst corner error " << worst
              << " px" << std::endl;
  }
}

TEST(Rasterizer, CornersThroughADistortedLensAreWhereSfmsCameraModelProjects) {
  const Scene scene = TiltedCard();
  Lens lens;
  lens.k1 = -0.15;
  lens.k2 = 0.04;
  lens.p1 = 0.002;
  lens.p2 = -0.001;
  const RenderedView view = Rasterizer(lens, RasterOptions()).Render(scene, Pose());
  const double params[8] = {lens.fx, lens.fy, lens.cx, lens.cy, lens.k1, lens.k2, lens.p1, lens.p2};
  std::array<Eigen::Vector2d, 4> expected;
  const std::array<Eigen::Vector3d, 4> corners = Corners(scene.pieces[1]);
  for (int k = 0; k < 4; ++k) {
    sfm::ImageFromNormalized(sfm::CameraModelId::kOpenCV, params, corners[k].x() / corners[k].z(),
                             corners[k].y() / corners[k].z(), &expected[k].x(), &expected[k].y());
  }
  // Curved edges: quadratics fitted near each corner (3 % to 35 % of the edge).
  const double worst = WorstCornerError(lens, view.color, scene.pieces[1], expected, 0.03, 0.35, 2);
  EXPECT_LT(worst, 0.05);
  std::cout << "distorted lens: worst corner error " << worst << " px" << std::endl;
}

TEST(Rasterizer, DepthIsThePlanesAnalyticDepthAtEveryPixelCentre) {
  const Scene scene = TiltedCard();
  for (bool distorted : {false, true}) {
    Lens lens;
    if (distorted) lens.k1 = -0.1;
    const Rasterizer rasterizer(lens, RasterOptions());
    const RenderedView view = rasterizer.Render(scene, Pose());
    int card_pixels = 0;
    for (int y = 0; y < lens.height; ++y) {
      for (int x = 0; x < lens.width; ++x) {
        const int p = view.piece.at<int>(y, x);
        ASSERT_GE(p, 0);
        const Piece& piece = scene.pieces[p];
        // The ray of the pixel centre (undistorted by the lens) meets the piece's plane at z.
        const Eigen::Vector2d uv = lens.NormalizedFromPixel({x, y});
        const Eigen::Vector3d ray(uv.x(), uv.y(), 1.0);
        const Eigen::Vector3d normal = piece.s_axis.cross(piece.t_axis);
        const double z = normal.dot(piece.origin) / normal.dot(ray);
        EXPECT_NEAR(view.depth.at<float>(y, x), z, 2e-6 * z) << x << ", " << y;
        card_pixels += p == 1;
      }
    }
    EXPECT_GT(card_pixels, 20000);
  }
}

TEST(Rasterizer, PixelsInsideAndOutsideTheCardAreExactlyItsColours) {
  const Scene scene = TiltedCard();
  const Lens lens;
  const RenderedView view = Rasterizer(lens, RasterOptions()).Render(scene, Pose());
  double perimeter = 0.0;
  const std::array<Eigen::Vector3d, 4> corners = Corners(scene.pieces[1]);
  for (int k = 0; k < 4; ++k) {
    const std::vector<Eigen::Vector2d> edge = ProjectEdge(lens, corners[k], corners[(k + 1) % 4]);
    perimeter += (edge.back() - edge.front()).norm();
  }
  int mixed = 0;
  for (int y = 0; y < view.color.rows; ++y) {
    for (int x = 0; x < view.color.cols; ++x) {
      const float value = view.color.at<cv::Vec3f>(y, x)[0];
      EXPECT_GE(value, kBackdrop - 1e-3f);
      EXPECT_LE(value, kCard + 1e-3f);
      mixed += value > kBackdrop + 1e-3f && value < kCard - 1e-3f;
    }
  }
  // Anti-aliased: about one pixel per pixel of outline mixes the two (a slanted edge crosses
  // between one and two pixels per unit length; a few land exactly on a sample boundary).
  EXPECT_GT(mixed, 0.7 * perimeter);
  EXPECT_LT(mixed, 2.0 * perimeter);
}

TEST(Rasterizer, SameSceneAndPoseGiveTheSameViewAndGeometryAgreesWithRender) {
  const Scene scene = TiltedCard();
  const Rasterizer rasterizer{Lens(), RasterOptions()};
  const RenderedView a = rasterizer.Render(scene, Pose());
  const RenderedView b = rasterizer.Render(scene, Pose());
  EXPECT_EQ(cv::norm(a.color, b.color, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth, b.depth, cv::NORM_INF), 0.0);
  const RenderedView geometry = rasterizer.RenderGeometry(scene, Pose());
  EXPECT_EQ(cv::norm(a.piece, geometry.piece, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth, geometry.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.color, rasterizer.RenderColor(scene, Pose()), cv::NORM_INF), 0.0);
}

TEST(Rasterizer, NothingBehindTheCameraOrNearerThanTheNearPlaneIsDrawn) {
  // A card that straddles the camera plane: only its part in front is drawn, and a card wholly
  // behind the camera is not drawn at all.
  Scene scene = CardScene({-2.0, 0.5, -3.0}, {4.0, 0.0, 0.0}, {0.0, 0.0, 8.0});
  Piece behind = scene.pieces[1];
  behind.origin = {-1.0, -1.0, -5.0};
  behind.s_axis = {2.0, 0.0, 0.0};
  behind.t_axis = {0.0, 2.0, 0.0};
  scene.pieces.push_back(behind);
  const RenderedView view = Rasterizer(Lens(), RasterOptions()).Render(scene, Pose());
  int card = 0;
  for (int y = 0; y < view.piece.rows; ++y) {
    for (int x = 0; x < view.piece.cols; ++x) {
      const int p = view.piece.at<int>(y, x);
      EXPECT_NE(p, 2);
      if (p == 1) {
        ++card;
        EXPECT_GE(view.depth.at<float>(y, x), RasterOptions().near_plane);
      }
    }
  }
  EXPECT_GT(card, 1000);  // the floor-like card in front is seen
}

}  // namespace
}  // namespace comic::render
