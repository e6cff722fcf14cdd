#include "python/detector_keywords.h"

#include <pybind11/stl.h>

#include <variant>

#include "io/core/error.h"
#include "python/keyword_options.h"
#include "sfm/run/detector_option_table.h"

namespace comic::python {
namespace {

// A keyword per table entry that the search `name` reads, and the spellings comic.detect took
// before the table (the search's field names; accepted for one release, docs/apps.md).
void AddComicKeywords(const std::string& name, sfm::DetectRunOptions* run, OptionTable* table) {
  for (const sfm::DetectorOption& entry : sfm::DetectorOptionTable()) {
    if (!entry.AppliesTo(name)) continue;
    table->emplace(entry.keyword,
                   std::visit([run](auto field) { return Field(&field(*run)); }, entry.field));
  }
  if (name == "comic-paper") {
    table->insert({{"coarse_initialisation", Negated(&run->full_resolution_init)},
                   {"seed_neighbouring_corners", Negated(&run->no_neighbour_seeds)},
                   {"skip_duplicate_paths", Negated(&run->every_path)}});
  }
}

// The baselines' options by their fields' names.
void AddBaselineKeywords(const std::string& name, frontend::DetectorOptions* o,
                         OptionTable* table) {
  if (name == "harris") {
    frontend::HarrisDetectorOptions* h = &o->harris;
    table->insert({{"derivative_sigma", Field(&h->derivative_sigma)},
                   {"integration_sigma", Field(&h->integration_sigma)},
                   {"k", Field(&h->k)},
                   {"nms_radius", Field(&h->nms_radius)},
                   {"border", Field(&h->border)},
                   {"min_response", Field(&h->min_response)}});
  } else if (name == "hessian") {
    frontend::HessianDetectorOptions* h = &o->hessian;
    table->insert({{"sigma", Field(&h->sigma)},
                   {"nms_radius", Field(&h->nms_radius)},
                   {"border", Field(&h->border)},
                   {"min_response", Field(&h->min_response)}});
  } else if (name == "mser") {
    frontend::MserDetectorOptions* m = &o->mser;
    table->insert({{"delta", Field(&m->delta)},
                   {"min_area", Field(&m->min_area)},
                   {"max_area", Field(&m->max_area)},
                   {"max_variation", Field(&m->max_variation)},
                   {"merge_radius", Field(&m->merge_radius)}});
  } else if (name == "fast") {
    frontend::FastDetectorOptions* f = &o->fast;
    table->insert({{"min_threshold", Field(&f->min_threshold)},
                   {"nonmax_suppression", Field(&f->nonmax_suppression)}});
  }
}

OptionTable KeywordTable(const std::string& name, DetectorDoor door, sfm::DetectRunOptions* run) {
  OptionTable table;
  AddComicKeywords(name, run, &table);
  AddBaselineKeywords(name, &run->other, &table);
  table.emplace("scale_levels", Field(&run->other.scale_space.num_levels));
  if (door != DetectorDoor::kRun) table.emplace("threads", Field(&run->threads));
  if (door == DetectorDoor::kDetect) table.emplace("max_features", Field(&run->max_features));
  return table;
}

}  // namespace

sfm::DetectRunOptions DetectRunFromKeywords(const std::string& name, const py::dict& options,
                                            DetectorDoor door) {
  sfm::DetectRunOptions run;
  run.detector = name;
  frontend::CheckDetectorName(name);  // the command line's message, listing the names
  // Outside comic.detect the detector keeps its own thread count unless told (the runs set it).
  if (door != DetectorDoor::kDetect)
    run.threads = frontend::ComicDirectDetectorOptions().num_threads;
  if (options.empty()) return run;
  COMIC_CHECK(name.find('+') == std::string::npos, kInvalidArgument,
              "detector_options are one detector's; '" << name << "' names several");
  ApplyOptions(options, KeywordTable(name, door, &run), "detector '" + name + "'");
  run.Check();
  return run;
}

frontend::DetectorOptions MakeDetectorOptions(const std::string& name, const py::dict& options,
                                              DetectorDoor door) {
  return DetectRunFromKeywords(name, options, door).ToDetectorOptions();
}

py::list DetectorOptionEntries() {
  py::list entries;
  sfm::DetectRunOptions defaults;
  for (const sfm::DetectorOption& entry : sfm::DetectorOptionTable()) {
    py::dict d = OptionEntryDict(entry, defaults);
    py::list detectors;
    for (const char* name : {"comic", "comic-paper"}) {
      if (entry.AppliesTo(name)) detectors.append(name);
    }
    d["detectors"] = detectors;
    entries.append(d);
  }
  return entries;
}

}  // namespace comic::python
