// Minimises the EAM objective over the free control points of a B-spline with NLopt's L-BFGS
// (LD_LBFGS) and the analytic gradient of BsplineCost. The first three control points (the
// start state) and the last three (the target at rest) stay fixed.
#pragma once

#include <string>
#include <vector>

#include "mmh/eam/bspline_cost.hpp"
#include "mmh/eam/uniform_bspline.hpp"

namespace mmh::eam {

struct OptimizeResult {
  bool ok = false;  // a finite point at least as good as the initial one was found
  int evaluations = 0;
  CostTerms terms;    // at the returned point
  std::string error;  // why not ok
};

// Optimises the control points listed in free_points (sorted, each within 3 .. n-4) in place;
// the others stay where they are. `error` is set (and ok stays true) when NLopt stopped with an
// error after finding a usable point.
// NLopt stops after max_evaluations or when a step improves the cost by less than ftol_rel.
// keep_altitude: optimise x and y only (the caller knows that no term pushes vertically).
OptimizeResult optimizeControlPoints(UniformBspline& spline, const BsplineCost& cost,
                                     const std::vector<int>& free_points, int max_evaluations,
                                     double ftol_rel = 1e-3, bool keep_altitude = false);
// All of 3 .. n-4.
OptimizeResult optimizeControlPoints(UniformBspline& spline, const BsplineCost& cost,
                                     int max_evaluations, double ftol_rel = 1e-3,
                                     bool keep_altitude = false);

}  // namespace mmh::eam
