// Timoshenko cantilever (plane stress): tip deflection, L2 and energy errors over three
// refinements, observed convergence rates, and the explicit internal force at the static solution.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "cutbench/efg/verification.hpp"

using namespace cutbench::efg;

BOOST_AUTO_TEST_SUITE(cantilever)

BOOST_AUTO_TEST_CASE(timoshenko_convergence) {
  for (auto kind : {WeightKind::regularized, WeightKind::cubic_spline}) {
    WeightParams w;
    w.kind = kind;
    const int grids[3][2] = {{13, 4}, {25, 7}, {49, 13}};
    CantileverResult r[3];
    for (int k = 0; k < 3; ++k) {
      r[k] = timoshenko_cantilever(grids[k][0], grids[k][1], 2.5, w);
      BOOST_TEST_MESSAGE((kind == WeightKind::regularized ? "regularised" : "cubic spline")
                         << " h = " << r[k].h << ": tip " << r[k].tip << " (exact " << r[k].tip_exact
                         << ", rel err " << r[k].tip_rel_error << "), L2 " << r[k].l2_rel_error << ", energy "
                         << r[k].energy_rel_error << ", explicit residual " << r[k].max_fint_residual);
      BOOST_TEST(r[k].max_fint_residual < 1e-8);
    }
    const double rate_l2 = std::log(r[1].l2_rel_error / r[2].l2_rel_error) / std::log(2.0);
    const double rate_en = std::log(r[1].energy_rel_error / r[2].energy_rel_error) / std::log(2.0);
    BOOST_TEST_MESSAGE("rates (h = 2 -> 1): L2 " << rate_l2 << ", energy " << rate_en);
    BOOST_TEST(r[2].tip_rel_error < 0.01);
    BOOST_TEST(r[2].tip_rel_error < r[0].tip_rel_error);
    BOOST_TEST(rate_l2 > 1.5);
    BOOST_TEST(rate_en > 0.8);
  }
}

BOOST_AUTO_TEST_SUITE_END()
