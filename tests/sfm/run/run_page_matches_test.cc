// The matrix of tracks shared between frames: known counts for a few tracks, one frame per cell
// and frames grouped into cells.
#include "sfm/run/run_page_matches.h"

#include <gtest/gtest.h>

namespace comic::sfm {
namespace {

// Four frames, tracks over frames {0, 1, 2}, {1, 3} and {0, 3}.
frontend::FeatureTracks ThreeTracks() {
  frontend::FeatureTracks tracks;
  tracks.features.resize(4);
  for (const std::vector<int>& frames : std::vector<std::vector<int>>{{0, 1, 2}, {1, 3}, {0, 3}}) {
    frontend::Track track;
    for (int f : frames) track.observations.push_back({f, 0});
    tracks.tracks.push_back(track);
  }
  return tracks;
}

TEST(SharedTracksBetweenFrames, OneCellPerFrame) {
  const SharedTrackMatrix matrix = SharedTracksBetweenFrames(ThreeTracks(), 200);
  EXPECT_EQ(matrix.cell_first_frames, (std::vector<int>{0, 1, 2, 3}));
  const std::vector<int64_t> expected = {0, 1, 1, 1,   // frame 0 with 1, 2 and 3
                                         1, 0, 1, 1,   // frame 1 with 0, 2 and 3
                                         1, 1, 0, 0,   // frame 2
                                         1, 1, 0, 0};  // frame 3
  EXPECT_EQ(matrix.counts, expected);
}

TEST(SharedTracksBetweenFrames, GroupsFramesIntoAtMostMaxCells) {
  // Cells {0, 1} and {2, 3}: every track links them; {0, 1, 2} also links frames 0 and 1.
  const SharedTrackMatrix matrix = SharedTracksBetweenFrames(ThreeTracks(), 2);
  EXPECT_EQ(matrix.cell_first_frames, (std::vector<int>{0, 2}));
  EXPECT_EQ(matrix.counts, (std::vector<int64_t>{1, 3, 3, 0}));
  EXPECT_EQ(matrix.At(0, 1), 3);
  // 1000 frames in at most 200 cells of 5.
  frontend::FeatureTracks long_clip;
  long_clip.features.resize(1000);
  const SharedTrackMatrix grouped = SharedTracksBetweenFrames(long_clip, 200);
  EXPECT_EQ(grouped.cell_first_frames.size(), 200u);
  EXPECT_EQ(grouped.cell_first_frames[1], 5);
  EXPECT_EQ(grouped.counts.size(), 200u * 200u);
}

TEST(MatchMatrixSection, OnlyWithTracks) {
  DetectorRun run;
  EXPECT_FALSE(MatchMatrixSection(run, RunPageOptions()));
  run.run.tracks = ThreeTracks();
  const auto section = MatchMatrixSection(run, RunPageOptions());
  ASSERT_TRUE(section);
  EXPECT_EQ((*section)["type"], "heatmap");
  EXPECT_EQ((*section)["num_frames"], 4);
  EXPECT_EQ((*section)["values"][1], 1);
}

}  // namespace
}  // namespace comic::sfm
