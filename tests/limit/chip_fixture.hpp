// Shared set-ups of the limit tests: the sliding single-shear-plane chip used to compare refinement
// strategies against Merchant (alpha = 6 deg, mu = 0.2, phi = phi_M, l = 1.5 t1, n = 4: 144 elements),
// and the paper's Table 2 / Table 3 chip at t1 = 0.5 mm (alpha = 6 deg, mu = 0.4809, phi = 30.4 deg,
// l = 1.899 t1; n = 6).
#pragma once
#include <cmath>

#include "cutbench/limit/cutting.hpp"

namespace cutbench::limit::test {

inline CuttingSetup sliding_chip_at_merchant() {
  CuttingSetup c;
  c.alpha = 6.0 * M_PI / 180;
  c.mu = 0.2;
  c.phi = merchant_shear_angle(c.alpha, c.mu);
  c.contact_length = 1.5;
  c.n = 4;
  return c;
}

inline CuttingSetup table3_chip_t1_05() {
  CuttingSetup c;
  c.alpha = 6.0 * M_PI / 180;
  c.mu = 0.4809;
  c.phi = 30.4 * M_PI / 180;
  c.contact_length = 1.899;
  c.n = 6;
  return c;
}

}  // namespace cutbench::limit::test
