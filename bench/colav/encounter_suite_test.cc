// Every situation of the encounter suite passes its COLREG checks under the
// scenario-based MPC (the expected behaviour is stated per situation in
// encounter_suite.cc).
#include "encounter_suite.h"

#include <gtest/gtest.h>

#include <cctype>
#include <iostream>
#include <set>

namespace seaplan::colav::suite {

// gtest prints parameters in test names and failures: the situation's name,
// not its bytes.
void PrintTo(const Situation& s, std::ostream* os) {
  *os << s.name;
}

namespace {

class EncounterSuiteTest : public ::testing::TestWithParam<Situation> {};

TEST_P(EncounterSuiteTest, KeepsTheSafetyDistanceUnderColreg) {
  const Situation& s = GetParam();
  auto r = suite::Run(s);
  ASSERT_TRUE(r.ok()) << r.status();
  std::string log;
  for (const std::string& line : r->outcome.log) log += "  " + line + "\n";
  for (const std::string& f : r->failures) ADD_FAILURE() << s.name << ": " << f;
  if (!r->failures.empty()) std::cerr << s.description << "\n" << log;
}

std::string Name(const ::testing::TestParamInfo<Situation>& info) {
  std::string n;
  for (char c : info.param.name) n += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Situations, EncounterSuiteTest, ::testing::ValuesIn(Situations()), Name);

TEST(EncounterSuiteCoverage, AtLeastTwentySituationsOfEveryKind) {
  const std::vector<Situation> all = Situations();
  EXPECT_GE(all.size(), 20u);
  int channel = 0, multi = 0;
  std::set<Role> roles;
  for (const Situation& s : all) {
    channel += s.setup.land.empty() ? 0 : 1;
    multi += s.setup.traffic.size() > 1 ? 1 : 0;
    for (const Expectation& e : s.expected) roles.insert(e.role);
  }
  EXPECT_GE(channel, 4);
  EXPECT_GE(multi, 4);
  for (Role r : {Role::kHeadOn, Role::kCrossingGiveWay, Role::kCrossingStandOn, Role::kOvertaking,
                 Role::kOvertaken}) {
    EXPECT_TRUE(roles.contains(r)) << RoleName(r);
  }
}

}  // namespace
}  // namespace seaplan::colav::suite
