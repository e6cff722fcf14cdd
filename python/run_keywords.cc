#include "python/run_keywords.h"

#include <type_traits>
#include <utility>
#include <variant>

#include "io/core/error.h"
#include "sfm/option_vocabulary.h"
#include "sfm/run/run_option_table.h"
#include "sfm/run/run_outputs.h"
#include "sfm/run/tracker_option_table.h"

namespace comic::python {
namespace {

// A setter of the tracker table's `entry` writing `options`' field: typed as the field, a
// named field (prediction="velocity") parsed by its name.
Setter TrackerEntrySetter(const sfm::TrackerOption& entry, frontend::TrackerOptions* options) {
  return std::visit(
      [options](auto field) -> Setter {
        if constexpr (std::is_same_v<decltype(field), sfm::TrackerOption::Named>) {
          return [options, field](py::handle value) {
            if (!py::isinstance<py::str>(value)) throw py::type_error("expects a str");
            field.set(*options, py::cast<std::string>(value));
          };
        } else {
          return Field(&field(*options));
        }
      },
      entry.field);
}

// comic.track's tracker options: a keyword per entry of the tracker table, as the apps' flags.
void AddSfmTrackerOptions(frontend::TrackerOptions* t, OptionTable* table) {
  for (const sfm::TrackerOption& entry : sfm::TrackerOptionTable()) {
    (*table)[entry.keyword] = TrackerEntrySetter(entry, t);
  }
}

// The tracker flags of comic_sfm and comic_export_colmap, given: a keyword per entry of the
// tracker table, whose value wins over the pairing's as the flag's does.
void AddRunTrackerSettings(sfm::TrackerSettings* t, OptionTable* table) {
  for (const sfm::TrackerOption& entry : sfm::TrackerOptionTable()) {
    Setter set = TrackerEntrySetter(entry, &t->values);
    (*table)[entry.keyword] = [t, set, flag = entry.flag](py::handle value) {
      set(value);
      t->MarkGiven(flag);
    };
  }
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
