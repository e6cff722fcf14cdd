#include "frontend/comic/comic_detector.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <unordered_map>
#include <vector>

#include "frontend/comic/corner_convergence.h"
#include "frontend/comic/corner_feature.h"
#include "frontend/comic/initial_corners.h"
#include "frontend/comic/neighbour_suppression.h"
#include "frontend/grid_cell_key.h"
#include "frontend/parallel_for.h"
#include "io/core/error.h"

namespace comic::frontend {

void ComicDetectorOptions::Check() const {
  // Upper bounds keep every derived size (σ, filter supports, block origins, segment lengths) far
  // inside int: the paper's values (§3: s = 8.4, B = 100, δ = 5, k = 12) sit well within them.
  COMIC_CHECK(scale > 0 && scale <= kMaxScale, kInvalidArgument,
              "comic: scale must be > 0 and <= " << kMaxScale << " px, got " << scale);
  COMIC_CHECK(block_size >= 8 && block_size <= kMaxBlockSize, kInvalidArgument,
              "comic: block_size must be >= 8 and <= " << kMaxBlockSize << ", got " << block_size);
  COMIC_CHECK(delta >= 1 && delta <= kMaxDelta, kInvalidArgument,
              "comic: delta must be >= 1 and <= " << kMaxDelta << " grey levels, got " << delta);
  COMIC_CHECK(
      half_length >= 2 && half_length <= kMaxHalfLength, kInvalidArgument,
      "comic: half_length must be >= 2 and <= " << kMaxHalfLength << ", got " << half_length);
  COMIC_CHECK(
      max_iterations >= 1 && max_iterations <= kMaxIterations, kInvalidArgument,
      "comic: max_iterations must be >= 1 and <= " << kMaxIterations << ", got " << max_iterations);
  COMIC_CHECK(convergence_tolerance >= 0, kInvalidArgument,
              "comic: convergence_tolerance must be >= 0");
  COMIC_CHECK(stop_tolerance >= 0, kInvalidArgument, "comic: stop_tolerance must be >= 0");
  COMIC_CHECK(merge_radius >= 0, kInvalidArgument, "comic: merge_radius must be >= 0");
  COMIC_CHECK(min_stability >= 0, kInvalidArgument, "comic: min_stability must be >= 0");
  COMIC_CHECK(num_threads >= 0, kInvalidArgument, "comic: num_threads must be >= 0");
  COMIC_CHECK(min_cornerness >= 0 && min_cornerness <= 0.25, kInvalidArgument,
              "comic: min_cornerness must be in [0, 0.25], got " << min_cornerness);
}

ComicDetector::ComicDetector(const ComicDetectorOptions& options) : options_(options) {
  options_.Check();
}

namespace {

constexpr double kSqrt2 = 1.41421356237309504880;

// The states (apex, threshold) convergence runs have passed through, hashed on a grid, with the
// run that passed through each.
class StateGrid {
 public:
  explicit StateGrid(double cell) : cell_(cell) {}

  void Insert(const cv::Point2f& apex, double threshold, int run) {
    cells_[Key(Cell(apex.x), Cell(apex.y))].push_back({apex, threshold, run});
  }
  // The first state (in insertion order, by cell) of another run that is not lost, within
  // `distance` px and `levels` grey levels; that run's number, or -1.
  int Find(const cv::Point2f& apex, double threshold, int run, double distance, double levels,
           const std::vector<uint8_t>& lost) const {
    const int64_t cx = Cell(apex.x), cy = Cell(apex.y);
    for (int64_t dy = -1; dy <= 1; ++dy) {
      for (int64_t dx = -1; dx <= 1; ++dx) {
        auto it = cells_.find(Key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (const State& state : it->second) {
          if (state.run != run && !lost[state.run] &&
              std::abs(state.threshold - threshold) <= levels &&
              std::hypot(state.apex.x - apex.x, state.apex.y - apex.y) <= distance) {
            return state.run;
          }
        }
      }
    }
    return -1;
  }

 private:
  struct State {
    cv::Point2f apex;
    double threshold;
    int run;
  };
  int64_t Cell(float v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
  static uint64_t Key(int64_t cx, int64_t cy) { return GridCellKey(cx, cy); }
  double cell_;
  std::unordered_map<uint64_t, std::vector<State>> cells_;
};

// Initialisation (Algorithm 1 lines 4-6): blocks B x B, stride B/2, scale 2s, δ/2; on the image
// halved by 2x2 means when coarse_initialisation is on. The initial corners in full-resolution
// coordinates, the most stable first, one per place and polarity among neighbouring levels.
std::vector<InitialCorner> DetectInitialCorners(const cv::Mat& gray,
                                                const ComicDetectorOptions& o) {
  const int factor = o.coarse_initialisation ? 2 : 1;
  cv::Mat init_image = gray;
  if (factor == 2) {
    // Exact 2x2 means: an even crop halved by INTER_AREA. Half-resolution pixel (x, y) covers
    // full-resolution pixels 2x, 2x + 1, so its centre is at 2x + 0.5.
    cv::resize(gray(cv::Rect(0, 0, gray.cols & ~1, gray.rows & ~1)), init_image, cv::Size(), 0.5,
               0.5, cv::INTER_AREA);
  }
  const int init_block = std::max(8, o.block_size / factor);
  const int init_stride = std::max(1, o.block_size / (2 * factor));
  InitialCornerOptions init_options;
  init_options.delta = 0.5 * o.delta;
  init_options.half_length =
      std::max(2, static_cast<int>(std::lround(2.0 * o.half_length / factor)));
  init_options.sigma = 2.0 * o.scale / kSqrt2 / factor;
  init_options.min_cornerness = o.min_cornerness;
  const std::vector<int> xs = BlockOrigins(init_image.cols, init_block, init_stride);
  const std::vector<int> ys = BlockOrigins(init_image.rows, init_block, init_stride);
  const int num_blocks = static_cast<int>(xs.size() * ys.size());
  const int num_workers = ResolveNumThreads(o.num_threads, 2 * num_blocks);
  // Two items per block (one per polarity), each appending to its own list.
  std::vector<std::vector<InitialCorner>> per_item(2 * num_blocks);
  {
    std::vector<InitialCornerDetector> detectors(num_workers);
    ParallelFor(2 * num_blocks, o.num_threads, [&](int item, int worker) {
      const int block = item / 2;
      const int bx = block % static_cast<int>(xs.size());
      const int by = block / static_cast<int>(xs.size());
      const cv::Rect rect(xs[bx], ys[by], init_block, init_block);
      const auto [x0, x1] = OwnedRange(xs, init_block, bx, init_image.cols);
      const auto [y0, y1] = OwnedRange(ys, init_block, by, init_image.rows);
      detectors[worker].DetectInBlock(init_image, rect, cv::Rect(x0, y0, x1 - x0, y1 - y0),
                                      item % 2 == 1, init_options, &per_item[item]);
    });
  }
  std::vector<InitialCorner> initial;
  for (auto& corners : per_item) {
    for (InitialCorner& corner : corners) {
      if (factor == 2) {
        auto to_full = [](const cv::Point2f& p) {
          return cv::Point2f(2 * p.x + 0.5f, 2 * p.y + 0.5f);
        };
        corner.position = to_full(corner.position);
        for (cv::Point2f& p : corner.curve) p = to_full(p);
      }
      initial.push_back(std::move(corner));
    }
  }
  per_item.clear();
  // The same corner comes from overlapping blocks at neighbouring levels: keep the most stable.
  // (Seeds of levels further apart are kept even at the same place: a weak curve at the foot of
  // an edge must not stand in for the edge's own.)
  std::sort(initial.begin(), initial.end(), [](const InitialCorner& a, const InitialCorner& b) {
    if (a.stability != b.stability) return a.stability > b.stability;
    if (a.cornerness != b.cornerness) return a.cornerness > b.cornerness;
    if (a.position.y != b.position.y) return a.position.y < b.position.y;
    if (a.position.x != b.position.x) return a.position.x < b.position.x;
    return a.level < b.level;
  });
  return SuppressNeighbours(
      std::move(initial), 1.0, [](const InitialCorner& c) { return c.position; },
      [&](const InitialCorner& a, const InitialCorner& b) {
        return a.polarity == b.polarity && std::abs(a.level - b.level) <= o.delta;
      });
}

// Feature convergence (Algorithm 1 lines 7-17): B/2 blocks, scale s, δ, weights.
ConvergenceOptions MakeConvergenceOptions(const ComicDetectorOptions& o) {
  ConvergenceOptions convergence;
  convergence.block_size = std::max(8, o.block_size / 2);
  convergence.half_length = o.half_length;
  convergence.sigma = o.scale / kSqrt2;
  convergence.delta = o.delta;
  convergence.min_cornerness = o.min_cornerness;
  convergence.max_iterations = o.max_iterations;
  convergence.tolerance = o.convergence_tolerance;
  convergence.stop_tolerance = o.stop_tolerance;
  convergence.corner.arm_end = o.half_length;
  convergence.corner.arm_begin = std::min(4.0, 0.5 * o.half_length);
  convergence.corner.max_vertex_shift = 0.25 * o.half_length;
  return convergence;
}

// Converges rounds of seeds on one image, remembering across rounds the states every seed has
// been in. All seeds of a round advance one iteration at a time (each iteration in parallel over
// the seeds). A seed that reaches, within stop_tolerance and half a grey level, a state (apex,
// MSICS) another seed has been in is suspended: from the same state the iteration goes the same
// way, to a corner the final merge would fold into the other's. It resumes if that other seed is
// lost. Which seeds are suspended depends only on the seed order, never on the threads.
class SeedConvergence {
 public:
  SeedConvergence(const cv::Mat& gray, const ComicDetectorOptions& options)
      : gray_(gray),
        options_(options),
        convergence_(MakeConvergenceOptions(options)),
        workspaces_(ResolveNumThreads(options.num_threads, 1 << 20)),
        visited_(std::max(1.0, 4 * options.stop_tolerance)) {}

  // Converges every seed; appends the settled corners to `corners` in seed order.
  void Converge(const std::vector<InitialCorner>& seeds, ComicDetectionStats* stats,
                std::vector<ConvergedCorner>* corners) {
    using Status = CornerConvergence::Status;
    const int n = static_cast<int>(seeds.size());
    const int first_run = static_cast<int>(run_lost_.size());
    run_lost_.resize(first_run + n, 0);
    std::vector<CornerConvergence> runs(n);
    std::vector<Status> status(n, Status::kRunning);
    std::vector<std::vector<int>> waiting(n);  // seeds suspended on each seed
    std::vector<int> active(n);
    for (int i = 0; i < n; ++i) {
      runs[i].Start(seeds[i].position, seeds[i].curve, seeds[i].level);
      active[i] = i;
    }
    while (!active.empty()) {
      ParallelFor(static_cast<int>(active.size()), options_.num_threads, [&](int a, int worker) {
        const int i = active[a];
        status[i] = runs[i].Step(gray_, convergence_, &workspaces_[worker]);
      });
      std::vector<int> next;
      for (int i : active) {
        if (status[i] == Status::kLost) {
          run_lost_[first_run + i] = 1;
          for (int w : waiting[i]) next.push_back(w);  // resume the seeds that followed it
          continue;
        }
        if (!options_.skip_duplicate_paths) {
          if (status[i] == Status::kRunning) next.push_back(i);
          continue;
        }
        const ConvergedCorner& state =
            status[i] == Status::kSettled ? runs[i].result() : runs[i].current();
        if (status[i] == Status::kRunning) {
          const int other = visited_.Find(state.apex, state.threshold, first_run + i,
                                          options_.stop_tolerance, 0.5, run_lost_);
          if (other >= first_run) {  // on the path of a seed of this round: wait for its outcome
            waiting[other - first_run].push_back(i);
            continue;
          }
          if (other >= 0) continue;  // on the path to a corner the first round settled
          next.push_back(i);
        }
        visited_.Insert(state.apex, state.threshold, first_run + i);
      }
      std::sort(next.begin(), next.end());
      active.swap(next);
    }
    stats->num_seeds += n;
    for (int i = 0; i < n; ++i) {
      stats->num_iterations += runs[i].iteration();
      if (status[i] == Status::kSettled) {
        ++stats->num_settled;
        corners->push_back(std::move(runs[i].result()));
      }
    }
  }

 private:
  const cv::Mat& gray_;
  const ComicDetectorOptions& options_;
  const ConvergenceOptions convergence_;
  std::vector<ConvergenceWorkspace> workspaces_;
  StateGrid visited_;
  std::vector<uint8_t> run_lost_;  // per run, all rounds numbered in one sequence
};

// Seeds of the second round: the other corners on the converged MSICSs that no corner found yet
// (corners closer together than the initialisation scale 2s can share one initial corner, and
// Algorithm 1 would keep only the nearest), without duplicates.
std::vector<InitialCorner> NeighbouringCornerSeeds(const std::vector<ConvergedCorner>& corners,
                                                   double merge_radius) {
  std::vector<InitialCorner> neighbours;
  for (const ConvergedCorner& corner : corners) {
    for (const cv::Point2f& apex : corner.other_corners) {
      InitialCorner seed;
      seed.position = apex;
      seed.level = corner.level;
      seed.polarity = corner.polarity;
      seed.curve = corner.curve;
      neighbours.push_back(std::move(seed));
    }
  }
  std::vector<InitialCorner> found(corners.size());
  for (size_t i = 0; i < corners.size(); ++i) found[i].position = corners[i].position;
  for (InitialCorner& seed : neighbours) found.push_back(std::move(seed));
  // Suppression in this order drops the seeds near a corner already found, and duplicates.
  found = SuppressNeighbours(
      std::move(found), std::max(1.0, merge_radius),
      [](const InitialCorner& c) { return c.position; },
      [](const InitialCorner&, const InitialCorner&) { return true; });
  std::vector<InitialCorner> new_seeds;
  for (InitialCorner& seed : found) {
    if (!seed.curve.empty()) new_seeds.push_back(std::move(seed));
  }
  return new_seeds;
}

// The settled corners at least min_stability stable, one per place: seeds converging to the same
// corner keep the most stable (ties broken by position, level).
std::vector<ConvergedCorner> MergeSettledCorners(std::vector<ConvergedCorner> corners,
                                                 const ComicDetectorOptions& o) {
  corners.erase(std::remove_if(corners.begin(), corners.end(),
                               [&](const ConvergedCorner& c) {
                                 // On the response as stored (float), so that a threshold equals a
                                 // cut of the unthresholded output.
                                 return static_cast<float>(c.stability) < o.min_stability;
                               }),
                corners.end());
  std::sort(corners.begin(), corners.end(), [](const ConvergedCorner& a, const ConvergedCorner& b) {
    if (a.stability != b.stability) return a.stability > b.stability;
    if (a.position.y != b.position.y) return a.position.y < b.position.y;
    if (a.position.x != b.position.x) return a.position.x < b.position.x;
    if (a.threshold != b.threshold) return a.threshold < b.threshold;
    return a.cornerness > b.cornerness;
  });
  return SuppressNeighbours(
      std::move(corners), o.merge_radius, [](const ConvergedCorner& c) { return c.position; },
      [](const ConvergedCorner&, const ConvergedCorner&) { return true; });
}

// Output: one feature per corner, with the side mask of its patch, strongest first.
FeatureSet CornerFeatures(const cv::Mat& gray, const std::vector<ConvergedCorner>& corners,
                          const ComicDetectorOptions& o) {
  FeatureSet features(corners.size());
  ParallelFor(static_cast<int>(corners.size()), o.num_threads, [&](int i, int) {
    const ConvergedCorner& c = corners[i];
    CornerOnCurve corner;
    corner.position = c.position;
    corner.stability = c.stability;
    corner.cornerness = c.cornerness;
    corner.level = c.level;
    corner.polarity = c.polarity;
    corner.apex = c.apex;
    corner.curve_threshold = c.threshold;
    features[i] = MakeCornerFeature(gray, o.scale, corner, c.segment);
  });
  SortByResponse(&features);
  return features;
}

}  // namespace

FeatureSet ComicDetector::Detect(const cv::Mat& gray, ComicDetectionStats* stats) const {
  COMIC_CHECK(!gray.empty() && gray.type() == CV_8UC1, kInvalidArgument,
              "comic: expected a non-empty 8-bit single-channel image");
  ComicDetectionStats local_stats;
  if (stats == nullptr) stats = &local_stats;
  *stats = ComicDetectionStats();
  if (gray.cols < options_.block_size || gray.rows < options_.block_size) return {};
  auto stage_start = std::chrono::steady_clock::now();
  // Milliseconds since the previous call (or the start).
  auto lap = [&stage_start] {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - stage_start).count();
    stage_start = now;
    return ms;
  };

  const std::vector<InitialCorner> initial = DetectInitialCorners(gray, options_);
  stats->initialisation_ms = lap();

  std::vector<ConvergedCorner> corners;
  SeedConvergence convergence(gray, options_);
  convergence.Converge(initial, stats, &corners);
  if (options_.seed_neighbouring_corners) {
    convergence.Converge(NeighbouringCornerSeeds(corners, options_.merge_radius), stats, &corners);
  }
  corners = MergeSettledCorners(std::move(corners), options_);
  stats->convergence_ms = lap();

  FeatureSet features = CornerFeatures(gray, corners, options_);
  stats->output_ms = lap();
  return features;
}

}  // namespace comic::frontend
