#include "mmh/som/ellipsoid.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <vector>

namespace mmh::som {

double Ellipsoid::volume() const {
  return 4.0 / 3.0 * M_PI * shape.determinant();
}

bool Ellipsoid::contains(const Eigen::Vector3d& p) const {
  return shape.ldlt().solve(p - center).squaredNorm() <= 1.0;
}

double Ellipsoid::support(const Eigen::Vector3d& a) const {
  return a.dot(center) + (shape * a).norm();
}

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Mat36 = Eigen::Matrix<double, 3, 6>;

// Unknowns y = (d_x, d_y, d_z, c00, c11, c22, c01, c02, c12); C = sum_p y_{3+p} E_p with the
// symmetric basis E_0..E_5 below.
Eigen::Matrix3d shapeOf(const Vec9& y) {
  Eigen::Matrix3d c;
  c << y[3], y[6], y[7], y[6], y[4], y[8], y[7], y[8], y[5];
  return c;
}

const Eigen::Matrix3d& basis(int p) {
  static const Eigen::Matrix3d e[6] = {(Eigen::Matrix3d() << 1, 0, 0, 0, 0, 0, 0, 0, 0).finished(),
                                       (Eigen::Matrix3d() << 0, 0, 0, 0, 1, 0, 0, 0, 0).finished(),
                                       (Eigen::Matrix3d() << 0, 0, 0, 0, 0, 0, 0, 0, 1).finished(),
                                       (Eigen::Matrix3d() << 0, 1, 0, 1, 0, 0, 0, 0, 0).finished(),
                                       (Eigen::Matrix3d() << 0, 0, 1, 0, 0, 0, 1, 0, 0).finished(),
                                       (Eigen::Matrix3d() << 0, 0, 0, 0, 0, 1, 0, 1, 0).finished()};
  return e[p];
}

// J(a) = [E_0 a, ..., E_5 a]: C a = J(a) (c00, c11, c22, c01, c02, c12).
Mat36 jacobianOf(const Eigen::Vector3d& a) {
  Mat36 j = Mat36::Zero();
  j(0, 0) = a[0];
  j(1, 1) = a[1];
  j(2, 2) = a[2];
  j(0, 3) = a[1];
  j(1, 3) = a[0];
  j(0, 4) = a[2];
  j(2, 4) = a[0];
  j(1, 5) = a[2];
  j(2, 5) = a[1];
  return j;
}

class BarrierProblem {
 public:
  explicit BarrierProblem(const Polytope& poly) : h_(poly.halfspaces()) {
    jtj_.resize(h_.rows());
    for (int i = 0; i < h_.rows(); ++i) {
      const Mat36 j = jacobianOf(h_.row(i).head<3>().transpose());
      jtj_[i] = j.transpose() * j;
    }
  }

  // f(y) = -log det C - mu sum log g_i; +inf outside the domain. Gradient and Hessian if asked.
  double value(const Vec9& y, double mu, Vec9* grad, Mat9* hess) const {
    const double inf = std::numeric_limits<double>::infinity();
    const Eigen::Matrix3d c = shapeOf(y);
    Eigen::LLT<Eigen::Matrix3d> llt(c);
    if (llt.info() != Eigen::Success) return inf;
    const Eigen::Matrix3d l = llt.matrixL();
    if (!(l.diagonal().minCoeff() > 0.0)) return inf;
    double f = -2.0 * l.diagonal().array().log().sum();
    const Eigen::Vector3d d = y.head<3>();
    if (grad) {
      grad->setZero();
      hess->setZero();
      const Eigen::Matrix3d ci = llt.solve(Eigen::Matrix3d::Identity());
      Eigen::Matrix3d m[6];
      for (int p = 0; p < 6; ++p) {
        m[p] = ci * basis(p);
        (*grad)[3 + p] = -m[p].trace();
      }
      for (int p = 0; p < 6; ++p)
        for (int q = p; q < 6; ++q)
          (*hess)(3 + p, 3 + q) = (*hess)(3 + q, 3 + p) = m[p].cwiseProduct(m[q].transpose()).sum();
    }
    for (int i = 0; i < h_.rows(); ++i) {
      const Eigen::Vector3d a = h_.row(i).head<3>().transpose();
      const Eigen::Vector3d w = c * a;
      const double s = w.norm();
      const double g = h_(i, 3) - a.dot(d) - s;
      if (!(g > 0.0)) return inf;
      f -= mu * std::log(g);
      if (!grad) continue;
      // dg/dy = -(a, J^T w/s); d2g/dy2 = -(J^T J - v v^T) / s in the C block.
      Vec9 dg;
      dg.head<3>() = -a;
      Vec6 v = Vec6::Zero();
      if (s > 1e-300) {
        const Eigen::Vector3d wh = w / s;
        v << a[0] * wh[0], a[1] * wh[1], a[2] * wh[2], a[1] * wh[0] + a[0] * wh[1],
            a[2] * wh[0] + a[0] * wh[2], a[2] * wh[1] + a[1] * wh[2];
      }
      dg.tail<6>() = -v;
      *grad -= (mu / g) * dg;
      hess->noalias() += (mu / (g * g)) * dg * dg.transpose();
      if (s > 1e-300)
        hess->bottomRightCorner<6, 6>() += (mu / (g * s)) * (jtj_[i] - v * v.transpose());
    }
    return f;
  }

 private:
  const Polytope::Matrix& h_;
  std::vector<Mat6> jtj_;
};

}  // namespace

bool inscribedEllipsoid(const Polytope& poly, const Ellipsoid& start, Ellipsoid* out,
                        const InscribedEllipsoidOptions& options) {
  const Polytope::Matrix& h = poly.halfspaces();
  if (h.rows() < 4) return false;
  // Shrink the start about its centre until it lies strictly inside.
  double scale = 1.0;
  for (int i = 0; i < h.rows(); ++i) {
    const Eigen::Vector3d a = h.row(i).head<3>().transpose();
    const double slack = h(i, 3) - a.dot(start.center);
    if (!(slack > 0.0)) return false;
    const double reach = (start.shape * a).norm();
    if (reach > 0.0) scale = std::min(scale, 0.9 * slack / reach);
  }
  if (!(scale > 0.0)) return false;
  const Eigen::Matrix3d c0 = scale * start.shape;
  Vec9 y;
  y << start.center, c0(0, 0), c0(1, 1), c0(2, 2), c0(0, 1), c0(0, 2), c0(1, 2);

  BarrierProblem problem(poly);
  Vec9 grad, trial;
  Mat9 hess;
  for (double mu = options.barrier_start;; mu *= 0.1) {
    const double mu_stage = std::max(mu, options.barrier_final);
    for (int step = 0; step < options.max_newton_steps; ++step) {
      const double f = problem.value(y, mu_stage, &grad, &hess);
      if (!std::isfinite(f)) return false;
      hess.diagonal().array() += 1e-12 * (1.0 + hess.diagonal().cwiseAbs().maxCoeff());
      const Vec9 delta = hess.ldlt().solve(-grad);
      const double decrement = -grad.dot(delta);
      if (!(decrement > 2.0 * options.newton_tolerance)) break;
      double alpha = 1.0;
      bool moved = false;
      while (alpha > 1e-8) {
        trial = y + alpha * delta;
        const double ft = problem.value(trial, mu_stage, nullptr, nullptr);
        if (ft <= f - 1e-4 * alpha * decrement) {
          y = trial;
          moved = true;
          break;
        }
        alpha *= 0.5;
      }
      if (!moved) break;
    }
    if (mu_stage <= options.barrier_final) break;
  }
  out->center = y.head<3>();
  out->shape = shapeOf(y);
  return true;
}

}  // namespace mmh::som
