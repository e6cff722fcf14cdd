#include "render/rasterizer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core/hal/intrin.hpp>

#include "io/core/error.h"

namespace comic::render {

// Samples per tile side for the distorted lens's coarse culling.
constexpr int kTile = 32;
// Pixel rows rasterised and shaded together (their samples stay in the cache).
constexpr int kBandRows = 8;

struct Rasterizer::PieceView {
  bool visible = false;
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();  // (s/z, t/z, 1/z) = g (u, v, 1)
  // Bounds of the visible part (clipped at the near plane) on the normalised plane z = 1.
  double u_min = 0.0, u_max = 0.0, v_min = 0.0, v_max = 0.0;
};

namespace {

// Sutherland–Hodgman: the part of a convex polygon (camera coordinates) with z >= near.
std::vector<Eigen::Vector3d> ClipNear(const std::vector<Eigen::Vector3d>& polygon, double near) {
  std::vector<Eigen::Vector3d> out;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector3d& a = polygon[k];
    const Eigen::Vector3d& b = polygon[(k + 1) % polygon.size()];
    const bool a_in = a.z() >= near;
    const bool b_in = b.z() >= near;
    if (a_in) out.push_back(a);
    if (a_in != b_in) out.push_back(a + (b - a) * ((near - a.z()) / (b.z() - a.z())));
  }
  return out;
}

// Restricts [lo, hi] to the indices i with alpha + beta * i >= 0.
void Constrain(double alpha, double beta, double* lo, double* hi) {
  if (beta > 0.0) {
    *lo = std::max(*lo, std::ceil(-alpha / beta));
  } else if (beta < 0.0) {
    *hi = std::min(*hi, std::floor(-alpha / beta));
  } else if (alpha < 0.0) {
    *hi = *lo - 1.0;
  }
}

// The depth test along one span of a row for a solid piece: sample i has inverse depth
// q0 + i·dq (in float, the same in the vector and the scalar loop) and replaces what is there if
// nearer. Four samples at a time with OpenCV's universal intrinsics.
void DepthTestSpan(float q0, float dq, int piece, int i0, int i1, float* depth, int* pieces) {
  int i = i0;
#if CV_SIMD128
  const cv::v_float32x4 v_q0 = cv::v_setall_f32(q0);
  const cv::v_float32x4 v_dq = cv::v_setall_f32(dq);
  const cv::v_int32x4 v_piece = cv::v_setall_s32(piece);
  for (; i + 3 <= i1; i += 4) {
    const cv::v_float32x4 index = cv::v_cvt_f32(cv::v_int32x4(i, i + 1, i + 2, i + 3));
    const cv::v_float32x4 q = v_q0 + index * v_dq;
    const cv::v_float32x4 old_depth = cv::v_load(depth + i);
    const cv::v_float32x4 nearer = q > old_depth;
    cv::v_store(depth + i, cv::v_select(nearer, q, old_depth));
    cv::v_store(pieces + i,
                cv::v_select(cv::v_reinterpret_as_s32(nearer), v_piece, cv::v_load(pieces + i)));
  }
#endif
  for (; i <= i1; ++i) {
    const float q = q0 + static_cast<float>(i) * dq;
    if (q > depth[i]) {
      depth[i] = q;
      pieces[i] = piece;
    }
  }
}

}  // namespace

void RasterOptions::Check() const {
  COMIC_CHECK(supersampling >= 1 && supersampling <= 8, kInvalidArgument,
              "supersampling must be in 1..8, got " << supersampling);
  COMIC_CHECK(near_plane > 0 && std::isfinite(near_plane), kInvalidArgument,
              "near plane must be > 0, got " << near_plane);
}

Rasterizer::Rasterizer(const Lens& lens, const RasterOptions& options)
    : lens_(lens), options_(options) {
  lens_.Check();
  options_.Check();
  samples_ = MakeGrid(options_.supersampling);
  centres_ = MakeGrid(1);
}

Rasterizer::SampleGrid Rasterizer::MakeGrid(int per_pixel) const {
  SampleGrid grid;
  grid.cols = lens_.width * per_pixel;
  grid.rows = lens_.height * per_pixel;
  grid.step = 1.0 / per_pixel;
  grid.offset = 0.5 * grid.step - 0.5;
  if (!lens_.HasDistortion()) return grid;
  grid.rays.create(grid.rows, grid.cols, CV_32FC2);
  for (int j = 0; j < grid.rows; ++j) {
    cv::Vec2f* row = grid.rays.ptr<cv::Vec2f>(j);
    // Newton from the previous sample's ray: a step away, so two or three iterations.
    const double v = (grid.offset + j * grid.step - lens_.cy) / lens_.fy;
    Eigen::Vector2d uv = lens_.NormalizedFromPixel({grid.offset, grid.offset + j * grid.step});
    for (int i = 0; i < grid.cols; ++i) {
      const Eigen::Vector2d distorted((grid.offset + i * grid.step - lens_.cx) / lens_.fx, v);
      uv = lens_.Undistort(distorted, uv);
      row[i] = cv::Vec2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
    }
  }
  const int tiles_x = (grid.cols + kTile - 1) / kTile;
  const int tiles_y = (grid.rows + kTile - 1) / kTile;
  grid.tile_ray_bounds.create(tiles_y, tiles_x, CV_32FC4);
  for (int ty = 0; ty < tiles_y; ++ty) {
    for (int tx = 0; tx < tiles_x; ++tx) {
      cv::Vec4f bounds(std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                       std::numeric_limits<float>::max(), -std::numeric_limits<float>::max());
      for (int j = ty * kTile; j < std::min(grid.rows, (ty + 1) * kTile); ++j) {
        for (int i = tx * kTile; i < std::min(grid.cols, (tx + 1) * kTile); ++i) {
          const cv::Vec2f uv = grid.rays.at<cv::Vec2f>(j, i);
          bounds = cv::Vec4f(std::min(bounds[0], uv[0]), std::max(bounds[1], uv[0]),
                             std::min(bounds[2], uv[1]), std::max(bounds[3], uv[1]));
        }
      }
      grid.tile_ray_bounds.at<cv::Vec4f>(ty, tx) = bounds;
    }
  }
  return grid;
}

std::vector<Rasterizer::PieceView> Rasterizer::ViewPieces(const Scene& scene,
                                                          const Pose& pose) const {
  std::vector<PieceView> views(scene.pieces.size());
  for (size_t p = 0; p < scene.pieces.size(); ++p) {
    const Piece& piece = scene.pieces[p];
    Eigen::Matrix3d m;
    m.col(0) = pose.rotation * piece.s_axis;
    m.col(1) = pose.rotation * piece.t_axis;
    m.col(2) = pose.CamFromWorld(piece.origin);
    // A plane through the camera centre is seen edge-on: nothing of it is visible.
    const double scale = m.col(0).norm() * m.col(1).norm() * m.col(2).norm();
    if (!(std::abs(m.determinant()) > 1e-9 * scale)) continue;
    const std::vector<Eigen::Vector3d> clipped = ClipNear(
        {m.col(2), m.col(2) + m.col(0), m.col(2) + m.col(0) + m.col(1), m.col(2) + m.col(1)},
        options_.near_plane);
    if (clipped.empty()) continue;
    PieceView& view = views[p];
    view.u_min = view.v_min = std::numeric_limits<double>::max();
    view.u_max = view.v_max = -std::numeric_limits<double>::max();
    for (const Eigen::Vector3d& c : clipped) {
      view.u_min = std::min(view.u_min, c.x() / c.z());
      view.u_max = std::max(view.u_max, c.x() / c.z());
      view.v_min = std::min(view.v_min, c.y() / c.z());
      view.v_max = std::max(view.v_max, c.y() / c.z());
    }
    view.g = m.inverse();
    view.visible = true;
  }
  return views;
}

void Rasterizer::RasterizeRows(const Scene& scene, const std::vector<PieceView>& views,
                               const SampleGrid& grid, int row_begin, int row_end,
                               ZBuffer* band) const {
  ZBuffer& z = *band;
  z.inverse_depth.create(row_end - row_begin, grid.cols, CV_32F);
  z.inverse_depth.setTo(0.0f);
  z.piece.create(row_end - row_begin, grid.cols, CV_32S);
  z.piece.setTo(-1);
  const double max_inverse_depth = 1.0 / options_.near_plane;
  // Draws sample (i, j) of piece p if it is nearer than what is there; (a1, a2, q) = g (u, v, 1).
  const auto draw = [&](int p, const AlphaMask* mask, int j, int i, double a1, double a2,
                        double q) {
    float& depth = z.inverse_depth.at<float>(j - row_begin, i);
    if (!(static_cast<float>(q) > depth)) return;
    if (mask != nullptr && !mask->Covers(a1 / q, a2 / q)) return;
    depth = static_cast<float>(q);
    z.piece.at<int>(j - row_begin, i) = p;
  };
  for (size_t p = 0; p < views.size(); ++p) {
    const PieceView& view = views[p];
    if (!view.visible) continue;
    const Eigen::Matrix3d& g = view.g;
    const Piece& piece = scene.pieces[p];
    const AlphaMask* mask = piece.alpha >= 0 ? &scene.alpha_masks[piece.alpha] : nullptr;
    const int pi = static_cast<int>(p);
    if (grid.rays.empty()) {
      // Pinhole: the rows the piece spans, then per row the span where 0 <= s, t <= 1 and
      // near <= z, all affine in the sample index i once multiplied by 1/z > 0.
      const double y_min = lens_.fy * view.v_min + lens_.cy;
      const double y_max = lens_.fy * view.v_max + lens_.cy;
      const int j0 = std::max<double>(row_begin, std::floor((y_min - grid.offset) / grid.step));
      const int j1 = std::min<double>(row_end - 1, std::ceil((y_max - grid.offset) / grid.step));
      const double u0 = (grid.offset - lens_.cx) / lens_.fx;
      const Eigen::Vector3d d = g.col(0) * (grid.step / lens_.fx);
      for (int j = j0; j <= j1; ++j) {
        const double v = (grid.offset + j * grid.step - lens_.cy) / lens_.fy;
        const Eigen::Vector3d a = g * Eigen::Vector3d(u0, v, 1.0);
        double lo = 0.0;
        double hi = grid.cols - 1.0;
        Constrain(a.x(), d.x(), &lo, &hi);
        Constrain(a.z() - a.x(), d.z() - d.x(), &lo, &hi);
        Constrain(a.y(), d.y(), &lo, &hi);
        Constrain(a.z() - a.y(), d.z() - d.y(), &lo, &hi);
        Constrain(a.z() - 1e-12, d.z(), &lo, &hi);
        Constrain(max_inverse_depth - a.z(), -d.z(), &lo, &hi);
        if (lo > hi) continue;
        float* depth_row = z.inverse_depth.ptr<float>(j - row_begin);
        int* piece_row = z.piece.ptr<int>(j - row_begin);
        const int i1 = static_cast<int>(hi);
        if (mask == nullptr) {
          DepthTestSpan(static_cast<float>(a.z()), static_cast<float>(d.z()), pi,
                        static_cast<int>(lo), i1, depth_row, piece_row);
        } else {
          // The depth test first (cheap), the mask only for nearer samples.
          const float q0 = static_cast<float>(a.z());
          const float dq = static_cast<float>(d.z());
          for (int i = static_cast<int>(lo); i <= i1; ++i) {
            const float q = q0 + static_cast<float>(i) * dq;
            if (!(q > depth_row[i])) continue;
            const double inverse = 1.0 / (a.z() + i * d.z());
            if (!mask->Covers((a.x() + i * d.x()) * inverse, (a.y() + i * d.y()) * inverse)) {
              continue;
            }
            depth_row[i] = q;
            piece_row[i] = pi;
          }
        }
      }
      continue;
    }
    // Distorted lens: the tiles whose rays reach the piece's bounds, then every sample in them.
    for (int ty = row_begin / kTile; ty <= (row_end - 1) / kTile; ++ty) {
      for (int tx = 0; tx < grid.tile_ray_bounds.cols; ++tx) {
        const cv::Vec4f& b = grid.tile_ray_bounds.at<cv::Vec4f>(ty, tx);
        if (b[1] < view.u_min || b[0] > view.u_max || b[3] < view.v_min || b[2] > view.v_max) {
          continue;
        }
        for (int j = std::max(row_begin, ty * kTile); j < std::min(row_end, (ty + 1) * kTile);
             ++j) {
          const cv::Vec2f* rays = grid.rays.ptr<cv::Vec2f>(j);
          for (int i = tx * kTile; i < std::min(grid.cols, (tx + 1) * kTile); ++i) {
            const Eigen::Vector3d a = g * Eigen::Vector3d(rays[i][0], rays[i][1], 1.0);
            const double q = a.z();
            if (!(q > 0.0) || q > max_inverse_depth) continue;
            if (a.x() < 0.0 || a.x() > q || a.y() < 0.0 || a.y() > q) continue;
            draw(pi, mask, j, i, a.x(), a.y(), q);
          }
        }
      }
    }
  }
}

namespace {

// What shading needs of a piece, in float: G, the texture and its placement.
struct ShadingPiece {
  float g[9];          // row-major
  float width = 0.0f;  // texels across the whole piece along s and t (region x repeat)
  float height = 0.0f;
  float rect_x = 0.0f, rect_y = 0.0f, rect_w = 1.0f, rect_h = 1.0f;
  bool mirror = false;
  const Texture* texture = nullptr;
  cv::Vec3f tint;
};

float WrapTexel(float r, float width, bool mirror) {
  if (!mirror) return std::clamp(r, 0.0f, width);
  float m = r - 2.0f * width * std::floor(r / (2.0f * width));
  return m > width ? 2.0f * width - m : m;
}

// The colour of a piece along the ray (u, v, 1), filtered for an area (du, dv) of the
// normalised plane: the texture lookup covers the texels that area spans (the Jacobian of
// (s, t) in (u, v)).
cv::Vec3f ShadePiece(const ShadingPiece& piece, float u, float v, float du, float dv) {
  const float* g = piece.g;
  const float z = 1.0f / (g[6] * u + g[7] * v + g[8]);
  const float s = (g[0] * u + g[1] * v + g[2]) * z;
  const float t = (g[3] * u + g[4] * v + g[5]) * z;
  const float su = z * du * piece.width;
  const float tv = z * dv * piece.height;
  const float ds_du = (g[0] - s * g[6]) * su;
  const float dt_du = (g[3] - t * g[6]) * z * du * piece.height;
  const float ds_dv = (g[1] - s * g[7]) * z * dv * piece.width;
  const float dt_dv = (g[4] - t * g[7]) * tv;
  const float footprint =
      std::sqrt(std::max(ds_du * ds_du + dt_du * dt_du, ds_dv * ds_dv + dt_dv * dt_dv));
  const float x = piece.rect_x + WrapTexel(s * piece.width, piece.rect_w, piece.mirror);
  const float y = piece.rect_y + WrapTexel(t * piece.height, piece.rect_h, piece.mirror);
  const cv::Vec3f colour = piece.texture->Sample(x, y, footprint);
  return cv::Vec3f(colour[0] * piece.tint[0], colour[1] * piece.tint[1], colour[2] * piece.tint[2]);
}

ShadingPiece MakeShadingPiece(const Scene& scene, const Piece& piece, const Eigen::Matrix3d& g) {
  ShadingPiece sp;
  for (int k = 0; k < 9; ++k) sp.g[k] = static_cast<float>(g(k / 3, k % 3));
  sp.rect_x = static_cast<float>(piece.texture_rect.x);
  sp.rect_y = static_cast<float>(piece.texture_rect.y);
  sp.rect_w = static_cast<float>(piece.texture_rect.width);
  sp.rect_h = static_cast<float>(piece.texture_rect.height);
  sp.width = static_cast<float>(piece.texture_rect.width * piece.repeat[0]);
  sp.height = static_cast<float>(piece.texture_rect.height * piece.repeat[1]);
  sp.mirror = piece.wrap == TextureWrap::kMirror;
  sp.texture = &scene.textures[piece.texture];
  sp.tint = piece.tint;
  return sp;
}

cv::Vec3f ShadeSky(const Scene& scene, const Pose& pose, double u, double v) {
  const Eigen::Vector3d direction = (pose.rotation.transpose() * Eigen::Vector3d(u, v, 1.0));
  const float w = static_cast<float>(std::clamp(direction.y() / direction.norm() / 0.6, 0.0, 1.0));
  return scene.sky_horizon + w * (scene.sky_zenith - scene.sky_horizon);
}

}  // namespace

struct Rasterizer::ShadingPieces {
  std::vector<ShadingPiece> pieces;
};

void Rasterizer::ShadeRows(const Scene& scene, const Pose& pose, const ShadingPieces& shading,
                           const ZBuffer& band, int y_begin, int y_end, cv::Mat* colour) const {
  const std::vector<ShadingPiece>& pieces = shading.pieces;
  const int ss = options_.supersampling;
  const float pixel_du = static_cast<float>(1.0 / lens_.fx);
  const float pixel_dv = static_cast<float>(1.0 / lens_.fy);
  // The ray through a point of pixel (x, y) at offset (dx, dy) from its centre: exact for a
  // pinhole; for a distorted lens the centre's ray moved by the local pinhole step (the offsets
  // are below a pixel).
  const auto ray = [&](int x, int y, float dx, float dy) {
    const Eigen::Vector2d centre = RayOfPixel(x, y);
    return cv::Vec2f(static_cast<float>(centre.x()) + dx * pixel_du,
                     static_cast<float>(centre.y()) + dy * pixel_dv);
  };
  const auto shade = [&](int p, const cv::Vec2f& uv, float area) {
    if (p < 0) return ShadeSky(scene, pose, uv[0], uv[1]);
    return ShadePiece(pieces[p], uv[0], uv[1], pixel_du * area, pixel_dv * area);
  };
  const float step = static_cast<float>(samples_.step);
  const float first_offset = static_cast<float>(samples_.offset);  // of sample 0, from pixel 0
  for (int y = y_begin; y < y_end; ++y) {
    cv::Vec3f* out = colour->ptr<cv::Vec3f>(y);
    const int* rows[8];
    for (int j = 0; j < ss; ++j) rows[j] = band.piece.ptr<int>((y - y_begin) * ss + j);
    for (int x = 0; x < lens_.width; ++x) {
      const int first = rows[0][x * ss];
      bool uniform = true;
      for (int j = 0; j < ss && uniform; ++j) {
        for (int i = x * ss; i < (x + 1) * ss; ++i) uniform &= rows[j][i] == first;
      }
      if (uniform) {
        out[x] = shade(first, ray(x, y, 0.0f, 0.0f), 1.0f);
        continue;
      }
      // The pieces covering the pixel's samples, with their counts and the centroids of their
      // samples: each is shaded once, at its centroid, filtered over its share of the pixel (as
      // multisample anti-aliasing shades once per primitive and pixel).
      int ids[64];
      int counts[64];
      float cx[64];
      float cy[64];
      int distinct = 0;
      for (int j = 0; j < ss; ++j) {
        for (int i = 0; i < ss; ++i) {
          const int p = rows[j][x * ss + i];
          int k = 0;
          while (k < distinct && ids[k] != p) ++k;
          if (k == distinct) {
            ids[k] = p;
            counts[k] = 0;
            cx[k] = cy[k] = 0.0f;
            ++distinct;
          }
          ++counts[k];
          cx[k] += first_offset + i * step;
          cy[k] += first_offset + j * step;
        }
      }
      cv::Vec3f sum(0.0f, 0.0f, 0.0f);
      for (int k = 0; k < distinct; ++k) {
        const float share = static_cast<float>(counts[k]) / (ss * ss);
        sum += counts[k] *
               shade(ids[k], ray(x, y, cx[k] / counts[k], cy[k] / counts[k]), std::sqrt(share));
      }
      out[x] = sum / static_cast<float>(ss * ss);
    }
  }
}

RenderedView Rasterizer::Geometry(const std::vector<PieceView>& views,
                                  const ZBuffer& centre) const {
  RenderedView view;
  view.piece = centre.piece;
  view.depth = cv::Mat::zeros(lens_.height, lens_.width, CV_32F);
  const bool pinhole = !lens_.HasDistortion();
  for (int y = 0; y < lens_.height; ++y) {
    const int* pieces = centre.piece.ptr<int>(y);
    float* depth = view.depth.ptr<float>(y);
    const double v = (y - lens_.cy) / lens_.fy;
    for (int x = 0; x < lens_.width; ++x) {
      const int p = pieces[x];
      if (p < 0) continue;
      // The depth again in double from the plane, not the float z-buffer.
      const Eigen::Vector2d uv =
          pinhole ? Eigen::Vector2d((x - lens_.cx) / lens_.fx, v) : RayOfPixel(x, y);
      const Eigen::Matrix3d& g = views[p].g;
      depth[x] = static_cast<float>(1.0 / (g(2, 0) * uv.x() + g(2, 1) * uv.y() + g(2, 2)));
    }
  }
  return view;
}

Eigen::Vector2d Rasterizer::RayOfPixel(int x, int y) const {
  if (centres_.rays.empty()) {
    return {(x - lens_.cx) / lens_.fx, (y - lens_.cy) / lens_.fy};
  }
  const cv::Vec2f& uv = centres_.rays.at<cv::Vec2f>(y, x);
  return {uv[0], uv[1]};
}

RenderedView Rasterizer::Draw(const Scene& scene, const Pose& pose, bool colour,
                              bool geometry) const {
  const std::vector<PieceView> views = ViewPieces(scene, pose);
  const int ss = options_.supersampling;
  ShadingPieces shading;
  shading.pieces.resize(views.size());
  for (size_t p = 0; p < views.size(); ++p) {
    if (views[p].visible) shading.pieces[p] = MakeShadingPiece(scene, scene.pieces[p], views[p].g);
  }
  RenderedView view;
  ZBuffer centre;
  const bool centres_from_samples = geometry && ss % 2 == 1;
  if (centres_from_samples) {
    centre.inverse_depth.create(lens_.height, lens_.width, CV_32F);
    centre.piece.create(lens_.height, lens_.width, CV_32S);
  }
  if (colour) {
    view.color.create(lens_.height, lens_.width, CV_32FC3);
    // Bands of pixel rows, rasterised and shaded while their samples are in the cache.
    ZBuffer band;
    for (int y0 = 0; y0 < lens_.height; y0 += kBandRows) {
      const int y1 = std::min(lens_.height, y0 + kBandRows);
      RasterizeRows(scene, views, samples_, y0 * ss, y1 * ss, &band);
      ShadeRows(scene, pose, shading, band, y0, y1, &view.color);
      if (!centres_from_samples) continue;
      // Odd supersampling: sample (ss/2, ss/2) of each pixel lies on its centre.
      for (int y = y0; y < y1; ++y) {
        const float* depth = band.inverse_depth.ptr<float>((y - y0) * ss + ss / 2);
        const int* pieces = band.piece.ptr<int>((y - y0) * ss + ss / 2);
        for (int x = 0; x < lens_.width; ++x) {
          centre.inverse_depth.at<float>(y, x) = depth[x * ss + ss / 2];
          centre.piece.at<int>(y, x) = pieces[x * ss + ss / 2];
        }
      }
    }
  }
  if (!geometry) return view;
  if (!colour || !centres_from_samples) {
    RasterizeRows(scene, views, centres_, 0, centres_.rows, &centre);
  }
  const RenderedView truth = Geometry(views, centre);
  view.depth = truth.depth;
  view.piece = truth.piece;
  return view;
}

RenderedView Rasterizer::Render(const Scene& scene, const Pose& cam_from_world) const {
  return Draw(scene, cam_from_world, true, true);
}

cv::Mat Rasterizer::RenderColor(const Scene& scene, const Pose& cam_from_world) const {
  return Draw(scene, cam_from_world, true, false).color;
}

RenderedView Rasterizer::RenderGeometry(const Scene& scene, const Pose& cam_from_world) const {
  return Draw(scene, cam_from_world, false, true);
}

}  // namespace comic::render
