#include "state_registry.h"

#include <gtest/gtest.h>

namespace seaplan::search {
namespace {

StateData MakeState(const StateRegistry& registry, std::initializer_list<int> facts,
                    std::vector<double> values, std::vector<RunningAction> running) {
  StateData s = registry.MakeEmpty();
  for (int f : facts) s.Set(f);
  s.values = std::move(values);
  s.running = std::move(running);
  return s;
}

TEST(StateRegistryTest, EqualStatesShareAnIdAndUnpackToTheSame) {
  StateRegistry registry(/*num_facts=*/130, /*num_vars=*/2);
  const StateData a =
      MakeState(registry, {0, 64, 129}, {1.5, -2.0}, {{3, 1.0, 2.0}, {7, 4.0, 4.0}});
  bool is_new = false;
  const StateId id = registry.Insert(a, &is_new);
  EXPECT_TRUE(is_new);
  EXPECT_EQ(registry.Insert(a, &is_new), id);
  EXPECT_FALSE(is_new);
  EXPECT_EQ(registry.size(), 1u);

  StateData out;
  registry.Unpack(id, &out);
  EXPECT_EQ(out.facts, a.facts);
  EXPECT_EQ(out.values, a.values);
  EXPECT_EQ(out.running, a.running);
  EXPECT_TRUE(out.Holds(129));
  EXPECT_FALSE(out.Holds(128));
}

TEST(StateRegistryTest, EveryPartOfTheStateDistinguishes) {
  StateRegistry registry(70, 1);
  const StateData base = MakeState(registry, {1, 69}, {3.0}, {{2, 1.0, 1.0}});
  StateData other_fact = base;
  other_fact.Clear(69);
  StateData other_value = base;
  other_value.values[0] = 4.0;
  StateData other_running = base;
  other_running.running[0].max_duration_s = 5.0;
  StateData other_til = base;
  other_til.next_til = 1;
  StateData other_variant = base;
  other_variant.variant = 3;
  bool is_new = false;
  const StateId id = registry.Insert(base, &is_new);
  for (const StateData* s :
       {&other_fact, &other_value, &other_running, &other_til, &other_variant}) {
    EXPECT_NE(registry.Insert(*s, &is_new), id);
    EXPECT_TRUE(is_new);
    StateData out;
    registry.Unpack(registry.Insert(*s, nullptr), &out);
    EXPECT_EQ(out.facts, s->facts);
    EXPECT_EQ(out.values, s->values);
    EXPECT_EQ(out.running, s->running);
    EXPECT_EQ(out.next_til, s->next_til);
    EXPECT_EQ(out.variant, s->variant);
  }
  EXPECT_EQ(registry.size(), 6u);
}

TEST(StateRegistryTest, ValuesAndRunningActionsAreStoredOncePerDistinctSet) {
  StateRegistry registry(10, 3);
  for (int f = 0; f < 10; ++f) {
    registry.Insert(MakeState(registry, {f}, {1.0, 2.0, f % 2 == 0 ? 0.0 : -0.0}, {{4, 2.0, 3.0}}),
                    nullptr);
  }
  EXPECT_EQ(registry.size(), 10u);
  // +0 and -0 are one value, so all ten states share one value vector.
  EXPECT_EQ(registry.distinct_values(), 1u);
  EXPECT_EQ(registry.distinct_running(), 1u);
}

TEST(StateRegistryTest, WithoutNumericVariablesOrRunningActions) {
  StateRegistry registry(0, 0);
  const StateData empty = registry.MakeEmpty();
  bool is_new = false;
  const StateId id = registry.Insert(empty, &is_new);
  EXPECT_TRUE(is_new);
  StateData later = empty;
  later.next_til = 2;
  EXPECT_NE(registry.Insert(later, nullptr), id);
  StateData out;
  registry.Unpack(id, &out);
  EXPECT_TRUE(out.facts.empty());
  EXPECT_TRUE(out.values.empty());
  EXPECT_TRUE(out.running.empty());
  EXPECT_EQ(out.next_til, 0);
}

}  // namespace
}  // namespace seaplan::search
