// Kahwash (2018) Appendix A failure criteria and their envelopes.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "cutbench/analytic/composite_failure.hpp"

using namespace cutbench::analytic;
namespace tt = boost::test_tools;

namespace {
constexpr double kPi = 3.14159265358979323846;
// Kahwash Table 2 (means), SI.
Lamina gfrp() {
  Lamina m;
  m.X_T = 697.8e6;
  m.X_C = 443.76e6;
  m.Y_T = 89.7216e6;
  m.Y_C = 148.33e6;
  m.S_L = 33.1e6;
  m.S_T = 0.0;  // default from alpha0
  m.E1 = 34.28e9;
  m.G12 = 2.05e9;
  m.nu12 = 0.24244;
  m.eps1_T = 0.0;  // X_T/E1 (Table 2's 2.3 % is not X_T/E1 = 2.04 %)
  return m;
}
const Criterion kAll[] = {Criterion::max_stress, Criterion::hashin, Criterion::larc02};
}  // namespace

BOOST_AUTO_TEST_SUITE(composite_failure)

BOOST_AUTO_TEST_CASE(larc_auxiliary_relations) {
  const double a0 = 53.0 * kPi / 180.0;
  BOOST_TEST(larc_eta_T(a0) == 0.2867, tt::tolerance(2e-4));
  const Lamina m = gfrp();
  // alpha0 maximises the transverse effective stress in pure compression, which equals S_T.
  const double ST = transverse_shear_strength(m.Y_C, a0);
  const double eta_T = larc_eta_T(a0);
  auto tT = [&](double a) { return m.Y_C * std::cos(a) * (std::sin(a) - eta_T * std::cos(a)); };
  BOOST_TEST(tT(a0) == ST, tt::tolerance(1e-13));
  BOOST_TEST(tT(a0 + 1e-3) < ST);
  BOOST_TEST(tT(a0 - 1e-3) < ST);
  BOOST_TEST_MESSAGE("GFRP S_T = " << ST / 1e6 << " MPa, eta_L = " << larc_eta_L(m.S_L, m.Y_C, a0)
                     << ", psi_C = " << larc_misalignment_angle_at_XC(m.S_L, m.X_C, larc_eta_L(m.S_L, m.Y_C, a0)) * 180 / kPi
                     << " deg, g(Table 2) = " << larc_toughness_ratio(34.28e9, 11.57e9, 0.0932, 2.05e9, m.Y_T, m.S_L));
}

BOOST_AUTO_TEST_CASE(every_criterion_is_one_at_each_uniaxial_strength) {
  const Lamina m = gfrp();
  struct Case { PlaneStress s; FailureMode mode; };
  const Case cases[] = {
      {{m.X_T, 0, 0}, FailureMode::fibre_tension},
      {{-m.X_C, 0, 0}, FailureMode::fibre_compression},
      {{0, m.Y_T, 0}, FailureMode::matrix_tension},
      {{0, -m.Y_C, 0}, FailureMode::matrix_compression},
      {{0, 0, m.S_L}, FailureMode::shear},
      {{0, 0, -m.S_L}, FailureMode::shear},
  };
  for (auto c : kAll) {
    for (const auto& k : cases) {
      const auto r = failure_indices(c, k.s, m);
      BOOST_TEST_INFO("criterion " << static_cast<int>(c) << " stress " << k.s.s11 << " " << k.s.s22 << " " << k.s.t12);
      BOOST_TEST(r.index == 1.0, tt::tolerance(1e-12));
      FailureMode expected = k.mode;
      if (k.mode == FailureMode::shear && c != Criterion::max_stress) expected = FailureMode::matrix_tension;
      BOOST_TEST(static_cast<int>(r.mode) == static_cast<int>(expected));
      // Below the strength the index is below 1, above it above 1.
      PlaneStress lo{0.99 * k.s.s11, 0.99 * k.s.s22, 0.99 * k.s.t12};
      PlaneStress hi{1.01 * k.s.s11, 1.01 * k.s.s22, 1.01 * k.s.t12};
      BOOST_TEST(failure_indices(c, lo, m).index < 1.0);
      BOOST_TEST(failure_indices(c, hi, m).index > 1.0);
    }
  }
}

BOOST_AUTO_TEST_CASE(hashin_with_explicit_transverse_shear_strength) {
  Lamina m = gfrp();
  m.S_T = 50e6;
  BOOST_TEST(hashin_failure({0, -m.Y_C, 0}, m).matrix == 1.0, tt::tolerance(1e-12));
  // S_T = Y_C/2 collapses the compression form to (s22/Y_C)^2.
  m.S_T = m.Y_C / 2;
  BOOST_TEST(hashin_failure({0, -0.5 * m.Y_C, 0}, m).matrix == 0.25, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(larc02_strain_based_fibre_tension_and_g) {
  Lamina m = gfrp();
  m.eps1_T = 0.023;  // Table 2 value: index 1 at s11 = E1 eps1_T = 788 MPa, not X_T
  BOOST_TEST(larc02_failure({m.E1 * 0.023, 0, 0}, m).fibre == 1.0, tt::tolerance(1e-12));
  m.g = 0.5;  // linear-quadratic form still reaches 1 at Y_T
  BOOST_TEST(larc02_failure({0, m.Y_T, 0}, m).matrix == 1.0, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(larc02_fracture_plane_search_matches_a_dense_scan) {
  // The matrix-compression index is the maximum over the fracture angle a in [0, alpha0] of
  // (tau_T/S_T)^2 + (tau_L/S_L)^2 (Davila-Camanho LaRC02, Kahwash Appendix A), tau_T =
  // <-s22 cos a (sin a - eta_T cos a)>, tau_L = <cos a (|t12| + eta_L s22 cos a)>. Reference: a scan
  // of 200,001 angles refined by 200 golden-section steps, written out here independently of the
  // library's grid-and-Newton search.
  const Lamina m = gfrp();
  const double ST = transverse_shear_strength(m.Y_C, m.alpha0), eT = larc_eta_T(m.alpha0);
  const double eL = larc_eta_L(m.S_L, m.Y_C, m.alpha0);
  auto f = [&](double s22, double t12, double a) {
    const double c = std::cos(a), s = std::sin(a);
    const double tT = std::max(0.0, -s22 * c * (s - eT * c)), tL = std::max(0.0, c * (std::abs(t12) + eL * s22 * c));
    return (tT / ST) * (tT / ST) + (tL / m.S_L) * (tL / m.S_L);
  };
  auto dense = [&](double s22, double t12) {
    const int n = 200000;
    int best = 0;
    for (int i = 1; i <= n; ++i) {
      if (f(s22, t12, m.alpha0 * i / n) > f(s22, t12, m.alpha0 * best / n)) best = i;
    }
    double lo = m.alpha0 * std::max(0, best - 1) / n, hi = m.alpha0 * std::min(n, best + 1) / n;
    for (int it = 0; it < 200; ++it) {
      const double x1 = hi - 0.6180339887498949 * (hi - lo), x2 = lo + 0.6180339887498949 * (hi - lo);
      (f(s22, t12, x1) < f(s22, t12, x2) ? lo : hi) = f(s22, t12, x1) < f(s22, t12, x2) ? x1 : x2;
    }
    return std::max(f(s22, t12, 0.5 * (lo + hi)), f(s22, t12, m.alpha0 * best / n));
  };
  unsigned long long state = 12345;
  auto uniform = [&state]() {  // 64-bit LCG (Knuth), top 53 bits
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  double worst = 0.0;
  for (int k = 0; k < 400; ++k) {
    // transverse compression from 0.001 to 2 Y_C, shear up to +-2 S_L; every tenth state pure
    // compression (the maximum at an interior angle near alpha0) and every tenth pure shear-free
    const double s22 = -m.Y_C * (0.001 + 1.999 * uniform());
    const double t12 = k % 10 == 0 ? 0.0 : m.S_L * (4.0 * uniform() - 2.0);
    const FailureIndices r = larc02_failure({0.0, s22, t12}, m);
    const double ref = dense(s22, t12);
    BOOST_TEST(r.fracture_angle >= 0.0);
    BOOST_TEST(r.fracture_angle <= m.alpha0);
    BOOST_TEST(f(s22, t12, r.fracture_angle) == r.matrix, tt::tolerance(1e-15));  // value at the angle returned
    worst = std::max(worst, std::abs(r.matrix - ref) / ref);
    BOOST_TEST(r.matrix == ref, tt::tolerance(1e-13));
  }
  BOOST_TEST_MESSAGE("LaRC02 fracture-plane search against the dense scan: largest relative difference " << worst);
  // Pure transverse compression s22 = -Y_C: the index is 1 at the fracture angle alpha0 (the
  // definition of S_T and eta_T from alpha0).
  const FailureIndices uc = larc02_failure({0.0, -m.Y_C, 0.0}, m);
  BOOST_TEST(uc.matrix == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(uc.fracture_angle == m.alpha0, tt::tolerance(1e-6));
}

BOOST_AUTO_TEST_CASE(larc02_transverse_compression_raises_shear_strength) {
  // Kahwash Fig. 3b: LaRC02 predicts the beneficial effect of moderate transverse compression on
  // shear failure. Maximum stress has none; Hashin with S_T from the LaRC02 relation (the same
  // symbol S^tr in Appendix A) has a smaller one (34.2 vs 40.7 MPa at s22 = -0.3 Y_C).
  const Lamina m = gfrp();
  const double s22 = -0.3 * m.Y_C;
  auto shear_at = [&](Criterion c) {
    // tau12 at failure for fixed s22 along the direction (s22, tau) -> ray angle atan2(tau, s22).
    double lo = 0, hi = 10 * m.S_L;
    for (int i = 0; i < 200; ++i) {
      const double t = 0.5 * (lo + hi);
      (failure_indices(c, {0, s22, t}, m).index < 1 ? lo : hi) = t;
    }
    return lo;
  };
  BOOST_TEST_MESSAGE("tau12 at failure, s22 = -0.3 Y_C: LaRC02 " << shear_at(Criterion::larc02) / 1e6
                     << " MPa, Hashin " << shear_at(Criterion::hashin) / 1e6 << " MPa, S_L 33.1 MPa");
  BOOST_TEST(shear_at(Criterion::larc02) > shear_at(Criterion::hashin));
  BOOST_TEST(shear_at(Criterion::hashin) > m.S_L);
  BOOST_TEST(shear_at(Criterion::max_stress) == m.S_L, tt::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(envelope_axes_hit_the_strengths) {
  const Lamina m = gfrp();
  for (auto c : kAll) {
    auto r = [&](EnvelopePlane p, double th) { return failure_envelope_point(c, p, th, 0.0, m).radius; };
    BOOST_TEST(r(EnvelopePlane::s11_s22, 0.0) == m.X_T, tt::tolerance(1e-9));
    BOOST_TEST(r(EnvelopePlane::s11_s22, kPi) == m.X_C, tt::tolerance(1e-9));
    BOOST_TEST(r(EnvelopePlane::s11_s22, kPi / 2) == m.Y_T, tt::tolerance(1e-9));
    BOOST_TEST(r(EnvelopePlane::s11_s22, -kPi / 2) == m.Y_C, tt::tolerance(1e-9));
    BOOST_TEST(r(EnvelopePlane::s22_t12, kPi / 2) == m.S_L, tt::tolerance(1e-9));
    BOOST_TEST(r(EnvelopePlane::s22_t12, 0.0) == m.Y_T, tt::tolerance(1e-9));
    BOOST_TEST(r(EnvelopePlane::s22_t12, kPi) == m.Y_C, tt::tolerance(1e-9));
    // Every envelope point has index 1.
    for (int i = 0; i < 24; ++i) {
      const double th = i * kPi / 12;
      for (auto p : {EnvelopePlane::s11_s22, EnvelopePlane::s22_t12}) {
        const auto e = failure_envelope_point(c, p, th, 0.0, m);
        const PlaneStress s = p == EnvelopePlane::s11_s22 ? PlaneStress{e.s1, e.s2, 0} : PlaneStress{0, e.s1, e.s2};
        BOOST_TEST(failure_indices(c, s, m).index == 1.0, tt::tolerance(1e-8));
      }
    }
  }
  // Max stress and Hashin share the s11-s22 envelope when tau12 = 0 (Kahwash Sec. 3.3).
  for (int i = 0; i < 36; ++i) {
    const double th = i * kPi / 18;
    BOOST_TEST(failure_envelope_point(Criterion::max_stress, EnvelopePlane::s11_s22, th, 0, m).radius ==
               failure_envelope_point(Criterion::hashin, EnvelopePlane::s11_s22, th, 0, m).radius,
               tt::tolerance(1e-9));
  }
}

BOOST_AUTO_TEST_SUITE_END()
