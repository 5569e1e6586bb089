// Cutting: thrust force versus friction coefficient for the two contact models (coarse).
#include <boost/test/unit_test.hpp>
#include <iostream>

#include "cutbench/sph/runners.hpp"

using namespace cutbench::sph;

BOOST_AUTO_TEST_SUITE(cutting_friction)

// With the penalty contact and stick-slip friction the thrust force rises with mu (paper Fig 6
// trend); with the velocity-level contact the chip sticks and F_t hardly depends on mu.
BOOST_AUTO_TEST_CASE(thrust_rises_with_friction_under_penalty_contact) {
  double ft[2][2];
  for (int penalty = 0; penalty < 2; ++penalty)
    for (int k = 0; k < 2; ++k) {
      CuttingSetup c;
      c.particles_over_height = 9;
      c.length = 0.6e-3;
      c.cut_distance = 0.12e-3;
      c.history_window = c.cut_distance / c.speed / 5.0;
      c.friction = k == 0 ? 0.35 : 0.65;
      c.penalty_contact = penalty == 1;
      const auto r = run_cutting(c);
      ft[penalty][k] = r.ft_mean;
      std::cout << (penalty ? "penalty" : "velocity") << " contact, mu " << c.friction << ": F_c "
                << r.fc_mean / 1e3 << " N/mm, F_t " << r.ft_mean / 1e3 << " N/mm\n";
    }
  BOOST_TEST(ft[1][1] > 1.05 * ft[1][0]);
}

BOOST_AUTO_TEST_SUITE_END()
