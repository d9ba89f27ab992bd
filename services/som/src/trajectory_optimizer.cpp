#include "mmh/som/trajectory_optimizer.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlopt.hpp>

#include "mmh/common/minco_penalty.hpp"
#include "mmh/common/time_map.hpp"

namespace mmh::som {

double smoothedL1(double x, double mu, double* grad) {
  if (x <= 0.0) {
    *grad = 0.0;
    return 0.0;
  }
  if (x < mu) {
    const double r = x / mu, r2 = r * r;
    *grad = r2 * (3.0 - 2.0 * r);
    return (mu - 0.5 * x) * r2 * r;
  }
  *grad = 1.0;
  return x - 0.5 * mu;
}

// Initial durations of the segments of a polyline, from a speed profile that keeps a_max along
// it and slows down for its corners: at every vertex where the polyline turns by theta, at most
// sqrt(a_max r), r = e / tan(theta / 2) the radius of the arc tangent to both segments at
// e = half the shorter one (the turn the optimiser will round it into), then a forward pass from
// the start speed v0 and a backward pass from rest at the end, each at a_max, and on every
// segment the fastest trapezoid between its end speeds under vm. A straight line gives the
// rest-to-rest (or v0-to-rest) trapezoid. A profile that ignores the corners starts L-BFGS at
// full speed through a bend that a moving start cannot take within a_max, a local minimum it
// does not leave (the answer then fails on the acceleration limit).
std::vector<double> cornerAwareDurations(const std::vector<Eigen::Vector3d>& points, double v0,
                                         double vm, double a) {
  const size_t n = points.size();
  std::vector<double> len(n > 0 ? n - 1 : 0), v(n, vm);
  for (size_t i = 0; i + 1 < n; ++i) len[i] = (points[i + 1] - points[i]).norm();
  for (size_t i = 1; i + 1 < n; ++i) {
    if (len[i - 1] < 1e-9 || len[i] < 1e-9) continue;
    const Eigen::Vector3d d0 = (points[i] - points[i - 1]) / len[i - 1];
    const Eigen::Vector3d d1 = (points[i + 1] - points[i]) / len[i];
    const double theta = std::acos(std::clamp(d0.dot(d1), -1.0, 1.0));
    if (theta < 1e-3) continue;
    const double radius = 0.5 * std::min(len[i - 1], len[i]) / std::tan(0.5 * theta);
    v[i] = std::min(vm, std::sqrt(a * radius));
  }
  if (n > 0) {
    v.front() = std::clamp(v0, 0.0, vm);
    v.back() = 0.0;
  }
  for (size_t i = 1; i < n; ++i)
    v[i] = std::min(v[i], std::sqrt(v[i - 1] * v[i - 1] + 2.0 * a * len[i - 1]));
  for (size_t i = n - 1; i-- > 1;)
    v[i] = std::min(v[i], std::sqrt(v[i + 1] * v[i + 1] + 2.0 * a * len[i]));
  std::vector<double> durations(len.size(), 0.0);
  for (size_t i = 0; i < len.size(); ++i) {
    const double l = len[i], va = v[i], vb = v[i + 1];
    if (l <= 0.0) continue;
    // Faster peak than both ends allow (vm capped); if the ends cannot be joined at a_max (a
    // start too fast to brake in time), the mean speed.
    const double peak2 = a * l + 0.5 * (va * va + vb * vb);
    if (std::abs(va * va - vb * vb) > 2.0 * a * l + 1e-9) {
      durations[i] = 2.0 * l / std::max(1e-6, va + vb);
      continue;
    }
    const double vp = std::min(vm, std::sqrt(peak2));
    const double s_acc = (vp * vp - va * va) / (2.0 * a), s_dec = (vp * vp - vb * vb) / (2.0 * a);
    durations[i] =
        (vp - va) / a + (vp - vb) / a + std::max(0.0, l - s_acc - s_dec) / std::max(vp, 1e-6);
  }
  return durations;
}

TrajectoryOptimizer::InnerRegion TrajectoryOptimizer::innerRegion(const Polytope& poly,
                                                                  const Ellipsoid& ellipsoid,
                                                                  double margin_m) {
  // For p = d + C u: a . p - b = (a . d - b) + (C a) . u <= (a . d - b) + |C a| |u| (C
  // symmetric), so |u| <= (b - a . d - margin) / |C a| keeps face a the margin inside; the
  // smallest such bound over the faces, less a micrometre for the rounding of u.
  constexpr double kRoundingM = 1e-6;
  InnerRegion inner;
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(ellipsoid.shape);
  if (!lu.isInvertible()) return inner;
  double radius = std::numeric_limits<double>::infinity();
  const Polytope::Matrix& h = poly.halfspaces();
  for (int i = 0; i < h.rows(); ++i) {
    const Eigen::Vector3d a = h.row(i).head<3>().transpose();
    const double slack = h(i, 3) - a.dot(ellipsoid.center) - margin_m - kRoundingM;
    const double reach = (ellipsoid.shape * a).norm();
    if (!(slack > 0.0) || !(reach > 0.0)) return inner;
    radius = std::min(radius, slack / reach);
  }
  if (!std::isfinite(radius)) return inner;
  inner.to_unit = lu.inverse();
  inner.center = ellipsoid.center;
  inner.radius2 = radius * radius;
  return inner;
}

TrajectoryOptimizer::TrajectoryOptimizer(const OptimizerParams& params, double max_vel_mps,
                                         double max_acc_mps2)
    : params_(params), max_vel_(max_vel_mps), max_acc_(max_acc_mps2) {}

bool TrajectoryOptimizer::setup(const KinematicState& start, const Eigen::Vector3d& target,
                                const Corridor& corridor) {
  const int n = static_cast<int>(corridor.polytopes.size());
  if (n == 0 || static_cast<int>(corridor.junctions.size()) != n - 1) return false;
  corridor_ = &corridor;
  // Polyline start -> junctions -> target; segment j lies in polytope j (both ends are in it).
  std::vector<Eigen::Vector3d> nodes{start.position};
  nodes.insert(nodes.end(), corridor.junctions.begin(), corridor.junctions.end());
  nodes.push_back(target);
  std::vector<Eigen::Vector3d> waypoints{start.position};
  piece_polytope_.clear();
  for (int j = 0; j < n; ++j) {
    const double len = (nodes[j + 1] - nodes[j]).norm();
    const int k = std::max(1, static_cast<int>(std::ceil(len / params_.piece_length_m - 1e-9)));
    for (int i = 1; i <= k; ++i) {
      waypoints.push_back(nodes[j] + (nodes[j + 1] - nodes[j]) * (static_cast<double>(i) / k));
      piece_polytope_.push_back(j);
    }
  }
  pieces_ = static_cast<int>(piece_polytope_.size());

  // Initial durations from a corner-aware speed profile along the polyline.
  Eigen::Vector3d dir0 = waypoints[1] - waypoints[0];
  dir0 = dir0.norm() > 1e-9 ? Eigen::Vector3d(dir0.normalized()) : Eigen::Vector3d::Zero();
  const std::vector<double> initial_durations =
      cornerAwareDurations(waypoints, std::max(0.0, start.velocity.dot(dir0)), max_vel_, max_acc_);

  moving_start_ = start.velocity.norm() > 0.1 || start.acceleration.norm() > 0.1;
  head_.col(0) = start.position;
  head_.col(1) = start.velocity;
  head_.col(2) = start.acceleration;
  tail_.setZero();
  tail_.col(0) = target;
  minco_.setConditions(head_, tail_, pieces_);

  inner_.assign(n, InnerRegion());
  if (corridor.ellipsoids.size() == static_cast<size_t>(n)) {
    for (int j = 0; j < n; ++j)
      inner_[j] =
          innerRegion(corridor.polytopes[j], corridor.ellipsoids[j], params_.corridor_margin_m);
  }

  const int m = pieces_;
  x0_.resize(3 * (m - 1) + m);
  for (int i = 0; i < m - 1; ++i) x0_.segment<3>(3 * i) = waypoints[i + 1];
  for (int i = 0; i < m; ++i) {
    const double dt = initial_durations[i];
    const double floor = std::max(0.05, (waypoints[i + 1] - waypoints[i]).norm() / max_vel_);
    x0_[3 * (m - 1) + i] = tauFromDuration(std::max(dt, floor));
  }
  points_.resize(3, m - 1);
  durations_.resize(m);
  grad_coeffs_.resize(6 * m, 3);
  grad_durations_.resize(m);

  return true;
}

double TrajectoryOptimizer::evaluate(const Eigen::VectorXd& x, Eigen::VectorXd* grad,
                                     double* control, double* time, double* penalty) {
  ++evaluations_;
  const int m = pieces_;
  points_ = Eigen::Map<const Eigen::Matrix3Xd>(x.data(), 3, m - 1);
  for (int i = 0; i < m; ++i) durations_[i] = durationFromTau(x[3 * (m - 1) + i]);
  minco_.setParameters(points_, durations_);
  grad_coeffs_.setZero();
  grad_durations_.setZero();
  const double energy = minco_.energy();
  minco_.addEnergyGradient(grad_coeffs_, grad_durations_);
  const double rho = params_.time_weight;
  const double time_cost = rho * durations_.sum();
  grad_durations_.array() += rho;

  const double mu = params_.penalty_smoothing;
  const double wc = corridor_boost_ * params_.weight_corridor,
               wv = limit_boost_ * params_.weight_velocity,
               wa = limit_boost_ * params_.weight_acceleration;
  const double vl = max_vel_ * (1.0 - params_.limit_margin),
               al = max_acc_ * (1.0 - params_.limit_margin);
  const double v2 = vl * vl, a2 = al * al;
  const double shrink = params_.corridor_margin_m;
  const std::vector<Polytope>& polys = corridor_->polytopes;
  auto pointwise = [&](const PenaltyPoint& pt, Eigen::Vector3d& gp, Eigen::Vector3d& gv,
                       Eigen::Vector3d& ga) {
    double value = 0.0, g = 0.0;
    const int k = piece_polytope_[pt.piece];
    const InnerRegion& inner = inner_[k];
    const bool deep_inside =
        inner.radius2 > 0.0 &&
        (inner.to_unit * (pt.pos - inner.center)).squaredNorm() < inner.radius2;
    const Polytope::Matrix& h = polys[k].halfspaces();
    for (int j = 0; j < (deep_inside ? 0 : h.rows()); ++j) {
      const double viol =
          h(j, 0) * pt.pos.x() + h(j, 1) * pt.pos.y() + h(j, 2) * pt.pos.z() - h(j, 3) + shrink;
      if (viol <= 0.0) continue;
      value += wc * smoothedL1(viol, mu, &g);
      gp += (wc * g) * Eigen::Vector3d(h(j, 0), h(j, 1), h(j, 2));
    }
    const double dv = pt.vel.squaredNorm() - v2;
    if (dv > 0.0) {
      value += wv * smoothedL1(dv, mu, &g);
      gv += (2.0 * wv * g) * pt.vel;
    }
    const double da = pt.acc.squaredNorm() - a2;
    if (da > 0.0) {
      value += wa * smoothedL1(da, mu, &g);
      ga += (2.0 * wa * g) * pt.acc;
    }
    return value;
  };
  const double pen =
      integratePenalty(minco_, params_.samples_per_piece, pointwise, grad_coeffs_, grad_durations_);
  if (grad) {
    minco_.propagateGradient(grad_coeffs_, grad_durations_, grad_points_, grad_total_);
    grad->resize(x.size());
    Eigen::Map<Eigen::Matrix3Xd>(grad->data(), 3, m - 1) = grad_points_;
    for (int i = 0; i < m; ++i)
      (*grad)[3 * (m - 1) + i] = grad_total_[i] * durationGradient(x[3 * (m - 1) + i]);
  }
  if (control) *control = energy;
  if (time) *time = time_cost;
  if (penalty) *penalty = pen;
  return energy + time_cost + pen;
}

double TrajectoryOptimizer::objective(const Eigen::VectorXd& x, Eigen::VectorXd* grad) {
  return evaluate(x, grad, nullptr, nullptr, nullptr);
}

Trajectory TrajectoryOptimizer::trajectoryAt(const Eigen::VectorXd& x) {
  evaluate(x, nullptr, nullptr, nullptr, nullptr);
  return minco_.trajectory();
}

void TrajectoryOptimizer::costParts(const Eigen::VectorXd& x, double* control, double* time,
                                    double* penalty) {
  evaluate(x, nullptr, control, time, penalty);
}

namespace {
struct NloptContext {
  TrajectoryOptimizer* self;
  Eigen::VectorXd x, g, best_x;
  double best = std::numeric_limits<double>::infinity();
  double scale = 1.0;
  int calls = 0;
};
}  // namespace

double TrajectoryOptimizer::nloptObjective(unsigned n, const double* x, double* grad, void* data) {
  auto* ctx = static_cast<NloptContext*>(data);
  ++ctx->calls;
  ctx->x = Eigen::Map<const Eigen::VectorXd>(x, n);
  const double f = ctx->self->evaluate(ctx->x, grad ? &ctx->g : nullptr, nullptr, nullptr, nullptr);
  if (grad) Eigen::Map<Eigen::VectorXd>(grad, n) = ctx->g * ctx->scale;
  if (std::isfinite(f) && f < ctx->best) {
    ctx->best = f;
    ctx->best_x = ctx->x;
  }
  return std::isfinite(f) ? f * ctx->scale : std::numeric_limits<double>::max();
}

double TrajectoryOptimizer::runNlopt(Eigen::VectorXd& x, int max_evaluations, int* result,
                                     std::string* message) {
  const unsigned n = static_cast<unsigned>(x.size());
  NloptContext ctx{this, x, Eigen::VectorXd::Zero(n), x};
  // NLopt's L-BFGS (Luksan) starts with a steepest-descent step as long as the gradient: scale
  // the cost so that this first step is a sensible distance in the variables.
  Eigen::VectorXd g0;
  objective(x, &g0);
  ctx.scale = params_.first_step / std::max(1e-12, g0.norm());
  nlopt::opt opt(nlopt::LD_LBFGS, n);
  opt.set_min_objective(&TrajectoryOptimizer::nloptObjective, &ctx);
  opt.set_ftol_rel(params_.rel_cost_tolerance);
  opt.set_maxeval(max_evaluations);
  opt.set_vector_storage(params_.lbfgs_memory);
  std::vector<double> xv(x.data(), x.data() + n);
  double f = 0.0;
  try {
    *result = opt.optimize(xv, f);
  } catch (const nlopt::roundoff_limited&) {
    *result = nlopt::ROUNDOFF_LIMITED;  // the best point so far is still usable
  } catch (const std::exception& e) {
    *result = nlopt::FAILURE;
    *message = std::string("nlopt: ") + e.what();
  }
  if (std::isfinite(ctx.best)) x = ctx.best_x;
  return ctx.best;
}

double TrajectoryOptimizer::corridorViolation(const Eigen::VectorXd& x) {
  evaluate(x, nullptr, nullptr, nullptr, nullptr);
  const Eigen::MatrixX3d& c = minco_.coeffs();
  const int samples = 2 * params_.samples_per_piece;
  double worst = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < pieces_; ++i) {
    const Polytope& poly = corridor_->polytopes[piece_polytope_[i]];
    const Eigen::Matrix<double, 6, 3> ci = c.block<6, 3>(6 * i, 0);
    for (int j = 0; j <= samples; ++j) {
      const double t = durations_[i] * j / samples;
      const Eigen::RowVector3d p =
          ci.row(0) +
          t * (ci.row(1) + t * (ci.row(2) + t * (ci.row(3) + t * (ci.row(4) + t * ci.row(5)))));
      worst = std::max(worst, poly.maxViolation(p.transpose()));
    }
  }
  return worst;
}

void TrajectoryOptimizer::sampledMaxima(const Trajectory& traj, double* speed, double* acc) {
  // Dense samples are enough here: the verification computes the exact maxima afterwards.
  constexpr int kSamples = 32;
  double v2 = 0.0, a2 = 0.0;
  for (const Piece& piece : traj.pieces()) {
    const Eigen::Matrix<double, 3, kMaxPolyOrder>& c = piece.coeffs;
    for (int j = 0; j <= kSamples; ++j) {
      const double t = piece.duration * j / kSamples;
      const Eigen::Vector3d v =
          c.col(1) +
          t * (2.0 * c.col(2) + t * (3.0 * c.col(3) + t * (4.0 * c.col(4) + t * 5.0 * c.col(5))));
      const Eigen::Vector3d a =
          2.0 * c.col(2) + t * (6.0 * c.col(3) + t * (12.0 * c.col(4) + t * 20.0 * c.col(5)));
      v2 = std::max(v2, v.squaredNorm());
      a2 = std::max(a2, a.squaredNorm());
    }
  }
  *speed = std::sqrt(v2);
  *acc = std::sqrt(a2);
}

double TrajectoryOptimizer::limitExcess(const Eigen::VectorXd& x) {
  double v, a;
  sampledMaxima(trajectoryAt(x), &v, &a);
  return std::max(v / max_vel_, std::sqrt(a / max_acc_));
}

bool TrajectoryOptimizer::optimize(OptimizerOutput* out) {
  *out = OptimizerOutput();
  if (pieces_ == 0) {
    out->message = "optimizer was not set up";
    return false;
  }
  evaluations_ = 0;
  corridor_boost_ = 1.0;
  Eigen::VectorXd x = x0_;
  double best = runNlopt(x, params_.max_evaluations, &out->nlopt_result, &out->message);
  // Penalties are soft: if the result still leaves the polytopes, or exceeds the limits by more
  // than the final time stretch may fix, raise the weight of what is violated and continue from
  // where it stopped.
  for (int round = 0; round < params_.extra_rounds && std::isfinite(best); ++round) {
    // The corridor first (safety); the limits only once inside it (the time stretch at the end
    // fixes small excesses, but not those a moving start forces early on).
    if (corridorViolation(x) > 0.0) {
      corridor_boost_ *= params_.extra_round_weight_factor;
    } else if (moving_start_ && limitExcess(x) > 1.0 + params_.extra_round_limit_excess) {
      limit_boost_ *= params_.extra_round_weight_factor;
    } else {
      break;
    }
    best = runNlopt(x, params_.extra_round_evaluations, &out->nlopt_result, &out->message);
    ++out->extra_rounds;
  }
  corridor_boost_ = 1.0;
  limit_boost_ = 1.0;
  if (!std::isfinite(best)) {
    if (out->message.empty()) out->message = "no finite cost was reached";
    return false;
  }
  out->evaluations = evaluations_;
  out->cost_total = evaluate(x, nullptr, &out->cost_control, &out->cost_time, &out->cost_penalty);
  Trajectory traj = minco_.trajectory();
  // Limit repair: the penalties leave a small excess over v_max / a_max; stretch all durations
  // (keeping the waypoints) until the exact maxima keep the limits. Stretching by k divides the
  // speeds by about k and the accelerations by about k^2 (exactly for a start at rest).
  const int m = pieces_;
  points_ = Eigen::Map<const Eigen::Matrix3Xd>(x.data(), 3, m - 1);
  for (int i = 0; i < m; ++i) durations_[i] = durationFromTau(x[3 * (m - 1) + i]);
  double stretch = 1.0, v = 0.0, a = 0.0;
  sampledMaxima(traj, &v, &a);
  double excess = std::max(v / max_vel_, a / max_acc_);
  for (int pass = 0; pass < 8 && excess > 1.0 + params_.repair_tolerance; ++pass) {
    const double k =
        std::max({v / max_vel_, std::sqrt(a / max_acc_), 1.0 + 0.5 * params_.repair_tolerance});
    // A moving start fixes the first moments, so stretching does not always help: it is
    // bounded and kept only while it lowers the excess (the verification refuses the rest).
    if (stretch * k > params_.max_repair_stretch) break;
    minco_.setParameters(points_, durations_ * k);
    Trajectory longer = minco_.trajectory();
    double lv, la;
    sampledMaxima(longer, &lv, &la);
    const double longer_excess = std::max(lv / max_vel_, la / max_acc_);
    if (longer_excess >= excess) break;
    durations_ *= k;
    stretch *= k;
    traj = std::move(longer);
    excess = longer_excess;
    v = lv;
    a = la;
    ++out->repairs;
  }
  // The banded solve meets the start state to rounding; make it exact.
  PieceCoeffs& c = traj.pieces().front().coeffs;
  c.col(0) = head_.col(0);
  c.col(1) = head_.col(1);
  c.col(2) = 0.5 * head_.col(2);
  out->trajectory = std::move(traj);
  out->piece_polytope = piece_polytope_;
  return true;
}

}  // namespace mmh::som
