#define BOOST_TEST_MODULE mpm_contact
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdio>

#include "cutbench/mpm/problem.hpp"
#include "mpm_test_util.hpp"

using namespace cutbench::mpm;
using namespace cutbench::mpm::testing;
namespace tt = boost::test_tools;

namespace {
struct SlideResult {
  double Fx = 0.0, Fy = 0.0, weight = 0.0, accel = 0.0;
};

// An elastic block (10 x 5 mm) pressed by gravity onto a rigid plate that slides under it at
// V = 1 m/s. While the block slips, the plate's force on it is F_t = mu F_n with F_n = m g.
SlideResult slide(double mu, double g, int detection = 1) {
  const double dx = 1e-3;
  MpmConfig cfg;
  cfg.grid.dx = dx;
  cfg.grid.x0 = -8 * dx;
  cfg.grid.y0 = -6 * dx;
  cfg.grid.nx = 40;
  cfg.grid.ny = 16;
  cfg.material = elastic();
  cfg.numerics.pic_fraction = 1.0;
  cfg.contact.mu = mu;
  cfg.contact.detection = detection;
  if (detection == 2) cfg.contact.gap_factor = 0.0;
  cfg.contact.n_above = Eigen::Vector2d(0.0, -1.0);  // from the block into the plate below
  cfg.tool.velocity = Eigen::Vector2d(1.0, 0.0);
  cfg.gravity = Eigen::Vector2d(0.0, -g);
  MpmProblem pb(cfg);
  fill_rect(pb, dx, 0.0, 10 * dx, 0.0, 5 * dx, false);   // block
  fill_rect(pb, dx, -6 * dx, 20 * dx, -2 * dx, 0.0, true);  // rigid plate
  pb.setup();
  double mass = 0.0;
  for (std::size_t p = 0; p < pb.size(); ++p) {
    if (!pb.rigid(p)) mass += pb.mass(p);
  }
  // let the block settle for 0.2 ms, then average while it still slips (slip ends at V/(mu g))
  const double t_end = mu > 0.0 ? std::min(2.0e-3, 0.8 / (mu * g)) : 2.0e-3;
  SlideResult r;
  long n = 0;
  double v0 = 0.0, t0 = 0.0;
  while (pb.time() < t_end) {
    pb.step();
    if (pb.time() < 0.2e-3) continue;
    if (n == 0) {
      v0 = pb.momentum().x() / mass;
      t0 = pb.time();
    }
    r.Fx += pb.contact_forces().total.x();
    r.Fy += pb.contact_forces().total.y();
    ++n;
  }
  r.Fx /= static_cast<double>(n);
  r.Fy /= static_cast<double>(n);
  r.weight = mass * g;
  r.accel = (pb.momentum().x() / mass - v0) / (pb.time() - t0);
  return r;
}
}  // namespace

BOOST_AUTO_TEST_CASE(block_sliding_on_rigid_plate_coulomb) {
  const double g = 2000.0;
  for (int det : {0, 1, 2}) {
  for (double mu : {0.2, 0.5}) {
    const SlideResult r = slide(mu, g, det);
    std::printf("sliding block (contact detection %d) mu = %.2f: F_t = %.4f N/m, F_n = %.4f N/m (weight %.4f), F_t/F_n = %.4f (exact %.2f), "
                "block acceleration %.1f m/s^2 (mu g = %.1f)\n",
                det, mu, r.Fx, r.Fy, r.weight, r.Fx / r.Fy, mu, r.accel, mu * g);
    BOOST_TEST(r.Fx / r.Fy == mu, tt::tolerance(0.02));
    BOOST_TEST(r.Fy == r.weight, tt::tolerance(0.05));
    BOOST_TEST(r.accel == mu * g, tt::tolerance(0.05));
  }
  }
}

BOOST_AUTO_TEST_CASE(frictionless_plate_transmits_no_tangential_force) {
  const SlideResult r = slide(0.0, 2000.0);
  std::printf("frictionless: F_t = %.3e N/m, F_n = %.4f N/m\n", r.Fx, r.Fy);
  BOOST_TEST(std::fabs(r.Fx) < 1e-12 * r.Fy);
  BOOST_TEST(r.Fy == r.weight, tt::tolerance(0.05));
}

BOOST_AUTO_TEST_CASE(rigid_velocity_ramp_displacement) {
  MpmConfig cfg;
  cfg.grid.dx = 1e-3;
  cfg.grid.x0 = cfg.grid.y0 = -4e-3;
  cfg.grid.nx = cfg.grid.ny = 30;
  cfg.material = elastic();
  cfg.tool.velocity = Eigen::Vector2d(2.0, 0.0);
  cfg.tool.t_ramp = 1e-4;
  MpmProblem pb(cfg);
  fill_rect(pb, 1e-3, 10e-3, 12e-3, 10e-3, 12e-3, false);
  fill_rect(pb, 1e-3, 0.0, 2e-3, 0.0, 2e-3, true);
  pb.setup();
  while (pb.time() < 3e-4) pb.step();
  const double exact = 2.0 * (0.5 * 1e-4 + (pb.time() - 1e-4));
  BOOST_TEST(pb.rigid_displacement().x() == exact, tt::tolerance(1e-3));
  for (std::size_t p = 0; p < pb.size(); ++p) {
    if (pb.rigid(p)) BOOST_TEST(pb.velocity(p).x() == 2.0, tt::tolerance(1e-12));
  }
}

// Grid-kinetic-energy feedback damping: alpha grows while there is kinetic energy, removes it,
// and is switched off (alpha = 0) after t_off.
BOOST_AUTO_TEST_CASE(feedback_damping_removes_kinetic_energy_until_t_off) {
  auto run = [](double gain, double& ke_mid, double& alpha_mid, double& alpha_end) {
    MpmConfig cfg;
    cfg.grid.dx = 1e-3;
    cfg.grid.x0 = cfg.grid.y0 = -4e-3;
    cfg.grid.nx = 30;
    cfg.grid.ny = 12;
    cfg.material = elastic();
    cfg.numerics.pic_fraction = 0.0;
    cfg.damping.gain = gain;
    cfg.damping.t_off = 2e-4;
    cfg.damping.v_ref = 1.0;
    MpmProblem pb(cfg);
    fill_rect(pb, 1e-3, 0.0, 20e-3, 0.0, 2e-3, false,
              [](double x, double) { return Eigen::Vector2d(std::sin(M_PI * x / 20e-3), 0.0); });
    pb.setup();
    while (pb.time() < 1.9e-4) pb.step();
    ke_mid = pb.kinetic_energy() + pb.strain_energy();
    alpha_mid = pb.feedback_alpha();
    while (pb.time() < 3e-4) pb.step();
    alpha_end = pb.feedback_alpha();
  };
  double e0, a0, z0, e1, a1, z1;
  run(0.0, e0, a0, z0);
  run(1e9, e1, a1, z1);
  std::printf("feedback damping: energy at 0.19 ms %.4g J/m without, %.4g J/m with (alpha %.3g 1/s)\n", e0, e1, a1);
  BOOST_TEST(a0 == 0.0);
  BOOST_TEST(a1 > 0.0);
  BOOST_TEST(e1 < 0.5 * e0);
  BOOST_TEST(z1 == 0.0);
}

// Contact detection: a block moving at 10 m/s toward a rigid wall 1.5 cells away. Domain-extent
// detection (2) starts contact when the domains touch (t* = gap / v); the velocity test alone (0)
// engages as soon as the two materials share nodes (here a cell before they touch).
BOOST_AUTO_TEST_CASE(contact_detection_starts_when_domains_touch) {
  const double dx = 1e-3, gap = 1.5 * dx, v = 10.0;
  double first[3] = {-1.0, -1.0, -1.0};
  for (int det : {0, 2}) {
    MpmConfig cfg;
    cfg.grid.dx = dx;
    cfg.grid.x0 = -12 * dx;
    cfg.grid.y0 = -4 * dx;
    cfg.grid.nx = 20;
    cfg.grid.ny = 12;
    cfg.material = elastic();
    cfg.contact.detection = det;
    cfg.contact.gap_factor = 0.0;
    cfg.contact.n_above = Eigen::Vector2d(1.0, 0.0);  // from the block into the wall
    MpmProblem pb(cfg);
    fill_rect(pb, dx, -gap - 6 * dx, -gap, 0.0, 4 * dx, false, [&](double, double) { return Eigen::Vector2d(v, 0.0); });
    fill_rect(pb, dx, 0.0, 2 * dx, -2 * dx, 6 * dx, true);
    pb.setup();
    while (pb.time() < 2.0 * gap / v) {
      pb.step();
      if (pb.contact_forces().total.norm() > 0.0) {
        first[det] = pb.time();
        break;
      }
    }
  }
  const double tstar = gap / v;
  std::printf("contact onset: detection 0 at %.3g s, detection 2 at %.3g s; domains touch at %.3g s\n", first[0],
              first[2], tstar);
  BOOST_TEST(first[0] < 0.5 * tstar);  // a cell early
  BOOST_TEST(first[2] == tstar, tt::tolerance(0.05));
}
