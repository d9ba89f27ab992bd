#include "mmh/som/plan_output.hpp"

#include <utility>

namespace mmh::som {

PlanOutput withEffortOf(PlanOutput answer, const PlanOutput& latest) {
  answer.timings = latest.timings;
  answer.astar_expansions = latest.astar_expansions;
  answer.optimizer_evaluations = latest.optimizer_evaluations;
  answer.check_margin_retries = latest.check_margin_retries;
  answer.lead_paths = latest.lead_paths;
  answer.clearance_fallbacks = latest.clearance_fallbacks;
  return answer;
}

void addEffortOf(PlanOutput* into, const PlanOutput& other) {
  for (auto [a, b] : {std::pair{&into->timings.checks, &other.timings.checks},
                      std::pair{&into->timings.astar, &other.timings.astar},
                      std::pair{&into->timings.corridor, &other.timings.corridor},
                      std::pair{&into->timings.optimize, &other.timings.optimize},
                      std::pair{&into->timings.verify, &other.timings.verify}})
    *a += *b;
  into->astar_expansions += other.astar_expansions;
  into->optimizer_evaluations += other.optimizer_evaluations;
  into->check_margin_retries += other.check_margin_retries;
  into->lead_paths += other.lead_paths;
  into->clearance_fallbacks += other.clearance_fallbacks;
}

}  // namespace mmh::som
