// report.html of a distributed run (python/comic/distributed.py, docs/distributed.md): the page
// of comic_sfm's report (io/report/html_page.h, the same sections and style as run_page.h) built
// from the run's report.json, so that the page says what the JSON says. It holds the summary
// (status, frames in the first model, chunks, the merged models' counts, the merge's time and
// worker), the chunks that failed for good and the frames left out, the table of chunks (clip,
// frames, worker, time, status, registered frames, how each was merged; each row links to the
// chunk's own report.html), the merged models, the windows of the final adjustment, and
// report.json itself.
//
//   const io::HtmlPage page = DistributedRunPage(report_json);
//   io::WriteHtmlPage("out/report.html", page);  // atomically, as every output
#pragma once

#include <nlohmann/json.hpp>

#include "io/report/html_page.h"

namespace comic::sfm {

// The page of the distributed run whose report.json is `report` (the fields docs/distributed.md
// lists: status, num_frames, num_registered, unregistered_frames, failed_chunks, chunks[], merge,
// models, wall_time_s). Throws comic::Error(kInvalidArgument) naming a missing or mistyped field.
io::HtmlPage DistributedRunPage(const nlohmann::json& report);

}  // namespace comic::sfm
