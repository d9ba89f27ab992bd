#include "mmh/fpm/spatio_temporal_optimizer.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mmh/common/time_map.hpp"

namespace mmh::fpm {

void SpatioTemporalOptimizer::setup(const std::vector<KnotState>& knots,
                                    const std::vector<bool>& fixed_position,
                                    const Eigen::VectorXd& durations) {
  knots_ = knots;
  fixed_ = fixed_position;
  durations_ = durations;
  origin_.setZero();
  basis_ = Eigen::Matrix3d::Identity();
  countVariables();
  grad_knots_.assign(knots_.size(), KnotState{});
  grad_durations_.setZero(durations.size());
}

void SpatioTemporalOptimizer::restrictTo(const Eigen::Vector3d& origin,
                                         const Eigen::Matrix3Xd& basis) {
  origin_ = origin;
  basis_ = basis;
  const Eigen::Matrix3d projector = basis_ * basis_.transpose();
  for (size_t i = 1; i + 1 < knots_.size(); ++i) {
    KnotState& k = knots_[i];
    k.p = origin_ + projector * (k.p - origin_);
    k.v = projector * k.v;
    k.a = projector * k.a;
  }
  countVariables();
}

void SpatioTemporalOptimizer::countVariables() {
  const int dim = static_cast<int>(basis_.cols());
  num_vars_ = static_cast<int>(durations_.size());
  for (size_t i = 1; i + 1 < knots_.size(); ++i) num_vars_ += (fixed_[i - 1] ? 2 : 3) * dim;
}

std::vector<double> SpatioTemporalOptimizer::pack() const {
  std::vector<double> x;
  x.reserve(num_vars_);
  const int dim = static_cast<int>(basis_.cols());
  const auto put = [&](const Eigen::Vector3d& v) {
    for (int c = 0; c < dim; ++c) x.push_back(basis_.col(c).dot(v));
  };
  for (size_t i = 1; i + 1 < knots_.size(); ++i) {
    const KnotState& k = knots_[i];
    if (!fixed_[i - 1]) put(k.p - origin_);
    put(k.v);
    put(k.a);
  }
  for (int i = 0; i < durations_.size(); ++i) x.push_back(tauFromDuration(durations_[i]));
  return x;
}

void SpatioTemporalOptimizer::unpack(const double* x) {
  int n = 0;
  const int dim = static_cast<int>(basis_.cols());
  const auto get = [&]() {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int c = 0; c < dim; ++c) v += basis_.col(c) * x[n++];
    return v;
  };
  for (size_t i = 1; i + 1 < knots_.size(); ++i) {
    KnotState& k = knots_[i];
    if (!fixed_[i - 1]) k.p = origin_ + get();
    k.v = get();
    k.a = get();
  }
  for (int i = 0; i < durations_.size(); ++i) durations_[i] = durationFromTau(x[n++]);
}

double SpatioTemporalOptimizer::evaluateRaw(const double* x, double* grad,
                                            CostBreakdown* breakdown) {
  unpack(x);
  const int pieces = static_cast<int>(durations_.size());
  for (KnotState& g : grad_knots_) g = KnotState{};
  grad_durations_.setZero(pieces);
  const double vl2 = settings_.v_limit * settings_.v_limit;
  const double al2 = settings_.a_limit * settings_.a_limit;
  const double w = settings_.penalty_weight;
  double energy = 0.0, penalty = 0.0;

  for (int i = 0; i < pieces; ++i) {
    const int K = samples_[i];
    const KnotState &ka = knots_[i], &kb = knots_[i + 1];
    const double T = durations_[i], T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T, T6 = T5 * T;
    const Eigen::Vector3d dp = kb.p - ka.p;
    const Eigen::Vector3d c1 = ka.v, c2 = 0.5 * ka.a;
    const Eigen::Vector3d c3 =
        10.0 * dp / T3 - (4.0 * kb.v + 6.0 * ka.v) / T2 - (1.5 * ka.a - 0.5 * kb.a) / T;
    const Eigen::Vector3d c4 =
        -15.0 * dp / T4 + (7.0 * kb.v + 8.0 * ka.v) / T3 + (1.5 * ka.a - kb.a) / T2;
    const Eigen::Vector3d c5 = 6.0 * dp / T5 - 3.0 * (kb.v + ka.v) / T4 - 0.5 * (ka.a - kb.a) / T3;

    // Jerk energy of the piece and its partial derivatives.
    energy += 36.0 * c3.squaredNorm() * T + 144.0 * c3.dot(c4) * T2 +
              192.0 * c4.squaredNorm() * T3 + 240.0 * c3.dot(c5) * T3 + 720.0 * c4.dot(c5) * T4 +
              720.0 * c5.squaredNorm() * T5;
    Eigen::Vector3d g1 = Eigen::Vector3d::Zero(), g2 = Eigen::Vector3d::Zero();
    Eigen::Vector3d g3 = 72.0 * c3 * T + 144.0 * c4 * T2 + 240.0 * c5 * T3;
    Eigen::Vector3d g4 = 144.0 * c3 * T2 + 384.0 * c4 * T3 + 720.0 * c5 * T4;
    Eigen::Vector3d g5 = 240.0 * c3 * T3 + 720.0 * c4 * T4 + 1440.0 * c5 * T5;
    double gT = 36.0 * c3.squaredNorm() + 288.0 * c3.dot(c4) * T + 576.0 * c4.squaredNorm() * T2 +
                720.0 * c3.dot(c5) * T2 + 2880.0 * c4.dot(c5) * T3 + 3600.0 * c5.squaredNorm() * T4;

    // Penalties on the samples t_j = j T / K, trapezoid rule in time. Velocity and acceleration
    // by Horner's rule; most samples are inside the limits and cost nothing more.
    const Eigen::Vector3d v1 = 2.0 * c2, v2 = 3.0 * c3, v3 = 4.0 * c4, v4 = 5.0 * c5;
    const Eigen::Vector3d a1 = 6.0 * c3, a2 = 12.0 * c4, a3 = 20.0 * c5;
    for (int j = 0; j <= K; ++j) {
      const double alpha = static_cast<double>(j) / K;
      const double t = alpha * T;
      const Eigen::Vector3d vel = c1 + t * (v1 + t * (v2 + t * (v3 + t * v4)));
      const Eigen::Vector3d acc = v1 + t * (a1 + t * (a2 + t * a3));
      const double ev = vel.squaredNorm() - vl2, ea = acc.squaredNorm() - al2;
      if (ev <= 0.0 && ea <= 0.0) continue;
      const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
      double f = 0.0;
      Eigen::Vector3d gv = Eigen::Vector3d::Zero(), ga = Eigen::Vector3d::Zero();
      // Quadratic in the excess of the squared norm: C1, and steep enough near zero that the
      // optimum oversteps the penalty limit by far less than the margin to the true limit.
      if (ev > 0.0) {
        f += w * ev * ev;
        gv = (4.0 * w * ev) * vel;
      }
      if (ea > 0.0) {
        f += w * ea * ea;
        ga = (4.0 * w * ea) * acc;
      }
      const double weight = (j == 0 || j == K) ? 0.5 : 1.0;
      const double dt = weight * T / K;
      penalty += dt * f;
      g1 += dt * gv;
      g2 += dt * (2.0 * t * gv + 2.0 * ga);
      g3 += dt * (3.0 * t2 * gv + 6.0 * t * ga);
      g4 += dt * (4.0 * t3 * gv + 12.0 * t2 * ga);
      g5 += dt * (5.0 * t4 * gv + 20.0 * t3 * ga);
      // d/dT of dt f(state(alpha T)) = f weight / K + dt alpha (gv . acc + ga . jerk).
      const Eigen::Vector3d jerk = 6.0 * c3 + 24.0 * c4 * t + 60.0 * c5 * t2;
      gT += weight * f / K + dt * alpha * (gv.dot(acc) + ga.dot(jerk));
    }
    if (!grad) continue;

    // Chain rule from the coefficients to the knot states and the duration.
    const Eigen::Vector3d g_dp = 10.0 / T3 * g3 - 15.0 / T4 * g4 + 6.0 / T5 * g5;
    KnotState &ga_k = grad_knots_[i], &gb_k = grad_knots_[i + 1];
    ga_k.p -= g_dp;
    gb_k.p += g_dp;
    ga_k.v += g1 - 6.0 / T2 * g3 + 8.0 / T3 * g4 - 3.0 / T4 * g5;
    gb_k.v += -4.0 / T2 * g3 + 7.0 / T3 * g4 - 3.0 / T4 * g5;
    ga_k.a += 0.5 * g2 - 1.5 / T * g3 + 1.5 / T2 * g4 - 0.5 / T3 * g5;
    gb_k.a += 0.5 / T * g3 - 1.0 / T2 * g4 + 0.5 / T3 * g5;
    const Eigen::Vector3d dc3 =
        -30.0 * dp / T4 + 2.0 * (4.0 * kb.v + 6.0 * ka.v) / T3 + (1.5 * ka.a - 0.5 * kb.a) / T2;
    const Eigen::Vector3d dc4 =
        60.0 * dp / T5 - 3.0 * (7.0 * kb.v + 8.0 * ka.v) / T4 - 2.0 * (1.5 * ka.a - kb.a) / T3;
    const Eigen::Vector3d dc5 =
        -30.0 * dp / T6 + 12.0 * (kb.v + ka.v) / T5 + 1.5 * (ka.a - kb.a) / T4;
    grad_durations_[i] = gT + g3.dot(dc3) + g4.dot(dc4) + g5.dot(dc5) + settings_.time_weight;
  }
  const double time = settings_.time_weight * durations_.sum();
  if (breakdown) *breakdown = CostBreakdown{energy, time, penalty};
  if (grad) {
    int n = 0;
    const int dim = static_cast<int>(basis_.cols());
    const auto put = [&](const Eigen::Vector3d& g) {
      for (int c = 0; c < dim; ++c) grad[n++] = basis_.col(c).dot(g);
    };
    for (size_t i = 1; i + 1 < knots_.size(); ++i) {
      const KnotState& g = grad_knots_[i];
      if (!fixed_[i - 1]) put(g.p);
      put(g.v);
      put(g.a);
    }
    for (int i = 0; i < pieces; ++i, ++n) grad[n] = grad_durations_[i] * durationGradient(x[n]);
  }
  return energy + time + penalty;
}

double SpatioTemporalOptimizer::evaluate(const std::vector<double>& x, std::vector<double>* grad) {
  if (grad) grad->assign(x.size(), 0.0);
  return evaluateRaw(x.data(), grad ? grad->data() : nullptr, nullptr);
}

double SpatioTemporalOptimizer::nloptObjective(unsigned, const double* x, double* grad,
                                               void* data) {
  auto* self = static_cast<SpatioTemporalOptimizer*>(data);
  ++self->evaluations_;
  double cost = self->evaluateRaw(x, grad, nullptr);
  if (!std::isfinite(cost)) return std::numeric_limits<double>::max();
  if (cost < self->best_cost_) {
    self->best_cost_ = cost;
    self->best_x_.assign(x, x + self->num_vars_);
  }
  cost *= self->scale_;
  if (grad)
    for (int i = 0; i < self->num_vars_; ++i) grad[i] *= self->scale_;
  return cost;
}

void SpatioTemporalOptimizer::setSettings(const OptimizerSettings& settings) {
  settings_ = settings;
  // Samples per piece, fixed for a run (the cost must not jump as durations change): about one
  // per 0.1 s, at least 2 and at most samples_per_piece intervals.
  samples_.resize(durations_.size());
  for (int i = 0; i < durations_.size(); ++i)
    samples_[i] = std::clamp(static_cast<int>(std::ceil(durations_[i] / 0.05)), 2,
                             std::max(2, settings.samples_per_piece));
}

int SpatioTemporalOptimizer::optimize(const OptimizerSettings& settings) {
  setSettings(settings);
  evaluations_ = 0;
  std::vector<double> x = pack();
  // NLopt's L-BFGS takes the plain negative gradient as its first trial step: scale the cost so
  // that the largest initial partial derivative is a modest step in any variable.
  std::vector<double> g0(x.size());
  best_cost_ = evaluateRaw(x.data(), g0.data(), nullptr);
  best_x_ = x;
  double gmax = 0.0;
  for (double g : g0) gmax = std::max(gmax, std::abs(g));
  scale_ = gmax > 0.0 && std::isfinite(gmax) ? 0.1 / gmax : 1.0;
  nlopt_opt opt = nlopt_create(NLOPT_LD_LBFGS, static_cast<unsigned>(x.size()));
  nlopt_set_min_objective(opt, &SpatioTemporalOptimizer::nloptObjective, this);
  nlopt_set_maxeval(opt, settings.max_evaluations);
  nlopt_set_ftol_rel(opt, settings.relative_tolerance);
  // A short memory: NLopt's L-BFGS costs O(n m) per evaluation, and from a good initial guess a
  // few corrections are all it uses.
  nlopt_set_vector_storage(opt, 4);
  double value = 0.0;
  nlopt_optimize(opt, x.data(), &value);  // whatever the result: keep the best point seen
  nlopt_destroy(opt);
  unpack(best_x_.data());
  return evaluations_ + 1;
}

CostBreakdown SpatioTemporalOptimizer::costs(const OptimizerSettings& settings) {
  setSettings(settings);
  const std::vector<double> x = pack();
  CostBreakdown c;
  evaluateRaw(x.data(), nullptr, &c);
  return c;
}

}  // namespace mmh::fpm
