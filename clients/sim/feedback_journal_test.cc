#include "feedback_journal.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace seaplan::sim {
namespace {

namespace fs = std::filesystem;

class FeedbackJournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("seaplan-journal-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = (dir_ / "feedback.journal").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  std::string path_;
};

TEST_F(FeedbackJournalTest, ReopenedJournalHandsBackTheUnacknowledgedReportsInOrder) {
  {
    auto j = FeedbackJournal::Open(path_);
    ASSERT_TRUE(j.ok()) << j.status();
    EXPECT_TRUE(j->unacknowledged_at_open().empty());
    EXPECT_EQ(j->max_sequence(), 0);
    // Binary payloads (NUL, newline, space) survive the text format.
    ASSERT_TRUE(j->Append({{10, std::string("a\n b\0c", 6)}, {11, "second"}}).ok());
    ASSERT_TRUE(j->Append({{12, "third"}}).ok());
    ASSERT_TRUE(j->Acknowledge(11).ok());
  }
  auto j = FeedbackJournal::Open(path_);
  ASSERT_TRUE(j.ok()) << j.status();
  ASSERT_EQ(j->unacknowledged_at_open().size(), 2u);
  EXPECT_EQ(j->unacknowledged_at_open()[0].sequence, 10);
  EXPECT_EQ(j->unacknowledged_at_open()[0].payload, std::string("a\n b\0c", 6));
  EXPECT_EQ(j->unacknowledged_at_open()[1].sequence, 12);
  EXPECT_EQ(j->unacknowledged_at_open()[1].payload, "third");
  EXPECT_EQ(j->max_sequence(), 12);
  // Acknowledging the rest in a second run leaves nothing for a third.
  ASSERT_TRUE(j->Acknowledge(10).ok());
  ASSERT_TRUE(j->Acknowledge(12).ok());
  *j = std::move(*FeedbackJournal::Open(path_));  // the first handle is closed first
  EXPECT_TRUE(j->unacknowledged_at_open().empty());
  EXPECT_EQ(j->max_sequence(), 12);
}

TEST_F(FeedbackJournalTest, TornLastLineIsDroppedAndTheNextRecordStartsOnItsOwnLine) {
  {
    auto j = FeedbackJournal::Open(path_);
    ASSERT_TRUE(j.ok()) << j.status();
    ASSERT_TRUE(j->Append({{1, "kept"}}).ok());
  }
  {
    std::ofstream out(path_, std::ios::app);
    out << "R 2 dG9y";  // a crash in the middle of the second record
  }
  {
    auto j = FeedbackJournal::Open(path_);
    ASSERT_TRUE(j.ok()) << j.status();
    ASSERT_EQ(j->unacknowledged_at_open().size(), 1u);
    EXPECT_EQ(j->unacknowledged_at_open()[0].payload, "kept");
    ASSERT_TRUE(j->Append({{3, "after"}}).ok());
  }
  auto j = FeedbackJournal::Open(path_);
  ASSERT_TRUE(j.ok()) << j.status();
  ASSERT_EQ(j->unacknowledged_at_open().size(), 2u);
  EXPECT_EQ(j->unacknowledged_at_open()[1].sequence, 3);
  EXPECT_EQ(j->unacknowledged_at_open()[1].payload, "after");
}

TEST_F(FeedbackJournalTest, DamagedRecordIsRefusedWithItsLine) {
  {
    std::ofstream out(path_);
    out << "R 1 a2VwdA==\nX 2\n";
  }
  auto j = FeedbackJournal::Open(path_);
  ASSERT_FALSE(j.ok());
  EXPECT_EQ(j.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_NE(j.status().message().find("feedback.journal:2:"), std::string::npos) << j.status();
}

TEST_F(FeedbackJournalTest, UnwritableFolderIsAClearError) {
  auto j = FeedbackJournal::Open((dir_ / "missing" / "feedback.journal").string());
  ASSERT_FALSE(j.ok());
  EXPECT_NE(j.status().message().find("missing/feedback.journal"), std::string::npos) << j.status();
}

}  // namespace
}  // namespace seaplan::sim
