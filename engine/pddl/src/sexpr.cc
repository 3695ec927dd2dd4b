#include "seaplan/pddl/parser.h"
#include "sexpr_internal.h"

namespace seaplan::pddl::internal {
namespace {

bool IsSpace(unsigned char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

// Characters that end an atom.
bool IsDelimiter(unsigned char c) {
  return IsSpace(c) || c == '(' || c == ')' || c == ';';
}

}  // namespace

ReadResult ReadSExprs(std::string_view text, const std::string& file,
                      std::vector<Diagnostic>& diagnostics) {
  ReadResult result;
  // stack[0] is a pseudo list holding the top-level expressions.
  std::vector<SExpr> stack(1);
  stack.reserve(kMaxNestingDepth + 2);
  int line = 1;
  int column = 1;
  std::size_t i = 0;
  // A UTF-8 byte order mark (files saved by some Windows editors) is skipped.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") i = 3;
  int bad_chars_reported = 0;
  const std::size_t n = text.size();
  while (i < n) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++line;
      column = 1;
      ++i;
      continue;
    }
    if (IsSpace(c)) {
      ++column;
      ++i;
      continue;
    }
    if (c == ';') {
      while (i < n && text[i] != '\n') ++i;
      continue;
    }
    if (c == '(') {
      if (static_cast<int>(stack.size()) > kMaxNestingDepth) {
        diagnostics.push_back(
            {Severity::kError,
             DiagnosticKind::kSyntax,
             {file, line, column},
             "(",
             "nesting deeper than " + std::to_string(kMaxNestingDepth) + " levels",
             "a shallower expression"});
        result.ok = false;
        return result;
      }
      SExpr list;
      list.is_list = true;
      list.line = line;
      list.column = column;
      stack.push_back(std::move(list));
      ++column;
      ++i;
      continue;
    }
    if (c == ')') {
      if (stack.size() == 1) {
        diagnostics.push_back({Severity::kError,
                               DiagnosticKind::kSyntax,
                               {file, line, column},
                               ")",
                               "unmatched ')'",
                               "'(' before it or end of file"});
      } else {
        SExpr done = std::move(stack.back());
        stack.pop_back();
        stack.back().items.push_back(std::move(done));
      }
      ++column;
      ++i;
      continue;
    }
    // An atom: everything up to the next delimiter.
    const int start_column = column;
    std::size_t start = i;
    bool bad = false;
    while (i < n && !IsDelimiter(static_cast<unsigned char>(text[i]))) {
      const unsigned char ch = static_cast<unsigned char>(text[i]);
      if (ch < 0x20 || ch >= 0x7f) bad = true;
      ++i;
      ++column;
    }
    std::string atom(text.substr(start, i - start));
    for (char& ch : atom) {
      if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
    }
    if (bad) {
      // Binary junk or non-ASCII: report (a few times, not per byte) and drop the token.
      if (bad_chars_reported < 5) {
        std::string shown;
        for (unsigned char ch : atom) {
          if (ch >= 0x20 && ch < 0x7f) {
            shown += static_cast<char>(ch);
          } else {
            static const char* kHex = "0123456789abcdef";
            shown += "\\x";
            shown += kHex[ch >> 4];
            shown += kHex[ch & 15];
          }
          if (shown.size() > 40) {
            shown += "...";
            break;
          }
        }
        diagnostics.push_back({Severity::kError,
                               DiagnosticKind::kSyntax,
                               {file, line, start_column},
                               shown,
                               "invalid character in token",
                               "printable ASCII"});
      }
      ++bad_chars_reported;
      result.ok = result.ok && bad_chars_reported < 1000;
      continue;
    }
    SExpr leaf;
    leaf.atom = std::move(atom);
    leaf.line = line;
    leaf.column = start_column;
    stack.back().items.push_back(std::move(leaf));
  }
  result.eof_line = line;
  result.eof_column = column;
  if (stack.size() > 1) {
    // Report the outermost unclosed list (where the text was most likely cut
    // off) and the innermost one; then close them all so semantic checks go on.
    const SExpr& innermost = stack.back();
    std::string what = "(";
    if (!innermost.items.empty() && innermost.items[0].IsAtom()) what += innermost.items[0].atom;
    if (innermost.items.size() > 1 && innermost.items[1].IsAtom())
      what += " " + innermost.items[1].atom;
    diagnostics.push_back({Severity::kError,
                           DiagnosticKind::kSyntax,
                           {file, line, column},
                           "end of file",
                           "unexpected end of file: " + std::to_string(stack.size() - 1) +
                               " list(s) not closed; the innermost, '" + what + "' opened at " +
                               std::to_string(innermost.line) + ":" +
                               std::to_string(innermost.column) + ", may be cut off",
                           "')'"});
    while (stack.size() > 1) {
      SExpr done = std::move(stack.back());
      stack.pop_back();
      stack.back().items.push_back(std::move(done));
    }
  }
  result.top_level = std::move(stack[0].items);
  return result;
}

}  // namespace seaplan::pddl::internal
