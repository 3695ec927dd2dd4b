#include "server/auth/csrf.h"

#include <gtest/gtest.h>

#include "server/auth/token.h"

namespace seaplan::server::auth {
namespace {

TEST(CsrfTest, DerivedFromTheTokenAndCheckedExactly) {
  auto a = GenerateToken();
  auto b = GenerateToken();
  ASSERT_TRUE(a.ok() && b.ok());
  const std::string csrf = CsrfTokenFor(a->bearer);
  EXPECT_EQ(csrf.size(), 43u);
  EXPECT_EQ(csrf, CsrfTokenFor(a->bearer));  // any replica computes the same
  EXPECT_NE(csrf, CsrfTokenFor(b->bearer));
  // It reveals nothing of the token it is derived from.
  EXPECT_EQ(csrf.find(a->bearer.substr(25, 8)), std::string::npos);
  EXPECT_TRUE(CsrfTokenMatches(a->bearer, csrf));
  EXPECT_FALSE(CsrfTokenMatches(b->bearer, csrf));
  EXPECT_FALSE(CsrfTokenMatches(a->bearer, ""));
  EXPECT_FALSE(CsrfTokenMatches(a->bearer, csrf.substr(1)));
  EXPECT_FALSE(CsrfTokenMatches("", CsrfTokenFor("")));
}

}  // namespace
}  // namespace seaplan::server::auth
