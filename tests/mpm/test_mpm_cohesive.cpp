#define BOOST_TEST_MODULE mpm_cohesive
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdio>

#include "cutbench/mpm/cohesive.hpp"
#include "cutbench/mpm/problem.hpp"
#include "mpm_test_util.hpp"

using namespace cutbench::mpm;
using namespace cutbench::mpm::testing;
namespace tt = boost::test_tools;

namespace {
// Work of the traction along a proportional opening path (dn, dt) = s (cn, ct), s: 0 -> smax,
// by the trapezoidal rule; stops when the segment fails.
double path_work(const TractionLaw& l1, const TractionLaw& l2, double cn, double ct, double smax, CohesiveState& st,
                 int n = 200000) {
  double w = 0.0, tprev_n = 0.0, tprev_t = 0.0, sprev = 0.0;
  for (int k = 1; k <= n; ++k) {
    const double s = smax * k / n;
    const CohesiveTraction t = cohesive_update(l1, l2, s * cn, s * ct, st);
    w += 0.5 * (t.tn + tprev_n) * cn * (s - sprev) + 0.5 * (t.tt + tprev_t) * ct * (s - sprev);
    tprev_n = t.tn;
    tprev_t = t.tt;
    sprev = s;
    if (st.failed) break;
  }
  return w;
}
}  // namespace

BOOST_AUTO_TEST_CASE(cubic_law_shape_and_toughness) {
  const TractionLaw law = TractionLaw::from_toughness(TractionLawType::cubic, 2000.0, 40e6);
  BOOST_TEST(law.delta_c == 16.0 * 2000.0 / (9.0 * 40e6), tt::tolerance(1e-14));
  BOOST_TEST(law.envelope(law.delta_c / 3.0) == 40e6, tt::tolerance(1e-12));  // peak
  BOOST_TEST(law.toughness() == 2000.0, tt::tolerance(1e-12));
  // closed-form partial area against quadrature
  const double d = 0.4 * law.delta_c;
  double q = 0.0;
  const int n = 100000;
  for (int k = 0; k < n; ++k) q += law.envelope((k + 0.5) * d / n) * d / n;
  BOOST_TEST(law.area(d) == q, tt::tolerance(1e-8));
}

BOOST_AUTO_TEST_CASE(energy_released_equals_Gc_mode_I_and_II) {
  for (auto type : {TractionLawType::cubic, TractionLawType::triangular}) {
    const TractionLaw law = TractionLaw::from_toughness(type, 2000.0, 40e6);
    for (int mode = 0; mode < 2; ++mode) {
      CohesiveState st;
      const double w = path_work(law, law, mode == 0 ? 1.0 : 0.0, mode == 0 ? 0.0 : 1.0, 1.2 * law.delta_c, st);
      std::printf("%s law, mode %s: work to failure %.4f J/m^2 (G_c = 2000), J_I = %.1f, J_II = %.1f\n",
                  type == TractionLawType::cubic ? "cubic" : "triangular", mode == 0 ? "I" : "II", w, st.JI, st.JII);
      BOOST_TEST(st.failed);
      BOOST_TEST(w == 2000.0, tt::tolerance(1e-3));
      BOOST_TEST(st.JI + st.JII == 2000.0, tt::tolerance(1e-3));
    }
  }
}

BOOST_AUTO_TEST_CASE(decoupled_mixed_mode_failure) {
  // equal opening in both modes with equal laws: failure when J_I = J_II = G_c / 2
  const TractionLaw law = TractionLaw::from_toughness(TractionLawType::cubic, 2000.0, 40e6);
  CohesiveState st;
  const double w = path_work(law, law, 1.0, 1.0, law.delta_c, st);
  BOOST_TEST(st.failed);
  BOOST_TEST(st.JI / 2000.0 + st.JII / 2000.0 == 1.0, tt::tolerance(1e-3));
  BOOST_TEST(st.JI == 1000.0, tt::tolerance(2e-3));
  BOOST_TEST(w == 2000.0, tt::tolerance(2e-3));
  // different toughness in mode II: J_I/J_Ic + J_II/J_IIc = 1 at failure
  const TractionLaw l2 = TractionLaw::from_toughness(TractionLawType::cubic, 4000.0, 40e6);
  CohesiveState s2;
  path_work(law, l2, 1.0, 0.5, 2.0 * l2.delta_c, s2);
  BOOST_TEST(s2.failed);
  BOOST_TEST(s2.JI / 2000.0 + s2.JII / 4000.0 == 1.0, tt::tolerance(1e-3));
}

BOOST_AUTO_TEST_CASE(unloading_follows_secant) {
  const TractionLaw law = TractionLaw::from_toughness(TractionLawType::cubic, 2000.0, 40e6);
  CohesiveState st;
  const double dm = 0.5 * law.delta_c;
  cohesive_update(law, law, dm, 0.0, st);
  const CohesiveTraction t = cohesive_update(law, law, 0.25 * law.delta_c, 0.0, st);
  BOOST_TEST(t.tn == 0.5 * law.envelope(dm), tt::tolerance(1e-12));
  const double k = 27.0 * law.sigma_c / (4.0 * std::pow(law.delta_c, 3)) * std::pow(law.delta_c - dm, 2);
  BOOST_TEST(t.tn == k * 0.25 * law.delta_c, tt::tolerance(1e-12));
  // compression carries no cohesive traction (left to crack contact)
  BOOST_TEST(cohesive_update(law, law, -1e-6, 0.0, st).tn == 0.0);
}

// MPM level: an elastic block bonded to a fixed base along a cohesive crack is thrown upward with
// kinetic energy 20 G_c L. With FLIP (conservative), the energy lost once it has separated equals
// the energy released by the cohesive zone, G_c L. (At lower speeds, 2-10 G_c L, the block is
// pulled back onto the base and the inelastic crack contact dissipates more: not a clean test.)
BOOST_AUTO_TEST_CASE(mpm_block_debonding_energy_balance) {
  const double dx = 0.5e-3, L = 10e-3, H = 2e-3, Gc = 2000.0;
  MpmConfig cfg;
  cfg.grid.dx = dx;
  cfg.grid.x0 = -4 * dx;
  cfg.grid.y0 = -8 * dx;
  cfg.grid.nx = static_cast<int>(std::lround(L / dx)) + 8;
  cfg.grid.ny = 40;
  cfg.material = elastic();
  cfg.numerics.pic_fraction = 0.0;
  cfg.numerics.position_order = 0;
  // USL: the strain rate from the grid velocities; with FLIP the re-extrapolating schemes add
  // particle-velocity noise at the block edges to it (lost 17.1 J/m with MUSL, 17.9 with USAVG at cfl 0.4,
  // solvers/mpm/README.md), which is not what this test isolates
  cfg.numerics.strain_update = Numerics::StrainUpdate::usl;
  cfg.crack.enabled = true;
  cfg.crack.y = -0.02 * dx;  // just below the node row at the interface
  cfg.crack.x_begin = 0.0;
  cfg.crack.x_end = L;
  cfg.crack.mode1 = TractionLaw::from_toughness(TractionLawType::cubic, Gc, 40e6);
  cfg.crack.mode2 = cfg.crack.mode1;
  cfg.fixed_mask = [&](double, double y) { return y <= -3 * dx + 1e-12 ? 3 : 0; };
  const double rho = cfg.material.rho;
  const double v0 = std::sqrt(2.0 * 20.0 * Gc * L / (rho * L * H));
  MpmProblem pb(cfg);
  fill_rect(pb, dx, 0.0, L, -3 * dx, 0.0, false);
  fill_rect(pb, dx, 0.0, L, 0.0, H, false, [&](double, double) { return Eigen::Vector2d(0.0, v0); });
  pb.setup();
  const double e0 = pb.kinetic_energy() + pb.strain_energy();
  BOOST_TEST(pb.energy_balance().residual == 0.0);  // the initial energy is part of the balance
  while (pb.time() < 40e-6) pb.step();
  const double ef = pb.kinetic_energy() + pb.strain_energy();
  std::size_t failed = 0;
  for (const auto& s : pb.crack().state) failed += s.failed ? 1 : 0;
  std::printf("debonding: v0 = %.2f m/s, E0 = %.3f J/m, E_final = %.3f J/m, lost %.3f J/m, released %.3f J/m, "
              "G_c L = %.3f J/m (%.2f%%); %zu/%zu segments failed, mode-I fraction %.3f\n",
              v0, e0, ef, e0 - ef, pb.released_energy(), Gc * L, 100.0 * ((e0 - ef) / (Gc * L) - 1.0), failed,
              pb.crack().state.size(), pb.mode1_fraction());
  const EnergyBalance eb = pb.energy_balance();
  std::printf("debonding audit: kinetic %.3f strain %.3f plastic %.3f cohesive %.3f PIC %.3f residual %.3f J/m\n",
              eb.kinetic, eb.strain, eb.plastic, eb.cohesive, eb.audit.pic_damping, eb.residual);
  BOOST_TEST(failed == pb.crack().state.size());
  BOOST_TEST(pb.released_energy() == Gc * L, tt::tolerance(0.02));
  // The kinetic energy lost is the fracture energy plus the scheme's numerical terms, which the
  // audit measures (chiefly the cohesive lag: the explicit step applies each traction for a whole
  // step, so the cohesive work runs ahead of the traction law's energy, in proportion to the step).
  // Measured here: e0 - ef = 17.48 / 19.34 / 20.78 / 21.89 J/m at cfl = 0.5 / 0.4 / 0.3 / 0.1 with
  // numerical terms of -2.53 / -0.66 / 0.78 / 1.89 J/m (cohesive lag -4.28 ... -0.04); e0 - ef alone
  // is near G_c L only where the terms cancel (cfl 0.35-0.4), so it is checked with them.
  BOOST_TEST(e0 - ef - eb.numerical == Gc * L, tt::tolerance(0.01));
  // Looser than the former 5 % on e0 - ef, which bounded these terms only where they cancel: a
  // judgement that the scheme's own terms stay a small part of the fracture energy; measured 0.03 to
  // 0.13 of G_c L over cfl 0.1-0.5, and not vanishing as the step falls (the increment loss stays).
  BOOST_TEST(std::fabs(eb.numerical) <= 0.2 * Gc * L);
  BOOST_TEST(pb.mode1_fraction() > 0.9);
}
