#define BOOST_TEST_MODULE mpm_core
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <map>
#include <cstdio>
#include <vector>

#include "cutbench/mpm/coverage.hpp"
#include "cutbench/mpm/material.hpp"
#include "cutbench/mpm/problem.hpp"
#include "cutbench/mpm/shape.hpp"
#include "mpm_test_util.hpp"
#include "release_only.hpp"

using namespace cutbench::mpm;
using namespace cutbench::mpm::testing;
namespace tt = boost::test_tools;

BOOST_AUTO_TEST_CASE(ugimp_partition_of_unity_and_gradient) {
  const double dx = 1.0, lp = 0.25;
  for (double xp = 3.0; xp < 4.0; xp += 0.013) {
    double w[3], dw[3];
    ugimp_axis(xp, 0.0, dx, lp, w, dw);
    BOOST_TEST(w[0] + w[1] + w[2] == 1.0, tt::tolerance(1e-13));
    BOOST_TEST(dw[0] + dw[1] + dw[2] == 0.0, tt::tolerance(1e-12));
    // first moment: sum S_i x_i = xp (linear completeness)
    const int i0 = ugimp_axis(xp, 0.0, dx, lp, w, dw);
    double m1 = 0.0, g1 = 0.0;
    for (int k = 0; k < 3; ++k) {
      m1 += w[k] * (i0 + k);
      g1 += dw[k] * (i0 + k);
    }
    BOOST_TEST(m1 == xp, tt::tolerance(1e-12));
    BOOST_TEST(g1 == 1.0, tt::tolerance(1e-12));
    // derivative against finite differences (away from kinks)
    double wp[3], dwp[3], wm[3], dwm[3];
    const double h = 1e-7;
    const int ip = ugimp_axis(xp + h, 0.0, dx, lp, wp, dwp);
    const int im = ugimp_axis(xp - h, 0.0, dx, lp, wm, dwm);
    if (ip == i0 && im == i0) {
      for (int k = 0; k < 3; ++k) BOOST_TEST(dw[k] == (wp[k] - wm[k]) / (2 * h), tt::tolerance(1e-5));
    }
  }
}

// A coordinate that is not finite or is astronomically far returns "off the grid" (-1) with zero
// weights instead of converting an out-of-range double to int (undefined behaviour).
BOOST_AUTO_TEST_CASE(ugimp_off_grid_for_non_finite_coordinates) {
  for (double xp : {std::nan(""), HUGE_VAL, -HUGE_VAL, 1e300, -1e300}) {
    double w[3] = {1.0, 1.0, 1.0}, dw[3] = {1.0, 1.0, 1.0};
    BOOST_TEST(ugimp_axis(xp, 0.0, 1.0, 0.25, w, dw) == -1);
    for (int k = 0; k < 3; ++k) {
      BOOST_TEST(w[k] == 0.0);
      BOOST_TEST(dw[k] == 0.0);
    }
  }
}

// J2 return mapping in simple shear against the small-strain closed form with linear hardening:
// tau = G gamma below tau_y = sigma_y0/sqrt(3), then d tau/d gamma = G (Ep/3) / (G + Ep/3).
BOOST_AUTO_TEST_CASE(j2_simple_shear_closed_form) {
  const HyperelasticJ2 mat = polyethylene(100e6);
  PlasticState st;
  Eigen::Matrix3d Fold = Eigen::Matrix3d::Identity();
  const int n = 2000;
  const double gmax = 0.2;
  const double tau_y = mat.sigma_y0 / std::sqrt(3.0);
  const double Hs = mat.G * (mat.Ep / 3.0) / (mat.G + mat.Ep / 3.0);
  double max_consistency = 0.0;
  double tau_xy = 0.0;
  for (int k = 1; k <= n; ++k) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    F(0, 1) = gmax * k / n;
    const Eigen::Matrix3d f = F * Fold.inverse();
    Fold = F;
    double dl = 0.0;
    const Eigen::Matrix3d tau = update_stress(mat, f, F.determinant(), st, &dl);
    if (dl > 0.0) {
      const Eigen::Matrix3d s = tau - tau.trace() / 3.0 * Eigen::Matrix3d::Identity();
      const double yield = std::sqrt(2.0 / 3.0) * (mat.sigma_y0 + mat.Ep * st.alpha);
      max_consistency = std::max(max_consistency, std::fabs(s.norm() - yield) / yield);
    }
    tau_xy = tau(0, 1);
    if (k == n / 10) {  // gamma = 0.02, elastic
      BOOST_TEST(tau_xy == mat.G * 0.02, tt::tolerance(1e-3));
    }
  }
  const double exact = tau_y + Hs * (gmax - tau_y / mat.G);
  std::printf("J2 simple shear: tau_xy(0.2) = %.4f MPa, small-strain closed form %.4f MPa (%.2f%%); "
              "max consistency error %.2e\n",
              tau_xy / 1e6, exact / 1e6, 100.0 * (tau_xy / exact - 1.0), max_consistency);
  BOOST_TEST(max_consistency < 1e-10);
  BOOST_TEST(tau_xy == exact, tt::tolerance(0.03));
  // plastic strain: alpha = gamma_p / sqrt(3) with gamma_p = gamma - tau/G
  const double alpha_exact = (gmax - exact / mat.G) / std::sqrt(3.0);
  BOOST_TEST(st.alpha == alpha_exact, tt::tolerance(0.03));
  // stored elastic energy after plastic flow: the elastic shear strain tau/G holds tau^2/(2G) per
  // unit volume (small elastic strain), however far det(be_bar) has drifted from 1
  const double w = strain_energy_density(mat, st.be_bar, 1.0);
  std::printf("J2 simple shear: stored energy %.5g J/m^3, tau^2/(2G) = %.5g J/m^3; det(be_bar) - 1 = %.2e\n", w,
              tau_xy * tau_xy / (2.0 * mat.G), st.be_bar.determinant() - 1.0);
  BOOST_TEST(w == tau_xy * tau_xy / (2.0 * mat.G), tt::tolerance(0.01));
}

// Single radial-return step against its closed form (EQUATIONS A2).
BOOST_AUTO_TEST_CASE(j2_single_step_closed_form) {
  const HyperelasticJ2 mat = polyethylene(50e6);
  PlasticState st;
  Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
  f(0, 0) = 1.08;
  f(1, 1) = 1.0 / 1.08;  // isochoric plane-strain stretch
  double dl = 0.0;
  update_stress(mat, f, 1.0, st, &dl);
  Eigen::Matrix3d b = f * f.transpose();
  const double ib = b.trace() / 3.0;
  const Eigen::Matrix3d s_tr = mat.G * (b - ib * Eigen::Matrix3d::Identity());
  const double expect = (s_tr.norm() - std::sqrt(2.0 / 3.0) * mat.sigma_y0) / (2.0 * (mat.G * ib + mat.Ep / 3.0));
  BOOST_TEST(dl == expect, tt::tolerance(1e-12));
  BOOST_TEST(st.alpha == std::sqrt(2.0 / 3.0) * expect, tt::tolerance(1e-12));
}

namespace {
struct Bar {
  double dx = 1e-3, L = 0.05;
};

// Fixed-free bar in uniaxial strain (all nodes roller-supported in y), fundamental mode.
using Scheme = Numerics::StrainUpdate;
const char* scheme_name(Scheme s) { return s == Scheme::usl ? "USL" : s == Scheme::musl ? "MUSL" : "USAVG"; }

MpmProblem make_bar(const Bar& b, double v0, double pic, bool rollers, Scheme scheme = Scheme::usl,
                    double leave_limit = 0.01) {
  MpmConfig cfg;
  cfg.numerics.leave_limit = leave_limit;
  cfg.grid.dx = b.dx;
  cfg.grid.x0 = -3 * b.dx;
  cfg.grid.y0 = -3 * b.dx;
  cfg.grid.nx = static_cast<int>(std::lround(b.L / b.dx)) + 7;
  cfg.grid.ny = 8;
  cfg.material = elastic();
  cfg.numerics.pic_fraction = pic;
  cfg.numerics.position_order = 0;
  cfg.numerics.strain_update = scheme;
  cfg.fixed_mask = [rollers](double x, double) { return (x <= 1e-12 ? 1 : 0) | (rollers ? 2 : 0); };
  MpmProblem pb(cfg);
  const double L = b.L;
  fill_rect(pb, b.dx, 0.0, L, 0.0, 2 * b.dx, false,
            [&](double x, double) { return Eigen::Vector2d(v0 * std::sin(M_PI * x / (2 * L)), 0.0); });
  pb.setup();
  return pb;
}
}  // namespace

BOOST_AUTO_TEST_CASE(elastic_wave_speed_in_bar) {
 for (Scheme scheme : {Scheme::usl, Scheme::musl, Scheme::usavg}) {
  Bar b;
  MpmProblem pb = make_bar(b, 0.5, 0.0, true, scheme);
  const double c = pb.config().material.p_wave_speed();
  const double T = 4.0 * b.L / c;
  std::vector<double> crossings;
  double prev = pb.momentum().x(), tprev = 0.0;
  while (pb.time() < 4.2 * T) {
    pb.step();
    const double m = pb.momentum().x();
    if ((prev > 0.0) != (m > 0.0)) crossings.push_back(tprev + (pb.time() - tprev) * prev / (prev - m));
    prev = m;
    tprev = pb.time();
  }
  BOOST_REQUIRE(crossings.size() >= 5);
  const double period = 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double c_meas = 4.0 * b.L / period;
  std::printf("wave speed (%s): measured %.2f m/s, plane-strain P-wave sqrt((K+4G/3)/rho) = %.2f m/s (%.3f%%)\n",
              scheme_name(scheme), c_meas, c, 100.0 * (c_meas / c - 1.0));
  BOOST_TEST(c_meas == c, tt::tolerance(0.02));
 }
}

// Energy of a free elastic vibration with FLIP (no PIC damping) over about five periods. The
// strain-update schemes differ here: USL's strain rate lags the forces and loses energy; USAVG,
// NairnMPM's default, averages a strain-first and a strain-last half step, whose energy errors
// have opposite signs (Bardenhagen 2002; Nairn's NairnMPM notes), and conserves it best. The
// scheme test: USAVG's drift is the smallest of the three.
BOOST_AUTO_TEST_CASE(flip_energy_conservation_elastic_vibration) {
  Bar b;
  std::map<Scheme, double> drift;
  for (Scheme scheme : {Scheme::usl, Scheme::musl, Scheme::usavg}) {
    MpmProblem pb = make_bar(b, 10.0, 0.0, false, scheme);  // plane strain, free lateral faces, cell crossing
    const double e0 = pb.kinetic_energy() + pb.strain_energy();
    const double c = pb.config().material.p_wave_speed();
    const double T = 4.0 * b.L / c;  // upper bound on the period (bar wave is slower)
    double emin = e0, emax = e0;
    while (pb.time() < 5.0 * T) {
      pb.step();
      const double e = pb.kinetic_energy() + pb.strain_energy();
      emin = std::min(emin, e);
      emax = std::max(emax, e);
    }
    const double ef = pb.kinetic_energy() + pb.strain_energy();
    drift[scheme] = ef / e0 - 1.0;
    const EnergyBalance eb = pb.energy_balance();
    std::printf("FLIP energy over ~5 periods (%s): E0 = %.6g J/m, min %.6g, max %.6g, final %.6g (drift %.3f%%); "
                "audit residual %.3g J/m\n",
                scheme_name(scheme), e0, emin, emax, ef, 100.0 * drift[scheme], eb.residual);
    BOOST_TEST((emax - emin) / e0 < 0.02);
    // FLIP, no tool, no damping: the increment loss, the stress lag (the grid forces' work at
    // mid-step velocities less the stress power the updates book) and the residual are the energy
    // lost, as an identity
    BOOST_TEST(eb.audit.pic_damping == 0.0);
    BOOST_TEST(eb.audit.increment_loss >= 0.0);
    BOOST_TEST(std::fabs(eb.residual + eb.audit.increment_loss + eb.stress_lag - (e0 - ef)) < 1e-9 * e0);
    // the audit attributes the scheme's drift (0.5 % of E0 for USL and MUSL) to its terms: the
    // residual, the booked stress power less the stored elastic energy, is second order in the step
    // (measured 8.3e-5 J/m for USL and MUSL, 4.2e-5 for USAVG, of E0 = 2.5). Bound: a fiftieth of
    // the USL drift. Booking the stress power at the stress before each increment instead leaves
    // -0.367 J/m (USL): dtau : l / 2 per step, under-booked loading and unloading alike.
    BOOST_TEST(std::fabs(eb.residual) < 1e-4 * e0);
  }
  BOOST_TEST(std::fabs(drift[Scheme::usavg]) < std::fabs(drift[Scheme::usl]));
  BOOST_TEST(std::fabs(drift[Scheme::usavg]) < std::fabs(drift[Scheme::musl]));
  // PIC for comparison: strongly dissipative (the reason it serves as damping)
  MpmProblem pic = make_bar(b, 10.0, 1.0, false);
  const double e0 = pic.kinetic_energy() + pic.strain_energy();
  while (pic.time() < 5.0 * 4.0 * b.L / pic.config().material.p_wave_speed()) pic.step();
  const double ep = pic.kinetic_energy() + pic.strain_energy();
  const EnergyBalance pb_pic = pic.energy_balance();
  std::printf("PIC energy after the same time: %.6g J/m (%.1f%% of E0); audit: PIC damping %.4g, increment loss %.4g, "
              "residual %.4g J/m\n",
              ep, 100.0 * ep / e0, pb_pic.audit.pic_damping, pb_pic.audit.increment_loss, pb_pic.residual);
  // the audit closes on the PIC run too (measured: PIC damping 1.023, increment loss 0.015,
  // residual 7.6e-5 J/m of the 1.085 lost; an audit counting the extrapolation loss instead of the
  // increment loss reads -0.431)
  BOOST_TEST(std::fabs(pb_pic.residual) < 1e-3 * (e0 - ep));
  BOOST_TEST(ep < (1.0 + drift[Scheme::usavg]) * e0);
}

// The kinematic update is objective: a quarter turn of a free body leaves no stress. Tested with
// USL, whose strain rate is the gradient of the grid velocities; the re-extrapolating schemes
// (MUSL, USAVG) add the FLIP particle-velocity noise at the body's edges to the strain rate (von
// Mises up to 7e-3 G at 20 cells across, solvers/mpm/README.md), a different error from the one
// this test isolates.
BOOST_AUTO_TEST_CASE(large_rigid_rotation_without_spurious_stress,
                     CUTBENCH_RELEASE_ONLY("paths covered by flip_energy_conservation_elastic_vibration")) {
 for (Scheme scheme : {Scheme::usl}) {
  MpmConfig cfg;
  cfg.numerics.strain_update = scheme;
  // 20 x 20 cells across the body: FLIP loses ~1.3% of the angular velocity over a quarter turn at
  // this resolution (6% at 10 x 10 cells, 0.3% at 40 x 40), a discretisation error, not stress.
  const double dx = 0.5e-3, a = 5e-3, omega = 1000.0;
  cfg.grid.dx = dx;
  cfg.grid.x0 = cfg.grid.y0 = -24 * dx;
  cfg.grid.nx = cfg.grid.ny = 48;
  cfg.material = polyethylene();
  cfg.numerics.pic_fraction = 0.0;  // FLIP: PIC would dissipate the rotation
  cfg.numerics.position_order = 0;
  MpmProblem pb(cfg);
  std::vector<Eigen::Vector2d> x0;
  fill_rect(pb, dx, -a, a, -a, a, false, [&](double x, double y) {
    x0.emplace_back(x, y);
    return Eigen::Vector2d(-omega * y, omega * x);
  });
  pb.setup();
  const double t_end = 0.5 * M_PI / omega;  // quarter turn
  while (pb.time() < t_end) pb.step();
  double smax = 0.0, angle_err = 0.0, jerr = 0.0, stretch_err = 0.0, pos_err = 0.0, mean_err = 0.0;
  for (std::size_t p = 0; p < pb.size(); ++p) {
    const Eigen::Vector2d& X = x0[pb.id(p)];
    const double th = omega * pb.time();
    const Eigen::Vector2d xr(std::cos(th) * X.x() - std::sin(th) * X.y(), std::sin(th) * X.x() + std::cos(th) * X.y());
    pos_err = std::max(pos_err, (pb.position(p) - xr).norm() / a);
    smax = std::max(smax, von_mises(pb.cauchy_stress(p)));
    const Eigen::Matrix2d F = pb.deformation_gradient(p);
    const double ang = std::atan2(F(1, 0) - F(0, 1), F(0, 0) + F(1, 1));
    angle_err = std::max(angle_err, std::fabs(ang - omega * pb.time()));
    mean_err += (ang - omega * pb.time()) / static_cast<double>(pb.size());
    jerr = std::max(jerr, std::fabs(pb.jacobian(p) - 1.0));
    const Eigen::Matrix2d C = F.transpose() * F;
    stretch_err = std::max(stretch_err, (C - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff());
  }
  const double centrifugal = cfg.material.rho * omega * omega * a * a;
  std::printf("%s rotation by %.1f deg: max von Mises %.3g Pa (G = %.3g Pa, centrifugal scale rho w^2 a^2 = %.3g Pa), "
              "max |angle err| %.2e rad (mean %.2e), max |J-1| %.2e, max |C-I| %.2e, max position error %.4f a\n",
              scheme_name(scheme), omega * pb.time() * 180.0 / M_PI, smax, cfg.material.G, centrifugal, angle_err, mean_err, jerr, stretch_err, pos_err);
  BOOST_TEST(smax < 1e-3 * cfg.material.G);
  BOOST_TEST(angle_err < 0.03);
  BOOST_TEST(stretch_err < 2e-3);
 }
}

BOOST_AUTO_TEST_CASE(momentum_conservation_on_grid) {
  for (int variant = 0; variant < 6; ++variant) {
    const double pic = variant % 2 == 0 ? 0.0 : 1.0;
    const Scheme scheme = static_cast<Scheme>(variant / 2);
    MpmConfig cfg;
    const double dx = 1e-3;
    cfg.grid.dx = dx;
    cfg.grid.x0 = cfg.grid.y0 = -8 * dx;
    cfg.grid.nx = cfg.grid.ny = 16;
    cfg.material = polyethylene();
    cfg.numerics.pic_fraction = pic;
    cfg.numerics.min_mass_fraction = 0.0;  // keep every node that a particle touches: exact balance
    cfg.numerics.strain_update = scheme;
    MpmProblem pb(cfg);
    unsigned seed = 12345u;
    auto rnd = [&]() {
      seed = seed * 1103515245u + 12345u;
      return static_cast<double>((seed >> 8) & 0xffff) / 65535.0 - 0.5;
    };
    fill_rect(pb, dx, -3e-3, 3e-3, -2e-3, 2e-3, false, [&](double, double) { return Eigen::Vector2d(10 * rnd(), 10 * rnd()); });
    pb.setup();
    const Eigen::Vector2d p0 = pb.momentum();
    double err = 0.0, gerr = 0.0;
    for (int k = 0; k < 200; ++k) {
      pb.step();
      err = std::max(err, (pb.momentum() - p0).norm());
      gerr = std::max(gerr, (pb.grid_momentum() - p0).norm());
    }
    double scale = 0.0;
    for (std::size_t p = 0; p < pb.size(); ++p) scale += pb.mass(p) * 10.0;
    std::printf("momentum (PIC fraction %.0f, %s): max |P - P0| particles %.2e, grid %.2e (scale %.2e)\n", pic,
                scheme_name(scheme), err, gerr, scale);
    BOOST_TEST(err < 1e-12 * scale);
    BOOST_TEST(gerr < 1e-12 * scale);
  }
}

// The solver's packed plane-strain kernel agrees with the generic 3x3 update.
BOOST_AUTO_TEST_CASE(plane_strain_kernel_matches_generic_update) {
  const HyperelasticJ2 mat = polyethylene(100e6);
  unsigned seed = 7u;
  auto rnd = [&]() {
    seed = seed * 1103515245u + 12345u;
    return static_cast<double>((seed >> 8) & 0xffff) / 65535.0 - 0.5;
  };
  PlasticState st;
  double b[4] = {1.0, 0.0, 1.0, 1.0}, alpha = 0.0, J = 1.0;
  double maxdiff = 0.0;
  for (int k = 0; k < 400; ++k) {
    Eigen::Matrix2d l;
    l << 0.02 * rnd(), 0.02 * rnd(), 0.02 * rnd(), 0.02 * rnd();
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    f.topLeftCorner<2, 2>() += l;
    J *= f.determinant();
    const Eigen::Matrix3d tau = update_stress(mat, f, J, st);
    double t[4];
    update_stress_plane_strain(mat, l, J, b, alpha, t);
    maxdiff = std::max({maxdiff, std::fabs(t[0] - tau(0, 0)), std::fabs(t[1] - tau(0, 1)), std::fabs(t[2] - tau(1, 1)),
                        std::fabs(t[3] - tau(2, 2))});
    BOOST_REQUIRE(std::fabs(alpha - st.alpha) < 1e-12);
  }
  BOOST_TEST(st.alpha > 0.01);  // it did yield
  BOOST_TEST(maxdiff < 1e-6 * mat.G);
}

// Fig 2 metric: an affinely deformed lattice fills space exactly; a missing particle is a hole.
BOOST_AUTO_TEST_CASE(domain_coverage_metric) {
  const double s = 1.0;
  Eigen::Matrix2d F;
  F << 1.3, 0.4, -0.2, 0.9;
  std::vector<double> x, y, fxx, fxy, fyx, fyy;
  for (int j = 0; j < 10; ++j) {
    for (int i = 0; i < 10; ++i) {
      const Eigen::Vector2d X((i + 0.5) * s, (j + 0.5) * s), xx = F * X;
      x.push_back(xx.x());
      y.push_back(xx.y());
      fxx.push_back(F(0, 0));
      fxy.push_back(F(0, 1));
      fyx.push_back(F(1, 0));
      fyy.push_back(F(1, 1));
    }
  }
  const DomainCoverage full = domain_coverage(x, y, fxx, fxy, fyx, fyy, {}, s, 16);
  BOOST_TEST(full.particles == 100u);
  BOOST_TEST(full.gap_fraction < 0.01);
  BOOST_TEST(full.overlap_fraction < 0.01);
  std::vector<bool> use(100, true);
  use[55] = false;  // interior hole
  const DomainCoverage hole = domain_coverage(x, y, fxx, fxy, fyx, fyy, use, s, 16);
  BOOST_TEST(hole.gap_fraction == 1.0 / 99.0, tt::tolerance(0.15));
  // domains not deformed with the positions (F = I while positions sheared): gaps and overlaps
  std::vector<double> one(100, 1.0), zero(100, 0.0);
  const DomainCoverage bad = domain_coverage(x, y, one, zero, zero, one, {}, s, 16);
  BOOST_TEST(bad.gap_fraction + bad.overlap_fraction > 0.1);
}

// Position updates (EQUATIONS A4) in free fall under gravity: the 2nd-order update integrates the
// constant acceleration exactly, the 0th-order (standard MPM) one overshoots by g dt t / 2.
BOOST_AUTO_TEST_CASE(position_update_orders_in_free_fall) {
  const double g = 1000.0;
  for (double pic : {0.0, 1.0}) {
    double err[3];
    double dt = 0.0, t = 0.0;
    for (int order = 0; order <= 2; ++order) {
      MpmConfig cfg;
      cfg.grid.dx = 1e-3;
      cfg.grid.x0 = cfg.grid.y0 = -20e-3;
      cfg.grid.nx = cfg.grid.ny = 30;
      cfg.material = elastic();
      cfg.numerics.pic_fraction = pic;
      cfg.numerics.position_order = order;
      cfg.gravity = Eigen::Vector2d(0.0, -g);
      MpmProblem pb(cfg);
      fill_rect(pb, 1e-3, -2e-3, 2e-3, -2e-3, 2e-3, false);
      pb.setup();
      double y0 = 0.0;
      for (std::size_t p = 0; p < pb.size(); ++p) y0 += pb.position(p).y();
      for (int k = 0; k < 400; ++k) pb.step();
      double y = 0.0;
      for (std::size_t p = 0; p < pb.size(); ++p) y += pb.position(p).y();
      const double n = static_cast<double>(pb.size());
      dt = pb.dt();
      t = pb.time();
      err[order] = (y - y0) / n + 0.5 * g * t * t;  // mean displacement minus the exact -g t^2/2
    }
    std::printf("free fall (PIC fraction %.0f), t = %.3g s: position error order 0: %.3e m (expected -g dt t/2 = "
                "%.3e), order 1: %.3e m, order 2: %.3e m\n",
                pic, t, err[0], -0.5 * g * dt * t, err[1], err[2]);
    BOOST_TEST(err[0] == -0.5 * g * dt * t, tt::tolerance(1e-5));
    BOOST_TEST(std::fabs(err[2]) < 1e-5 * std::fabs(err[0]));  // round-off only
  }
}

// The blow-up guard: a sound state reports no fault; a non-finite velocity, and a particle that
// leaves the grid, are named with the step and time.
BOOST_AUTO_TEST_CASE(fault_names_nonfinite_and_escaped_particles) {
  Bar b;
  MpmProblem pb = make_bar(b, 10.0, 0.0, false);
  pb.step();
  BOOST_TEST(pb.fault().empty());
  pb.set_velocity(3, std::nan(""), 0.0);
  pb.step();
  const std::string f = pb.fault();
  BOOST_TEST_MESSAGE(f);
  BOOST_TEST(f.find("non-finite") != std::string::npos);
  BOOST_TEST(f.find("step 2") != std::string::npos);

  // NairnMPM's rule: a particle that leaves the grid is returned into it and counted once; the run
  // stops when more than leave_limit of the deformable particles have left (0: at the first one).
  // A huge velocity on one particle sends it and its grid neighbours (order-0 update) off the grid.
  auto launch = [&](double limit) {
    MpmProblem run = make_bar(b, 10.0, 0.0, false, Scheme::usl, limit);
    run.set_velocity(0, 1e9, 0.0);
    run.step();
    run.step();
    return run;
  };
  MpmProblem loose = launch(0.5);
  const long left = loose.frozen();
  BOOST_TEST(left > 0);
  BOOST_TEST(static_cast<double>(left) < 0.5 * static_cast<double>(loose.num_deformable()));
  BOOST_TEST(loose.fault().empty(), loose.fault());
  for (std::size_t p = 0; p < loose.size(); ++p) {  // returned: every particle has a finite position
    BOOST_TEST(std::isfinite(loose.position(p).x()));
  }
  loose.step();
  BOOST_TEST(loose.frozen() >= left);  // each particle counted once, however often it leaves

  MpmProblem strict = launch(0.0);
  BOOST_TEST_MESSAGE(strict.fault());
  BOOST_TEST(strict.fault().find("particles have left the grid (limit 0 of the") != std::string::npos);
  MpmProblem tight = launch(static_cast<double>(left - 1) / static_cast<double>(loose.num_deformable()));
  BOOST_TEST(tight.fault().find("particles have left the grid") != std::string::npos);
  MpmProblem enough = launch(static_cast<double>(left) / static_cast<double>(loose.num_deformable()));
  BOOST_TEST(enough.fault().empty(), enough.fault());
}
