// Merging the models of overlapping chunks of a sequence, each reconstructed on its own (e.g. as
// one task of a cluster, python/comic/distributed.py), into one model by the frames they share.
//
//   std::vector<Reconstruction> chunks = ...;  // in frame order, image names unique per frame
//   ChunkMergingResult merged = MergeChunkModels(chunks, ChunkMergingOptions());
//   merged.models[0];                            // the first chunk's model grown by the others
//
// The chunks are separate runs: their tracks, ids and gauges are unrelated. What ties them is the
// frame: a frame in two chunks is named alike in both, and a deterministic detector gives it the
// same features at the same pixels in both, so a feature of a shared frame with a 3-D point in
// both models is a pair of points for one physical point. The similarity between the two worlds
// comes from those pairs (RANSAC over triples with a fixed seed, Umeyama, refitted on the
// agreeing pairs), unlike IncrementalMapper::MergeModel, which merges models of one set of tracks.
#pragma once

#include <string>
#include <vector>

#include "sfm/bundle_adjuster.h"
#include "sfm/reconstruction.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

struct ChunkMergingOptions {
  // A point pair agrees with a similarity when the mapped point lies within this fraction of its
  // depth (in the shared frame that sees it) from the merged model's point: a single shared frame
  // leaves the scale to the depths.
  double max_relative_distance = 0.05;
  // A chunk joins a model with at least this many agreeing pairs, and this fraction of them.
  int min_num_inliers = 15;
  double min_inlier_ratio = 0.25;
  // The final bundle adjustment of each merged model: windows of this many frames in name order,
  // each starting half a window after the one before (as --global-ba-max-images bounds
  // comic_sfm's); 0 adjusts every frame at once, -1 skips the adjustment.
  int global_ba_max_images = 300;
  BundleAdjustmentOptions bundle_adjustment;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

// How one chunk was merged.
struct ChunkMergeOutcome {
  int model_index = -1;        // the model of ChunkMergingResult::models it is in (-1: none)
  bool started_model = false;  // it began that model (the first chunk, or one that joined none)
  int num_shared_frames = 0;   // frames registered both in it and in the model it was tried on
  int num_point_pairs = 0;     // pairs of 3-D points seen by one feature of a shared frame
  int num_inliers = 0;         // pairs agreeing with the similarity
  Sim3d model_from_chunk;      // the similarity used (identity for a chunk that began a model)
  std::string reason;  // why it joined no earlier model ("" for the first chunk and those joining)
};

struct ChunkMergingResult {
  // Each chunk joins the model the chunk before it is in when the two agree, else begins a new
  // one; models in the order they began (a chunk with no registered frame begins none).
  std::vector<Reconstruction> models;
  std::vector<ChunkMergeOutcome> chunks;             // one per input chunk
  std::vector<BundleAdjustmentSummary> adjustments;  // the final adjustments, model by model
};

// Merges `chunks` (in sequence order) as described above. Cameras identical in two chunks become
// one; frames only a joining chunk registered are added with their poses mapped; its points are
// mapped and fused with the model's points that a shared frame's feature gives both when the two
// agree (within max_relative_distance, as the similarity's pairs).
ChunkMergingResult MergeChunkModels(const std::vector<Reconstruction>& chunks,
                                    const ChunkMergingOptions& options);

}  // namespace comic::sfm
