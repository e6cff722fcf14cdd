#include "sfm/run/distributed_run_page.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "io/core/error.h"
#include "io/report/number_text.h"
#include "io/report/page_sections.h"
#include "io/report/report_table.h"
#include "sfm/run/run_page.h"

namespace comic::sfm {

namespace {

// report.json is written by Python: a field that is missing or of another type is a broken
// report, said as such rather than as nlohmann's words.
const nlohmann::json& Field(const nlohmann::json& object, const char* name) {
  COMIC_CHECK(object.is_object() && object.contains(name), kInvalidArgument,
              "distributed report: no field '" << name << "'");
  return object.at(name);
}

template <typename T>
T Get(const nlohmann::json& object, const char* name) {
  try {
    return Field(object, name).get<T>();
  } catch (const nlohmann::json::exception& e) {
    COMIC_CHECK(false, kInvalidArgument,
                "distributed report: field '" << name << "' has the wrong type: " << e.what());
  }
  return T();
}

io::PageTone StatusTone(const std::string& status) {
  if (status == "success") return io::PageTone::kGood;
  if (status == "partial") return io::PageTone::kWarning;
  return io::PageTone::kBad;
}

std::string Percent(int64_t part, int64_t whole) {
  return io::NumberText("%.0f", whole > 0 ? 100.0 * part / whole : 0.0) + " %";
}

std::string FrameRange(const nlohmann::json& chunk) {
  return std::to_string(Get<int64_t>(chunk, "first")) + "–" +
         std::to_string(Get<int64_t>(chunk, "last"));
}

// How a chunk went into the merged models, in words: which model, through how many shared frames
// and agreeing point pairs, or why it joined none.
std::string MergeWords(const nlohmann::json& chunk) {
  const nlohmann::json merge = chunk.value("merge", nlohmann::json());
  if (merge.is_null()) {
    if (Get<std::string>(chunk, "status") == "failed") return "not merged: the chunk failed";
    return "not merged: no model";
  }
  const std::string model = "model " + std::to_string(Get<int64_t>(merge, "model_index"));
  const std::string reason = merge.value("reason", std::string());
  if (Get<int64_t>(merge, "num_shared_frames") == 0 && reason.empty()) return "began " + model;
  if (!reason.empty()) return "began " + model + ": " + reason;
  const int64_t shared = Get<int64_t>(merge, "num_shared_frames");
  return "joined " + model + " through " + std::to_string(shared) +
         (shared == 1 ? " shared frame, " : " shared frames, ") +
         std::to_string(Get<int64_t>(merge, "num_inliers")) + " of " +
         std::to_string(Get<int64_t>(merge, "num_point_pairs")) + " point pairs agreeing, scale " +
         io::NumberText("%.4g", Get<double>(merge, "scale"));
}

io::PageSection SummarySection(const nlohmann::json& report) {
  const std::string status = Get<std::string>(report, "status");
  const int64_t frames = Get<int64_t>(report, "num_frames");
  const int64_t registered = Get<int64_t>(report, "num_registered");
  const nlohmann::json& chunks = Field(report, "chunks");
  const nlohmann::json& models = Field(report, "models");
  const nlohmann::json& merge = Field(report, "merge");
  int64_t clips = 0;
  for (const nlohmann::json& chunk : chunks) {
    clips = std::max<int64_t>(clips, Get<int64_t>(chunk, "clip") + 1);
  }
  const size_t failed = Field(report, "failed_chunks").size();
  std::vector<io::PageFact> facts = {
      {"status", status, StatusTone(status)},
      {"registered",
       std::to_string(registered) + " of " + std::to_string(frames) + " frames (" +
           Percent(registered, frames) + ") in the first model",
       registered == frames ? io::PageTone::kGood
                            : (registered == 0 ? io::PageTone::kBad : io::PageTone::kWarning)},
      {"clips", std::to_string(clips)},
      {"chunks", std::to_string(chunks.size()) + " (" + std::to_string(failed) + " failed)",
       failed == 0 ? io::PageTone::kNeutral : io::PageTone::kBad},
      {"models",
       std::to_string(models.size()) +
           (models.size() > 1 ? " (chunks that joined no model began one of their own)" : "")}};
  if (!models.empty()) {
    facts.push_back({"first model",
                     std::to_string(Get<int64_t>(models[0], "num_images")) + " frames, " +
                         std::to_string(Get<int64_t>(models[0], "num_points3D")) + " 3-D points"});
  }
  facts.push_back({"merge", io::NumberText("%.2f s", Get<double>(merge, "time_s")) + " on worker " +
                                Get<std::string>(merge, "worker")});
  facts.push_back({"whole run", io::NumberText("%.2f s", Get<double>(report, "wall_time_s")) +
                                    " wall clock (this page not counted)"});
  return io::FactsSection("Summary", facts);
}

// The chunks that failed for good (their frames are in no model), and the frames left out.
void AppendNotices(const nlohmann::json& report, std::vector<io::PageSection>* sections) {
  const nlohmann::json& failed = Field(report, "failed_chunks");
  if (!failed.empty()) {
    std::string text;
    for (const nlohmann::json& entry : failed) {
      const int64_t index = Get<int64_t>(entry, "index");
      const nlohmann::json& chunk = Field(report, "chunks").at(index);
      const nlohmann::json& names = Field(entry, "frames");
      text += (text.empty() ? "" : " ") + std::string("Chunk ") + std::to_string(index) +
              " (clip " + std::to_string(Get<int64_t>(chunk, "clip")) + ", frames " +
              FrameRange(chunk) + ": " + std::to_string(names.size()) + " frames) failed after " +
              "its retries: " + chunk.value("error", std::string("no error recorded")) + ".";
    }
    sections->push_back(
        io::NoticeSection(io::PageTone::kBad, "Chunks that failed for good",
                          text + " The other chunks were merged; the run is partial."));
  }
  const nlohmann::json& left_out = Field(report, "unregistered_frames");
  if (!left_out.empty()) {
    constexpr size_t kListed = 8;
    std::string names;
    for (size_t i = 0; i < std::min(left_out.size(), kListed); ++i) {
      names += (i ? ", " : "") + left_out[i].get<std::string>();
    }
    if (left_out.size() > kListed) names += ", …";
    sections->push_back(io::NoticeSection(
        io::PageTone::kWarning, "Frames left out",
        std::to_string(left_out.size()) + " frames are not in the first model: " + names + "."));
  }
}

io::PageSection ChunksSection(const nlohmann::json& report) {
  io::ReportTable table(
      {"chunk", "clip", "frames", "worker", "time (s)", "status", "registered", "merge"});
  table.SetPrecision("time (s)", 2);
  std::vector<std::string> links;
  for (const nlohmann::json& chunk : Field(report, "chunks")) {
    const int64_t frames = Get<int64_t>(chunk, "num_frames");
    const int64_t index = Get<int64_t>(chunk, "index");
    const std::string range =
        FrameRange(chunk) + " (" + std::to_string(frames) + (frames == 1 ? " frame)" : " frames)");
    // A chunk that failed for good has neither a worker nor a time of its own.
    const io::ReportTable::Cell worker =
        chunk.contains("worker") ? io::ReportTable::Cell(Get<std::string>(chunk, "worker"))
                                 : io::ReportTable::Cell();
    const io::ReportTable::Cell time = chunk.contains("time_s")
                                           ? io::ReportTable::Cell(Get<double>(chunk, "time_s"))
                                           : io::ReportTable::Cell();
    table.AddRow({index, Get<int64_t>(chunk, "clip"), range, worker, time,
                  Get<std::string>(chunk, "status"), Get<int64_t>(chunk, "num_registered"),
                  MergeWords(chunk)});
    // Each chunk keeps its own comic_sfm page under chunks/NNNN/ (relative: the page moves with
    // the output folder).
    char folder[32];
    std::snprintf(folder, sizeof(folder), "chunks/%04lld/report.html",
                  static_cast<long long>(index));
    links.push_back(chunk.value("path", nlohmann::json()).is_null() ? "" : folder);
  }
  io::PageSection section = io::TableSection(
      "Chunks", table,
      "Each chunk is comic_sfm's run on its frames, as one Dask task; its own page (3-D view, "
      "timeline, frames) is linked from its number. registered: frames in the chunk's own model. "
      "merge: how the chunk's model went into the merged models (a similarity from the points "
      "its shared frames give both).",
      links);
  section[kDurationsKey] = true;  // its time column
  return section;
}

io::PageSection ModelsSection(const nlohmann::json& report) {
  io::ReportTable table({"model", "folder", "frames", "3-D points"});
  int64_t k = 0;
  for (const nlohmann::json& model : Field(report, "models")) {
    table.AddRow({k, k == 0 ? std::string(". and sparse/0") : "sparse/" + std::to_string(k),
                  Get<int64_t>(model, "num_images"), Get<int64_t>(model, "num_points3D")});
    ++k;
  }
  return io::TableSection("Merged models", table,
                          "The first model is written as comic_sfm writes its model (cameras.txt, "
                          "images.txt, points3D.txt, sparse/0, points.ply); further ones are "
                          "chunks that joined no earlier model.");
}

io::PageSection AdjustmentSection(const nlohmann::json& report) {
  io::ReportTable table({"window", "frames", "RMS before (px)", "RMS after (px)"});
  int64_t k = 0;
  for (const nlohmann::json& window : Field(Field(report, "merge"), "adjustments")) {
    table.AddRow({k++, Get<int64_t>(window, "num_images"), Get<double>(window, "initial_rmse_px"),
                  Get<double>(window, "final_rmse_px")});
  }
  return io::TableSection("Adjustment of the merged models", table,
                          "One sweep of bundle adjustment in windows of --global-ba-max-images "
                          "frames, half a window apart, model by model.");
}

}  // namespace

io::HtmlPage DistributedRunPage(const nlohmann::json& report) {
  io::HtmlPage page;
  const int64_t chunks = static_cast<int64_t>(Field(report, "chunks").size());
  page.title = "comic.distributed · " + std::to_string(chunks) + " chunks";
  page.subtitle = "report.html of a distributed run: status " + Get<std::string>(report, "status") +
                  ", " + std::to_string(Get<int64_t>(report, "num_registered")) + "/" +
                  std::to_string(Get<int64_t>(report, "num_frames")) + " frames in the first model";
  std::vector<io::PageSection> sections = {SummarySection(report)};
  AppendNotices(report, &sections);
  sections.push_back(ChunksSection(report));
  sections.push_back(ModelsSection(report));
  if (!Field(Field(report, "merge"), "adjustments").empty()) {
    sections.push_back(AdjustmentSection(report));
  }
  sections.push_back(io::JsonSection("report.json", report));
  page.sections = sections;
  return page;
}

}  // namespace comic::sfm
