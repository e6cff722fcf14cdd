#include "frontend/comic/comic_direct_detector.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <unordered_map>
#include <vector>

#include "frontend/comic/curve_cornerness.h"
#include "frontend/comic/image_component_tree.h"
#include "frontend/comic/iso_curve.h"
#include "frontend/comic/iso_curve_stability.h"
#include "frontend/comic/neighbour_suppression.h"
#include "frontend/comic/segment_stability.h"
#include "frontend/comic/side_mask.h"
#include "frontend/parallel_for.h"
#include "io/core/error.h"

namespace comic::frontend {

void ComicDirectDetectorOptions::Check() const {
  COMIC_CHECK(scale > 0, kInvalidArgument, "comic: scale must be > 0, got " << scale);
  COMIC_CHECK(delta >= 1, kInvalidArgument, "comic: delta must be >= 1, got " << delta);
  COMIC_CHECK(half_length >= 2, kInvalidArgument,
              "comic: half_length must be >= 2, got " << half_length);
  COMIC_CHECK(min_cornerness >= 0 && min_cornerness <= 0.25, kInvalidArgument,
              "comic: min_cornerness must be in [0, 0.25], got " << min_cornerness);
  COMIC_CHECK(max_arm_rms > 0.03, kInvalidArgument,
              "comic: max_arm_rms must be > 0.03 (where the fade begins), got " << max_arm_rms);
  COMIC_CHECK(level_radius >= 0, kInvalidArgument,
              "comic: level_radius must be >= 0, got " << level_radius);
  COMIC_CHECK(bridge_levels >= 0, kInvalidArgument,
              "comic: bridge_levels must be >= 0, got " << bridge_levels);
  COMIC_CHECK(max_level_gap >= 0, kInvalidArgument,
              "comic: max_level_gap must be >= 0, got " << max_level_gap);
  COMIC_CHECK(min_run_levels >= 1, kInvalidArgument,
              "comic: min_run_levels must be >= 1, got " << min_run_levels);
  COMIC_CHECK(level_step >= 1 && level_step <= 8, kInvalidArgument,
              "comic: level_step must be in [1, 8], got " << level_step);
  COMIC_CHECK(link_radius > 0, kInvalidArgument,
              "comic: link_radius must be > 0, got " << link_radius);
  COMIC_CHECK(consensus_fraction >= 0 && consensus_fraction <= 1, kInvalidArgument,
              "comic: consensus_fraction must be in [0, 1], got " << consensus_fraction);
  COMIC_CHECK(presmoothing_sigma >= 0, kInvalidArgument,
              "comic: presmoothing_sigma must be >= 0, got " << presmoothing_sigma);
  COMIC_CHECK(merge_radius >= 0, kInvalidArgument, "comic: merge_radius must be >= 0");
  COMIC_CHECK(min_stability >= 0, kInvalidArgument, "comic: min_stability must be >= 0");
  COMIC_CHECK(num_threads >= 0, kInvalidArgument, "comic: num_threads must be >= 0");
}

ComicDirectDetector::ComicDirectDetector(const ComicDirectDetectorOptions& options)
    : options_(options) {
  options_.Check();
}

namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
// A feature whose patch lies in the image but holds fewer pixels than this on one side of its
// curve cannot be matched by the side-split matcher of paper §4 (Algorithm 2's d_min, the
// PatchMatcherOptions::min_side_overlap default): it is a sliver of a region, not a corner of two.
constexpr int kMinSidePixels = 40;

// One κ maximum on the curve of one level.
struct LevelCorner {
  int tree = 0;   // 0: lower level sets (dark components), 1: upper
  int level = 0;  // grey level I of the image: the curve is at I + 0.5 (runs link these)
  cv::Point2f apex;
  cv::Point2f vertex;
  double cornerness = 0.0;
  Polarity polarity = Polarity::kNone;
  std::vector<cv::Point2f> segment;  // ±k samples at 1 px, dark side on the left
  int segment_centre = 0;
  double stability = 0.0;  // ρ_w, filled later
};

// A curve to trace: the outer boundary of tree node `node` at tree level `level`.
struct CurveJob {
  int tree;
  int node;
  int level;
  // The node's canonical pixel: jobs are ordered as the nodes of ComponentTree, whose ids these
  // pixels are (the order decides which of two equal κ maxima is kept, LinkAcrossLevels).
  int key;
  bool operator<(const CurveJob& o) const {
    if (tree != o.tree) return tree < o.tree;
    if (key != o.key) return key < o.key;
    return level < o.level;
  }
  bool operator==(const CurveJob& o) const {
    return tree == o.tree && key == o.key && level == o.level;
  }
};

// The component tree of one polarity, its stable lineage maxima and the curves they ask for.
struct PolarityTree {
  ImageComponentTree tree;
  std::vector<int> stable_level;
  std::vector<CurveJob> jobs;
};

void BuildPolarityTree(const cv::Mat& image, int tree_index, const ComicDirectDetectorOptions& o,
                       PolarityTree* out) {
  ImageComponentTree& tree = out->tree;
  tree.Build(image, tree_index == 1);
  // Stable lineage maxima (the unweighted ρ of §3 on the tree): the iso-curves that can hold a
  // feature. Their segment must be complete, so the boundary needs 2k + 1 edges at least.
  const int k = o.half_length;
  const std::vector<StableComponent> stable =
      FindMaximallyStableComponents(tree, o.delta, 2 * k + 1, 0.0, 1);
  const int root = tree.Root();
  // Per node: the level of its nearest stable ancestor-or-self (-1: none), so that the levels
  // between two stable maxima of one lineage are traced too when they are close: a corner's run
  // must not break at a level no maximum happened to be near.
  std::vector<int>& stable_level = out->stable_level;
  stable_level.assign(tree.NumNodes(), -1);
  for (const StableComponent& component : stable) stable_level[component.node] = component.level;
  {
    const std::vector<int>& nodes = tree.Nodes();
    for (auto it = nodes.rbegin(); it != nodes.rend(); ++it) {
      const int parent = tree.Parent(*it);
      if (stable_level[*it] < 0 && parent >= 0) stable_level[*it] = stable_level[parent];
    }
  }
  out->jobs.clear();
  auto add_job = [&](int from_node, int level) {
    if (level < 0 || level > 254) return;
    if ((tree_index == 1 ? 254 - level : level) % o.level_step != 0) return;
    const int node = level >= tree.Level(from_node) ? tree.AncestorAtLevel(from_node, level)
                                                    : tree.MainDescendantAtLevel(from_node, level);
    if (node < 0 || node == root || tree.Perimeter(node) < 2 * k + 1) return;
    out->jobs.push_back({tree_index, node, level, tree.CanonicalPixel(node)});
  };
  for (const StableComponent& component : stable) {
    const int parent = tree.Parent(component.node);
    const int above = parent < 0 ? -1 : stable_level[parent];
    if (above > component.level && above - component.level <= o.bridge_levels) {
      for (int level = component.level + o.level_radius + 1; level < above - o.level_radius;
           ++level) {
        add_job(component.node, level);
      }
    }
    for (int level = component.level - o.level_radius; level <= component.level + o.level_radius;
         ++level) {
      add_job(component.node, level);
    }
  }
  std::sort(out->jobs.begin(), out->jobs.end());
  out->jobs.erase(std::unique(out->jobs.begin(), out->jobs.end()), out->jobs.end());
}

struct CurveWorkspace {
  IsoCurve curve;
  std::vector<double> arc_lengths;
  std::vector<double> kappa;
  CornernessWorkspace cornerness;
};

// Traces the outer boundary of `job` and appends its κ maxima to `corners`.
void CornersOfCurve(const cv::Mat& image, const PolarityTree& tree_data, const CurveJob& job,
                    const ComicDirectDetectorOptions& o, const CurveCornerOptions& corner_options,
                    CurveWorkspace* ws, std::vector<LevelCorner>* corners) {
  const ImageComponentTree& tree = tree_data.tree;
  const bool upper = job.tree == 1;
  const int first = tree.FirstPixel(job.node);
  const int x = first % tree.width();
  const int y = first / tree.width();
  cv::Point in_pixel(x, y);
  cv::Point out_pixel;
  if (y > 0) {
    out_pixel = cv::Point(x, y - 1);
  } else if (x > 0) {
    out_pixel = cv::Point(x - 1, y);
  } else {
    // The component holds the top-left pixel: walk the first row to its first outside pixel.
    int end = 0;
    const uint8_t* row = image.ptr<uint8_t>(0);
    const uint8_t flip = upper ? 255 : 0;
    while (end < tree.width() && (row[end] ^ flip) <= job.level) ++end;
    if (end == tree.width()) return;
    in_pixel = cv::Point(end - 1, 0);
    out_pixel = cv::Point(end, 0);
  }
  // In the tree's values the component is {value <= level}; in the image's grey values its curve
  // is at 254.5 - level for upper sets (the component is {v >= 255 - level}). The tracer's inside
  // is the dark side.
  const double threshold = upper ? 254.5 - job.level : job.level + 0.5;
  const IsoCurveTracer tracer(image, cv::Rect(0, 0, image.cols, image.rows), threshold);
  const CurveEdge seed = upper ? CurveEdge{out_pixel, in_pixel} : CurveEdge{in_pixel, out_pixel};
  tracer.TracePoints(seed, 4 * (image.cols + image.rows) + tree.Perimeter(job.node), &ws->curve);
  const IsoCurve& curve = ws->curve;
  const int k = o.half_length;
  if (static_cast<int>(curve.points.size()) < 2 * k + 1) return;
  PolylineArcLengths(curve.points, curve.closed, &ws->arc_lengths);
  const double length = ws->arc_lengths.back();
  // A closed curve must be long enough for a segment to be a proper part of it (at most half):
  // on a small loop κ is near its maximum everywhere and the corner is arbitrary.
  if (curve.closed && length < 4 * k + 1) return;
  int origin = 0;
  const std::vector<cv::Point2f> samples =
      ResamplePolyline(curve.points, ws->arc_lengths, curve.closed, 1.0, 0.0, 0,
                       static_cast<int>(length) + 1, &origin);
  const int n = static_cast<int>(samples.size());
  if (n < 2 * k + 1) return;
  const double sigma = o.scale / kSqrt2;
  CurveCornernessCumulative(samples, curve.closed, sigma, k, &ws->cornerness, &ws->kappa);
  const int nms_radius = std::max(1, static_cast<int>(std::lround(sigma)));
  for (int index : CornernessMaxima(ws->kappa, curve.closed, nms_radius, o.min_cornerness)) {
    const CurveCorner refined =
        RefineCurveCorner(samples, curve.closed, ws->kappa, index, corner_options);
    LevelCorner corner;
    corner.tree = job.tree;
    corner.level = upper ? 254 - job.level : job.level;
    corner.apex = refined.apex;
    corner.vertex = refined.vertex;
    corner.cornerness = refined.cornerness;
    corner.polarity = refined.polarity;
    corner.segment.reserve(2 * k + 1);
    for (int j = index - k; j <= index + k; ++j) {
      if (!curve.closed && (j < 0 || j >= n)) continue;
      if (j == index) corner.segment_centre = static_cast<int>(corner.segment.size());
      corner.segment.push_back(samples[((j % n) + n) % n]);
    }
    corners->push_back(std::move(corner));
  }
}

// Links each κ maximum to the mutually nearest maximum of the next grey level with the same
// corner polarity within `radius`: next[i] is the index linked after i, or -1. A level line's
// corner is a property of the image, not of the tree whose component it bounds: the same curve is
// the outer boundary of a dark component at some levels and of a bright one at others (and of both
// where neither encloses the other), so both trees' maxima are linked on one scale of grey
// levels. `duplicate[i]` marks a maximum already seen at the same level and place (the same curve
// traced from both trees, or from two components the tree separates but marching squares joins
// across a saddle): it is neither linked nor a run of its own.
std::vector<int> LinkAcrossLevels(const std::vector<LevelCorner>& corners, double radius,
                                  int level_step, int max_gap, std::vector<uint8_t>* duplicate) {
  const int n = static_cast<int>(corners.size());
  const double cell = std::max(radius, 1.0);
  auto cell_of = [cell](float v) { return static_cast<int64_t>(std::floor(v / cell)); };
  // The maxima of each grey level by cell row (`cell` px high), in index order within a row: the
  // 3 × 3 cells around a point are read from three rows of one level, filtered by column (rows
  // hold about one maximum a level; a hash map of cells found the same neighbours with more
  // instructions).
  constexpr int kLevels = 256;
  int64_t min_row = 0, max_row = 0;
  for (int i = 0; i < n; ++i) {
    const int64_t row = cell_of(corners[i].apex.y);
    min_row = i == 0 ? row : std::min(min_row, row);
    max_row = i == 0 ? row : std::max(max_row, row);
  }
  const int64_t origin_row = min_row - 1;  // rows origin_row .. max_row + 1 can be asked for
  const int64_t num_rows = max_row - origin_row + 2;
  auto bucket = [&](int level, int64_t row) { return level * num_rows + (row - origin_row); };
  std::vector<int> row_start(kLevels * num_rows + 1, 0);
  for (int i = 0; i < n; ++i) {
    const LevelCorner& c = corners[i];
    if (c.level >= 0 && c.level < kLevels) ++row_start[bucket(c.level, cell_of(c.apex.y)) + 1];
  }
  for (size_t b = 1; b < row_start.size(); ++b) row_start[b] += row_start[b - 1];
  std::vector<int> members(row_start.back());
  {
    std::vector<int> fill(row_start.begin(), row_start.end() - 1);
    for (int i = 0; i < n; ++i) {
      const LevelCorner& c = corners[i];
      if (c.level >= 0 && c.level < kLevels)
        members[fill[bucket(c.level, cell_of(c.apex.y))]++] = i;
    }
  }
  // Calls visit(j) for every maximum j at `level` in the 3 × 3 cells around `c`'s, until it
  // returns true.
  auto for_neighbours = [&](const LevelCorner& c, int level, auto&& visit) {
    if (level < 0 || level >= kLevels) return;
    const int64_t cx = cell_of(c.apex.x), cy = cell_of(c.apex.y);
    for (int64_t row = cy - 1; row <= cy + 1; ++row) {
      if (row < origin_row || row >= origin_row + num_rows) continue;
      const int64_t b = bucket(level, row);
      for (int m = row_start[b]; m < row_start[b + 1]; ++m) {
        const int j = members[m];
        const int64_t column = cell_of(corners[j].apex.x);
        if (column < cx - 1 || column > cx + 1) continue;
        if (visit(j)) return;
      }
    }
  };
  duplicate->assign(n, 0);

  constexpr double kSamePlace = 0.05;  // px: the same curve traced twice
  for (int i = 0; i < n; ++i) {
    const LevelCorner& c = corners[i];
    // Against the earlier maxima that are not duplicates themselves.
    for_neighbours(c, c.level, [&](int j) {
      if (j >= i || (*duplicate)[j]) return false;
      if (corners[j].polarity == c.polarity &&
          std::hypot(corners[j].apex.x - c.apex.x, corners[j].apex.y - c.apex.y) < kSamePlace) {
        (*duplicate)[i] = 1;
        return true;
      }
      return false;
    });
  }
  // The nearest maximum at level + step (ties: the lower index).
  auto nearest = [&](int i, int step) {
    const LevelCorner& c = corners[i];
    int best = -1;
    double best_distance = radius;
    for_neighbours(c, c.level + step, [&](int j) {
      if ((*duplicate)[j] || corners[j].polarity != c.polarity) return false;
      const double d = std::hypot(corners[j].apex.x - c.apex.x, corners[j].apex.y - c.apex.y);
      if (d < best_distance || (d == best_distance && best >= 0 && j < best)) {
        best_distance = d;
        best = j;
      }
      return false;
    });
    return best;
  };
  // A κ maximum may vanish at a level or two (noise, a saddle of the curve, a level neither tree
  // traces): with none at the next level, the nearest of the following ones is linked.
  auto following = [&](int i, int direction) {
    for (int step = 1; step <= max_gap + 1; ++step) {
      const int j = nearest(i, step * direction * level_step);
      if (j >= 0) return j;
    }
    return -1;
  };
  std::vector<int> next(n, -1);
  for (int i = 0; i < n; ++i) {
    if ((*duplicate)[i]) continue;
    const int j = following(i, 1);
    if (j >= 0 && following(j, -1) == i) next[i] = j;
  }
  return next;
}

struct RunFeature {
  cv::Point2f position;
  double stability = 0.0;
  int member = -1;  // the member whose curve, level and κ the feature carries
  int record = -1;  // index in ComicDirectDetectionStats::runs (when recorded)
};

// The runs of linked κ maxima that span min_run_levels grey levels: their members concatenated,
// run r in members[begin[r], begin[r + 1]), runs in the order of their first member.
struct RunList {
  std::vector<int> members;
  std::vector<int> begin;
};

// Stage 1: the image every later stage reads (a new buffer: `gray` is the caller's and must not
// be written).
cv::Mat PresmoothedImage(const cv::Mat& gray, const ComicDirectDetectorOptions& o) {
  if (!(o.presmoothing_sigma > 0)) return gray;
  // 8-bit Gaussian filtering is bit-exact in OpenCV (fixed point), whatever the threads.
  cv::Mat image;
  cv::GaussianBlur(gray, image, cv::Size(0, 0), o.presmoothing_sigma, o.presmoothing_sigma,
                   cv::BORDER_REPLICATE);
  return image;
}

// Stage 3: κ maxima on every curve to trace (Algorithm 1's segment and corner at scale s), in job
// order whatever the threads.
std::vector<LevelCorner> CornersOfCurves(const cv::Mat& image, const PolarityTree (&trees)[2],
                                         const std::vector<CurveJob>& jobs,
                                         const ComicDirectDetectorOptions& o) {
  const int k = o.half_length;
  CurveCornerOptions corner_options;
  corner_options.arm_end = k;
  corner_options.arm_begin = std::min(4.0, 0.5 * k);
  corner_options.max_vertex_shift = 0.25 * k;
  corner_options.straight_arms_rms_end = o.max_arm_rms;
  const int num_workers = ResolveNumThreads(o.num_threads, 1 << 20);
  std::vector<CurveWorkspace> workspaces(num_workers);
  std::vector<std::vector<LevelCorner>> per_job(jobs.size());
  ParallelFor(static_cast<int>(jobs.size()), o.num_threads, [&](int j, int worker) {
    CornersOfCurve(image, trees[jobs[j].tree], jobs[j], o, corner_options, &workspaces[worker],
                   &per_job[j]);
  });
  std::vector<LevelCorner> corners;
  for (auto& list : per_job) {
    for (LevelCorner& c : list) corners.push_back(std::move(c));
  }
  return corners;
}

// Stage 4: one corner seen at consecutive levels is a run. A run must span min_run_levels grey
// levels: a κ maximum seen at a few levels only is a wiggle of a curve (noise, texture), not a
// corner of the level lines, and one grey level of noise removes it.
RunList LinkRuns(const std::vector<LevelCorner>& corners, const ComicDirectDetectorOptions& o,
                 int* num_runs) {
  std::vector<uint8_t> duplicate;
  const std::vector<int> next =
      LinkAcrossLevels(corners, o.link_radius, o.level_step, o.max_level_gap, &duplicate);
  std::vector<uint8_t> has_previous(duplicate);
  for (int j : next) {
    if (j >= 0) has_previous[j] = 1;
  }
  RunList runs;
  for (int start = 0; start < static_cast<int>(corners.size()); ++start) {
    if (has_previous[start]) continue;
    ++*num_runs;
    const size_t first = runs.members.size();
    for (int i = start; i >= 0; i = next[i]) runs.members.push_back(i);
    const int span = std::abs(corners[runs.members.back()].level - corners[start].level) + 1;
    if (span < o.min_run_levels) {
      runs.members.resize(first);
      continue;
    }
    runs.begin.push_back(static_cast<int>(first));
  }
  runs.begin.push_back(static_cast<int>(runs.members.size()));
  return runs;
}

// Stage 5: ρ_w of every member of a run (Eq. 1, §2.1 weights), on its own segment.
void EvaluateRunStability(const cv::Mat& image, const RunList& runs,
                          const ComicDirectDetectorOptions& o, std::vector<LevelCorner>* corners) {
  SegmentStabilityOptions stability_options;
  stability_options.half_length = o.half_length;
  stability_options.sigma = o.scale / kSqrt2;
  stability_options.delta = o.delta;
  const SegmentStabilityEvaluator evaluator(stability_options);
  ParallelFor(static_cast<int>(runs.members.size()), o.num_threads, [&](int i, int) {
    LevelCorner& c = (*corners)[runs.members[i]];
    c.stability = evaluator.Evaluate(image, c.segment, c.segment_centre, c.level + 0.5);
  });
}

// Stage 6: one feature per run (its smoothed ρ_w peak, at the consensus window's mean vertex);
// with stats->record_runs, one record per run.
std::vector<RunFeature> FeaturesOfRuns(const std::vector<LevelCorner>& corners, const RunList& runs,
                                       const ComicDirectDetectorOptions& o,
                                       ComicDirectDetectionStats* stats) {
  using Fate = ComicDirectRunRecord::Fate;
  std::vector<RunFeature> features_of_runs;
  std::vector<int> run;
  std::vector<double> smoothed;
  for (size_t r_index = 0; r_index + 1 < runs.begin.size(); ++r_index) {
    run.assign(runs.members.begin() + runs.begin[r_index],
               runs.members.begin() + runs.begin[r_index + 1]);
    const int m = static_cast<int>(run.size());
    // ρ_w smoothed across levels ([1 2 1] / 4, ends replicated): one grey level of noise moves a
    // single level's ρ_w, not the run's peak.
    smoothed.assign(m, 0.0);
    for (int r = 0; r < m; ++r) {
      const double before = corners[run[std::max(0, r - 1)]].stability;
      const double after = corners[run[std::min(m - 1, r + 1)]].stability;
      smoothed[r] = 0.25 * before + 0.5 * corners[run[r]].stability + 0.25 * after;
    }
    int peak = 0;
    for (int r = 1; r < m; ++r) {
      if (smoothed[r] > smoothed[peak]) peak = r;
    }
    ComicDirectRunRecord* record = nullptr;
    if (stats->record_runs) {
      stats->runs.emplace_back();
      record = &stats->runs.back();
      record->tree = corners[run[0]].tree;
      record->first_level = corners[run[0]].level;
      record->last_level = corners[run[m - 1]].level;
      record->peak_level = corners[run[peak]].level;
      record->polarity = corners[run[0]].polarity;
      record->peak_vertex = corners[run[peak]].vertex;
      record->stability = smoothed[peak];
      record->fate = Fate::kNoStability;
    }
    if (!(smoothed[peak] > 0.0)) continue;
    // Consensus: the levels around the peak that are equally stable (smoothed ρ_w within
    // consensus_fraction of the peak's; ρ_w is nearly flat across the steep part of an edge) form
    // a window; the feature is the mean of the vertices over the window, cut symmetric about its
    // centre. Across levels the vertex drifts along the corner's bisector (the iso-curves of a
    // blurred edge are offsets of it), linearly near the middle of the edge, so the symmetric mean
    // is the vertex at the window's centre, the middle of the edge, with the noise of the single
    // levels averaged out; the window's ends, not the flat peak, decide where it is.
    const double floor = o.consensus_fraction * smoothed[peak];
    int begin = peak;
    int end = peak;
    while (begin > 0 && smoothed[begin - 1] >= floor) --begin;
    while (end + 1 < m && smoothed[end + 1] >= floor) ++end;
    const int centre = (begin + end) / 2;
    const int half = std::min(centre - begin, end - centre);
    double sum_x = 0.0, sum_y = 0.0;
    for (int r = centre - half; r <= centre + half; ++r) {
      sum_x += corners[run[r]].vertex.x;
      sum_y += corners[run[r]].vertex.y;
    }
    const int member = centre;
    const double sum_w = 2 * half + 1;
    RunFeature f;
    f.position = cv::Point2f(static_cast<float>(sum_x / sum_w), static_cast<float>(sum_y / sum_w));
    f.stability = smoothed[peak];
    f.member = run[member];
    if (record != nullptr) {
      record->window_begin = corners[run[begin]].level;
      record->window_end = corners[run[end]].level;
      record->position = f.position;
      record->fate = Fate::kBelowThreshold;
      f.record = static_cast<int>(stats->runs.size()) - 1;
    }
    // On the response as stored (float), so that a threshold equals a cut of the full output.
    if (static_cast<float>(f.stability) < o.min_stability) continue;
    features_of_runs.push_back(f);
  }
  return features_of_runs;
}

// Stage 7: duplicates merged (both polarities, neighbouring runs), side masks, features outside
// the image or with a thin side dropped, ordered by response.
FeatureSet OutputFeatures(const cv::Mat& gray, const cv::Mat& image,
                          const std::vector<LevelCorner>& corners,
                          std::vector<RunFeature> features_of_runs,
                          const ComicDirectDetectorOptions& o, ComicDirectDetectionStats* stats) {
  using Fate = ComicDirectRunRecord::Fate;
  const bool record_runs = stats->record_runs;
  std::sort(features_of_runs.begin(), features_of_runs.end(),
            [&](const RunFeature& a, const RunFeature& b) {
              if (a.stability != b.stability) return a.stability > b.stability;
              if (a.position.y != b.position.y) return a.position.y < b.position.y;
              if (a.position.x != b.position.x) return a.position.x < b.position.x;
              return a.member < b.member;
            });
  if (record_runs) {
    for (const RunFeature& f : features_of_runs) stats->runs[f.record].fate = Fate::kMerged;
  }
  features_of_runs = SuppressNeighbours(std::move(features_of_runs), o.merge_radius,
                                        [](const RunFeature& f) { return f.position; });
  if (record_runs) {
    for (const RunFeature& f : features_of_runs) stats->runs[f.record].fate = Fate::kOutput;
  }
  FeatureSet features(features_of_runs.size());
  ParallelFor(static_cast<int>(features.size()), o.num_threads, [&](int i, int) {
    const RunFeature& r = features_of_runs[i];
    const LevelCorner& c = corners[r.member];
    Feature& f = features[i];
    f.x = r.position.x;
    f.y = r.position.y;
    f.scale = static_cast<float>(o.scale);
    f.response = static_cast<float>(r.stability);
    f.cornerness = static_cast<float>(c.cornerness);
    f.level = c.level;
    f.polarity = c.polarity;
    f.curve = c.segment;
    const cv::Point centre(static_cast<int>(std::lround(f.x)), static_cast<int>(std::lround(f.y)));
    f.side_mask = ComputeSideMask(image, c.level + 0.5, c.apex, centre);
  });
  auto thin_side = [&](const Feature& f) {
    if (!PatchFits(f, gray.size())) return false;
    const auto count = [&](PatchSide side) {
      return std::count(f.side_mask.begin(), f.side_mask.end(), side);
    };
    return count(PatchSide::kPlus) < kMinSidePixels || count(PatchSide::kMinus) < kMinSidePixels;
  };
  // A corner is observed inside the image: the vertex refinement and the run's consensus can
  // extrapolate a corner near the border beyond it (fuzz_image_detectors: x = -1.8 on a 64x48
  // image; one feature in 2143 on KITTI 06 frame 0, at y = -0.85), and such a position cannot be
  // matched or triangulated honestly.
  auto outside = [&](const Feature& f) {
    return !(f.x >= -0.5f && f.y >= -0.5f && f.x <= gray.cols - 0.5f && f.y <= gray.rows - 0.5f);
  };
  if (record_runs) {
    for (size_t i = 0; i < features.size(); ++i) {
      if (outside(features[i])) {
        stats->runs[features_of_runs[i].record].fate = Fate::kOutsideImage;
      } else if (thin_side(features[i])) {
        stats->runs[features_of_runs[i].record].fate = Fate::kThinSide;
      }
    }
  }
  features.erase(std::remove_if(features.begin(), features.end(),
                                [&](const Feature& f) { return outside(f) || thin_side(f); }),
                 features.end());
  SortByResponse(&features);
  return features;
}

}  // namespace

FeatureSet ComicDirectDetector::Detect(const cv::Mat& gray,
                                       ComicDirectDetectionStats* stats) const {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "comic: expected a non-empty 8-bit single-channel image");
  const ComicDirectDetectorOptions& o = options_;
  ComicDirectDetectionStats local_stats;
  if (stats == nullptr) stats = &local_stats;
  const bool record_runs = stats->record_runs;
  *stats = ComicDirectDetectionStats();
  stats->record_runs = record_runs;
  const int k = o.half_length;
  if (gray.cols < 2 * k + 1 || gray.rows < 2 * k + 1) return {};
  auto stage_start = std::chrono::steady_clock::now();
  auto lap = [&stage_start] {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - stage_start).count();
    stage_start = now;
    return ms;
  };

  // Stages 1-2: trees of both polarities and their stable lineage maxima.
  const cv::Mat image = PresmoothedImage(gray, o);
  PolarityTree trees[2];
  ParallelFor(2, o.num_threads, [&](int t, int) { BuildPolarityTree(image, t, o, &trees[t]); });
  std::vector<CurveJob> jobs = trees[0].jobs;
  jobs.insert(jobs.end(), trees[1].jobs.begin(), trees[1].jobs.end());
  stats->trees_ms = lap();

  std::vector<LevelCorner> corners = CornersOfCurves(image, trees, jobs, o);
  stats->num_curves = static_cast<int>(jobs.size());
  stats->num_maxima = static_cast<int>(corners.size());
  stats->curves_ms = lap();

  const RunList runs = LinkRuns(corners, o, &stats->num_runs);
  EvaluateRunStability(image, runs, o, &corners);
  std::vector<RunFeature> features_of_runs = FeaturesOfRuns(corners, runs, o, stats);
  stats->stability_ms = lap();

  FeatureSet features = OutputFeatures(gray, image, corners, std::move(features_of_runs), o, stats);
  stats->output_ms = lap();
  return features;
}

}  // namespace comic::frontend
