#pragma once
// Johnson-Cook flow stress (Afrasiabi et al. 2021, Eq. 9) and the radial-return mapping of J2
// plasticity used by the SPH solid solver (plane strain: the stress carries a zz component).
//
//   sigma_y = [A + B eps_p^n] [1 + C ln(max(epsdot_p / epsdot_0, 1))] [1 - T*^m],
//   T* = (T - T_r) / (T_m - T_r) clamped to [0, 1].
//
// The rate factor is floored at 1 (no softening below the reference rate), which is the usual
// choice in SPH cutting codes; the paper is silent.
#include <Eigen/Core>

namespace cutbench::sph {

struct JohnsonCook {
  double A = 862e6, B = 331e6, C = 0.01, m = 0.8, n = 0.35;  // Ti6Al4V, paper Sec. 5.2
  double T_ref = 300.0, T_melt = 1878.0;                      // K, paper Table 1
  double eps_rate_ref = 1.0;                                 // 1/s
  // Temperature-dependent strain softening of Sima & Oezel (2010), the law of the authors'
  // refinement paper (their ref. [20]) for the Fig. 10 cut; off unless `softening`:
  //   sigma_y = [A + B eps^n exp(-eps^a)] [rate factor] [1 - T*^m] [D + (1 - D) tanh(1 / (eps + S)^c)^s],
  //   D = 1 - (T / T_m)^d,  S = (T / T_m)^b  (T in K).
  bool softening = false;
  double sa = 0.0, sb = 0.0, sc = 0.0, sd = 0.0, ss = 0.0;

  double flow_stress(double eps_p, double eps_rate_p, double T) const;
  // d sigma_y / d eps_p at fixed rate, and d sigma_y / d (eps rate) at fixed strain.
  double d_strain(double eps_p, double eps_rate_p, double T) const;
  double d_rate(double eps_p, double eps_rate_p, double T) const;
  // eps_p^n (0 for eps_p <= 0), as radial_return computes and returns it
  double eps_pow_n(double eps_p) const;
};

// The Sima & Oezel (2010) Ti6Al4V constants (A 724.7 MPa, B 683.1 MPa, C 0.035, m 1, n 0.47,
// a 2, b 5, c 2, d 1, s 0.05, T_m 1878 K, T_r 300 K, reference rate 1/s).
JohnsonCook sima_ozel_ti6al4v();

// 3x3 symmetric stress with the out-of-plane component (plane strain).
using Stress3 = Eigen::Matrix3d;

struct ReturnResult {
  Stress3 deviator;            // returned deviatoric stress
  double delta_eps_p = 0.0;    // equivalent plastic strain increment
  double flow_stress = 0.0;    // sigma_y at the end of the step (or at the start if elastic)
  double eps_p_pow_n = 0.0;    // eps_p^n at the end of the step (0 for eps_p = 0), for the next call
  int iterations = 0;
  bool plastic = false;
};

// Radial return: given the trial deviatoric stress, shear modulus G, plastic strain eps_p at the
// start of the step, step dt and temperature T, find d >= 0 with
//   q_trial - 3 G d = sigma_y(eps_p + d, d / dt, T),   q = sqrt(3/2 s:s),
// by safeguarded Newton (bisection fallback), and scale the deviator by (1 - 3 G d / q_trial).
// `guess` (optional, > 0): first Newton iterate, e.g. the particle's increment of the previous
// step (clipped to the bracket); the root and the tolerance are the same, only the path differs.
// `eps_p_pow_n` (optional, >= 0): eps_p^n as an earlier call returned it (saves one pow per call).
ReturnResult radial_return(const JohnsonCook& jc, const Stress3& trial_deviator, double G, double eps_p,
                           double dt, double T, double guess = 0.0, double eps_p_pow_n = -1.0);

double von_mises(const Stress3& deviator);

}  // namespace cutbench::sph
