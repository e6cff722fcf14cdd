// report.html of a distributed run: what the page says about a successful run and a partial one
// (a chunk failed for good, one began a model of its own), that it is written whole, and that a
// broken report.json is refused with the field named; in Chromium the page draws.
#include "sfm/run/distributed_run_page.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/headless_browser.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

using comic::test::ScopedTempDir;

const nlohmann::json& Section(const io::HtmlPage& page, const std::string& title) {
  for (const nlohmann::json& section : page.sections) {
    if (section["title"] == title) return section;
  }
  ADD_FAILURE() << "no section " << title;
  static const nlohmann::json kNone;
  return kNone;
}

bool HasSection(const io::HtmlPage& page, const std::string& title) {
  for (const nlohmann::json& section : page.sections) {
    if (section["title"] == title) return true;
  }
  return false;
}

nlohmann::json Fact(const io::HtmlPage& page, const std::string& label) {
  for (const nlohmann::json& fact : Section(page, "Summary")["facts"]) {
    if (fact["label"] == label) return fact;
  }
  return nlohmann::json();
}

nlohmann::json Chunk(int index, int first, int last, const std::string& status, int registered,
                     nlohmann::json merge) {
  return {{"index", index},
          {"clip", 0},
          {"first", first},
          {"last", last},
          {"num_frames", last - first + 1},
          {"worker", "tcp://127.0.0.1:4000" + std::to_string(index)},
          {"time_s", 1.5 + index},
          {"status", status},
          {"num_registered", registered},
          {"path", "/out/chunks/000" + std::to_string(index)},
          {"merge", merge}};
}

nlohmann::json Merge(int model, int shared, int pairs, int inliers, double scale,
                     const std::string& reason) {
  return {{"model_index", model},     {"started_model", shared == 0}, {"num_shared_frames", shared},
          {"num_point_pairs", pairs}, {"num_inliers", inliers},       {"scale", scale},
          {"reason", reason}};
}

// Three chunks of 5 frames sharing 1, all merged into one model of 13 frames.
nlohmann::json SuccessfulRun() {
  return {{"status", "success"},
          {"num_frames", 13},
          {"num_registered", 13},
          {"unregistered_frames", nlohmann::json::array()},
          {"failed_chunks", nlohmann::json::array()},
          {"chunks",
           {Chunk(0, 0, 4, "success", 5, Merge(0, 0, 0, 0, 1.0, "")),
            Chunk(1, 4, 8, "success", 5, Merge(0, 1, 300, 290, 0.5, "")),
            Chunk(2, 8, 12, "success", 5, Merge(0, 1, 200, 150, 2.0, ""))}},
          {"merge",
           {{"time_s", 0.75},
            {"worker", "tcp://127.0.0.1:40001"},
            {"adjustments",
             {{{"usable", true},
               {"num_images", 13},
               {"initial_rmse_px", 0.9},
               {"final_rmse_px", 0.4}}}}}},
          {"models", {{{"num_images", 13}, {"num_points3D", 1234}}}},
          {"wall_time_s", 12.5}};
}

TEST(DistributedRunPage, ShowsEveryChunkAndTheMergedModel) {
  const io::HtmlPage page = DistributedRunPage(SuccessfulRun());
  EXPECT_EQ(page.title, "comic.distributed · 3 chunks");
  EXPECT_EQ(Fact(page, "status")["value"], "success");
  EXPECT_EQ(Fact(page, "status")["tone"], "good");
  EXPECT_EQ(Fact(page, "registered")["value"], "13 of 13 frames (100 %) in the first model");
  EXPECT_EQ(Fact(page, "chunks")["value"], "3 (0 failed)");
  EXPECT_EQ(Fact(page, "first model")["value"], "13 frames, 1234 3-D points");
  EXPECT_EQ(Fact(page, "merge")["value"], "0.75 s on worker tcp://127.0.0.1:40001");
  EXPECT_FALSE(HasSection(page, "Chunks that failed for good"));
  EXPECT_FALSE(HasSection(page, "Frames left out"));

  const nlohmann::json& chunks = Section(page, "Chunks");
  EXPECT_EQ(chunks["columns"], nlohmann::json({"chunk", "clip", "frames", "worker", "time (s)",
                                               "status", "registered", "merge"}));
  ASSERT_EQ(chunks["rows"].size(), 3u);
  EXPECT_EQ(chunks["rows"][1], nlohmann::json({"1", "0", "4–8 (5 frames)", "tcp://127.0.0.1:40001",
                                               "2.50", "success", "5",
                                               "joined model 0 through 1 shared frame, 290 of "
                                               "300 point pairs agreeing, scale 0.5"}));
  EXPECT_EQ(chunks["rows"][0][7], "began model 0");
  EXPECT_EQ(chunks["links"], nlohmann::json({"chunks/0000/report.html", "chunks/0001/report.html",
                                             "chunks/0002/report.html"}));
  EXPECT_EQ(chunks["durations"], true);  // left out when pages are compared

  const nlohmann::json& models = Section(page, "Merged models");
  EXPECT_EQ(models["rows"], nlohmann::json({{"0", ". and sparse/0", "13", "1234"}}));
  const nlohmann::json& windows = Section(page, "Adjustment of the merged models");
  EXPECT_EQ(windows["rows"], nlohmann::json({{"0", "13", "0.900", "0.400"}}));
  EXPECT_EQ(Section(page, "report.json")["document"], SuccessfulRun());
}

// A chunk failed for good (no worker, time or path of its own), the chunk after it began a
// model of its own.
nlohmann::json PartialRun() {
  nlohmann::json report = SuccessfulRun();
  report["status"] = "partial";
  report["num_registered"] = 5;
  report["unregistered_frames"] = {"a5", "a6", "a7", "a8", "a9", "a10", "a11", "a12", "a13"};
  report["failed_chunks"] = {{{"index", 1}, {"frames", {"a4", "a5", "a6", "a7", "a8"}}}};
  // A chunk that failed for good has no worker, time or path of its own.
  report["chunks"][1] = {{"index", 1},          {"clip", 0},
                         {"first", 4},          {"last", 8},
                         {"num_frames", 5},     {"status", "failed"},
                         {"num_registered", 0}, {"path", nullptr},
                         {"merge", nullptr},    {"error", "RuntimeError('worker lost')"}};
  report["chunks"][2]["merge"] = Merge(1, 0, 0, 0, 1.0, "no frame registered in both");
  report["models"] = {{{"num_images", 5}, {"num_points3D", 600}},
                      {{"num_images", 5}, {"num_points3D", 500}}};
  return report;
}

TEST(DistributedRunPage, PartialRunNamesTheFailedChunkAndTheModelsOfTheirOwn) {
  const io::HtmlPage page = DistributedRunPage(PartialRun());
  EXPECT_EQ(Fact(page, "status")["tone"], "warning");
  EXPECT_EQ(Fact(page, "registered")["value"], "5 of 13 frames (38 %) in the first model");
  EXPECT_EQ(Fact(page, "chunks")["value"], "3 (1 failed)");
  EXPECT_EQ(Fact(page, "chunks")["tone"], "bad");
  const nlohmann::json& failed = Section(page, "Chunks that failed for good");
  EXPECT_EQ(failed["tone"], "bad");
  EXPECT_NE(failed["text"].get<std::string>().find(
                "Chunk 1 (clip 0, frames 4–8: 5 frames) failed after its retries: "
                "RuntimeError('worker lost')."),
            std::string::npos);
  const nlohmann::json& left_out = Section(page, "Frames left out");
  EXPECT_EQ(left_out["text"],
            "9 frames are not in the first model: a5, a6, a7, a8, a9, a10, "
            "a11, a12, ….");
  const nlohmann::json& rows = Section(page, "Chunks")["rows"];
  EXPECT_EQ(rows[1], nlohmann::json({"1", "0", "4–8 (5 frames)", "", "", "failed", "0",
                                     "not merged: the chunk failed"}));
  EXPECT_EQ(rows[2][7], "began model 1: no frame registered in both");
  EXPECT_EQ(Section(page, "Chunks")["links"][1], "");
  EXPECT_EQ(Section(page, "Merged models")["rows"][1],
            nlohmann::json({"1", "sparse/1", "5", "500"}));
}

TEST(DistributedRunPage, IsWrittenWholeAsOneFile) {
  ScopedTempDir dir;
  const std::string path = io::JoinPaths(dir.path(), "report.html");
  io::WriteHtmlPage(path, DistributedRunPage(SuccessfulRun()));
  const std::string html = io::ReadFileToString(path);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("tcp://127.0.0.1:40002"), std::string::npos);
  EXPECT_NE(html.find("</html>"), std::string::npos);
  // Nothing staged is left beside it.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(DistributedRunPage, DrawsInChromium) {
  ScopedTempDir dir;
  const std::string path = io::JoinPaths(dir.path(), "report.html");
  io::WriteHtmlPage(path, DistributedRunPage(PartialRun()));
  std::string why;
  const auto page = comic::test::LoadInChromium(path, 1280, 900, &why);
  if (!page) GTEST_SKIP() << why;
  EXPECT_EQ(comic::test::HtmlAttribute(page->dom, "data-comic-page"), "drawn");
  EXPECT_NE(page->dom.find("id=\"comic-page-errors\" hidden"), std::string::npos);
  EXPECT_NE(page->dom.find("Chunks that failed for good"), std::string::npos);
  EXPECT_NE(page->dom.find("tcp://127.0.0.1:40002"), std::string::npos);
  EXPECT_NE(page->dom.find("began model 1: no frame registered in both"), std::string::npos);
  EXPECT_EQ(comic::test::HtmlAttribute(page->dom, "data-scene"), "");  // no 3-D view
}

TEST(DistributedRunPage, RefusesABrokenReportNamingTheField) {
  nlohmann::json report = SuccessfulRun();
  report.erase("num_frames");
  try {
    DistributedRunPage(report);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("'num_frames'"), std::string::npos);
  }
  report = SuccessfulRun();
  report["chunks"][0]["num_registered"] = "five";
  EXPECT_THROW(DistributedRunPage(report), Error);
}

}  // namespace
}  // namespace comic::sfm
