#include "sfm/run/detector_option_table.h"

#include <algorithm>
#include <utility>

namespace comic::sfm {
namespace {

using Options = DetectRunOptions;
using Searches = DetectorOption::Searches;

// The keyword is the flag's name with underscores, as every keyword of comic.detect.
DetectorOption Entry(std::string flag, std::string metavar, Searches searches, std::string help,
                     DetectorOption::Field field) {
  std::string keyword = flag;
  std::replace(keyword.begin(), keyword.end(), '-', '_');
  return {std::move(flag), std::move(keyword), std::move(metavar),
          std::move(help), searches,           field};
}

// The options both searches read.
std::vector<DetectorOption> SharedOptions() {
  return {
      Entry("scale", "S", Searches::kBoth,
            "detection scale s in px (paper: 8.4; comic-paper initialises at 2s)",
            [](Options& o) -> double& { return o.scale; }),
      Entry("delta", "D", Searches::kBoth,
            "intensity offset delta of the Up/Down iso-curves, grey levels",
            [](Options& o) -> int& { return o.delta; }),
      Entry("half-length", "K", Searches::kBoth,
            "points on either side of the corner in a segment, k",
            [](Options& o) -> int& { return o.half_length; }),
      Entry("merge-radius", "PX", Searches::kBoth,
            "features closer than this are merged (higher rho kept)",
            [](Options& o) -> double& { return o.merge_radius; }),
      Entry("min-stability", "RHO", Searches::kBoth,
            "stability threshold on rho = len / dA, 1/px (0 = all)",
            [](Options& o) -> double& { return o.min_stability; }),
      Entry("min-cornerness", "KAPPA", Searches::kBoth,
            "cornerness threshold on kappa, in [0, 0.25]",
            [](Options& o) -> double& { return o.min_cornerness; }),
  };
}

// Algorithm 1's ("comic-paper").
std::vector<DetectorOption> PaperOptions() {
  return {
      Entry("block-size", "B", Searches::kPaper,
            "comic-paper: block size B in px (paper: 100): B x B initialisation blocks, B/2 "
            "convergence blocks",
            [](Options& o) -> int& { return o.block_size; }),
      Entry("max-iterations", "N", Searches::kPaper,
            "comic-paper: feature-convergence iterations before a corner is dropped",
            [](Options& o) -> int& { return o.max_iterations; }),
      Entry("convergence-tolerance", "PX", Searches::kPaper,
            "comic-paper: a corner has settled when it moves at most this",
            [](Options& o) -> double& { return o.convergence_tolerance; }),
      Entry("stop-tolerance", "PX", Searches::kPaper,
            "comic-paper: convergence iterations stop once a corner moves at most this",
            [](Options& o) -> double& { return o.stop_tolerance; }),
      Entry("no-neighbour-seeds", "", Searches::kPaper,
            "comic-paper: do not converge again from the other corners found on each MSICS "
            "(corners closer than the initialisation scale 2s may be missed)",
            [](Options& o) -> bool& { return o.no_neighbour_seeds; }),
      Entry("every-path", "", Searches::kPaper,
            "comic-paper: converge every seed to the end (default: a seed that reaches another "
            "seed's state waits for that seed's outcome)",
            [](Options& o) -> bool& { return o.every_path; }),
      Entry("full-resolution-init", "", Searches::kPaper,
            "comic-paper: run the initialisation stage at full resolution (default: on the image "
            "halved, same physical scale, 4x fewer pixels)",
            [](Options& o) -> bool& { return o.full_resolution_init; }),
  };
}

// The direct search's ("comic").
std::vector<DetectorOption> DirectOptions() {
  return {
      Entry("presmoothing-sigma", "PX", Searches::kDirect,
            "comic: Gaussian pre-smoothing of the image, px (0 = none)",
            [](Options& o) -> double& { return o.presmoothing_sigma; }),
      Entry("level-radius", "N", Searches::kDirect,
            "comic: levels traced on either side of each stable maximum of the tree",
            [](Options& o) -> int& { return o.level_radius; }),
      Entry("bridge-levels", "N", Searches::kDirect,
            "comic: two stable maxima of one lineage at most this many levels apart have the "
            "levels between them traced too",
            [](Options& o) -> int& { return o.bridge_levels; }),
      Entry("link-radius", "PX", Searches::kDirect,
            "comic: corners of consecutive levels closer than this form one run",
            [](Options& o) -> double& { return o.link_radius; }),
      Entry("consensus-fraction", "F", Searches::kDirect,
            "comic: run members with rho >= F x the peak's vote for the position",
            [](Options& o) -> double& { return o.consensus_fraction; }),
  };
}

}  // namespace

bool DetectorOption::AppliesTo(const std::string& detector) const {
  if (detector == "comic") return searches != Searches::kPaper;
  if (detector == "comic-paper") return searches != Searches::kDirect;
  return false;
}

std::vector<DetectorOption> DetectorOptionTable() {
  std::vector<DetectorOption> table = SharedOptions();
  for (auto part : {PaperOptions, DirectOptions}) {
    std::vector<DetectorOption> entries = part();
    table.insert(table.end(), entries.begin(), entries.end());
  }
  return table;
}

}  // namespace comic::sfm
