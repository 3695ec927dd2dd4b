#include "seaplan/common/json.h"

#include <gtest/gtest.h>

namespace seaplan {
namespace {

TEST(JsonStringTest, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(JsonString(""), "\"\"");
  EXPECT_EQ(JsonString("port \"a\"\\b"), "\"port \\\"a\\\"\\\\b\"");
  EXPECT_EQ(JsonString("a\nb\rc\td"), "\"a\\nb\\rc\\td\"");
  EXPECT_EQ(JsonString(std::string_view("\x01\x1f", 2)), "\"\\u0001\\u001f\"");
  EXPECT_EQ(JsonString("Ålesund"), "\"Ålesund\"") << "UTF-8 passes through";
}

}  // namespace
}  // namespace seaplan
