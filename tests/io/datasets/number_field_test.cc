// The one number-in-text rule shared by io/datasets' readers: whole field, in range, finite.
#include "io/datasets/number_field.h"

#include <gtest/gtest.h>

#include <string>

namespace comic::io {
namespace {

TEST(NumberField, ReadsTheNumberFormsCalibrationsAreWrittenIn) {
  double value = 0;
  ASSERT_TRUE(ParseNumberField("718.856", &value));
  EXPECT_EQ(value, 718.856);
  ASSERT_TRUE(ParseNumberField("-1.5e-03", &value));
  EXPECT_EQ(value, -1.5e-3);
  ASSERT_TRUE(ParseNumberField("+7", &value));
  EXPECT_EQ(value, 7.0);
  ASSERT_TRUE(ParseNumberField(".5", &value));
  EXPECT_EQ(value, 0.5);
}

TEST(NumberField, RefusesPartialOutOfRangeAndNonFiniteFields) {
  double value = 0;
  EXPECT_FALSE(ParseNumberField("", &value));
  EXPECT_FALSE(ParseNumberField("1.5px", &value));  // trailing letters
  EXPECT_FALSE(ParseNumberField(" 1.5", &value)) << "leading space is not part of a field";
  EXPECT_FALSE(ParseNumberField(std::string("1\0"
                                            "5",
                                            3),
                                &value));            // an embedded NUL
  EXPECT_FALSE(ParseNumberField("1e999", &value));   // overflow
  EXPECT_FALSE(ParseNumberField("1e-400", &value));  // underflow
  EXPECT_FALSE(ParseNumberField("inf", &value));
  EXPECT_FALSE(ParseNumberField("nan", &value));
  EXPECT_FALSE(ParseNumberField("-", &value));
}

}  // namespace
}  // namespace comic::io
