#include "fjord_mission.h"

#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_split.h"
#include "gtest/gtest.h"
#include "seaplan/task/grounder.h"
#include "seaplan/testing/shared_data.h"

namespace seaplan::bench {
namespace {

std::string ReadExample(const std::string& name) {
  return seaplan::testing::ReadFile(std::filesystem::path(SEAPLAN_FJORD_EXAMPLES_DIR) / name);
}

// The (name a b) facts of the problem's text, as pairs.
std::vector<std::pair<std::string, std::string>> Facts(const std::string& text,
                                                       const std::string& name) {
  std::vector<std::pair<std::string, std::string>> facts;
  const std::string opening = "(" + name + " ";
  for (std::size_t at = text.find(opening); at != std::string::npos;
       at = text.find(opening, at + 1)) {
    const std::size_t end = text.find(')', at);
    std::vector<std::string> words =
        absl::StrSplit(text.substr(at + opening.size(), end - at - opening.size()), ' ');
    if (words.size() == 2) facts.emplace_back(words[0], words[1]);
  }
  return facts;
}

std::string InitOf(const std::string& text) {
  return text.substr(text.find("(:init"), text.find("(:goal") - text.find("(:init"));
}
std::string GoalOf(const std::string& text) {
  return text.substr(text.find("(:goal"));
}

TEST(FjordMissionTest, SameSpecSameTextOtherSeedOtherText) {
  FjordMissionSpec spec;
  spec.seed = 7;
  const auto first = GenerateFjordMission(spec);
  const auto again = GenerateFjordMission(spec);
  spec.seed = 8;
  const auto other = GenerateFjordMission(spec);
  ASSERT_TRUE(first.ok() && again.ok() && other.ok());
  EXPECT_EQ(*first, *again);
  EXPECT_NE(*first, *other);
}

TEST(FjordMissionTest, GroundsWithBothFjordDomains) {
  const std::string domains[] = {ReadExample("domain.pddl"), ReadExample("domain-fuel.pddl")};
  ASSERT_TRUE(absl::StrContains(domains[0], "(define (domain fjord)"))
      << "examples/fjord/domain.pddl not found in " << SEAPLAN_FJORD_EXAMPLES_DIR;
  for (const auto domain : {FjordDomain::kFjord, FjordDomain::kFjordFuel}) {
    for (const int size : {3, 5}) {
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        FjordMissionSpec spec{domain, size, 4 * size, 4 * size, seed, 3};
        const auto text = GenerateFjordMission(spec);
        ASSERT_TRUE(text.ok()) << text.status();
        const auto loaded =
            task::LoadTask(domains[domain == FjordDomain::kFjordFuel ? 1 : 0], *text);
        ASSERT_TRUE(loaded.ok()) << FjordMissionName(spec) << "\n" << *text;
        EXPECT_TRUE(absl::StrContains(*text, "(define (problem " + FjordMissionName(spec) + ")"));
        EXPECT_TRUE(absl::StrContains(*text, "(:domain " + std::string(FjordDomainName(domain))));
      }
    }
  }
}

TEST(FjordMissionTest, ShipsStartApartRoutesConnectEveryPortAndOneContainerPerShipAtTheEnd) {
  for (const auto domain : {FjordDomain::kFjord, FjordDomain::kFjordFuel}) {
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      const FjordMissionSpec spec{domain, 4, 16, 16, seed, 3};
      const auto text = GenerateFjordMission(spec);
      ASSERT_TRUE(text.ok());
      const std::string init = InitOf(*text), goal = GoalOf(*text);

      std::set<std::string> start_ports;
      std::set<std::string> charger_ports;
      std::map<std::string, std::string> container_origin;
      for (const auto& [subject, port] : Facts(init, "at")) {
        if (absl::StartsWith(subject, "ship")) start_ports.insert(port);
        if (absl::StartsWith(subject, "teamf")) charger_ports.insert(port);
        if (absl::StartsWith(subject, "cont-")) container_origin[subject] = port;
      }
      EXPECT_EQ(start_ports.size(), 4u) << "ships must start at different ports";
      EXPECT_EQ(container_origin.size(), 16u);

      std::map<std::string, std::set<std::string>> routes;
      for (const auto& [from, to] : Facts(init, "connected")) routes[from].insert(to);
      std::set<std::string> reached = {"port-01"};
      std::vector<std::string> frontier = {"port-01"};
      while (!frontier.empty()) {
        const std::string port = frontier.back();
        frontier.pop_back();
        for (const auto& next : routes[port])
          if (reached.insert(next).second) frontier.push_back(next);
      }
      EXPECT_EQ(reached.size(), 16u) << "route graph not connected, seed " << seed;
      if (domain == FjordDomain::kFjordFuel) {
        for (const auto& [port, next] : routes) {
          bool to_charger = charger_ports.count(port) > 0;
          for (const auto& n : next) to_charger = to_charger || charger_ports.count(n) > 0;
          EXPECT_TRUE(to_charger) << port << " has no direct route to a charger";
        }
      }

      std::set<std::string> ships_loaded, goal_containers;
      for (const auto& [container, ship] : Facts(goal, "loaded")) {
        EXPECT_TRUE(ships_loaded.insert(ship).second) << ship << " must carry two containers";
        goal_containers.insert(container);
      }
      for (const auto& [subject, port] : Facts(goal, "at")) {
        if (!absl::StartsWith(subject, "cont-")) continue;
        EXPECT_NE(container_origin[subject], port) << subject << " already delivered";
        goal_containers.insert(subject);
      }
      EXPECT_EQ(goal_containers.size(), 16u) << "every container has one goal";
    }
  }
}

TEST(FjordMissionTest, RejectsSpecsOutOfRange) {
  FjordMissionSpec spec;
  spec.ships = 0;
  EXPECT_EQ(GenerateFjordMission(spec).status().code(), absl::StatusCode::kInvalidArgument);
  spec.ships = 5;
  spec.ports = 4;
  EXPECT_EQ(GenerateFjordMission(spec).status().code(), absl::StatusCode::kInvalidArgument);
  spec.ports = 12;
  spec.containers = 0;
  EXPECT_EQ(GenerateFjordMission(spec).status().code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace seaplan::bench
