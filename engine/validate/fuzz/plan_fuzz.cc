// libFuzzer target for plan I/O and the validator: any input ends in a parse
// error or a validation result, never a crash, a hang or unbounded memory;
// every plan that parses prints and parses back to itself.
//
//   bash scripts/fuzz.sh run plan 60   (tests/fuzz/README.md)
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "seaplan/task/grounder.h"
#include "seaplan/validate/plan.h"
#include "seaplan/validate/validator.h"

namespace {

// Durative, instantaneous, numeric, timed literals, duration inequalities.
constexpr const char* kDomain = R"(
(define (domain fuzz)
 (:requirements :typing :durative-actions :numeric-fluents :timed-initial-literals
                :duration-inequalities :negative-preconditions :conditional-effects)
 (:types boat berth)
 (:predicates (tide) (sea ?b - boat) (moored ?b - boat ?x - berth) (free ?x - berth) (seen ?b - boat))
 (:functions (fuel ?b - boat))
 (:durative-action enter :parameters (?b - boat ?x - berth)
  :duration (= ?duration 10)
  :condition (and (at start (sea ?b)) (at start (free ?x)) (over all (tide)) (at start (>= (fuel ?b) 5)))
  :effect (and (at start (not (sea ?b))) (at start (not (free ?x))) (at start (decrease (fuel ?b) 5))
               (at end (moored ?b ?x))))
 (:durative-action leave :parameters (?b - boat ?x - berth)
  :duration (and (>= ?duration 1) (<= ?duration 30))
  :condition (and (at start (moored ?b ?x)) (at end (tide)))
  :effect (and (at start (not (moored ?b ?x))) (at end (free ?x)) (at end (sea ?b))
               (at end (increase (fuel ?b) (* 0.5 ?duration)))
               (at end (when (seen ?b) (not (seen ?b))))))
 (:action look :parameters (?b - boat) :precondition (not (seen ?b)) :effect (seen ?b)))
)";

constexpr const char* kProblem = R"(
(define (problem fuzz) (:domain fuzz)
 (:objects b1 b2 - boat x1 x2 - berth)
 (:init (sea b1) (sea b2) (free x1) (free x2) (= (fuel b1) 12) (= (fuel b2) 4)
        (at 5 (tide)) (at 200 (not (tide))))
 (:goal (and (moored b1 x1) (seen b2))))
)";

const seaplan::validate::Validator& TheValidator() {
  static const seaplan::validate::Validator* validator = [] {
    auto loaded = seaplan::task::LoadTask(kDomain, kProblem);
    if (!loaded.ok()) std::abort();  // the built-in task must load
    auto created = seaplan::validate::Validator::Create(loaded.task);
    if (!created.ok()) std::abort();
    return new seaplan::validate::Validator(std::move(*created));
  }();
  return *validator;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto plan = seaplan::validate::ParsePlan(text);
  if (!plan.ok()) return 0;
  const auto again = seaplan::validate::ParsePlan(seaplan::validate::FormatPlan(*plan));
  if (!again.ok() || again->steps.size() != plan->steps.size()) std::abort();
  for (std::size_t i = 0; i < plan->steps.size(); ++i) {
    const auto& a = plan->steps[i];
    const auto& b = again->steps[i];
    if (a.start_s != b.start_s || a.duration_s != b.duration_s || a.name != b.name ||
        a.args != b.args) {
      std::abort();
    }
  }
  const auto result = TheValidator().Validate(*plan);
  if (result.valid == result.first_failure.has_value()) std::abort();
  (void)result.ToString();
  return 0;
}
