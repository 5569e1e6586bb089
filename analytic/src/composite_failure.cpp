#include "cutbench/analytic/composite_failure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cutbench/common/errors.hpp"
#include "gsl_util.hpp"

namespace cutbench::analytic {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double sq(double x) { return x * x; }
double macaulay(double x) { return x > 0.0 ? x : 0.0; }

double effective_S_T(const Lamina& m) {
  return (m.S_T > 0.0) ? m.S_T : transverse_shear_strength(m.Y_C, m.alpha0);
}

// Governing mode: the largest of the fibre, matrix and shear indices (ties: first listed).
void finish(FailureIndices& r, FailureMode fibre_mode, FailureMode matrix_mode) {
  r.index = r.fibre;
  r.mode = fibre_mode;
  if (r.matrix > r.index) {
    r.index = r.matrix;
    r.mode = matrix_mode;
  }
  if (!std::isnan(r.shear) && r.shear > r.index) {
    r.index = r.shear;
    r.mode = FailureMode::shear;
  }
}

// LaRC matrix tension form (g = 1: the quadratic form printed by Kahwash).
double larc_matrix_tension(double s22, double t12, double Y_T, double S_L, double g) {
  return (1.0 - g) * s22 / Y_T + g * sq(s22 / Y_T) + sq(t12 / S_L);
}

struct PlaneSearch {
  double value;
  double angle;
};

// cos and sin of the search grid alpha0 i / n, i = 0..n, kept per thread for the last alpha0: the
// grid values are those of std::cos / std::sin of the same argument, so the search is unchanged
// (it is the hot spot of an EFG run with LaRC02: 80 % of the time went into these 181 sincos).
struct FractureGrid {
  static constexpr int n = 180;
  double alpha0 = -1.0;
  double c[n + 1], s[n + 1];
  const FractureGrid& at(double a0) {
    if (a0 != alpha0) {
      for (int i = 0; i <= n; ++i) {
        const double a = a0 * i / n;
        c[i] = std::cos(a);
        s[i] = std::sin(a);
      }
      alpha0 = a0;
    }
    return *this;
  }
};

// max over a in [0, a0] of (tau_T/S_T)^2 + (tau_L/S_L)^2 (LaRC02 matrix compression), with
// tau_T = <-s22 c (s - eta_T c)>, tau_L = <c (|t12| + eta_L s22 c)>, c = cos a, s = sin a. The grid
// brackets the global maximum; a safeguarded Newton iteration on dg/da = 0 (analytic first and
// second derivatives, bisection whenever a Newton step leaves the bracket or does not shrink it
// fast enough) then locates it to round-off in 4-6 steps, one sincos each.
PlaneSearch larc_matrix_compression(double s22, double t12, double S_T, double S_L, double eta_T,
                                    double eta_L, double alpha0) {
  const double at = std::abs(t12);
  auto g = [&](double c, double s) {
    const double tT = macaulay(-s22 * c * (s - eta_T * c));
    const double tL = macaulay(c * (at + eta_L * s22 * c));
    return sq(tT / S_T) + sq(tL / S_L);
  };
  // g, dg/da and d2g/da2 at a (the Macaulay brackets contribute only where open)
  struct Derivs {
    double g, d1, d2;
  };
  auto derivs = [&](double a) {
    const double c = std::cos(a), s = std::sin(a);
    const double c2 = c * c - s * s, s2 = 2.0 * s * c;  // cos 2a, sin 2a
    const double tT = -s22 * c * (s - eta_T * c), tL = c * (at + eta_L * s22 * c);
    const double tT1 = -s22 * (c2 + eta_T * s2), tT2 = -s22 * (-2.0 * s2 + 2.0 * eta_T * c2);
    const double tL1 = -at * s - eta_L * s22 * s2, tL2 = -at * c - 2.0 * eta_L * s22 * c2;
    Derivs r{0.0, 0.0, 0.0};
    const double wT = 1.0 / (S_T * S_T), wL = 1.0 / (S_L * S_L);
    if (tT > 0.0) {
      r.g += tT * tT * wT;
      r.d1 += 2.0 * tT * tT1 * wT;
      r.d2 += 2.0 * (tT1 * tT1 + tT * tT2) * wT;
    }
    if (tL > 0.0) {
      r.g += tL * tL * wL;
      r.d1 += 2.0 * tL * tL1 * wL;
      r.d2 += 2.0 * (tL1 * tL1 + tL * tL2) * wL;
    }
    return r;
  };
  thread_local FractureGrid table;
  const FractureGrid& grid = table.at(alpha0);
  const int n = FractureGrid::n;
  // The grid values first (independent of each other, so the loop vectorises), then their largest
  // in four independent chains, then its first index: the same value and index as a running
  // maximum (which chained every point to the comparison before it), bit for bit. A NaN is never
  // taken unless it is values[0], which then stays, as in the running maximum.
  double values[FractureGrid::n + 1];
  for (int i = 0; i <= n; ++i) values[i] = g(grid.c[i], grid.s[i]);
  double lane[4] = {values[0], values[0], values[0], values[0]};
  int i = 1;
  for (; i + 3 <= n; i += 4) {
    for (int k = 0; k < 4; ++k) lane[k] = values[i + k] > lane[k] ? values[i + k] : lane[k];
  }
  for (; i <= n; ++i) lane[0] = values[i] > lane[0] ? values[i] : lane[0];
  double best_v = lane[0];
  for (int k = 1; k < 4; ++k) best_v = lane[k] > best_v ? lane[k] : best_v;
  int best = 0;
  if (best_v > values[0]) {
    while (!(values[best] == best_v)) ++best;
  }
  PlaneSearch out{best_v, alpha0 * best / n};
  // A stationary point of g in the grid intervals next to the best grid point: dg/da > 0 at lo and
  // < 0 at hi. Otherwise the maximum over the bracket is at the grid point itself (or an end).
  double lo = alpha0 * std::max(0, best - 1) / n, hi = alpha0 * std::min(n, best + 1) / n;
  if (best > 0 && best < n) {
    // keep the half-interval whose ends straddle the sign change of dg/da
    const double d_mid = derivs(out.angle).d1;
    if (d_mid > 0.0) lo = out.angle;
    else if (d_mid < 0.0) hi = out.angle;
    else return out;
  }
  const Derivs dlo = derivs(lo), dhi = derivs(hi);
  if (!(dlo.d1 > 0.0 && dhi.d1 < 0.0)) return out;
  double a = 0.5 * (lo + hi), step_old = hi - lo, step = step_old;
  for (int it = 0; it < 60; ++it) {
    const Derivs d = derivs(a);
    if (d.d1 > 0.0) lo = a;
    else if (d.d1 < 0.0) hi = a;
    else break;
    // Newton on dg/da when it stays inside the bracket and halves the step at least every two
    // iterations; bisection otherwise
    const double newton = d.d2 < 0.0 ? a - d.d1 / d.d2 : HUGE_VAL;
    double next;
    if (newton > lo && newton < hi && std::abs(newton - a) < 0.5 * std::abs(step_old)) {
      next = newton;
    } else {
      next = 0.5 * (lo + hi);
    }
    step_old = step;
    step = next - a;
    a = next;
    if (std::abs(step) <= 1e-14 || hi - lo <= 1e-14) break;  // radians: the value is flat to 1e-28 there
  }
  const double va = g(std::cos(a), std::sin(a));
  if (va >= out.value) out = {va, a};
  return out;
}

}  // namespace

double transverse_shear_strength(double Y_C, double alpha0) {
  return Y_C * std::cos(alpha0) * (std::sin(alpha0) + std::cos(alpha0) / std::tan(2.0 * alpha0));
}

double larc_eta_T(double alpha0) { return -1.0 / std::tan(2.0 * alpha0); }

double larc_eta_L(double S_L, double Y_C, double alpha0) {
  return -S_L * std::cos(2.0 * alpha0) / (Y_C * sq(std::cos(alpha0)));
}

double larc_misalignment_angle_at_XC(double S_L, double X_C, double eta_L) {
  const double q = S_L / X_C;
  const double disc = 1.0 - 4.0 * (q + eta_L) * q;
  if (disc < 0.0) {
    throw InputError("S_L", "LaRC02 kinking: 1 - 4 (S_L/X_C + eta_L)(S_L/X_C) < 0, no misalignment angle");
  }
  return std::atan((1.0 - std::sqrt(disc)) / (2.0 * (q + eta_L)));
}

double larc_toughness_ratio(double E1, double E2, double nu21, double G12, double Y_T, double S_L) {
  const double L22 = 2.0 * (1.0 / E2 - nu21 * nu21 / E1);
  const double L44 = 1.0 / G12;
  return L22 / L44 * sq(Y_T / S_L);
}

FailureIndices max_stress_failure(const PlaneStress& s, const Lamina& m) {
  FailureIndices r;
  r.fibre = s.s11 > 0.0 ? sq(s.s11 / m.X_T) : sq(s.s11 / m.X_C);
  r.matrix = s.s22 > 0.0 ? sq(s.s22 / m.Y_T) : sq(s.s22 / m.Y_C);
  r.shear = sq(s.t12 / m.S_L);
  finish(r, s.s11 > 0.0 ? FailureMode::fibre_tension : FailureMode::fibre_compression,
         s.s22 >= 0.0 ? FailureMode::matrix_tension : FailureMode::matrix_compression);
  return r;
}

FailureIndices hashin_failure(const PlaneStress& s, const Lamina& m) {
  FailureIndices r;
  r.shear = kNaN;
  if (s.s11 > 0.0) {
    r.fibre = sq(s.s11 / m.X_T) + sq(s.t12 / m.S_L);
  } else {
    r.fibre = sq(s.s11 / m.X_C);
  }
  if (s.s22 >= 0.0) {
    r.matrix = sq(s.s22 / m.Y_T) + sq(s.t12 / m.S_L);
  } else {
    const double ST = effective_S_T(m);
    r.matrix = sq(s.s22 / (2.0 * ST)) + (sq(m.Y_C / (2.0 * ST)) - 1.0) * s.s22 / m.Y_C +
               sq(s.t12 / m.S_L);
  }
  finish(r, s.s11 > 0.0 ? FailureMode::fibre_tension : FailureMode::fibre_compression,
         s.s22 >= 0.0 ? FailureMode::matrix_tension : FailureMode::matrix_compression);
  return r;
}

FailureIndices larc02_failure(const PlaneStress& s, const Lamina& m) { return larc02_failure(s, m, true); }

namespace {
// The lamina constants of LaRC02 (transverse shear strength, friction coefficients, the
// misalignment angle at X_C), kept per thread for the last lamina: they cost trigonometric
// functions of constants on every call otherwise (9 % of an EFG run with LaRC02).
struct LarcConstants {
  double Y_C = kNaN, alpha0 = kNaN, S_L = kNaN, X_C = kNaN;
  double ST = 0.0, eta_T = 0.0, eta_L = 0.0, psiC = 0.0;
  bool have_psi = false;
  const LarcConstants& of(const Lamina& m) {
    if (!(Y_C == m.Y_C && alpha0 == m.alpha0 && S_L == m.S_L && X_C == m.X_C)) {
      ST = transverse_shear_strength(m.Y_C, m.alpha0);
      eta_T = larc_eta_T(m.alpha0);
      eta_L = larc_eta_L(m.S_L, m.Y_C, m.alpha0);
      have_psi = false;
      Y_C = m.Y_C;
      alpha0 = m.alpha0;
      S_L = m.S_L;
      X_C = m.X_C;
    }
    return *this;
  }
  double misalignment_at_XC() {  // throws (every time) when the lamina has none
    if (!have_psi) {
      psiC = larc_misalignment_angle_at_XC(S_L, X_C, eta_L);
      have_psi = true;
    }
    return psiC;
  }
};
}  // namespace

FailureIndices larc02_failure(const PlaneStress& s, const Lamina& m, bool matrix_compression_search) {
  FailureIndices r;
  r.shear = kNaN;
  r.fracture_angle = kNaN;
  r.misalignment = kNaN;
  thread_local LarcConstants constants;
  constants.of(m);
  const double ST = constants.ST, eta_T = constants.eta_T, eta_L = constants.eta_L;
  const double eps1T = (m.eps1_T > 0.0) ? m.eps1_T : m.X_T / m.E1;

  // Misalignment-frame stresses (used for fibre compression and for matrix compression when
  // s11 < -Y_C).
  double s22m = s.s22, t12m = s.t12;
  bool kink_degenerate = false;
  if (s.s11 < 0.0) {
    const double psiC = constants.misalignment_at_XC();
    const double den = m.G12 + s.s11 - s.s22;
    if (!(den > 0.0)) {
      kink_degenerate = true;  // compression beyond the shear stiffness: kink band unstable
    } else {
      const double psi = (std::abs(s.t12) + (m.G12 - m.X_C) * psiC) / den;
      r.misalignment = psi;
      const double c = std::cos(psi), sn = std::sin(psi), at = std::abs(s.t12);
      s22m = sn * sn * s.s11 + c * c * s.s22 - 2.0 * sn * c * at;
      t12m = -sn * c * s.s11 + sn * c * s.s22 + (c * c - sn * sn) * at;
    }
  }

  // Fibre modes.
  if (s.s11 >= 0.0) {
    r.fibre = (s.s11 - m.nu12 * s.s22) / m.E1 / eps1T;
  } else if (kink_degenerate) {
    r.fibre = 1e6;
  } else if (s22m < 0.0) {
    r.fibre = macaulay(std::abs(t12m) + eta_L * s22m) / m.S_L;
  } else {
    r.fibre = larc_matrix_tension(s22m, t12m, m.Y_T, m.S_L, m.g);
  }

  // Matrix modes.
  if (s.s22 >= 0.0) {
    r.matrix = larc_matrix_tension(s.s22, s.t12, m.Y_T, m.S_L, m.g);
  } else if (!matrix_compression_search) {
    r.matrix = kNaN;
  } else {
    const bool use_m = s.s11 < -m.Y_C && !kink_degenerate;
    const auto ps = larc_matrix_compression(use_m ? s22m : s.s22, use_m ? t12m : s.t12, ST, m.S_L,
                                            eta_T, eta_L, m.alpha0);
    r.matrix = ps.value;
    r.fracture_angle = ps.angle;
  }
  finish(r, s.s11 >= 0.0 ? FailureMode::fibre_tension : FailureMode::fibre_compression,
         s.s22 >= 0.0 ? FailureMode::matrix_tension : FailureMode::matrix_compression);
  return r;
}

FailureIndices failure_indices(Criterion c, const PlaneStress& s, const Lamina& m) {
  switch (c) {
    case Criterion::max_stress: return max_stress_failure(s, m);
    case Criterion::hashin: return hashin_failure(s, m);
    case Criterion::larc02: return larc02_failure(s, m);
  }
  throw InputError("criterion", "unknown failure criterion");
}

EnvelopePoint failure_envelope_point(Criterion c, EnvelopePlane plane, double theta, double fixed,
                                     const Lamina& m) {
  const double ct = std::cos(theta), st = std::sin(theta);
  auto stress_at = [&](double r) {
    PlaneStress s;
    if (plane == EnvelopePlane::s11_s22) {
      s.s11 = r * ct;
      s.s22 = r * st;
      s.t12 = fixed;
    } else {
      s.s11 = fixed;
      s.s22 = r * ct;
      s.t12 = r * st;
    }
    return s;
  };
  auto f = [&](double r) { return failure_indices(c, stress_at(r), m).index - 1.0; };
  const double smin = std::min({m.X_T, m.X_C, m.Y_T, m.Y_C, m.S_L});
  const double smax = std::max({m.X_T, m.X_C, m.Y_T, m.Y_C, m.S_L});
  if (f(0.0) >= 0.0) {
    throw NumericalError("failure envelope: the fixed stress alone already fails the lamina");
  }
  double root = 0.0;
  if (!detail::first_root_geometric(f, 1e-6 * smin, 1e3 * smax, 1.02, "failure envelope", root)) {
    throw NumericalError("failure envelope: no failure along this ray up to 1000 x the largest strength");
  }
  const PlaneStress s = stress_at(root);
  EnvelopePoint p;
  p.radius = root;
  p.s1 = plane == EnvelopePlane::s11_s22 ? s.s11 : s.s22;
  p.s2 = plane == EnvelopePlane::s11_s22 ? s.s22 : s.t12;
  return p;
}

ParamSpec criterion_param(const std::string& default_option) {
  return option_param("criterion", "failure criterion",
                      {{"max_stress", "maximum stress"}, {"hashin", "Hashin"}, {"larc02", "LaRC02"}}, default_option);
}

}  // namespace cutbench::analytic
