// libFuzzer target for the PDDL front end: parser and grounder must end every
// input in diagnostics or a task, never a crash, a hang, a stack overflow or
// unbounded memory. See engine/pddl/README.md for how to build and run it.
//
// Input: either one PDDL text (parsed as a domain, and as a problem against a
// built-in fjord domain, then grounded), or "<domain>\n====\n<problem>"
// (parsed and grounded as a pair).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "seaplan/pddl/parser.h"
#include "seaplan/task/grounder.h"

namespace {

constexpr std::string_view kSeparator = "\n====\n";

constexpr const char* kDomain = R"(
(define (domain fuzz) (:requirements :typing :durative-actions :fluents :adl)
 (:types ship - vehicle port - location vehicle cont - subject route)
 (:predicates (at ?x - subject ?l - location) (loaded ?c - cont ?v - vehicle)
              (connects ?r - route ?a ?b - location) (free ?v - vehicle))
 (:functions (len ?r - route) (speed ?v - vehicle) (fuel ?v - vehicle))
 (:durative-action move :parameters (?v - ship ?a ?b - port ?r - route)
  :duration (= ?duration (/ (len ?r) (speed ?v)))
  :condition (and (at start (at ?v ?a)) (at start (connects ?r ?a ?b)) (at start (>= (fuel ?v) 1)))
  :effect (and (at start (not (at ?v ?a))) (at end (at ?v ?b)) (at end (decrease (fuel ?v) 1))))
 (:action load :parameters (?v - ship ?c - cont ?p - port)
  :precondition (and (at ?v ?p) (at ?c ?p) (free ?v) (or (not (loaded ?c ?v)) (= ?p ?p)))
  :effect (and (not (at ?c ?p)) (loaded ?c ?v) (forall (?d - cont) (when (loaded ?d ?v) (not (free ?v)))))))
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  seaplan::task::GroundingOptions options;
  options.max_actions = 20'000;  // keep each run fast; budgets are part of what is tested
  options.max_facts = 20'000;
  if (const auto split = text.find(kSeparator); split != std::string_view::npos) {
    auto loaded = seaplan::task::LoadTask(text.substr(0, split),
                                          text.substr(split + kSeparator.size()), options);
    (void)loaded;
    return 0;
  }
  auto domain = seaplan::pddl::ParseDomain(text);
  (void)domain;
  static const auto* fixed =
      new seaplan::pddl::DomainParseResult(seaplan::pddl::ParseDomain(kDomain));
  if (fixed->domain) {
    auto problem = seaplan::pddl::ParseProblem(text, *fixed->domain);
    if (problem.problem) {
      auto grounded = seaplan::task::Ground(*fixed->domain, *problem.problem, options);
      (void)grounded;
    }
  }
  return 0;
}
