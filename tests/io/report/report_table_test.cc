#include "io/report/report_table.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/core/error.h"

namespace comic::io {
namespace {

ReportTable Example() {
  ReportTable table({"detector", "M_score %", "ResM"});
  table.SetPrecision("M_score %", 1);
  table.AddRow({std::string("comic"), 40.94, int64_t{27}});
  table.AddRow({std::string("harris, full"), 24.66, ReportTable::Cell{}});
  return table;
}

TEST(ReportTable, Markdown) {
  EXPECT_EQ(Example().ToMarkdown(),
            "| detector | M_score % | ResM |\n"
            "|---|---:|---:|\n"
            "| comic | 40.9 | 27 |\n"
            "| harris, full | 24.7 | – |\n");
}

TEST(ReportTable, CsvQuotesWhereNeeded) {
  EXPECT_EQ(Example().ToCsv(),
            "detector,M_score %,ResM\n"
            "comic,40.9,27\n"
            "\"harris, full\",24.7,\n");
}

TEST(ReportTable, JsonKeepsFullPrecisionAndNulls) {
  const nlohmann::json json = Example().ToJson();
  ASSERT_EQ(json.size(), 2u);
  EXPECT_DOUBLE_EQ(json[0]["M_score %"].get<double>(), 40.94);
  EXPECT_EQ(json[0]["ResM"].get<int64_t>(), 27);
  EXPECT_TRUE(json[1]["ResM"].is_null());
}

TEST(ReportTable, NonFiniteNumbers) {
  ReportTable table({"x"});
  table.AddRow({std::nan("")});
  EXPECT_NE(table.ToMarkdown().find("nan"), std::string::npos);
  EXPECT_TRUE(table.ToJson()[0]["x"].is_null());
}

TEST(ReportTable, RejectsBadShapes) {
  ReportTable table({"a", "b"});
  EXPECT_THROW(table.AddRow({int64_t{1}}), Error);
  EXPECT_THROW(table.SetPrecision("c", 2), Error);
  EXPECT_THROW(ReportTable({}), Error);
}

}  // namespace
}  // namespace comic::io
