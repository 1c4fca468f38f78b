// Motion graph (thesis §3.3): "each graph was represented as a piecewise linear function with 4
// single precision float data points each (linearly interpolated when read)". The knots sit at
// φ = 0, 1/3, 2/3, 1 of the phase the graph is read with (gait phase Φ for leg-frame graphs,
// swing progress ϕ for h_sw, t_sw and k_ft). Stored as double: the optimiser and the parameter
// schema work in double, and the cost is nil (4 numbers per graph).
#pragma once

namespace gaitlab::gait {

struct MotionGraph {
  static constexpr int kKnots = 4;
  double knots[kKnots] = {0.0, 0.0, 0.0, 0.0};  // values at φ = 0, 1/3, 2/3, 1

  static constexpr MotionGraph constant(double v) { return MotionGraph{{v, v, v, v}}; }
  static constexpr MotionGraph of(double k0, double k1, double k2, double k3) {
    return MotionGraph{{k0, k1, k2, k3}};
  }

  // Value at φ; φ outside [0, 1] is clamped (so is NaN, to 0), so a caller reading slightly past
  // the end of a phase (late strike: swing progress held at 1) gets the end value.
  double eval(double phi) const {
    if (!(phi > 0.0)) return knots[0];  // also catches NaN
    if (phi >= 1.0) return knots[kKnots - 1];
    const double x = phi * (kKnots - 1);
    int i = static_cast<int>(x);
    if (i > kKnots - 2) i = kKnots - 2;  // guards rounding of x just below 3
    const double t = x - i;
    return knots[i] + (knots[i + 1] - knots[i]) * t;
  }
};

}  // namespace gaitlab::gait
