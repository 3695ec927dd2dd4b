// The first parsing stage: text -> a tree of s-expressions with positions.
// Iterative (no recursion), nesting capped at kMaxNestingDepth, tokens lower
// cased, ';' comments skipped. Unbalanced input is repaired (missing ')' are
// added at the end of the file, stray ')' dropped) after reporting a syntax
// error, so later stages can still report semantic errors.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "seaplan/pddl/diagnostic.h"

namespace seaplan::pddl::internal {

struct SExpr {
  bool is_list = false;
  std::string atom;  // lower case; empty for lists
  int line = 0;
  int column = 0;
  std::vector<SExpr> items;  // lists only

  bool IsAtom() const { return !is_list; }
  bool IsAtom(std::string_view text) const { return !is_list && atom == text; }
  // The first item's atom text when this is a list starting with an atom; "" otherwise.
  std::string_view Head() const {
    return is_list && !items.empty() && !items[0].is_list ? std::string_view(items[0].atom)
                                                          : std::string_view();
  }
};

struct ReadResult {
  std::vector<SExpr> top_level;
  bool ok = true;    // false when the input was hopeless (too deep): ignore top_level
  int eof_line = 1;  // position just past the last character
  int eof_column = 1;
};

ReadResult ReadSExprs(std::string_view text, const std::string& file,
                      std::vector<Diagnostic>& diagnostics);

}  // namespace seaplan::pddl::internal
