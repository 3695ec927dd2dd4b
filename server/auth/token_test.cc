#include "server/auth/token.h"

#include <gtest/gtest.h>

#include <set>

namespace seaplan::server::auth {
namespace {

TEST(TokenTest, GeneratedTokensParseAndHashToTheStoredHash) {
  auto t = GenerateToken();
  ASSERT_TRUE(t.ok()) << t.status();
  EXPECT_EQ(t->id.size(), 16u);
  EXPECT_EQ(t->secret_hash.size(), 64u);
  auto parsed = ParseToken(t->bearer);
  ASSERT_TRUE(parsed.ok()) << parsed.status();
  EXPECT_EQ(parsed->id, t->id);
  // 256 bits in base64url without padding.
  EXPECT_EQ(parsed->secret.size(), 43u);
  EXPECT_EQ(HashSecret(parsed->secret), t->secret_hash);
  // The bearer holds the secret, never the hash.
  EXPECT_EQ(t->bearer.find(t->secret_hash), std::string::npos);
}

TEST(TokenTest, TokensDiffer) {
  std::set<std::string> ids, bearers;
  for (int i = 0; i < 200; ++i) {
    auto t = GenerateToken();
    ASSERT_TRUE(t.ok());
    ids.insert(t->id);
    bearers.insert(t->bearer);
  }
  EXPECT_EQ(ids.size(), 200u);
  EXPECT_EQ(bearers.size(), 200u);
}

TEST(TokenTest, MalformedTokensAreUnauthenticated) {
  auto good = GenerateToken();
  ASSERT_TRUE(good.ok());
  const std::string b = good->bearer;
  for (const std::string& bad :
       {std::string(), std::string("seaplan_"), std::string("Bearer ") + b, b.substr(1), b + "x",
        b.substr(0, b.size() - 1), "seaplan_0123456789ABCDEF_" + b.substr(25),
        "seaplan_0123456789abcdef-" + b.substr(25), b.substr(0, 30) + "!" + b.substr(31)}) {
    auto parsed = ParseToken(bad);
    EXPECT_EQ(parsed.status().code(), absl::StatusCode::kUnauthenticated) << bad;
  }
}

TEST(TokenTest, HashIsSha256Hex) {
  // SHA-256("abc"), FIPS 180-2 appendix B.1.
  EXPECT_EQ(HashSecret("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_TRUE(EqualConstantTime("abc", "abc"));
  EXPECT_FALSE(EqualConstantTime("abc", "abd"));
  EXPECT_FALSE(EqualConstantTime("abc", "abcd"));
}

}  // namespace
}  // namespace seaplan::server::auth
