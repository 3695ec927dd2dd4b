#include "seaplan/pddl/type_hierarchy.h"

#include <vector>

#include "gtest/gtest.h"

namespace seaplan::pddl {
namespace {

TEST(TypeHierarchyTest, IdsAndTransitiveAncestors) {
  // vessel - object; tug ferry - vessel; harbour-tug - tug; and a parent with
  // no declaration of its own.
  const std::vector<TypeDecl> types = {{"vessel", {"object"}, {}},
                                       {"tug", {"vessel"}, {}},
                                       {"ferry", {"vessel"}, {}},
                                       {"harbour-tug", {"tug", "asset"}, {}}};
  const TypeHierarchy h(types);
  EXPECT_EQ(h.Id("object"), 0);
  EXPECT_EQ(h.Id("vessel"), 1);
  EXPECT_EQ(h.Id("harbour-tug"), 4);
  EXPECT_EQ(h.Id("asset"), 5);  // undeclared parents come after the declared types
  EXPECT_EQ(h.Id("port"), -1);
  EXPECT_EQ(h.size(), 6);
  EXPECT_EQ(h.Name(2), "tug");

  EXPECT_TRUE(h.IsSubtype("harbour-tug", "vessel"));
  EXPECT_TRUE(h.IsSubtype("harbour-tug", "asset"));
  EXPECT_TRUE(h.IsSubtype("ferry", "object"));
  EXPECT_TRUE(h.IsSubtype("tug", "tug"));
  EXPECT_FALSE(h.IsSubtype("tug", "ferry"));
  EXPECT_FALSE(h.IsSubtype("vessel", "tug"));
  EXPECT_FALSE(h.IsSubtype("object", "vessel"));
  // Undeclared names: themselves and object only.
  EXPECT_TRUE(h.IsSubtype("port", "port"));
  EXPECT_TRUE(h.IsSubtype("port", "object"));
  EXPECT_FALSE(h.IsSubtype("port", "vessel"));
  EXPECT_EQ(h.FindCycle(), "");
}

TEST(TypeHierarchyTest, DuplicateDeclarationsMergeParents) {
  const std::vector<TypeDecl> types = {
      {"a", {"b"}, {}}, {"b", {"object"}, {}}, {"c", {"object"}, {}}, {"a", {"c"}, {}}};
  const TypeHierarchy h(types);
  EXPECT_EQ(h.size(), 4);
  EXPECT_TRUE(h.IsSubtype("a", "b"));
  EXPECT_TRUE(h.IsSubtype("a", "c"));
  EXPECT_FALSE(h.IsSubtype("b", "c"));
}

TEST(TypeHierarchyTest, FindsCyclesAndIgnoresSelfParents) {
  const std::vector<TypeDecl> self = {{"a", {"a"}, {}}};
  EXPECT_EQ(TypeHierarchy(self).FindCycle(), "");
  const std::vector<TypeDecl> cycle = {
      {"root", {"object"}, {}}, {"a", {"b"}, {}}, {"b", {"c"}, {}}, {"c", {"a"}, {}}};
  const TypeHierarchy h(cycle);
  EXPECT_EQ(h.FindCycle(), "a");
  EXPECT_TRUE(h.IsSubtype("a", "c"));
  EXPECT_TRUE(h.IsSubtype("c", "a"));
  EXPECT_FALSE(h.IsSubtype("a", "root"));
}

TEST(TypeHierarchyTest, CopiesAnswerLikeTheOriginal) {
  const std::vector<TypeDecl> types = {{"tug", {"vessel"}, {}}, {"vessel", {"object"}, {}}};
  TypeHierarchy copy;
  {
    const TypeHierarchy original(types);
    copy = original;
  }
  EXPECT_EQ(copy.Id("vessel"), 2);
  EXPECT_TRUE(copy.IsSubtype("tug", "vessel"));
}

}  // namespace
}  // namespace seaplan::pddl
