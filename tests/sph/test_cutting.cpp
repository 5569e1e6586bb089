// Smoke test of the cutting runner at a very coarse resolution (9 particles over the height):
// a chip forms, the forces are positive and of the right order, heat is generated. Not a
// reproduction: the paper's resolution is 41 particles over the height.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <iostream>

#include "cutbench/sph/runners.hpp"

using namespace cutbench::sph;

BOOST_AUTO_TEST_SUITE(cutting)

BOOST_AUTO_TEST_CASE(coarse_cut_smoke) {
  CuttingSetup c;
  c.particles_over_height = 9;
  c.length = 0.6e-3;
  c.cut_distance = 0.12e-3;
  c.history_window = c.cut_distance / c.speed / 10.0;
  const auto r = run_cutting(c);
  std::cout << "coarse cut (dx " << r.dx * 1e6 << " um, " << r.particles << " particles, " << r.steps
            << " steps): F_c " << r.fc_mean / 1e3 << " N/mm, F_t " << r.ft_mean / 1e3 << " N/mm, rake T "
            << r.rake_temperature << " K, T_max " << r.T_max << " K, chip height " << r.chip_height * 1e3
            << " mm, plastic heat " << r.plastic_heat << " J/m, friction heat " << r.friction_heat
            << " J/m, tool rake T " << r.tool_rake_temperature << " K, tool T_max " << r.tool_T_max << " K\n";
  BOOST_TEST(std::isfinite(r.fc_mean));
  BOOST_TEST(r.fc_mean / 1e3 > 50.0);   // N/mm; experiment 157.5
  BOOST_TEST(r.fc_mean / 1e3 < 500.0);
  BOOST_TEST(r.ft_mean > 0.0);
  BOOST_TEST(r.chip_height > 0.0);
  BOOST_TEST(r.T_max > 400.0);
  BOOST_TEST(r.plastic_heat > 0.0);
  BOOST_TEST(r.friction_heat > 0.0);
  BOOST_TEST(r.fc.size() >= 9u);
  BOOST_TEST(r.tool_T_max > 300.0);  // heat reached the tool
  BOOST_TEST(r.tool_T_max < r.T_max);
  BOOST_TEST(r.snapshot.fields.at("T").size() == r.particles);
}

BOOST_AUTO_TEST_SUITE_END()
