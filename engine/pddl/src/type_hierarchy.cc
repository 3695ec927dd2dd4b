#include "seaplan/pddl/type_hierarchy.h"

namespace seaplan::pddl {

TypeHierarchy::TypeHierarchy(std::span<const TypeDecl> types) {
  auto intern = [&](const std::string& name) {
    auto it = index_.find(name);
    if (it != index_.end()) return it->second;
    const int id = static_cast<int>(names_.size());
    names_.push_back(name);
    index_.emplace(name, id);
    return id;
  };
  intern("object");
  for (const TypeDecl& t : types) intern(t.name);
  for (const TypeDecl& t : types) {
    for (const std::string& p : t.parents) intern(p);
  }
  parents_.assign(names_.size(), {});
  for (const TypeDecl& t : types) {
    const int child = Id(t.name);
    for (const std::string& p : t.parents) {
      const int parent = Id(p);
      if (parent != child) parents_[static_cast<std::size_t>(child)].push_back(parent);
    }
  }
  const std::size_t n = names_.size();
  words_per_row_ = (n + 63) / 64;
  ancestor_bits_.assign(n * words_per_row_, 0);
  auto set = [&](std::size_t t, std::size_t a) {
    std::uint64_t& word = ancestor_bits_[t * words_per_row_ + a / 64];
    const std::uint64_t bit = std::uint64_t{1} << (a % 64);
    const bool was = (word & bit) != 0;
    word |= bit;
    return !was;
  };
  std::vector<int> todo;
  for (std::size_t t = 0; t < n; ++t) {
    set(t, t);
    set(t, 0);  // everything is an object
    todo.assign(1, static_cast<int>(t));
    while (!todo.empty()) {
      const auto u = static_cast<std::size_t>(todo.back());
      todo.pop_back();
      for (int p : parents_[u]) {
        if (set(t, static_cast<std::size_t>(p))) todo.push_back(p);
      }
    }
  }
}

int TypeHierarchy::Id(std::string_view type) const {
  auto it = index_.find(type);
  return it == index_.end() ? -1 : it->second;
}

bool TypeHierarchy::IsSubtype(int type, int ancestor) const {
  const auto a = static_cast<std::size_t>(ancestor);
  return (ancestor_bits_[static_cast<std::size_t>(type) * words_per_row_ + a / 64] >> (a % 64)) &
         1U;
}

bool TypeHierarchy::IsSubtype(std::string_view type, std::string_view ancestor) const {
  if (type == ancestor || ancestor == "object") return true;
  const int t = Id(type);
  const int a = Id(ancestor);
  return t >= 0 && a >= 0 && IsSubtype(t, a);
}

std::string TypeHierarchy::FindCycle() const {
  for (int t = 0; t < size(); ++t) {
    for (int p : parents_[static_cast<std::size_t>(t)]) {
      if (IsSubtype(p, t)) return names_[static_cast<std::size_t>(t)];
    }
  }
  return "";
}

}  // namespace seaplan::pddl
