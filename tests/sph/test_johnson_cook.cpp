// Johnson-Cook flow stress and radial return against closed forms.
#include <boost/test/unit_test.hpp>
#include <algorithm>
#include <cmath>

#include "cutbench/sph/johnson_cook.hpp"

using namespace cutbench::sph;
namespace tt = boost::test_tools;

BOOST_AUTO_TEST_SUITE(johnson_cook)

BOOST_AUTO_TEST_CASE(flow_stress_closed_form) {
  JohnsonCook jc;  // A 862, B 331 MPa, C 0.01, m 0.8, n 0.35
  jc.T_ref = 300.0;
  jc.T_melt = 1836.0;
  const double eps = 0.2, rate = 1e4, T = 700.0;
  const double expect = (862e6 + 331e6 * std::pow(0.2, 0.35)) * (1.0 + 0.01 * std::log(1e4)) *
                        (1.0 - std::pow(400.0 / 1536.0, 0.8));
  BOOST_TEST(jc.flow_stress(eps, rate, T) == expect, tt::tolerance(1e-14));
  BOOST_TEST(jc.flow_stress(0.0, 0.0, 300.0) == 862e6);
  BOOST_TEST(jc.flow_stress(0.0, 0.5, 250.0) == 862e6);  // rate and temperature factors floored
  BOOST_TEST(jc.flow_stress(0.3, 10.0, 2000.0) == 0.0);  // above melting
  // derivatives against central differences
  const double e = 1e-7;
  BOOST_TEST(jc.d_strain(eps, rate, T) ==
                 (jc.flow_stress(eps + e, rate, T) - jc.flow_stress(eps - e, rate, T)) / (2 * e),
             tt::tolerance(1e-6));
  BOOST_TEST(jc.d_rate(eps, rate, T) ==
                 (jc.flow_stress(eps, rate * (1 + e), T) - jc.flow_stress(eps, rate * (1 - e), T)) / (2 * e * rate),
             tt::tolerance(1e-6));
}

// Manufactured point test: pick the plastic increment d*, build the trial stress whose return is
// d* exactly (q_trial = 3 G d* + sigma_y(eps0 + d*, d*/dt, T)), and check the mapping finds it.
BOOST_AUTO_TEST_CASE(radial_return_recovers_manufactured_increment) {
  const JohnsonCook jc;
  const double G = 41.9e9, dt = 1e-9;
  Stress3 dir;
  dir << 1.0, 0.4, 0.0, 0.4, -0.3, 0.0, 0.0, 0.0, -0.7;  // traceless, plane-strain pattern
  dir /= von_mises(dir);
  for (double eps0 : {0.0, 0.05, 1.2})
    for (double d_star : {1e-8, 1e-5, 3e-3})
      for (double T : {300.0, 900.0}) {
        const double q = 3.0 * G * d_star + jc.flow_stress(eps0 + d_star, d_star / dt, T);
        const auto r = radial_return(jc, q * dir, G, eps0, dt, T);
        BOOST_TEST(r.plastic);
        BOOST_TEST(r.delta_eps_p == d_star, tt::tolerance(1e-9));
        BOOST_TEST(von_mises(r.deviator) == r.flow_stress, tt::tolerance(1e-10));  // on the yield surface
        BOOST_TEST((r.deviator / von_mises(r.deviator) - dir).norm() < 1e-12);       // radial
        BOOST_TEST(r.iterations < 60);
      }
  // elastic trial state comes back unchanged
  const auto el = radial_return(jc, 800e6 * dir, G, 0.0, dt, 300.0);
  BOOST_TEST(!el.plastic);
  BOOST_TEST(el.delta_eps_p == 0.0);
  BOOST_TEST((el.deviator - 800e6 * dir).norm() == 0.0);
}

// A warm start near the root (the particle's increment of its last step) converges in a few
// Newton steps: the bracket safeguard must not throw a converged iterate back across the bracket
// (it did when the last correction landed on the bracket end d had just become: 8 iterations on
// average in a cut, with a tail past 20). eps_p^n passed in gives the same return bit for bit.
BOOST_AUTO_TEST_CASE(radial_return_warm_start_converges_in_few_steps) {
  for (const JohnsonCook& jc : {JohnsonCook{}, sima_ozel_ti6al4v()}) {
    const double G = 41.9e9, dt = 2e-10;
    Stress3 dir;
    dir << 1.0, 0.4, 0.0, 0.4, -0.3, 0.0, 0.0, 0.0, -0.7;
    dir /= von_mises(dir);
    for (double eps0 : {0.02, 0.5, 2.0})
      for (double d_star : {1e-7, 1e-5, 1e-4})
        for (double T : {300.0, 700.0, 1100.0})
          for (double rel : {1e-3, 1e-2, -1e-2}) {
            const double q = 3.0 * G * d_star + jc.flow_stress(eps0 + d_star, d_star / dt, T);
            const auto r = radial_return(jc, q * dir, G, eps0, dt, T, d_star * (1.0 + rel));
            BOOST_TEST(r.delta_eps_p == d_star, tt::tolerance(1e-9));
            BOOST_TEST_INFO("eps0 " << eps0 << " d " << d_star << " T " << T << " rel " << rel << " softening " << jc.softening);
            BOOST_TEST(r.iterations <= 6);
            BOOST_TEST(r.eps_p_pow_n == jc.eps_pow_n(eps0 + r.delta_eps_p));
            const auto c = radial_return(jc, q * dir, G, eps0, dt, T, d_star * (1.0 + rel), jc.eps_pow_n(eps0));
            BOOST_TEST(c.delta_eps_p == r.delta_eps_p);
            BOOST_TEST(c.flow_stress == r.flow_stress);
            BOOST_TEST((c.deviator - r.deviator).norm() == 0.0);
          }
  }
}

// The solid skips the radial return when the von Mises stress is below A min(m, 1) (1 - T*), a
// lower bound of the J-C flow stress (T*^m lies below its tangent at T* = 1 for m <= 1; the rate
// factor is >= 1 and the strain factor >= A). Check the bound on a grid, for m < 1 and m > 1.
BOOST_AUTO_TEST_CASE(cheap_lower_bound_of_flow_stress) {
  for (double m : {0.8, 0.3, 1.0, 1.7}) {
    JohnsonCook jc;
    jc.m = m;
    for (int a = 0; a <= 40; ++a)
      for (double eps : {0.0, 1e-6, 0.1, 2.0})
        for (double rate : {0.0, 1.0, 1e5}) {
          const double T = jc.T_ref - 50.0 + (jc.T_melt - jc.T_ref + 100.0) * a / 40.0;
          const double ts = std::min(1.0, std::max(0.0, (T - jc.T_ref) / (jc.T_melt - jc.T_ref)));
          const double floor = jc.A * std::min(m, 1.0) * (1.0 - ts);
          BOOST_TEST(floor <= jc.flow_stress(eps, rate, T) * (1.0 + 1e-14));
        }
  }
}

// Sima & Oezel (2010) softening law against its closed form written out here independently:
// sigma = [A + B e^n exp(-e^a)] [1 + C ln(rate)] [1 - T*^m] [D + (1 - D) tanh(1/(e + S)^c)^s],
// D = 1 - (T/Tm)^d, S = (T/Tm)^b; its derivatives against central differences; the return
// mapping recovers a manufactured increment; the flow stress softens with strain when hot.
BOOST_AUTO_TEST_CASE(sima_ozel_softening_closed_form) {
  const JohnsonCook so = sima_ozel_ti6al4v();
  const double A = 724.7e6, B = 683.1e6, C = 0.035, m = 1.0, n = 0.47, a = 2.0, b = 5.0, c = 2.0, d = 1.0, s = 0.05;
  const double Tr = 300.0, Tm = 1878.0;
  auto closed = [&](double e, double rate, double T) {
    const double Dv = 1.0 - std::pow(T / Tm, d), Sv = std::pow(T / Tm, b);
    return (A + B * std::pow(e, n) * std::exp(-std::pow(e, a))) * (1.0 + C * std::log(rate)) *
           (1.0 - std::pow((T - Tr) / (Tm - Tr), m)) * (Dv + (1.0 - Dv) * std::pow(std::tanh(1.0 / std::pow(e + Sv, c)), s));
  };
  for (double e : {0.05, 0.3, 1.0, 2.5})
    for (double T : {400.0, 900.0, 1400.0}) {
      const double rate = 1e4;
      BOOST_TEST(so.flow_stress(e, rate, T) == closed(e, rate, T), tt::tolerance(1e-13));
      const double h = 1e-7;
      BOOST_TEST(so.d_strain(e, rate, T) == (closed(e + h, rate, T) - closed(e - h, rate, T)) / (2 * h), tt::tolerance(1e-5));
      BOOST_TEST(so.d_rate(e, rate, T) == (closed(e, rate * (1 + h), T) - closed(e, rate * (1 - h), T)) / (2 * h * rate),
                 tt::tolerance(1e-5));
    }
  // hot and strained: the flow stress falls with strain (the softening that serrates the chip)
  BOOST_TEST(so.flow_stress(2.0, 1e4, 1100.0) < so.flow_stress(0.5, 1e4, 1100.0));
  // the return mapping with softening
  const double G = 41.9e9, dt = 1e-9;
  Stress3 dir;
  dir << 1.0, 0.4, 0.0, 0.4, -0.3, 0.0, 0.0, 0.0, -0.7;
  dir /= von_mises(dir);
  for (double eps0 : {0.05, 1.2})
    for (double d_star : {1e-5, 3e-3})
      for (double T : {300.0, 1100.0}) {
        const double q = 3.0 * G * d_star + so.flow_stress(eps0 + d_star, d_star / dt, T);
        const auto r = radial_return(so, q * dir, G, eps0, dt, T);
        BOOST_TEST(r.delta_eps_p == d_star, tt::tolerance(1e-9));
      }
  // the solid's cheap floor A min(m, 1) (1 - T*) D stays below the softened flow stress
  for (int k = 0; k <= 40; ++k)
    for (double e : {0.0, 0.5, 3.0, 10.0}) {
      const double T = Tr + (Tm - Tr) * k / 40.0;
      const double ts = (T - Tr) / (Tm - Tr);
      BOOST_TEST(A * 1.0 * (1.0 - ts) * (1.0 - T / Tm) <= so.flow_stress(e, 0.0, T) * (1.0 + 1e-14));
    }
}

BOOST_AUTO_TEST_SUITE_END()
