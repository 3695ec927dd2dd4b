#include "server/auth/authenticator.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <atomic>
#include <fstream>
#include <thread>
#include <vector>

#include "seaplan/storage/sqlite_store.h"
#include "server/auth/bootstrap.h"

namespace seaplan::server::auth {
namespace {

class AuthenticatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto store = storage::SqliteStore::Open(":memory:");
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = std::move(*store);
  }
  Authenticator Auth() {
    return Authenticator(store_->tokens(), [this] { return now_ms_; });
  }

  std::unique_ptr<storage::SqliteStore> store_;
  storage::TimestampMs now_ms_ = 1'000'000;
};

TEST_F(AuthenticatorTest, IssuedTokenAuthenticatesWithItsRoleAndVessel) {
  Authenticator auth = Auth();
  auto issued = auth.Issue(Role::kVessel, "mass-1", "ship", 0, "admin-id");
  ASSERT_TRUE(issued.ok()) << issued.status();
  // Only the hash is stored.
  auto stored = store_->tokens().Get(issued->record.id);
  ASSERT_TRUE(stored.ok());
  EXPECT_EQ(issued->bearer.find(stored->secret_hash), std::string::npos);
  EXPECT_EQ(stored->created_by, "admin-id");

  auto caller = auth.Authenticate("Bearer " + issued->bearer);
  ASSERT_TRUE(caller.ok()) << caller.status();
  EXPECT_EQ(caller->token_id, issued->record.id);
  EXPECT_EQ(caller->role, Role::kVessel);
  EXPECT_EQ(caller->vessel_id, "mass-1");
  EXPECT_TRUE(auth.Authenticate("bearer  " + issued->bearer + " ").ok());

  EXPECT_TRUE(auth.Check("MissionService/ReportFeedback", "Bearer " + issued->bearer).ok());
  EXPECT_EQ(auth.Check("MissionService/CreateMission", "Bearer " + issued->bearer).status().code(),
            absl::StatusCode::kPermissionDenied);
}

TEST_F(AuthenticatorTest, BadCredentialsAreUnauthenticated) {
  Authenticator auth = Auth();
  auto issued = auth.Issue(Role::kOperator, "", "", 60'000, "");
  ASSERT_TRUE(issued.ok());
  const std::string& b = issued->bearer;
  auto code = [&](const std::string& header) { return auth.Authenticate(header).status().code(); };
  EXPECT_EQ(code(""), absl::StatusCode::kUnauthenticated);
  EXPECT_EQ(code(b), absl::StatusCode::kUnauthenticated);  // no "Bearer "
  EXPECT_EQ(code("Basic " + b), absl::StatusCode::kUnauthenticated);
  EXPECT_EQ(code("Bearer garbage"), absl::StatusCode::kUnauthenticated);
  // Right id, wrong secret.
  std::string wrong = b;
  wrong.back() = wrong.back() == 'A' ? 'B' : 'A';
  EXPECT_EQ(code("Bearer " + wrong), absl::StatusCode::kUnauthenticated);
  // Unknown id.
  auto other = GenerateToken();
  ASSERT_TRUE(other.ok());
  EXPECT_EQ(code("Bearer " + other->bearer), absl::StatusCode::kUnauthenticated);

  EXPECT_EQ(code("Bearer " + b), absl::StatusCode::kOk);
  now_ms_ += 60'000;  // expiry reached
  EXPECT_EQ(code("Bearer " + b), absl::StatusCode::kUnauthenticated);
  now_ms_ -= 1;
  EXPECT_EQ(code("Bearer " + b), absl::StatusCode::kOk);
  ASSERT_TRUE(store_->tokens().Revoke(issued->record.id, now_ms_).ok());
  auto revoked = auth.Authenticate("Bearer " + b);
  EXPECT_EQ(revoked.status().code(), absl::StatusCode::kUnauthenticated);
  EXPECT_NE(revoked.status().message().find("revoked"), std::string_view::npos);
}

TEST_F(AuthenticatorTest, IssueChecksVesselBinding) {
  Authenticator auth = Auth();
  EXPECT_EQ(auth.Issue(Role::kVessel, "", "", 0, "").status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(auth.Issue(Role::kViewer, "mass-1", "", 0, "").status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(auth.Issue(Role::kViewer, "", "", -5, "").status().code(),
            absl::StatusCode::kInvalidArgument);
}

std::filesystem::path FreshDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() /
             ("seaplan-auth-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

TEST_F(AuthenticatorTest, FirstStartWritesAnAdminTokenOnceWithMode0600) {
  Authenticator auth = Auth();
  const auto dir = FreshDir("first");
  auto first = EnsureAdminToken(auth, store_->tokens(), "", dir);
  ASSERT_TRUE(first.ok()) << first.status();
  ASSERT_FALSE(first->created_bearer.empty());
  EXPECT_EQ(first->created_file, dir / "admin.token");
  struct stat st {};
  ASSERT_EQ(::stat(first->created_file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  auto from_file = ReadTokenFile(first->created_file);
  ASSERT_TRUE(from_file.ok());
  EXPECT_EQ(*from_file, first->created_bearer);
  auto caller = auth.AuthenticateToken(*from_file);
  ASSERT_TRUE(caller.ok());
  EXPECT_EQ(caller->role, Role::kAdmin);
  // The second start creates nothing.
  auto second = EnsureAdminToken(auth, store_->tokens(), "", dir);
  ASSERT_TRUE(second.ok());
  EXPECT_TRUE(second->created_bearer.empty());
  // With every admin token revoked, the next start makes a new one.
  ASSERT_TRUE(store_->tokens().Revoke(caller->token_id, now_ms_).ok());
  auto third = EnsureAdminToken(auth, store_->tokens(), "", dir);
  ASSERT_TRUE(third.ok());
  EXPECT_FALSE(third->created_bearer.empty());
  EXPECT_NE(third->created_bearer, first->created_bearer);
  std::filesystem::remove_all(dir);
}

// Servers starting at once on one data folder (here: threads, each with its
// own connection to the folder's database): one creates the admin token and
// writes the file, the others find it; no temporary file is left behind.
TEST_F(AuthenticatorTest, FirstStartsAtOnceCreateOneAdminTokenAndOneFile) {
  constexpr int kServers = 4, kRounds = 5;
  for (int round = 0; round < kRounds; ++round) {
    const auto dir = FreshDir("at-once-" + std::to_string(round));
    std::filesystem::create_directories(dir);
    std::vector<std::unique_ptr<storage::SqliteStore>> stores;
    for (int i = 0; i < kServers; ++i) {
      auto store = storage::SqliteStore::Open((dir / "seaplan.db").string());
      ASSERT_TRUE(store.ok()) << store.status();
      stores.push_back(std::move(*store));
    }
    std::vector<absl::StatusOr<BootstrapResult>> results(kServers, absl::UnknownError("not run"));
    std::atomic<int> ready{0};
    std::vector<std::thread> servers;
    servers.reserve(kServers);
    for (int i = 0; i < kServers; ++i) {
      servers.emplace_back([&, i] {
        const Authenticator auth(stores[i]->tokens());
        ++ready;
        while (ready.load() < kServers) {
        }
        results[i] = EnsureAdminToken(auth, stores[i]->tokens(), "", dir);
      });
    }
    for (std::thread& t : servers) t.join();
    std::string created;
    for (const auto& r : results) {
      ASSERT_TRUE(r.ok()) << r.status();
      if (r->created_bearer.empty()) continue;
      EXPECT_TRUE(created.empty()) << "round " << round << ": two servers created a token";
      created = r->created_bearer;
    }
    ASSERT_FALSE(created.empty()) << "round " << round;
    EXPECT_EQ(*ReadTokenFile(dir / "admin.token"), created);
    EXPECT_EQ(stores[0]->tokens().List()->size(), 1u);
    EXPECT_TRUE(Authenticator(stores[0]->tokens()).AuthenticateToken(created).ok());
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      EXPECT_EQ(entry.path().filename().string().find("admin.token."), std::string::npos)
          << "left behind: " << entry.path();
    }
    for (auto& store : stores) ASSERT_TRUE(store->Close().ok());
    std::filesystem::remove_all(dir);
  }
}

TEST_F(AuthenticatorTest, AdminTokenFileIsImportedOnce) {
  Authenticator auth = Auth();
  const auto dir = FreshDir("import");
  std::filesystem::create_directories(dir);
  auto token = GenerateToken();
  ASSERT_TRUE(token.ok());
  const auto file = dir / "given.token";
  std::ofstream(file) << token->bearer << "\n";
  for (int start = 0; start < 2; ++start) {
    auto r = EnsureAdminToken(auth, store_->tokens(), file.string(), dir);
    ASSERT_TRUE(r.ok()) << r.status();
    EXPECT_TRUE(r->created_bearer.empty());
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "admin.token"));
  auto caller = auth.AuthenticateToken(token->bearer);
  ASSERT_TRUE(caller.ok()) << caller.status();
  EXPECT_EQ(caller->role, Role::kAdmin);
  EXPECT_EQ(store_->tokens().List()->size(), 1u);

  // Same id, other secret: refused.
  std::string forged = token->bearer;
  forged.back() = forged.back() == 'A' ? 'B' : 'A';
  std::ofstream(file) << forged << "\n";
  EXPECT_EQ(EnsureAdminToken(auth, store_->tokens(), file.string(), dir).status().code(),
            absl::StatusCode::kFailedPrecondition);
  std::ofstream(file) << "not a token\n";
  EXPECT_EQ(EnsureAdminToken(auth, store_->tokens(), file.string(), dir).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(
      EnsureAdminToken(auth, store_->tokens(), (dir / "missing").string(), dir).status().code(),
      absl::StatusCode::kNotFound);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace seaplan::server::auth
