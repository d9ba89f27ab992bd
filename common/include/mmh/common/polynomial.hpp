// One-dimensional polynomials in ascending coefficient order (c0 + c1 t + c2 t^2 + ...):
// evaluation, derivatives, products, and the real roots inside an interval.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mmh {

// Coefficients in ascending order; trailing zeros are allowed.
using PolyCoeffs = Eigen::VectorXd;

double polyEval(const PolyCoeffs& c, double t);
PolyCoeffs polyDerivative(const PolyCoeffs& c);
PolyCoeffs polyMultiply(const PolyCoeffs& a, const PolyCoeffs& b);
PolyCoeffs polyAdd(const PolyCoeffs& a, const PolyCoeffs& b);
// Antiderivative evaluated between 0 and t.
double polyIntegral(const PolyCoeffs& c, double t);

// All real roots of c in [lo, hi], sorted. Exact up to floating point: the polynomial is split
// into monotone pieces by the roots of its derivative (recursively) and each sign change is
// bracketed and refined by bisection/Newton, so no root is missed between samples.
std::vector<double> polyRealRoots(const PolyCoeffs& c, double lo, double hi);

// Maximum of c over [lo, hi] (checks the end points and every stationary point).
double polyMaxOnInterval(const PolyCoeffs& c, double lo, double hi, double* argmax = nullptr);

}  // namespace mmh
