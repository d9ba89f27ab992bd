// Real roots of a cubic polynomial in closed form (no allocation): what the exact maxima of
// speed need on cubic pieces, whose squared speed is a quartic.
#pragma once

namespace mmh::eam {

// Real roots of a x^3 + b x^2 + c x + d = 0, degenerate leading coefficients included (then
// the quadratic or linear roots). Returns how many were written to roots (at most 3).
int cubicRoots(double a, double b, double c, double d, double roots[3]);

}  // namespace mmh::eam
