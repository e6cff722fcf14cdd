#include "python/run_keywords.h"

#include <utility>
#include <variant>

#include "io/core/error.h"
#include "sfm/option_vocabulary.h"
#include "sfm/run/run_option_table.h"
#include "sfm/run/run_outputs.h"

namespace comic::python {
namespace {

// comic.track's tracker options named as the apps' tracker flags (apps/common/tracker_flags.h).
void AddSfmTrackerOptions(frontend::TrackerOptions* t, OptionTable* table) {
  table->insert({{"max_features", Field(&t->max_features)},
                 {"search_radius", Field(&t->matcher.radius)},
                 {"unpredicted_radius", Field(&t->unpredicted_radius)},
                 {"prediction", Parsed(&t->prediction, frontend::ParseMotionPrediction)},
                 {"coarse_radius", Field(&t->coarse_radius)},
                 {"match_window", Field(&t->match_window)},
                 {"track_conflicts", Parsed(&t->conflict_rule, frontend::ParseTrackConflictRule)},
                 {"verify_min_gap", Field(&t->verify_min_gap)},
                 {"match_turned", Field(&t->match_turned_180)},
                 {"max_cost", Field(&t->matcher.max_cost)}});
}

// The tracker flags of comic_sfm and comic_export_colmap (apps/common/tracker_flags.h), given.
void AddRunTrackerSettings(sfm::TrackerSettings* t, OptionTable* table) {
  table->insert({{"max_features", Given(&t->max_features)},
                 {"search_radius", Given(&t->search_radius)},
                 {"unpredicted_radius", Given(&t->unpredicted_radius)},
                 {"prediction", Given(&t->prediction)},
                 {"coarse_radius", Given(&t->coarse_radius)},
                 {"match_window", Given(&t->match_window)},
                 {"track_conflicts", Given(&t->track_conflicts)},
                 {"verify_min_gap", Given(&t->verify_min_gap)},
                 {"match_turned", Given(&t->match_turned)},
                 {"max_cost", Given(&t->max_cost)},
                 {"align_patches", Given(&t->align_patches)},
                 {"min_window_eigenvalue", Given(&t->min_window_eigenvalue)}});
  using Continuation = frontend::TrackContinuationOptions;
  std::optional<Continuation>* c = &t->continuation;
  table->insert(
      {{"max_continued_frames",
        InOptional(c, [](Continuation& o) -> int& { return o.max_continued_frames; })},
       {"max_alignment_residual",
        InOptional(c, [](Continuation& o) -> double& { return o.max_residual; })},
       {"aligned_radius",
        InOptional(c, [](Continuation& o) -> double& { return o.aligned_radius; })},
       {"min_alignment_correlation",
        InOptional(c, [](Continuation& o) -> double& { return o.min_correlation; })},
       {"alignment_min_eigenvalue",
        InOptional(c, [](Continuation& o) -> double& { return o.alignment.min_eigenvalue; })},
       {"bridge_frames", InOptional(c, [](Continuation& o) -> int& { return o.bridge_frames; })},
       {"alignment_max_fb",
        InOptional(c,
                   [](Continuation& o) -> double& { return o.alignment.max_forward_backward_px; })},
       {"alignment_iterations",
        InOptional(c, [](Continuation& o) -> int& { return o.alignment.max_iterations; })},
       {"alignment_levels",
        InOptional(c, [](Continuation& o) -> int& { return o.alignment.levels; })}});
}

// --first, --last, --stride, --resize-height, --max-pixels.
void AddRunSequenceOptions(io::ImageSequenceOptions* s, OptionTable* table) {
  AddSequenceOptions(s, table);
  (*table)["max_pixels"] = Field(&s->max_pixels);
}

// --colmap-db and its flags (apps/common/colmap_db_flags.h).
void AddColmapDatabaseOptions(sfm::ColmapDatabaseOptions* c, OptionTable* table) {
  table->insert({{"colmap_db", Field(&c->colmap_db)},
                 {"overwrite", Field(&c->overwrite)},
                 {"window", Field(&c->export_options.pair_window)},
                 {"max_error", Field(&c->export_options.two_view.max_error_px)},
                 {"min_inliers", Field(&c->export_options.two_view.min_num_inliers)},
                 {"colmap_threads", Field(&c->colmap_threads)}});
}

}  // namespace

void AddMatcherOptions(frontend::PatchMatcherOptions* m, OptionTable* table) {
  // The apps' names (apps/common/shared_flags.h): --search-radius, --max-cost, ...
  table->insert({{"search_radius", Field(&m->radius)},
                 {"cost", Parsed(&m->cost, frontend::ParseMatchCost)},
                 {"min_side_overlap", Field(&m->min_side_overlap)},
                 {"max_cost", Field(&m->max_cost)}});
}

void AddTrackerOptions(frontend::TrackerOptions* t, OptionTable* table) {
  AddMatcherOptions(&t->matcher, table);
  AddSfmTrackerOptions(t, table);
  table->insert({{"min_response", Field(&t->min_response)},
                 {"velocity_neighbours", Field(&t->velocity_neighbours)},
                 {"velocity_neighbour_radius", Field(&t->velocity_neighbour_radius)},
                 {"coarse_factor", Field(&t->coarse_factor)},
                 {"coarse_features", Field(&t->coarse_features)}});
}

void AddSequenceOptions(io::ImageSequenceOptions* s, OptionTable* table) {
  table->insert({{"resize_height", Field(&s->resize_height)},
                 {"first", Field(&s->first_frame)},
                 {"last", Field(&s->last_frame)},
                 {"stride", Field(&s->stride)}});
}

OptionTable ReconstructOptionTable(sfm::ReconstructionRunOptions* o, bool* quiet) {
  OptionTable table = {{"detector", Field(&o->detector)},
                       {"scale_levels", Field(&o->detector_options.scale_space.num_levels)},
                       {"detectors", Field(&o->detectors)},
                       {"intrinsics", Field(&o->camera.intrinsics)},
                       {"camera_model", Field(&o->camera.camera_model)},
                       {"allow_truncated", Field(&o->sequence.allow_truncated)},
                       {"matching", Field(&o->matching)},
                       {"matcher", Field(&o->matcher)},
                       {"threads", Field(&o->threads)},
                       {"masks", Field(&o->masks)},
                       {"mask_keeps_nonzero", Negated(&o->mask_drops_nonzero)},
                       {"regions", Field(&o->regions)},
                       {"boundary_band", Field(&o->boundary_band)},
                       {"output", Field(&o->output)},
                       {"write_frames", WriteFrames(&o->write_frames, sfm::kFramesInOutput)},
                       {"quiet", Field(quiet)}};
  // The plain options: a keyword per entry of the library's table, typed as its field. A keyword
  // also set up by hand above would leave one of the two setters unused.
  for (const sfm::RunOption& entry : sfm::RunOptionTable()) {
    Setter setter = std::visit([o](auto field) { return Field(&field(*o)); }, entry.field);
    const bool added = table.emplace(entry.keyword, std::move(setter)).second;
    COMIC_CHECK(added, kInvalidArgument, "reconstruct: two setters for '" << entry.keyword << "'");
  }
  AddRunSequenceOptions(&o->sequence, &table);
  AddRunTrackerSettings(&o->tracker, &table);
  AddColmapDatabaseOptions(&o->colmap, &table);
  return table;
}

OptionTable ExportOptionTable(sfm::ColmapExportRunOptions* o, bool* quiet) {
  OptionTable table = {{"intrinsics", Field(&o->camera.intrinsics)},
                       {"camera_model", Field(&o->camera.camera_model)},
                       {"detector", Field(&o->detector)},
                       {"matching", Field(&o->matching)},
                       {"matcher", Field(&o->matcher)},
                       {"threads", Field(&o->threads)},
                       {"image_path", Field(&o->image_path)},
                       {"sparse", Field(&o->sparse)},
                       {"write_frames", WriteFrames(&o->write_frames, sfm::kFramesBesideDatabase)},
                       {"quiet", Field(quiet)}};
  AddColmapDatabaseOptions(&o->colmap, &table);
  table.erase("colmap_db");  // the second argument
  AddRunSequenceOptions(&o->sequence, &table);
  AddRunTrackerSettings(&o->tracker, &table);
  return table;
}

}  // namespace comic::python
