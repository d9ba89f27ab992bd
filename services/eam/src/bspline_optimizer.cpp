#include "mmh/eam/bspline_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlopt.hpp>

namespace mmh::eam {
namespace {

constexpr int kFixed = 3;  // control points fixed at each end
constexpr int kBand = 3;   // a control point shares jerk terms with 3 neighbours on each side
constexpr int kLbfgsMemory = 4;

// Cholesky factor L (lower, bandwidth 3) of the smoothness Hessian over the free control points
// (the same for x, y and z). The optimiser works on y = L^T (Q - Q_start): there the smoothness
// term has the identity as Hessian, which removes the ill-conditioning of the jerk energy
// (its eigenvalues spread over ~ n^6) that otherwise makes L-BFGS crawl.
class SmoothnessPreconditioner {
 public:
  SmoothnessPreconditioner(const std::vector<int>& free_points, double hessian_scale) {
    const int n = static_cast<int>(free_points.size());
    l_.assign(static_cast<size_t>(n) * (kBand + 1), 0.0);
    n_ = n;
    // H_ab = scale * sum over intervals s of c_{a-s} c_{b-s}, c = (-1, 3, -3, 1), for the
    // intervals s whose four control points include both a and b.
    static const double c[4] = {-1.0, 3.0, -3.0, 1.0};
    auto h = [&](int a, int b) {
      double sum = 0.0;
      for (int s = std::max(a, b) - 3; s <= std::min(a, b); ++s) sum += c[a - s] * c[b - s];
      return hessian_scale * sum;
    };
    for (int i = 0; i < n; ++i) {
      for (int j = std::max(0, i - kBand); j <= i; ++j) {
        const int gap = free_points[i] - free_points[j];
        double s = gap <= kBand ? h(free_points[i], free_points[j]) : 0.0;
        for (int k = std::max(0, i - kBand); k < j; ++k) s -= at(i, k) * at(j, k);
        if (i == j) {
          at(i, i) = std::sqrt(std::max(s, 1e-12 * hessian_scale));
        } else {
          at(i, j) = s / at(j, j);
        }
      }
    }
    inv_diag_.resize(n);
    for (int i = 0; i < n; ++i) inv_diag_[i] = 1.0 / at(i, i);
    // L's columns below the diagonal, contiguous in the order the back substitution uses them
    // (its rows are contiguous in l_ already).
    below_.assign(static_cast<size_t>(n) * kBand, 0.0);
    for (int i = 0; i < n; ++i) {
      for (int k = i + 1; k <= std::min(n - 1, i + kBand); ++k)
        below_[kBand * i + (k - i - 1)] = at(k, i);
    }
  }
  // z = L^{-T} y (back substitution), per axis: y and z hold kAxes values per point. The axis
  // count is fixed at compile time: this and applyInverse run on every cost evaluation, and
  // with a run-time count their loops cost more than the cost itself.
  template <int kAxes>
  void applyInverseTransposed(const double* y, double* z) const {
    for (int i = n_ - 1; i >= 0; --i) {
      const int count = std::min(n_ - 1 - i, kBand);
      const double* l = &below_[kBand * i];
      const double* z_next = z + kAxes * (i + 1);
      for (int a = 0; a < kAxes; ++a) {
        double s = y[kAxes * i + a];
        for (int j = 0; j < count; ++j) s -= l[j] * z_next[kAxes * j + a];
        z[kAxes * i + a] = s * inv_diag_[i];
      }
    }
  }
  // w = L^{-1} g (forward substitution), per axis.
  template <int kAxes>
  void applyInverse(const double* g, double* w) const {
    for (int i = 0; i < n_; ++i) {
      const int count = std::min(i, kBand);
      const double* l = &l_[static_cast<size_t>(i) * (kBand + 1) + (kBand - count)];
      const double* w_prev = w + kAxes * (i - count);
      for (int a = 0; a < kAxes; ++a) {
        double s = g[kAxes * i + a];
        for (int j = 0; j < count; ++j) s -= l[j] * w_prev[kAxes * j + a];
        w[kAxes * i + a] = s * inv_diag_[i];
      }
    }
  }

 private:
  // Row i keeps L(i, i - kBand) .. L(i, i) contiguously, in the order of the columns.
  double& at(int i, int j) { return l_[static_cast<size_t>(i) * (kBand + 1) + (kBand - (i - j))]; }
  double at(int i, int j) const {
    return l_[static_cast<size_t>(i) * (kBand + 1) + (kBand - (i - j))];
  }
  int n_ = 0;
  std::vector<double> l_;
  std::vector<double> inv_diag_;
  std::vector<double> below_;  // below_[kBand i + j] = L(i + 1 + j, i)
};

struct Problem {
  const BsplineCost* cost;
  const std::vector<int>* free_points;
  const SmoothnessPreconditioner* precond;
  int first = 0, last = 0;   // span of the free points
  Eigen::Matrix3Xd q;        // all control points; the free ones are overwritten per evaluation
  Eigen::Matrix3Xd q_start;  // free points at the start (y = 0)
  Eigen::Matrix3Xd grad;
  std::vector<double> work, work2;
  double dt;
  int axes = 3;        // optimised coordinates per point: x, y (, z)
  double scale = 1.0;  // objective multiplier that makes the initial gradient O(1)
  int evaluations = 0;
  double best_f = std::numeric_limits<double>::infinity();
  std::vector<double> best_y;
};

// Control points from the optimisation variables y (kAxes = Problem::axes).
template <int kAxes>
void scatterAxes(Problem& pb, const double* y) {
  pb.precond->applyInverseTransposed<kAxes>(y, pb.work.data());
  const std::vector<int>& idx = *pb.free_points;
  for (size_t k = 0; k < idx.size(); ++k) {
    for (int a = 0; a < kAxes; ++a) pb.q(a, idx[k]) = pb.q_start(a, k) + pb.work[kAxes * k + a];
  }
}

void scatter(Problem& pb, const double* y) {
  if (pb.axes == 2)
    scatterAxes<2>(pb, y);
  else
    scatterAxes<3>(pb, y);
}

// The gradient in y from the gradient in the control points (pb.grad).
template <int kAxes>
void gatherGradient(Problem& pb, double* g) {
  const std::vector<int>& idx = *pb.free_points;
  for (size_t k = 0; k < idx.size(); ++k) {
    for (int a = 0; a < kAxes; ++a) pb.work2[kAxes * k + a] = pb.grad(a, idx[k]);
  }
  pb.precond->applyInverse<kAxes>(pb.work2.data(), g);
}

double objective(unsigned n, const double* y, double* g, void* data) {
  auto* pb = static_cast<Problem*>(data);
  scatter(*pb, y);
  const CostTerms t =
      pb->cost->evaluate(pb->q, pb->dt, g ? &pb->grad : nullptr, pb->first, pb->last);
  if (g) {
    if (pb->axes == 2)
      gatherGradient<2>(*pb, g);
    else
      gatherGradient<3>(*pb, g);
    for (unsigned i = 0; i < n; ++i) g[i] *= pb->scale;
  }
  ++pb->evaluations;
  if (std::isfinite(t.total) && t.total < pb->best_f) {
    pb->best_f = t.total;
    pb->best_y.assign(y, y + n);
  }
  return pb->scale * t.total;
}

}  // namespace

OptimizeResult optimizeControlPoints(UniformBspline& spline, const BsplineCost& cost,
                                     const std::vector<int>& free_points, int max_evaluations,
                                     double ftol_rel, bool keep_altitude) {
  OptimizeResult result;
  const int n_cols = spline.numControlPoints();
  for (size_t k = 0; k < free_points.size(); ++k) {
    const int i = free_points[k];
    if (i < kFixed || i >= n_cols - kFixed || (k > 0 && i <= free_points[k - 1])) {
      result.error = "free control points must be sorted and not fixed";
      return result;
    }
  }
  if (free_points.empty()) {
    result.terms = cost.evaluate(spline.controlPoints(), spline.knotSpan(), nullptr);
    result.ok = std::isfinite(result.terms.total);
    if (!result.ok) result.error = "cost is not finite";
    return result;
  }
  const int m = static_cast<int>(free_points.size());
  const double dt = spline.knotSpan();
  const SmoothnessPreconditioner precond(
      free_points, 2.0 * std::max(cost.weights().smooth, 1e-12) / std::pow(dt, 5));
  Problem pb;
  pb.cost = &cost;
  pb.free_points = &free_points;
  pb.precond = &precond;
  pb.first = free_points.front();
  pb.last = free_points.back();
  pb.q = spline.controlPoints();
  pb.q_start.resize(3, m);
  for (int k = 0; k < m; ++k) pb.q_start.col(k) = pb.q.col(free_points[k]);
  pb.grad.resize(3, n_cols);
  pb.axes = keep_altitude ? 2 : 3;
  pb.work.assign(pb.axes * m, 0.0);
  pb.work2.assign(pb.axes * m, 0.0);
  pb.dt = dt;
  const unsigned n = static_cast<unsigned>(pb.axes * m);
  std::vector<double> y(n, 0.0);

  // NLopt's L-BFGS takes its first step from the raw gradient; when it is huge (deep
  // collisions with a high weight) that step overshoots and the line search gives up ("nlopt
  // failure"). Scaling the objective (which does not move the minimum) avoids it.
  std::vector<double> g0(n);
  pb.scale = 1.0;
  objective(n, y.data(), g0.data(), &pb);
  double g_inf = 0.0;
  for (double v : g0) g_inf = std::max(g_inf, std::abs(v));
  pb.scale = g_inf > 1.0 ? 1.0 / g_inf : 1.0;
  pb.evaluations = 0;
  pb.best_f = std::numeric_limits<double>::infinity();

  nlopt::opt opt(nlopt::LD_LBFGS, n);
  opt.set_min_objective(objective, &pb);
  opt.set_maxeval(max_evaluations);
  opt.set_ftol_rel(ftol_rel);
  // A short memory: NLopt's L-BFGS spends O(n m) per step in its own bookkeeping, which here
  // costs more than the objective; with the preconditioned variables 4 pairs suffice.
  opt.set_vector_storage(kLbfgsMemory);
  double f = 0.0;
  try {
    opt.optimize(y, f);
  } catch (const nlopt::roundoff_limited&) {
    // L-BFGS stops this way when the line search cannot improve further: the best point so far
    // is still a valid answer.
  } catch (const std::exception& e) {
    result.error = std::string("NLopt: ") + e.what();
  }
  result.evaluations = pb.evaluations;
  if (pb.best_y.size() != n) {
    if (result.error.empty()) result.error = "no finite cost evaluated";
    return result;
  }
  scatter(pb, pb.best_y.data());
  if (!pb.q.allFinite()) {
    result.error = "control points are not finite";
    return result;
  }
  spline.controlPoints() = pb.q;
  result.terms = cost.evaluate(pb.q, dt, nullptr);
  result.ok = true;
  return result;
}

OptimizeResult optimizeControlPoints(UniformBspline& spline, const BsplineCost& cost,
                                     int max_evaluations, double ftol_rel, bool keep_altitude) {
  std::vector<int> all;
  for (int i = kFixed; i < spline.numControlPoints() - kFixed; ++i) all.push_back(i);
  return optimizeControlPoints(spline, cost, all, max_evaluations, ftol_rel, keep_altitude);
}

}  // namespace mmh::eam
