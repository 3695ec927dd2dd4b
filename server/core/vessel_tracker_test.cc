#include "server/core/vessel_tracker.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <thread>

#include "seaplan/storage/sqlite_store.h"

namespace seaplan::server {
namespace {

class VesselTrackerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("seaplan-vessel-tracker-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    auto store = storage::SqliteStore::Open((dir_ / "seaplan.db").string());
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = std::move(*store);
    storage::MissionRecord mission;
    mission.id = "m-1";
    mission.name = "m";
    mission.vessel_id = "mass-1";
    storage::PlanVersionRecord version;
    version.mission_id = "m-1";
    version.version = 1;
    ASSERT_TRUE(store_->missions().Create(mission, version, {}).ok());
  }
  void TearDown() override {
    if (store_) {
      EXPECT_TRUE(store_->Close().ok());
    }
    std::filesystem::remove_all(dir_);
  }

  static v1::ReportVesselStateRequest At(double lat) {
    v1::ReportVesselStateRequest req;
    req.set_mission_id("m-1");
    req.set_vessel_id("mass-1");
    req.mutable_state()->mutable_position()->set_latitude_deg(lat);
    req.mutable_state()->mutable_position()->set_longitude_deg(10.4);
    return req;
  }

  std::filesystem::path dir_;
  std::unique_ptr<storage::SqliteStore> store_;
  CallContext call_;
};

TEST_F(VesselTrackerTest, AtMostOneUpdatePerIntervalAndTheNewestIsKept) {
  VesselTracker tracker(store_->missions(), {std::chrono::hours(1), 100});
  auto first = tracker.ReportVesselState(At(63.40), call_);
  ASSERT_TRUE(first.ok()) << first.status();
  EXPECT_TRUE(first->published());
  auto second = tracker.ReportVesselState(At(63.41), call_);
  ASSERT_TRUE(second.ok());
  EXPECT_FALSE(second->published());  // inside the interval: kept, not sent

  auto update = tracker.Next("m-1", 0, true, std::chrono::milliseconds(0));
  ASSERT_TRUE(update.has_value());
  EXPECT_EQ(update->sequence(), 1);
  EXPECT_DOUBLE_EQ(update->state().position().latitude_deg(), 63.40);
  EXPECT_EQ(update->vessel_id(), "mass-1");
  // Nothing newer is published within the hour.
  EXPECT_FALSE(tracker.Next("m-1", 1, false, std::chrono::milliseconds(30)).has_value());
}

TEST_F(VesselTrackerTest, EveryReportPublishedWithoutAnIntervalAndTheTrackGrows) {
  VesselTracker tracker(store_->missions(), {std::chrono::milliseconds(0), 3});
  for (int i = 0; i < 5; ++i) {
    auto r = tracker.ReportVesselState(At(63.40 + 0.01 * i), call_);
    ASSERT_TRUE(r.ok());
    EXPECT_TRUE(r->published());
  }
  auto update = tracker.Next("m-1", 0, true, std::chrono::milliseconds(0));
  ASSERT_TRUE(update.has_value());
  EXPECT_EQ(update->sequence(), 5);
  EXPECT_DOUBLE_EQ(update->state().position().latitude_deg(), 63.44);
  // The track keeps the last 3 published positions; the update's own is not
  // repeated in it.
  ASSERT_EQ(update->track_size(), 2);
  EXPECT_DOUBLE_EQ(update->track(0).latitude_deg(), 63.42);
  EXPECT_DOUBLE_EQ(update->track(1).latitude_deg(), 63.43);
  EXPECT_EQ(tracker.Next("m-1", 0, false, std::chrono::milliseconds(0))->track_size(), 0);
}

TEST_F(VesselTrackerTest, RefusesUnknownMissionsOtherVesselsAndBadPositions) {
  VesselTracker tracker(store_->missions());
  auto unknown = At(63.4);
  unknown.set_mission_id("m-nope");
  EXPECT_EQ(tracker.ReportVesselState(unknown, call_).status().code(), absl::StatusCode::kNotFound);
  auto other = At(63.4);
  other.set_vessel_id("intruder");
  EXPECT_EQ(tracker.ReportVesselState(other, call_).status().code(),
            absl::StatusCode::kPermissionDenied);
  EXPECT_EQ(tracker.ReportVesselState(At(91), call_).status().code(),
            absl::StatusCode::kInvalidArgument);
  v1::ReportVesselStateRequest no_position;
  no_position.set_mission_id("m-1");
  EXPECT_EQ(tracker.ReportVesselState(no_position, call_).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_FALSE(tracker.Next("m-1", 0, false, std::chrono::milliseconds(0)).has_value());
}

TEST_F(VesselTrackerTest, CloseWakesAWaitingWatcher) {
  VesselTracker tracker(store_->missions());
  std::thread closer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    tracker.Close();
  });
  // Without Close this would wait the full minute.
  EXPECT_FALSE(tracker.Next("m-1", 0, false, std::chrono::minutes(1)).has_value());
  closer.join();
}

}  // namespace
}  // namespace seaplan::server
