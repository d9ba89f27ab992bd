// Fast Planning Mode (paper Sec. III.C.1): a spatio-temporal optimal polynomial trajectory from
// the start state to the local target at rest (through optional waypoints), ignoring obstacles,
// with |v| <= v_max and |a| <= a_max checked exactly over the whole trajectory.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mmh/common/plan_status.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/fpm/fpm_params.hpp"
#include "mmh/fpm/spatio_temporal_optimizer.hpp"

namespace mmh::fpm {

struct Request {
  KinematicState start;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> waypoints;  // passed in order, at any speed
  double max_speed_mps = 0.0;              // fly no faster (speedLimitFor); 0: params' max_vel_mps
};

struct Result {
  bool ok = false;
  PlanStatus status = PlanStatus::kOk;  // kOk when ok
  std::string detail;
  Trajectory trajectory;  // only when ok
  CostBreakdown cost;
  // Diagnostics.
  double max_speed = 0.0, max_acc = 0.0;  // exact maxima of the returned trajectory
  double profile_duration = 0.0;  // the trapezoidal profile the initial guess was built from
  int evaluations = 0;            // cost evaluations over all optimisation runs
  int repairs = 0;  // re-optimisations and retries with wider margins after a failed check
};

class Planner {
 public:
  explicit Planner(const Params& params) : params_(params) {}
  const Params& params() const { return params_; }

  Result plan(const Request& request) const;

 private:
  // Checks the request; fills status and detail and returns false if it cannot be planned.
  bool validate(const Request& request, Result& result) const;
  // One complete attempt with the guess and the penalties `margin_ratio` below the limits; true
  // (and `out` filled) when a candidate passes the exact limit check.
  bool planWithMargin(const Request& request, double margin_ratio, Result& out) const;

  Params params_;
};

}  // namespace mmh::fpm
