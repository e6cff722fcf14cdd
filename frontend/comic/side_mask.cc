#include "frontend/comic/side_mask.h"

#include <array>

#include "frontend/comic/iso_curve.h"

namespace comic::frontend {

std::vector<PatchSide> ComputeSideMask(const cv::Mat& gray, double threshold,
                                       const cv::Point2f& curve_point, const cv::Point& centre) {
  constexpr int kSize = kPatchSize;
  std::vector<PatchSide> mask(kSize * kSize, PatchSide::kNone);
  const cv::Rect patch(centre.x - kPatchRadius, centre.y - kPatchRadius, kSize, kSize);
  const IsoCurveTracer tracer(gray, patch, threshold);
  CurveEdge seed;
  if (!tracer.FindNearestCrossing(curve_point, 2, &seed)) return mask;
  IsoCurve curve;
  curve.edges.reserve(4 * kSize);  // a patch's curve is rarely longer: no regrowth
  tracer.Trace(seed, 8 * kSize * kSize, &curve);

  // Links cut by the curve: per patch pixel, the link to its right and the one below it.
  std::array<uint8_t, kSize * kSize> cut_right{};
  std::array<uint8_t, kSize * kSize> cut_down{};
  auto local_index = [&](const cv::Point& p) { return (p.y - patch.y) * kSize + (p.x - patch.x); };
  // Every pixel enters the queue at most once (it is labelled when it enters).
  std::array<int, kSize * kSize> queue;
  int head = 0, tail = 0;
  std::array<uint8_t, kSize * kSize> near_curve{};
  for (const CurveEdge& edge : curve.edges) {
    const cv::Point lo(std::min(edge.inside.x, edge.outside.x),
                       std::min(edge.inside.y, edge.outside.y));
    (edge.inside.y == edge.outside.y ? cut_right : cut_down)[local_index(lo)] = 1;
    const int inside = local_index(edge.inside);
    const int outside = local_index(edge.outside);
    // Seeds in curve order, so the fill (and any tie where the cut is open) is deterministic.
    if (mask[inside] == PatchSide::kNone) {
      mask[inside] = PatchSide::kMinus;
      queue[tail++] = inside;
    }
    if (mask[outside] == PatchSide::kNone) {
      mask[outside] = PatchSide::kPlus;
      queue[tail++] = outside;
    }
    const double v_in = tracer.Value(edge.inside);
    const double t = (threshold - v_in) / (tracer.Value(edge.outside) - v_in);
    if (t < 0.5) near_curve[inside] = 1;
    if (t > 0.5) near_curve[outside] = 1;
  }
  // Breadth-first fill of both sides within the image part of the patch, not across cut links.
  const cv::Rect image_rect(0, 0, gray.cols, gray.rows);
  // Most patches lie in the image: then no pixel needs the image test.
  const bool patch_in_image = (patch & image_rect) == patch;
  while (head < tail) {
    const int index = queue[head++];
    const int u = index % kSize;
    const int v = index / kSize;
    auto visit = [&](int nu, int nv, bool cut) {
      if (cut || nu < 0 || nv < 0 || nu >= kSize || nv >= kSize) return;
      const int next = nv * kSize + nu;
      if (mask[next] != PatchSide::kNone) return;
      if (!patch_in_image && !image_rect.contains(cv::Point(patch.x + nu, patch.y + nv))) return;
      mask[next] = mask[index];
      queue[tail++] = next;
    };
    visit(u + 1, v, u + 1 < kSize && cut_right[index]);
    visit(u - 1, v, u > 0 && cut_right[index - 1]);
    visit(u, v + 1, v + 1 < kSize && cut_down[index]);
    visit(u, v - 1, v > 0 && cut_down[index - kSize]);
  }
  for (int i = 0; i < kSize * kSize; ++i) {
    if (near_curve[i]) mask[i] = PatchSide::kNone;
  }
  return mask;
}

}  // namespace comic::frontend
