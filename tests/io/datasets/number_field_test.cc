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

// A file that fails to parse is quoted only as far as a short prefix (a poses file may be any
// file the user can read, /etc/shadow when run as root).
TEST(NumberField, QuotesOnlyAShortPrefix) {
  EXPECT_EQ(QuotedField("12x"), "'12x'");
  EXPECT_EQ(QuotedField(std::string(kQuotedFieldLength, 'a')),
            "'" + std::string(kQuotedFieldLength, 'a') + "'");
  EXPECT_EQ(QuotedField("root:$6$saltsaltsalt$hashhashhashhashhash:19000:0:99999:7:::"),
            "'root:$6$saltsaltsalt$has...'");
}

}  // namespace
}  // namespace comic::io
