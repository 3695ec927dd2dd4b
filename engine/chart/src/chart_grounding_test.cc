#include "seaplan/chart/chart_grounding_test.h"

#include <array>
#include <atomic>
#include <utility>
#include <vector>

namespace seaplan::chart {
namespace {

std::atomic<uint64_t> next_id{1};

struct QueryCache {
  static constexpr size_t kMaxEntries = 8;
  // (adapter id, its query). Ids are never reused, so a stale entry of a
  // destroyed adapter is never returned; the ObstacleQuery owns copies of
  // the geometry, so it does not dangle either.
  std::vector<std::pair<uint64_t, std::unique_ptr<ObstacleQuery>>> entries;
};

}  // namespace

ChartGroundingTest::ChartGroundingTest(std::shared_ptr<const ObstacleMap> map, EastNorth origin)
    : map_(std::move(map)), origin_(origin), id_(next_id.fetch_add(1)) {}

ObstacleQuery& ChartGroundingTest::Query() const {
  thread_local QueryCache cache;
  for (auto& [id, query] : cache.entries) {
    if (id == id_) return *query;
  }
  if (cache.entries.size() >= QueryCache::kMaxEntries) cache.entries.erase(cache.entries.begin());
  cache.entries.emplace_back(id_, std::make_unique<ObstacleQuery>(*map_));
  return *cache.entries.back().second;
}

namespace {
std::array<EastNorth, 4> ToChart(const risk::HullPolygon& hull, EastNorth origin) {
  std::array<EastNorth, 4> out;
  for (size_t i = 0; i < 4; ++i) {
    out[i] = {origin.east_m + hull.corners_ne[i][1], origin.north_m + hull.corners_ne[i][0]};
  }
  return out;
}
}  // namespace

bool ChartGroundingTest::HullIntersects(const risk::HullPolygon& hull) const {
  const auto ring = ToChart(hull, origin_);
  return Query().PolygonHits(ring);
}

double ChartGroundingTest::Clearance(const risk::HullPolygon& hull) const {
  const auto ring = ToChart(hull, origin_);
  return Query().PolygonDistanceM(ring);
}

}  // namespace seaplan::chart
