// Aghababaei et al. (2021) Eqs. 1-4.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "cutbench/analytic/chip_transition.hpp"
#include "cutbench/analytic/cutting.hpp"

using namespace cutbench::analytic;
namespace tt = boost::test_tools;

namespace {
constexpr double kPi = 3.14159265358979323846;
double deg(double d) { return d * kPi / 180.0; }
}  // namespace

BOOST_AUTO_TEST_SUITE(chip_transition)

BOOST_AUTO_TEST_CASE(eq2_follows_from_eq1) {
  // With N = 0, S = F_n, M = F_n alpha d and K_IC = sqrt(G E): G(F_n) = K_IC^2/E at F_fr/cos(l).
  const double E = 3e9, K = 1.5e6, w = 5e-3, d = 1e-3, a = 1.2, lam = deg(45);
  const double Fn = fracture_force(K, w, d, lam, a) / std::cos(lam);
  BOOST_TEST(dcb_energy_release_rate(E, w, d, 0.0, Fn, Fn * a * d) == K * K / E, tt::tolerance(1e-12));
  BOOST_TEST(dcb_energy_release_rate_per_width(E, d, 0.0, Fn / w, Fn * a * d / w) == K * K / E,
             tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(critical_depth_is_where_forces_balance) {
  const double lam = deg(45), mu = 0.3, a = 1.2, w = 4e-3;
  for (double K : {1e6, 3e6}) {
    for (double tau : {20e6, 60e6}) {
      const double dc = critical_depth(K, tau, lam, mu, a);
      const double phi = aghababaei_shear_angle(lam, mu);
      BOOST_TEST(fracture_force(K, w, dc, lam, a) == plastic_shearing_force(tau, w, dc, phi),
                 tt::tolerance(1e-12));
      // Below d_c plastic shearing needs less force; above, fracture does.
      BOOST_TEST(plastic_shearing_force(tau, w, 0.5 * dc, phi) < fracture_force(K, w, 0.5 * dc, lam, a));
      BOOST_TEST(plastic_shearing_force(tau, w, 2 * dc, phi) > fracture_force(K, w, 2 * dc, lam, a));
      BOOST_TEST(chip_regime(2 * dc, dc) == 1);
      BOOST_TEST(chip_regime(0.5 * dc, dc) == -1);
      BOOST_TEST(toughness_strength_ratio(dc, lam, mu, a) == K / tau, tt::tolerance(1e-12));
    }
  }
  // The paper's shear angle is Merchant's.
  BOOST_TEST(aghababaei_shear_angle(lam, mu) == merchant_shear_angle(lam, friction_angle(mu)),
             tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(inferred_toughness_ratios_of_the_three_polymers) {
  // d_c = 0.14, 2.16, 5.2 mm (PMMA, POM, PC) with alpha = 1.2, rake 45 deg, mu = 0.3.
  const double lam = deg(45), mu = 0.3, a = 1.2;
  const double shape = critical_depth_shape_factor(lam, mu, a);
  const double r1 = toughness_strength_ratio(0.14e-3, lam, mu, a);
  const double r2 = toughness_strength_ratio(2.16e-3, lam, mu, a);
  const double r3 = toughness_strength_ratio(5.2e-3, lam, mu, a);
  BOOST_TEST_MESSAGE("shape factor " << shape << "; K_IC/tau_ys [sqrt(mm)]: PMMA " << r1 * std::sqrt(1e3)
                                     << ", POM " << r2 * std::sqrt(1e3) << ", PC " << r3 * std::sqrt(1e3)
                                     << "; ratios 1 : " << r2 / r1 << " : " << r3 / r1);
  BOOST_TEST(r2 / r1 == 3.93, tt::tolerance(2e-3));
  BOOST_TEST(r3 / r1 == 6.09, tt::tolerance(2e-3));
}

BOOST_AUTO_TEST_SUITE_END()
