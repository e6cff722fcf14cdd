#include "io/report/json_text.h"

#include <gtest/gtest.h>

namespace comic::io {
namespace {

TEST(JsonText, WritesIndentedOrOneLine) {
  const nlohmann::json json = {{"frames", "straße/帧"}, {"n", 3}};
  EXPECT_EQ(JsonText(json, -1), "{\"frames\":\"straße/帧\",\"n\":3}");
  EXPECT_EQ(JsonText(json, 1), "{\n \"frames\": \"straße/帧\",\n \"n\": 3\n}\n");
}

// Issue 29: a Latin-1 frame name made dump() throw after the whole reconstruction.
TEST(JsonText, ReplacesBytesThatAreNotUtf8InsteadOfThrowing) {
  const nlohmann::json json = {{"frame", std::string("caf\xe9.png")}};
  EXPECT_THROW(json.dump(), nlohmann::json::type_error);
  EXPECT_EQ(JsonText(json, -1), "{\"frame\":\"caf\xef\xbf\xbd.png\"}");
}

}  // namespace
}  // namespace comic::io
