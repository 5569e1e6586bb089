// Progressive failure per Gauss point with the analytic library's criteria (per-mode damage,
// sudden irreversible degradation), and the rigid-tool central-difference contact of Eqs 39-43:
// contact timing, Coulomb slip F_t = mu F_n, stick, momentum balance of the reported forces; and
// checkpoint/resume of the cutting loop (bit for bit).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "cutbench/common/checkpoint.hpp"
#include "cutbench/efg/cutting.hpp"
#include "cutbench/efg/explicit.hpp"

using namespace cutbench::efg;
namespace an = cutbench::analytic;
namespace tt = boost::test_tools;

namespace {
const double kPi = std::acos(-1.0);

an::Lamina gfrp_lamina() {
  an::Lamina l;  // Kahwash Table 2 means
  l.X_T = 697.8e6;
  l.X_C = 443.76e6;
  l.Y_T = 89.7216e6;
  l.Y_C = 148.33e6;
  l.S_L = 33.1e6;
  l.E1 = 34.28e9;
  l.G12 = 2.05e9;
  l.nu12 = 0.24244;
  return l;
}

// Homogeneous small-strain state (exx, eyy, gxy) on every node of the discretisation.
std::vector<Vec2> homogeneous(const Discretisation& d, double exx, double eyy, double gxy) {
  std::vector<Vec2> u(d.nodes.size());
  for (std::size_t I = 0; I < u.size(); ++I) {
    const Vec2& X = d.nodes[I];
    u[I] = Vec2(exx * X.x() + gxy * X.y(), eyy * X.y());
  }
  return u;
}

// Small-strain maximum-stress failure with the mode-factor degradation (the tests of the factors).
ExplicitOptions max_stress_mode_factors() {
  ExplicitOptions opt;
  opt.kinematics = Kinematics::small_strain;
  opt.failure.enabled = true;
  opt.failure.criterion = an::Criterion::max_stress;
  opt.failure.lamina = gfrp_lamina();
  opt.failure.degradation = Degradation::mode_factors;
  return opt;
}

struct DamageCount {
  std::size_t fibre = 0, matrix = 0, interface = 0;
};
DamageCount count(const ExplicitEFG& s) {
  DamageCount c;
  for (std::size_t g = 0; g < s.num_gauss(); ++g) {
    const auto d = s.damage(g);
    c.fibre += d[0] > 0.5;
    c.matrix += d[1] > 0.5;
    c.interface += d[2] > 0.5;
  }
  return c;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(progressive_failure)

BOOST_AUTO_TEST_CASE(modes_thresholds_and_degradation) {
  const Orthotropic m;
  const Discretisation d = rectangle(0.004, 0.002, 9, 5, 2.5, 0.2, 1);
  const Eigen::Matrix3d Q = m.Q();
  const an::Criterion crits[3] = {an::Criterion::max_stress, an::Criterion::hashin, an::Criterion::larc02};
  const char* names[3] = {"max stress", "Hashin", "LaRC02"};
  for (int c = 0; c < 3; ++c) {
    ExplicitOptions opt;
    opt.kinematics = Kinematics::small_strain;
    opt.failure.enabled = true;
    opt.failure.criterion = crits[c];
    opt.failure.lamina = gfrp_lamina();
    const std::size_t ng = d.gauss.size();
    // Fibre tension at theta = 0 (sigma22 = 0): sigma11 = E1 eps.
    {
      ExplicitEFG s(d, m, 0.0, opt);
      const double e1 = 697.8e6 / m.E1, r = -Q(0, 1) / Q(1, 1);
      s.set_displacement(homogeneous(d, 0.99 * e1, 0.99 * r * e1, 0.0));
      const DamageCount below = count(s);
      s.set_displacement(homogeneous(d, 1.01 * e1, 1.01 * r * e1, 0.0));
      const DamageCount above = count(s);
      s.set_displacement(homogeneous(d, 0.5 * e1, 0.5 * r * e1, 0.0));  // unload: damage stays
      const DamageCount after = count(s);
      const double s11 = s.pk2(0)(0);
      BOOST_TEST_MESSAGE(names[c] << " fibre tension: damaged GPs below/above/unloaded " << below.fibre << "/"
                                  << above.fibre << "/" << after.fibre << " of " << ng << "; sigma11 unloaded "
                                  << s11 << " Pa (undamaged " << 0.5 * 697.8e6 << ")");
      BOOST_TEST(below.fibre + below.matrix + below.interface == 0u, names[c]);
      BOOST_TEST(above.fibre == ng, names[c]);
      BOOST_TEST(above.matrix == 0u, names[c]);
      BOOST_TEST(after.fibre == ng, names[c]);
      BOOST_TEST(std::abs(s11) < 0.02 * 0.5 * 697.8e6, names[c]);
    }
    // Transverse tension at theta = 90 deg: x is the material 2 direction, sigma_x = E2 eps.
    {
      ExplicitEFG s(d, m, kPi / 2, opt);
      // A small fibre tension (1e-5 strain) keeps sigma11 off zero, where rounding would pick
      // the fibre branch (LaRC02's kinking branch at sigma11 = -0 flags transverse tension too).
      const double e2 = 89.7216e6 / m.E2, r = -Q(0, 1) / Q(0, 0), ef = 1e-5;
      s.set_displacement(homogeneous(d, 0.99 * e2, 0.99 * r * e2 + ef, 0.0));
      const DamageCount below = count(s);
      s.set_displacement(homogeneous(d, 1.01 * e2, 1.01 * r * e2 + ef, 0.0));
      const DamageCount above = count(s);
      BOOST_TEST_MESSAGE(names[c] << " matrix tension (theta 90): matrix-damaged GPs below/above " << below.matrix
                                  << "/" << above.matrix);
      BOOST_TEST(below.fibre + below.matrix + below.interface == 0u, names[c]);
      BOOST_TEST(above.matrix == ng, names[c]);
      BOOST_TEST(above.fibre == 0u, names[c]);
    }
    // In-plane shear at theta = 0 (with a small fibre tension, 1e-5): interface mode for maximum
    // stress (its shear index), matrix mode for Hashin and LaRC02, and for Hashin also the fibre
    // mode, whose tension form (s11/X_T)^2 + (t12/S_L)^2 contains the shear.
    {
      ExplicitEFG s(d, m, 0.0, opt);
      const double g = 33.1e6 / m.G12, ef = 1e-5;
      s.set_displacement(homogeneous(d, ef, 0.0, 0.99 * g));
      const DamageCount below = count(s);
      s.set_displacement(homogeneous(d, ef, 0.0, 1.01 * g));
      const DamageCount above = count(s);
      BOOST_TEST_MESSAGE(names[c] << " shear: fibre/matrix/interface damaged " << above.fibre << "/" << above.matrix
                                  << "/" << above.interface);
      BOOST_TEST(below.fibre + below.matrix + below.interface == 0u, names[c]);
      if (crits[c] == an::Criterion::max_stress) {
        BOOST_TEST(above.interface == ng, names[c]);
        BOOST_TEST(above.matrix == 0u, names[c]);
      } else {
        BOOST_TEST(above.matrix == ng, names[c]);
        BOOST_TEST(above.interface == 0u, names[c]);
      }
      BOOST_TEST(above.fibre == (crits[c] == an::Criterion::hashin ? ng : 0u), names[c]);
    }
  }
}

// Mode-dependent degradation (Camanho & Matthews 1999 / Tserpes et al. 2002 factors): the stress
// of a single homogeneous state after failure equals the stiffness with the stated factors times
// the strain, and the sign of the failing stress selects the tension or compression factor.
BOOST_AUTO_TEST_CASE(mode_factor_degradation) {
  const Orthotropic m;
  const Discretisation d = rectangle(0.004, 0.002, 9, 5, 2.5, 0.2, 1);
  const ExplicitOptions opt = max_stress_mode_factors();
  const Eigen::Matrix3d Q = m.Q();
  auto scaled = [&](double kE1, double kE2, double kG, double knu) {
    Orthotropic o = m;
    o.E1 *= kE1;
    o.E2 *= kE2;
    o.G12 *= kG;
    o.nu12 *= knu;
    return o;
  };
  struct Case {
    const char* name;
    double theta, sign, strength;  // load along x: material 1 (theta 0) or 2 (theta 90 deg)
    int mode;
    Orthotropic expected;
  };
  const Case cases[4] = {
      {"fibre tension", 0.0, 1.0, 697.8e6, fibre_damage, scaled(0.07, 0.07, 0.07, 0.07)},
      {"fibre compression", 0.0, -1.0, 443.76e6, fibre_damage, scaled(0.14, 0.14, 0.14, 0.14)},
      {"matrix tension", kPi / 2, 1.0, 89.7216e6, matrix_damage, scaled(1.0, 0.2, 0.2, 1.0)},
      {"matrix compression", kPi / 2, -1.0, 148.33e6, matrix_damage, scaled(1.0, 0.4, 0.4, 1.0)},
  };
  for (const Case& c : cases) {
    ExplicitEFG s(d, m, c.theta, opt);
    const bool fibre = c.mode == fibre_damage;
    // Uniaxial stress along x before failure: lateral strain -Q12/Q22 (fibre) or -Q12/Q11 (matrix).
    const double Ex = fibre ? m.E1 : m.E2, r = fibre ? -Q(0, 1) / Q(1, 1) : -Q(0, 1) / Q(0, 0);
    const double e = c.sign * 1.01 * c.strength / Ex;
    s.set_displacement(homogeneous(d, e, r * e, 0.0));
    const auto dmg = s.damage(0);
    const auto comp = s.compressive(0);
    const Eigen::Vector3d eps(e, r * e, 0.0);
    const Eigen::Vector3d expected = c.expected.Qbar(c.theta) * eps;
    const double err = (s.pk2(0) - expected).norm() / expected.norm();
    BOOST_TEST_MESSAGE("mode factors, " << c.name << ": sigma_x " << s.pk2(0)(0) << " Pa, expected "
                                        << expected(0) << " (undamaged " << (m.Qbar(c.theta) * eps)(0)
                                        << "), relative error " << err);
    BOOST_TEST(dmg[c.mode] == 1.0, c.name);
    BOOST_TEST(dmg[fibre ? matrix_damage : fibre_damage] == 0.0, c.name);
    BOOST_TEST(static_cast<int>(comp[fibre ? 0 : 1]) == (c.sign < 0 ? 1 : 0), c.name);
    BOOST_TEST(err < 1e-10, c.name);
  }
  // Several failed modes: the rules apply in sequence (factors multiply); interface: G12, nu12
  // times the residual.
  {
    ExplicitEFG s(d, m, 0.3, opt);
    const Eigen::Matrix3d K = s.degraded_stiffness({1.0, 1.0, 1.0}, {1, 0});
    const Orthotropic o = scaled(0.14, 0.14 * 0.2, 0.14 * 0.2 * 0.01, 0.14 * 0.01);
    BOOST_TEST((K - o.Qbar(0.3)).norm() < 1e-12 * o.Qbar(0.3).norm());
  }
  // The sudden scheme is unchanged: failed moduli times `residual`.
  {
    ExplicitOptions so = opt;
    so.failure.degradation = Degradation::sudden;
    ExplicitEFG s(d, m, 0.3, so);
    const Eigen::Matrix3d K = s.degraded_stiffness({1.0, 0.0, 0.0}, {1, 0});
    const Orthotropic o = scaled(0.01, 1.0, 0.01, 0.01);
    BOOST_TEST((K - o.Qbar(0.3)).norm() < 1e-12 * o.Qbar(0.3).norm());
  }
}

// The damage matrix stores each failure index as its running maximum (capped at 1). With
// proportional growth a mode's moduli are scaled by 1 - d (1 - f) as soon as its index d rises, and
// stay so on unloading; with growth at failure the index is stored but the stiffness is untouched
// below 1. Uniaxial fibre tension at half the strength (maximum stress: d = 0.25), theta = 0.
BOOST_AUTO_TEST_CASE(damage_index_and_proportional_growth) {
  const Orthotropic m;
  const Discretisation d = rectangle(0.004, 0.002, 9, 5, 2.5, 0.2, 1);
  const Eigen::Matrix3d Q = m.Q();
  const double e = 0.5 * 697.8e6 / m.E1, r = -Q(0, 1) / Q(1, 1);
  const Eigen::Vector3d eps(e, r * e, 0.0);
  for (DamageGrowth growth : {DamageGrowth::at_failure, DamageGrowth::proportional}) {
    const bool prop = growth == DamageGrowth::proportional;
    ExplicitOptions opt = max_stress_mode_factors();
    opt.failure.growth = growth;
    ExplicitEFG s(d, m, 0.0, opt);
    s.set_displacement(homogeneous(d, e, r * e, 0.0));
    // the trial stress of the undamaged material gives the index (sigma11 / X_T)^2 = 0.25
    BOOST_TEST(s.failure_index(0)[fibre_damage] == 0.25, tt::tolerance(1e-9));
    BOOST_TEST(s.damage(0)[fibre_damage] == 0.0);
    const double k = prop ? 1.0 - 0.25 * (1.0 - 0.07) : 1.0;
    Orthotropic o = m;
    o.E1 *= k;
    o.E2 *= k;
    o.G12 *= k;
    o.nu12 *= k;
    const Eigen::Vector3d expected = o.Qbar(0.0) * eps;
    BOOST_TEST((s.pk2(0) - expected).norm() < 1e-9 * expected.norm(), (prop ? "proportional" : "at failure"));
    // unloading to half the strain: the index and (proportional) the degraded stiffness remain
    s.set_displacement(homogeneous(d, 0.5 * e, 0.5 * r * e, 0.0));
    BOOST_TEST(s.failure_index(0)[fibre_damage] == 0.25, tt::tolerance(1e-9));
    // (the degraded stiffness gives sigma22 != 0 at this strain, so the matrix index grows a
    // little on reloading: 3e-6 of the stress)
    BOOST_TEST((s.pk2(0) - 0.5 * expected).norm() < 1e-4 * expected.norm());
  }
}

// The cheap bound used to skip LaRC02's fracture-plane search is an upper bound of the searched
// matrix-compression index, and the fibre index is unchanged when the search is skipped.
BOOST_AUTO_TEST_CASE(larc02_matrix_compression_bound_holds) {
  const an::Lamina l = gfrp_lamina();
  double worst = 1e300;  // smallest bound / index over the sweep (>= 1 required)
  int n = 0;
  for (int i = 1; i <= 40; ++i) {
    for (int j = -40; j <= 40; ++j) {
      for (double s11 : {-140e6, 0.0, 300e6}) {
        an::PlaneStress ps;
        ps.s11 = s11;
        ps.s22 = -i * 5e6;  // -5 ... -200 MPa
        ps.t12 = j * 1.5e6;  // -60 ... 60 MPa
        const an::FailureIndices full = an::larc02_failure(ps, l);
        const an::FailureIndices fast = an::larc02_failure(ps, l, false);
        BOOST_TEST(fast.fibre == full.fibre);
        BOOST_TEST(std::isnan(fast.matrix));
        const double b = larc02_matrix_compression_bound(ps.s22, ps.t12, l);
        if (full.matrix > 0.0) {
          worst = std::min(worst, b / full.matrix);
          ++n;
        }
      }
    }
  }
  BOOST_TEST_MESSAGE("LaRC02 matrix-compression bound / searched index: min " << worst << " over " << n << " states");
  BOOST_TEST(worst >= 1.0);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(contact)

namespace {
struct BlockRun {
  double t_first = -1, dt_first = 0, t_exact = 0;
  double max_slip_ratio_error = 0;  // max | |F_t| - mu F_n | / (mu F_n) over all-slip steps
  double max_ratio = 0;             // max |F_t| / F_n over contact steps
  int stick_steps = 0, slip_steps = 0;
  double impulse_n = 0, impulse_t = 0, dpy = 0, dpx = 0, vy_end = 0;
  bool drag_opposes_slip = true;
};

// A 10 mm x 10 mm elastic block moving at (vx, -1 m/s) towards a rigid floor 10 um below it.
BlockRun block(double vx, double mu) {
  const Orthotropic m;
  const double H = 0.01, g0 = 1e-5, vy = -1.0;
  const Discretisation d = rectangle(H, H, 11, 11, 2.5);
  ExplicitOptions opt;
  ExplicitEFG s(d, m, 0.0, opt);
  s.set_initial_velocity(std::vector<Vec2>(d.nodes.size(), Vec2(vx, vy)));
  RigidTool floor;
  floor.vertices = {Vec2(-1, -g0 - 1), Vec2(1, -g0 - 1), Vec2(1, -g0), Vec2(-1, -g0)};
  floor.mu = mu;
  s.set_tool(floor);
  const auto momentum = [&] {
    Vec2 p = Vec2::Zero();
    for (std::size_t I = 0; I < d.nodes.size(); ++I) p += s.masses()[I] * s.velocities()[I];
    return p;
  };
  BlockRun r;
  r.t_exact = g0 / -vy;
  const Vec2 p0 = momentum();
  const double t_end = r.t_exact + 3.0 * H / std::sqrt(m.E2 / m.rho);
  while (s.time() < t_end) {
    const double dt = s.step();
    const Vec2 F = s.tool_force();  // force on the floor
    if (s.contact_count() > 0) {
      if (r.t_first < 0) {
        r.t_first = s.time();
        r.dt_first = dt;
      }
      const double Fn = -F.y(), Ft = F.x();
      r.impulse_n += Fn * dt;
      r.impulse_t += Ft * dt;
      r.max_ratio = std::max(r.max_ratio, std::abs(Ft) / Fn);
      if (s.stick_count() == 0) {
        ++r.slip_steps;
        r.max_slip_ratio_error = std::max(r.max_slip_ratio_error, std::abs(std::abs(Ft) - mu * Fn) / (mu * Fn));
        if (vx != 0.0 && Ft * vx < 0) r.drag_opposes_slip = false;  // floor dragged along the slip
      } else {
        ++r.stick_steps;
      }
    }
  }
  const Vec2 p1 = momentum();
  r.dpy = p1.y() - p0.y();
  r.dpx = p1.x() - p0.x();
  r.vy_end = p1.y() / (m.rho * H * H);
  return r;
}
}  // namespace

BOOST_AUTO_TEST_CASE(block_impact_timing_slip_and_momentum) {
  const double mu = 0.3;
  const BlockRun r = block(2.0, mu);
  BOOST_TEST_MESSAGE("sliding block: first contact at " << r.t_first << " s (gap/velocity " << r.t_exact
                                                       << " s, dt " << r.dt_first << "), slip steps " << r.slip_steps
                                                       << ", stick steps " << r.stick_steps << ", max | |F_t|/(mu F_n) - 1 | "
                                                       << r.max_slip_ratio_error << ", impulses n/t " << r.impulse_n
                                                       << "/" << r.impulse_t << " vs momentum change " << r.dpy << "/"
                                                       << r.dpx << ", rebound vy " << r.vy_end);
  BOOST_TEST(r.t_first >= r.t_exact);
  BOOST_TEST(r.t_first - r.dt_first < r.t_exact);
  BOOST_TEST(r.slip_steps > 10);
  BOOST_TEST(r.stick_steps == 0);
  BOOST_TEST(r.max_slip_ratio_error < 1e-12);
  BOOST_TEST(r.drag_opposes_slip);
  // Reported forces are momentum-consistent: impulse on the floor = -(momentum change of block).
  BOOST_TEST(std::abs(r.impulse_n - r.dpy) < 1e-9 * std::abs(r.dpy));
  BOOST_TEST(std::abs(r.impulse_t + r.dpx) < 1e-9 * std::abs(r.dpx));
  BOOST_TEST(std::abs(r.impulse_t / r.impulse_n - mu) < 1e-12);
  BOOST_TEST(r.vy_end > 0.5);  // elastic rebound
}

BOOST_AUTO_TEST_CASE(block_impact_sticks_at_low_slip_speed) {
  const double mu = 0.3;
  const BlockRun r = block(0.02, mu);
  BOOST_TEST_MESSAGE("slow block: stick steps " << r.stick_steps << ", slip steps " << r.slip_steps
                                                 << ", max |F_t|/F_n " << r.max_ratio);
  BOOST_TEST(r.stick_steps > 0);
  BOOST_TEST(r.max_ratio <= mu * (1 + 1e-12));
}

namespace {
struct PressedBlock {
  double weight = 0, Fn_mean = 0, Ft_mean = 0, vx_end = 0, ax_expected = 0, ax = 0;
  int stick_steps = 0, slip_steps = 0;
};
// A block resting on the floor under a body force g (down) and a tangential body force q g (+x):
// time averages of the reported floor forces against the applied loads.
PressedBlock pressed_block(double q, double mu) {
  const Orthotropic m;
  const double H = 0.005, g = 2.0e5;  // large g so that the static deflection spans many steps
  const Discretisation d = rectangle(H, H, 6, 6, 2.5);
  ExplicitOptions opt;
  ExplicitEFG s(d, m, 0.0, opt);
  std::vector<Vec2> f(d.nodes.size());
  double M = 0.0;
  for (std::size_t I = 0; I < f.size(); ++I) {
    f[I] = s.masses()[I] * Vec2(q * g, -g);
    M += s.masses()[I];
  }
  s.set_external_force(f);
  RigidTool floor;
  floor.vertices = {Vec2(-1, -1), Vec2(1, -1), Vec2(1, -1e-12), Vec2(-1, -1e-12)};
  floor.mu = mu;
  s.set_tool(floor);
  PressedBlock r;
  r.weight = M * g;
  double T = 0, In = 0, It = 0, t_half = 0, vx_half = 0;
  const int n = 6000;
  for (int k = 0; k < n; ++k) {
    const double dt = s.step();
    if (k == n / 2) {
      double p = 0;
      for (std::size_t I = 0; I < f.size(); ++I) p += s.masses()[I] * s.velocities()[I].x();
      vx_half = p / M;
      t_half = s.time();
    }
    if (k >= n / 2) {
      T += dt;
      In += -s.tool_force().y() * dt;
      It += s.tool_force().x() * dt;
      if (s.contact_count() > 0) (s.stick_count() == s.contact_count() ? r.stick_steps : r.slip_steps)++;
    }
  }
  double p = 0;
  for (std::size_t I = 0; I < f.size(); ++I) p += s.masses()[I] * s.velocities()[I].x();
  r.vx_end = p / M;
  r.ax = (r.vx_end - vx_half) / (s.time() - t_half);
  r.Fn_mean = In / T;
  r.Ft_mean = It / T;
  r.ax_expected = q > mu ? (q - mu) * g : 0.0;
  return r;
}
}  // namespace

BOOST_AUTO_TEST_CASE(pressed_block_reported_forces_equal_loads) {
  // Steady contact: the time-averaged reported normal force equals the weight (the Eq 39 value
  // summed literally would be twice it); below mu the block sticks and the floor carries the
  // tangential load; above mu it slides with F_t = mu F_n and acceleration (q - mu) g.
  const double mu = 0.3;
  const PressedBlock a = pressed_block(0.2, mu), b = pressed_block(0.5, mu);
  BOOST_TEST_MESSAGE("pressed block q = 0.2: F_n/W " << a.Fn_mean / a.weight << ", F_t/W " << a.Ft_mean / a.weight
                                                    << ", mean a_x " << a.ax << " m/s2, stick/slip steps " << a.stick_steps
                                                    << "/" << a.slip_steps);
  BOOST_TEST_MESSAGE("pressed block q = 0.5: F_n/W " << b.Fn_mean / b.weight << ", F_t/F_n " << b.Ft_mean / b.Fn_mean
                                                    << ", a_x " << b.ax << " m/s2 (expected " << b.ax_expected
                                                    << "), stick/slip steps " << b.stick_steps << "/" << b.slip_steps);
  BOOST_TEST(std::abs(a.Fn_mean / a.weight - 1.0) < 0.02);
  BOOST_TEST(std::abs(a.Ft_mean / a.weight - 0.2) < 0.01);
  BOOST_TEST(std::abs(b.Fn_mean / b.weight - 1.0) < 0.02);
  BOOST_TEST(std::abs(b.Ft_mean / b.Fn_mean - mu) < 0.01);
  BOOST_TEST(std::abs(b.ax / b.ax_expected - 1.0) < 0.05);
  BOOST_TEST(std::abs(a.ax) < 0.05 * b.ax_expected);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(cutting_setup)

BOOST_AUTO_TEST_CASE(rounded_edge_is_tangent_arc) {
  // Edge radius option: the arc points lie on a circle of the given radius, its end points on the
  // clearance and rake faces through the sharp edge, tangent to them, and the tool stays convex.
  const Vec2 E(1e-3, 0.5e-3);
  const double rho = 20e-6, rake = 0.1, cl = 7.0 * kPi / 180.0;
  const auto v = edge_vertices(E, rake, cl, rho, 8);
  BOOST_REQUIRE(v.size() == 9u);
  const Vec2 u1(-std::sin(rake), std::cos(rake)), u2(-std::cos(cl), std::sin(cl));  // face directions
  auto dist_line = [&](const Vec2& p, const Vec2& u) { return std::abs(u.x() * (p - E).y() - u.y() * (p - E).x()); };
  BOOST_TEST(dist_line(v.front(), u2) < 1e-12 * rho);  // on the clearance face
  BOOST_TEST(dist_line(v.back(), u1) < 1e-12 * rho);   // on the rake face
  // Circle through all points: centre from the first point along the inward clearance normal.
  const Vec2 C = v.front() + rho * Vec2(std::sin(cl), std::cos(cl));
  for (const auto& p : v) BOOST_TEST(std::abs((p - C).norm() - rho) < 1e-12 * rho);
  BOOST_TEST(std::abs((v.back() - C).dot(u1)) < 1e-12 * rho);  // tangent to the rake face
  // Convex, counter-clockwise with the rest of the tool polygon.
  std::vector<Vec2> poly = v;
  poly.push_back(E + Vec2(-1e-3 * std::tan(rake), 1e-3));
  poly.push_back(E + Vec2(-1e-3, 1e-3));
  poly.push_back(E + Vec2(-1e-3, 1e-3 * std::tan(cl)));
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2 a = poly[(k + 1) % poly.size()] - poly[k], b = poly[(k + 2) % poly.size()] - poly[(k + 1) % poly.size()];
    BOOST_TEST(a.x() * b.y() - a.y() * b.x() > 0.0);
  }
  BOOST_TEST(edge_vertices(E, rake, cl, 0.0, 8).size() == 1u);  // sharp edge: E itself
}

BOOST_AUTO_TEST_CASE(tool_engages_at_gap_over_speed) {
  // Smoke test of the cutting set-up (coarse, 10 um of travel): the tool first touches the
  // workpiece within one step of gap/speed, the workpiece resists the advance (F_c > 0), the
  // thrust is smaller than the cutting force (0 deg rake: only friction on the rake face) and
  // LaRC02 damages Gauss points ahead of the edge. Sanity checks, not a reproduction of Kahwash
  // Tables 4-6 (those are the kahwash2018 cases).
  CuttingSetup s;
  s.lamina = gfrp_lamina();
  s.theta = 30.0 * kPi / 180.0;
  s.spacing = 0.05e-3;
  s.time_scale = 50.0;
  s.travel = 0.01e-3;
  s.update_interval = 20;  // the cases' reference updates (every step costs about 7 times more)
  const CuttingResult r = run_cutting(s);
  BOOST_TEST_MESSAGE("cutting smoke test: " << r.nodes << " nodes, " << r.steps << " steps, contact at "
                                            << r.t_contact << " s (gap/speed " << r.t_contact_expected
                                            << " s), F_c " << r.Fc_mean << " N/m, F_t " << r.Ft_mean
                                            << " N/m, damaged fibre/matrix " << r.fibre_damaged << "/"
                                            << r.matrix_damaged << " of " << r.gauss);
  BOOST_TEST(r.t_contact >= r.t_contact_expected);
  BOOST_TEST(r.t_contact < r.t_contact_expected + 1.01 * r.dt_initial);
  BOOST_TEST(r.Fc_mean > 0.0);
  BOOST_TEST(std::abs(r.Ft_mean) < r.Fc_mean);
  BOOST_TEST(r.fibre_damaged + r.matrix_damaged > 0u);
}

BOOST_AUTO_TEST_SUITE_END()

// Checkpoint and resume of the cutting loop (cutbench run --run-cache): a run stopped after every
// checkpoint and resumed each time equals the uninterrupted run bit for bit, through contact,
// failure, erosion, the visibility cut line that grows during the run, chip completion and the
// damage snapshots; a checkpoint of another run is ignored.
BOOST_AUTO_TEST_SUITE(efg_checkpoint)

namespace {
CuttingSetup checkpoint_cut() {
  CuttingSetup s;  // the kahwash2018 quick mesh at 75 deg, LaRC02, the paper's failure model: to chip completion
  s.lamina = gfrp_lamina();
  s.theta = 75.0 * kPi / 180.0;
  s.S_sigma = 158.9e6;  // Table 1 at 75 deg
  s.S_tau = 85.1e6;
  s.update_interval = 20;  // the cases' reference updates (updated Lagrangian state across checkpoints)
  s.spacing = 0.0625e-3;
  s.work_length = 1.0e-3;
  s.work_height = 0.5e-3;
  s.time_scale = 200.0;
  s.travel = 0.15e-3;
  s.snapshots = 3;
  return s;
}

// The erosion options (kept for comparison): eroded Gauss points, released nodes and the
// separation guard across checkpoints, total Lagrangian, at 30 deg.
CuttingSetup erosion_cut() {
  CuttingSetup s = checkpoint_cut();
  s.theta = 30.0 * kPi / 180.0;
  s.S_sigma = s.S_tau = 0.0;
  s.growth = DamageGrowth::at_failure;
  s.erosion = Erosion::fibre_and_matrix;
  s.collapse_ratio = 0.1;
  s.completion_guard = CompletionGuard::separation;
  s.kinematics = Kinematics::total_lagrangian;
  return s;
}

std::string checkpoint_file(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "cutbench_efg_checkpoint";
  std::filesystem::create_directories(dir);
  const auto p = dir / name;
  std::filesystem::remove(p);
  return p.string();
}
}  // namespace

namespace {
CuttingResult require_resume_equals_uninterrupted(const CuttingSetup& s, const std::string& name) {
  const CuttingResult ref = run_cutting(s);
  const cutbench::CheckpointSpec spec{checkpoint_file(name + ".ckpt"), "efg test run", 0.0, true};
  CuttingResult r;
  int interruptions = 0;
  for (;;) {
    cutbench::CheckpointScope scope(spec);
    try {
      r = run_cutting(s);
      break;
    } catch (const cutbench::CheckpointStop&) {
      ++interruptions;
    }
    BOOST_REQUIRE(interruptions < 100000);
  }
  BOOST_TEST_MESSAGE("efg checkpoint test " << name << ": " << ref.steps << " steps, " << interruptions
                                             << " interruptions, last resume at step " << r.drive.resumed_from_step
                                             << ", completion at " << ref.travel_complete * 1e6 << " um, "
                                             << ref.eroded << " eroded Gauss points, " << ref.opaque_segments
                                             << " opaque segments");
  BOOST_TEST(interruptions == static_cast<int>((ref.steps - 1) / 256));
  BOOST_TEST(r.drive.resumed_from_step == 256u * static_cast<std::size_t>(interruptions));
  BOOST_TEST(r.steps == ref.steps);
  BOOST_TEST(r.t == ref.t, boost::test_tools::per_element());
  BOOST_TEST(r.travel == ref.travel, boost::test_tools::per_element());
  BOOST_TEST(r.Fc == ref.Fc, boost::test_tools::per_element());
  BOOST_TEST(r.Ft == ref.Ft, boost::test_tools::per_element());
  BOOST_TEST(r.dt == ref.dt, boost::test_tools::per_element());
  // the energy ledger is part of the state: its history and final terms resume bit for bit
  BOOST_TEST(r.e_tool == ref.e_tool, boost::test_tools::per_element());
  BOOST_TEST(r.e_residual == ref.e_residual, boost::test_tools::per_element());
  BOOST_TEST(r.energy_damage == ref.energy_damage);
  BOOST_TEST(r.energy_internal == ref.energy_internal);
  BOOST_TEST(r.energy_contact_loss == ref.energy_contact_loss);
  BOOST_TEST(r.Fc_mean == ref.Fc_mean);
  BOOST_TEST(r.Ft_mean == ref.Ft_mean);
  BOOST_TEST(r.Fc_peak == ref.Fc_peak);
  BOOST_TEST(r.dt_min == ref.dt_min);
  BOOST_TEST(r.t_contact == ref.t_contact);
  BOOST_TEST(r.t_complete == ref.t_complete);
  BOOST_TEST(r.travel_complete == ref.travel_complete);
  BOOST_TEST(r.dt_drop_ratio == ref.dt_drop_ratio);
  BOOST_TEST(r.travel_first_drop == ref.travel_first_drop);
  BOOST_TEST(r.travel_path == ref.travel_path);
  BOOST_TEST(r.travel_separated == ref.travel_separated);
  BOOST_TEST(r.travel_first_failure == ref.travel_first_failure);
  BOOST_TEST(r.Fc_first_failure == ref.Fc_first_failure);
  BOOST_TEST(r.fibre_damaged == ref.fibre_damaged);
  BOOST_TEST(r.matrix_damaged == ref.matrix_damaged);
  BOOST_TEST(r.eroded == ref.eroded);
  BOOST_TEST(r.released == ref.released);
  BOOST_TEST(r.collapse_eroded == ref.collapse_eroded);
  BOOST_TEST(r.chip_fibre == ref.chip_fibre);
  BOOST_TEST(r.chip_matrix == ref.chip_matrix);
  BOOST_TEST(r.opaque_segments == ref.opaque_segments);
  BOOST_REQUIRE(r.snapshots.size() == ref.snapshots.size());
  for (std::size_t k = 0; k < r.snapshots.size(); ++k) {
    BOOST_TEST(r.snapshots[k].travel == ref.snapshots[k].travel);
    BOOST_TEST(r.snapshots[k].x == ref.snapshots[k].x, boost::test_tools::per_element());
    BOOST_TEST(r.snapshots[k].fibre == ref.snapshots[k].fibre, boost::test_tools::per_element());
    BOOST_TEST(r.snapshots[k].matrix == ref.snapshots[k].matrix, boost::test_tools::per_element());
  }
  cutbench::remove_checkpoint(spec);
  return ref;
}
}  // namespace

BOOST_AUTO_TEST_CASE(interrupted_after_every_checkpoint_equals_uninterrupted) {
  // to chip completion: contact, damage growth, reference updates, the drop detector and its
  // guard, snapshots; and the same with the erosion options (eroded points, released nodes)
  const CuttingSetup complete = checkpoint_cut();
  BOOST_TEST(require_resume_equals_uninterrupted(complete, "completion").t_complete > 0.0);
  const CuttingResult eroded = require_resume_equals_uninterrupted(erosion_cut(), "erosion");
  BOOST_TEST(eroded.t_complete > 0.0);
  BOOST_TEST(eroded.eroded > 0u);
  // detector off, 0.08 mm of travel: the cut line grows by opaque segments after checkpoints, so
  // the resumed shape functions must see them (rebuilt from the stored segments)
  CuttingSetup longer = checkpoint_cut();
  longer.drop = 0.0;
  longer.travel = 0.08e-3;
  longer.snapshots = 0;
  BOOST_TEST(require_resume_equals_uninterrupted(longer, "cut_line").opaque_segments >= 4u);  // notch corner (2) + cut line
}

BOOST_AUTO_TEST_CASE(energy_ledger_closes_with_the_papers_failure_model) {
  // The energy audit (solvers/efg/README.md): tool work = contact loss + kinetic + strain + damage
  // energy up to the time step and the shape-function changes; and the internal forces' work over
  // the steps equals the strain plus the released energy. Both to 3 % of the tool's work, the
  // tolerance of the cases' energy checks. (Erosion, which zeroes a stress within one step, leaves
  // a few per cent: kahwash2018 FINDINGS F17.)
  const CuttingResult r = run_cutting(checkpoint_cut());
  BOOST_TEST_MESSAGE("energy (J/m): tool " << r.energy_tool << ", contact loss " << r.energy_contact_loss
                                           << ", kinetic " << r.energy_kinetic << ", strain " << r.energy_strain
                                           << ", damage " << r.energy_damage << ", internal work "
                                           << r.energy_internal << ", residual " << r.energy_residual);
  BOOST_TEST(r.energy_tool > 0.0);
  BOOST_TEST(r.energy_damage > 0.0);
  BOOST_TEST(r.energy_contact_loss >= 0.0);  // friction and the inelastic contact impulses dissipate
  BOOST_TEST(std::abs(r.energy_residual) <= 0.03 * r.energy_tool);
  BOOST_TEST(std::abs(r.energy_internal - r.energy_strain - r.energy_damage) <= 0.03 * r.energy_tool);
}

BOOST_AUTO_TEST_CASE(checkpoint_of_another_run_is_ignored) {
  CuttingSetup s = checkpoint_cut();
  s.travel = 0.02e-3;
  const std::string path = checkpoint_file("other.ckpt");
  {
    cutbench::CheckpointScope scope(cutbench::CheckpointSpec{path, "run A", 0.0, true});
    BOOST_CHECK_THROW(run_cutting(s), cutbench::CheckpointStop);
  }
  BOOST_REQUIRE(std::filesystem::exists(path));
  cutbench::CheckpointScope scope(cutbench::CheckpointSpec{path, "run B", 1e9, false});
  const CuttingResult r = run_cutting(s);
  BOOST_TEST(r.drive.resumed_from_step == 0u);
  BOOST_TEST(r.steps > 256L);
  std::filesystem::remove(path);
}

BOOST_AUTO_TEST_SUITE_END()
