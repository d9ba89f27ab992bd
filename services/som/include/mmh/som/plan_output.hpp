// What one SOM plan returns: the verified trajectory or the step that failed and why, the path
// and corridor it was planned along, its cost, and the effort each step took.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mmh/common/plan_status.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/som/corridor.hpp"
#include "mmh/som/step_timer.hpp"
#include "mmh/som/verification.hpp"

namespace mmh::som {

// The steps' times add up those of both threads when the two paths of the comparison are planned
// at once; `total` is the request's wall time and the CPU time of all its threads.
struct PlanTimings {
  StepTime checks, astar, corridor, optimize, verify, total;
};

struct PlanOutput {
  PlanStatus status = PlanStatus::kBadInput;
  std::string detail;
  Trajectory trajectory;  // verified; set only with kOk
  // With kVerify, the trajectory the verification refused (for diagnosis: mmh-replan --samples).
  Trajectory refused;
  std::vector<Eigen::Vector3d> path;  // shortened A* path
  Corridor corridor;
  std::vector<int> piece_polytope;
  double cost_total = 0.0, cost_control = 0.0, cost_time = 0.0, cost_penalty = 0.0;
  int optimizer_evaluations = 0;
  // Plans made again with the check-margin faces, then with those cells fenced whole (the plan
  // before ran through a cell the arbiter's check margin blocks; see Planner::plan).
  int check_margin_retries = 0;
  // Second candidates from a point ahead of a fast start (lead_point.hpp), and how many won.
  int lead_paths = 0;
  int lead_paths_taken = 0;
  // Paths searched again without the clearance cost (clearance_cost.hpp): its search found no
  // path, or no verified answer along it.
  int clearance_fallbacks = 0;
  // Answers along the path that keeps clear chosen over the shortest (clearance.compare).
  int clearance_taken = 0;
  int64_t astar_expansions = 0;
  VerifyReport verify;
  PlanTimings timings;
  bool ok() const { return status == PlanStatus::kOk; }
};

// `answer` with the effort of `latest` (times, expansions, evaluations and the counts of retries
// and second candidates): an earlier answer taken after later tries that began from it.
PlanOutput withEffortOf(PlanOutput answer, const PlanOutput& latest);

// Adds the effort of `other` (planned apart from *into, e.g. on another thread) to *into.
void addEffortOf(PlanOutput* into, const PlanOutput& other);

}  // namespace mmh::som
