#include "frontend/comic/side_mask.h"

#include <algorithm>
#include <array>

#include "frontend/comic/iso_curve.h"

namespace comic::frontend {

std::vector<PatchSide> ComputeSideMask(const cv::Mat& gray, double threshold,
                                       const cv::Point2f& curve_point, const cv::Point& centre) {
  constexpr int kSize = kPatchSize;
  // The fill runs on the patch framed by one pixel of wall (label kWall), so that a step out of
  // the patch, or out of the image, is one label test instead of bounds tests; the matcher asks
  // for a mask per feature of every baseline (level_line_sides.h), so this loop is hot.
  constexpr int kPadded = kSize + 2;
  constexpr uint8_t kUnlabelled = 0, kPlus = 1, kMinus = 2, kWall = 3;
  static_assert(static_cast<uint8_t>(PatchSide::kPlus) == kPlus &&
                    static_cast<uint8_t>(PatchSide::kMinus) == kMinus &&
                    static_cast<uint8_t>(PatchSide::kNone) == kUnlabelled,
                "labels are PatchSide values");
  std::vector<PatchSide> mask(kSize * kSize, PatchSide::kNone);
  const cv::Rect patch(centre.x - kPatchRadius, centre.y - kPatchRadius, kSize, kSize);
  const IsoCurveTracer tracer(gray, patch, threshold);
  CurveEdge seed;
  if (!tracer.FindNearestCrossing(curve_point, 2, &seed)) return mask;
  IsoCurve curve;
  curve.edges.reserve(4 * kSize);  // a patch's curve is rarely longer: no regrowth
  tracer.Trace(seed, 8 * kSize * kSize, &curve);

  std::array<uint8_t, kPadded * kPadded> label;
  label.fill(kWall);
  const cv::Rect image_rect(0, 0, gray.cols, gray.rows);
  const cv::Rect in_image = patch & image_rect;
  for (int y = in_image.y; y < in_image.y + in_image.height; ++y) {
    uint8_t* row = &label[(y - patch.y + 1) * kPadded + (in_image.x - patch.x + 1)];
    std::fill(row, row + in_image.width, kUnlabelled);
  }
  // Links cut by the curve, at padded indices: per pixel, the link to its right and the one below.
  std::array<uint8_t, kPadded * kPadded> cut_right{};
  std::array<uint8_t, kPadded * kPadded> cut_down{};
  auto padded_index = [&](const cv::Point& p) {
    return (p.y - patch.y + 1) * kPadded + (p.x - patch.x + 1);
  };
  // Every pixel enters the queue at most once (it is labelled when it enters).
  std::array<int16_t, kSize * kSize> queue;
  int head = 0, tail = 0;
  std::array<int16_t, 2 * kSize * kSize> near_curve;  // padded indices, cleared after the fill
  int num_near = 0;
  for (const CurveEdge& edge : curve.edges) {
    const cv::Point lo(std::min(edge.inside.x, edge.outside.x),
                       std::min(edge.inside.y, edge.outside.y));
    (edge.inside.y == edge.outside.y ? cut_right : cut_down)[padded_index(lo)] = 1;
    const int inside = padded_index(edge.inside);
    const int outside = padded_index(edge.outside);
    // Seeds in curve order, so the fill (and any tie where the cut is open) is deterministic.
    if (label[inside] == kUnlabelled) {
      label[inside] = kMinus;
      queue[tail++] = static_cast<int16_t>(inside);
    }
    if (label[outside] == kUnlabelled) {
      label[outside] = kPlus;
      queue[tail++] = static_cast<int16_t>(outside);
    }
    const double v_in = tracer.Value(edge.inside);
    const double t = (threshold - v_in) / (tracer.Value(edge.outside) - v_in);
    if (t < 0.5) near_curve[num_near++] = static_cast<int16_t>(inside);
    if (t > 0.5) near_curve[num_near++] = static_cast<int16_t>(outside);
  }
  // Breadth-first fill of both sides within the image part of the patch, not across cut links,
  // in the order right, left, down, up (the order fixes who wins where the cut is open).
  while (head < tail) {
    const int index = queue[head++];
    const uint8_t side = label[index];
    auto visit = [&](int next, uint8_t cut) {
      if (cut || label[next] != kUnlabelled) return;
      label[next] = side;
      queue[tail++] = static_cast<int16_t>(next);
    };
    visit(index + 1, cut_right[index]);
    visit(index - 1, cut_right[index - 1]);
    visit(index + kPadded, cut_down[index]);
    visit(index - kPadded, cut_down[index - kPadded]);
  }
  for (int k = 0; k < num_near; ++k) label[near_curve[k]] = kUnlabelled;
  for (int v = 0; v < kSize; ++v) {
    const uint8_t* row = &label[(v + 1) * kPadded + 1];
    for (int u = 0; u < kSize; ++u) {
      mask[v * kSize + u] = row[u] == kWall ? PatchSide::kNone : static_cast<PatchSide>(row[u]);
    }
  }
  return mask;
}

}  // namespace comic::frontend
