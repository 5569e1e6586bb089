// Transient conduction against analytic solutions; convection/radiation energy balance.
#include <boost/test/unit_test.hpp>
#include <chrono>
#include <cmath>
#include <iostream>

#include "cutbench/sph/heat.hpp"
#include "release_only.hpp"

using namespace cutbench::sph;
namespace tt = boost::test_tools;

namespace {
constexpr double kPi = 3.14159265358979323846;

struct Block {
  std::vector<Vec2> x;
  std::vector<double> v;
  std::vector<char> fixed;
};

// Cell-centred particles on [0, lx] x [0, ly] with spacing dx, plus `gx` Dirichlet layers beyond
// x = 0 and x = lx and `gy` beyond y = 0 and y = ly.
Block make_block(double lx, double ly, double dx, int gx, int gy) {
  Block b;
  const int nx = static_cast<int>(std::lround(lx / dx)), ny = static_cast<int>(std::lround(ly / dx));
  for (int j = -gy; j < ny + gy; ++j)
    for (int i = -gx; i < nx + gx; ++i) {
      b.x.emplace_back((i + 0.5) * dx, (j + 0.5) * dx);
      b.v.push_back(dx * dx);
      b.fixed.push_back(i < 0 || i >= nx || j < 0 || j >= ny);
    }
  return b;
}

double max_error(const HeatConduction& s, const std::function<double(const Vec2&, double)>& exact,
                 double scale) {
  double e = 0.0;
  for (std::size_t i = 0; i < s.positions().size(); ++i)
    if (!s.dirichlet()[i]) e = std::max(e, std::abs(s.temperature()[i] - exact(s.positions()[i], s.time())));
  return e / scale;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

BOOST_AUTO_TEST_SUITE(heat_conduction)

// 2D decaying mode sin(pi x) sin(pi y) exp(-2 pi^2 alpha t) on the unit square; three Dirichlet
// layers (the support is 3 dx) hold the exact (odd-extended) solution.
BOOST_AUTO_TEST_CASE(decaying_mode_2d_second_order) {
  const double alpha = 1.0, t_end = 0.02;
  const auto exact = [&](const Vec2& p, double t) {
    return std::sin(kPi * p.x()) * std::sin(kPi * p.y()) * std::exp(-2.0 * kPi * kPi * alpha * t);
  };
  const double scale = std::exp(-2.0 * kPi * kPi * alpha * t_end);
  std::vector<double> e_fmfs, e_brook;
  const std::vector<int> ns{10, 20, 40};
  const auto t0 = std::chrono::steady_clock::now();
  for (int n : ns) {
    for (auto scheme : {HeatScheme::fmfs, HeatScheme::brookshaw}) {
      const double dx = 1.0 / n;
      auto b = make_block(1.0, 1.0, dx, 3, 3);
      HeatOptions opt;
      opt.scheme = scheme;
      HeatConduction s(b.x, b.v, 1.5 * dx, HeatMaterial{1.0, 1.0, 1.0}, HeatBoundary{}, opt);
      s.set_dirichlet(b.fixed, exact);
      s.set_temperature(exact);
      s.setup();
      s.advance_to(t_end);
      (scheme == HeatScheme::fmfs ? e_fmfs : e_brook).push_back(max_error(s, exact, scale));
      if (scheme == HeatScheme::fmfs) {
        std::size_t used = 0, free_count = 0;
        for (std::size_t i = 0; i < b.x.size(); ++i) {
          used += s.fmfs_used()[i] && !b.fixed[i];
          free_count += !b.fixed[i];
        }
        BOOST_TEST(used == free_count);  // every free particle has full support: FMFS everywhere
      }
    }
  }
  for (std::size_t k = 0; k < ns.size(); ++k)
    std::cout << "2D mode n=" << ns[k] << ": FMFS rel max err " << e_fmfs[k] << ", Brookshaw " << e_brook[k]
              << (k ? "  FMFS order " + std::to_string(std::log2(e_fmfs[k - 1] / e_fmfs[k])) : std::string())
              << "\n";
  std::cout << "  (" << seconds_since(t0) << " s)\n";
  BOOST_TEST(std::log2(e_fmfs[1] / e_fmfs[2]) > 1.8);
  BOOST_TEST(std::log2(e_fmfs[0] / e_fmfs[1]) > 1.8);
  BOOST_TEST(e_fmfs.back() < 2e-3);
  // Brookshaw on a lattice with h/dx fixed carries a resolution-independent 0.67 % rate bias.
  BOOST_TEST(e_brook.back() > 2.0 * e_fmfs.back());
}

// 1D mode sin(pi x) exp(-pi^2 alpha t) in a strip whose top and bottom are adiabatic free
// surfaces: the paper's mixed scheme (FMFS inside, Brookshaw on the detected surface rows).
BOOST_AUTO_TEST_CASE(decaying_mode_strip_with_free_surfaces) {
  const double alpha = 1.0, t_end = 0.04;
  const auto exact = [&](const Vec2& p, double t) {
    return std::sin(kPi * p.x()) * std::exp(-kPi * kPi * alpha * t);
  };
  const double scale = std::exp(-kPi * kPi * alpha * t_end);
  const std::vector<int> ns{10, 20, 40};
  const char* names[3] = {"paper mixed (FMFS inside, Brookshaw on surface)", "Brookshaw band 2h", "Brookshaw"};
  std::vector<double> err[3];
  for (int n : ns) {
    for (int variant = 0; variant < 3; ++variant) {
      const double dx = 1.0 / n;
      auto b = make_block(1.0, 0.3, dx, 3, 0);
      HeatOptions opt;
      opt.scheme = variant == 2 ? HeatScheme::brookshaw : HeatScheme::fmfs;
      opt.brookshaw_band = variant == 1;
      HeatConduction s(b.x, b.v, 1.5 * dx, HeatMaterial{1.0, 1.0, 1.0}, HeatBoundary{}, opt);
      s.set_dirichlet(b.fixed, exact);
      s.set_temperature(exact);
      s.setup();
      // exactly the top and bottom rows of the free particles are detected as surface
      std::size_t wrong = 0;
      for (std::size_t i = 0; i < b.x.size(); ++i) {
        if (b.fixed[i]) continue;
        const bool edge_row = b.x[i].y() < dx || b.x[i].y() > 0.3 - dx;
        wrong += edge_row != static_cast<bool>(s.surface().surface[i]);
      }
      BOOST_TEST(wrong == 0u);
      s.advance_to(t_end);
      err[variant].push_back(max_error(s, exact, scale));
    }
  }
  for (int variant = 0; variant < 3; ++variant) {
    std::cout << "strip, " << names[variant] << ": rel max err";
    for (double e : err[variant]) std::cout << " " << e;
    std::cout << ", orders " << std::log2(err[variant][0] / err[variant][1]) << " "
              << std::log2(err[variant][1] / err[variant][2]) << "\n";
  }
  // Brookshaw's truncated support at an adiabatic free surface makes every variant first order.
  for (int variant = 0; variant < 3; ++variant) {
    BOOST_TEST(std::log2(err[variant][1] / err[variant][2]) > 0.8);
    BOOST_TEST(err[variant].back() < 0.03);
  }
}

// Uniformly hot block losing heat by convection and radiation on all sides.
BOOST_AUTO_TEST_CASE(convection_radiation_energy_balance) {
  const double dx = 1e-4, T0 = 1000.0;
  const HeatMaterial mat{50.0, 4430.0, 560.0};
  const HeatBoundary bc{50.0, 0.3, 300.0};
  for (int variant = 0; variant < 3; ++variant) {
    const auto scheme = variant == 0 ? HeatScheme::brookshaw : HeatScheme::fmfs;
    auto b = make_block(2e-3, 2e-3, dx, 0, 0);
    HeatOptions opt;
    opt.scheme = scheme;
    opt.brookshaw_band = variant == 2;
    HeatConduction s(b.x, b.v, 1.5 * dx, mat, bc, opt);
    s.set_temperature(std::vector<double>(b.x.size(), T0));
    s.setup();
    BOOST_TEST(s.surface().count() == 4u * 20u - 4u);
    double perimeter = 0.0, area = 0.0;
    for (std::size_t i = 0; i < b.x.size(); ++i) {
      area += b.v[i];
      if (s.heat_loss_particles()[i]) perimeter += std::sqrt(b.v[i]);  // the surface length choice
    }
    const double e0 = s.thermal_energy();
    const double t_end = 0.3;
    s.advance_to(t_end);
    const double lost = e0 - s.thermal_energy();
    // lumped (Biot ~ 1e-3) reference: rho c A dT/dt = -P q(T), RK4
    double T = T0;
    const int m = 2000;
    const double h = t_end / m, rc = mat.density * mat.specific_heat;
    auto f = [&](double tt_) { return -perimeter * s.surface_flux(tt_) / (rc * area); };
    for (int k = 0; k < m; ++k) {
      const double k1 = f(T), k2 = f(T + 0.5 * h * k1), k3 = f(T + 0.5 * h * k2), k4 = f(T + h * k3);
      T += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    const double lumped = rc * area * (T0 - T);
    const char* names[3] = {"Brookshaw", "paper mixed", "Brookshaw band"};
    std::cout << names[variant] << " energy balance: lost " << lost
              << " J/m, integral of flux " << s.boundary_heat_loss() << " J/m, rel. imbalance "
              << (lost - s.boundary_heat_loss()) / lost << ", lumped " << lumped << " (rel diff "
              << (lost - lumped) / lumped << "), steps " << s.steps() << "\n";
    const double imbalance = (lost - s.boundary_heat_loss()) / lost;
    if (variant == 0) {
      BOOST_TEST(std::abs(imbalance) < 1e-10);  // conservative pairwise form
      BOOST_TEST(lost == lumped, tt::tolerance(2e-3));
    } else if (variant == 1) {
      // KNOWN DEFECT of the paper's mixed scheme: the FMFS rows next to the surface read the
      // Brookshaw surface row's kink and drain ~15 % more heat than leaves through the boundary;
      // the excess does not shrink with resolution (13 %, 16 %, 17 % at dx = L/10, L/20, L/40).
      // Guarded here so that a change is noticed; see solvers/sph/README.md.
      BOOST_TEST(imbalance > 0.0);
      BOOST_TEST(imbalance < 0.25);
    } else {
      BOOST_TEST(std::abs(imbalance) < 1e-2);
      BOOST_TEST(lost == lumped, tt::tolerance(1e-2));
    }
  }
}

// FMFS only where lambda_i > 0.75 (Afrasiabi et al. 2021, Sec. 4.2). A particle next to a small
// internal void has lambda below 0.75 although Marrone's scan test keeps it off the free surface;
// its FMFS correction is ill-conditioned (in the cutting runs |B-hat| reached 60 times the lattice
// value at lambda 0.44 and an explicit conduction step became unstable), so it must use Brookshaw.
BOOST_AUTO_TEST_CASE(fmfs_only_for_full_neighbourhoods) {
  const double dx = 1.0;
  CubicSpline2D kern(1.5 * dx);
  std::vector<Vec2> x;
  std::vector<double> v;
  for (int j = 0; j < 21; ++j)
    for (int i = 0; i < 21; ++i) {
      // a plus-shaped void of five particles in the middle (a crack-like gap as in a sheared chip)
      if ((j == 10 && i >= 9 && i <= 11) || (i == 10 && j >= 9 && j <= 11)) continue;
      x.emplace_back(i * dx, j * dx);
      v.push_back(dx * dx);
    }
  const auto nl = build_neighbours(x, kern.support());
  const ParticleView view{x, v, nl, kern};
  const SurfaceOptions so;
  const auto surf = detect_free_surface(view, so);
  std::vector<char> use, loss;
  heat_masks(nl, surf, std::vector<char>(x.size(), 0), false, so.lambda_interior, use, loss);
  FmfsLaplacian fm;
  fm.update(view);
  std::size_t low_interior = 0, bad = 0;
  double bhat_low = 0.0, bhat_full = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const bool interior = !surf.surface[i];
    const bool full = surf.lambda[i] > so.lambda_interior;
    if (use[i] != (interior && full)) ++bad;
    if (interior && !full) {
      ++low_interior;
      bhat_low = std::max(bhat_low, fm.laplacian_correction(i).norm());
    }
    if (use[i]) bhat_full = std::max(bhat_full, fm.laplacian_correction(i).norm());
  }
  std::cout << "void: " << low_interior << " interior particles with lambda <= 0.75, largest |B-hat| " << bhat_low
            << "; FMFS particles: largest |B-hat| " << bhat_full << "\n";
  BOOST_TEST(bad == 0u);
  BOOST_TEST(low_interior > 0u);  // the case exercises the rule
  BOOST_TEST(bhat_full < 2.0);    // sqrt(2) on the lattice
  BOOST_TEST(bhat_low > 2.0 * bhat_full);  // 4.9: the ill-conditioned corrections are the excluded ones
}

BOOST_AUTO_TEST_SUITE_END()

#include "cutbench/sph/runners.hpp"

BOOST_AUTO_TEST_CASE(registered_heat_runner) {
  cutbench::SolverRegistry reg;
  register_solvers(reg);
  register_solvers(reg);
  BOOST_TEST(reg.all().size() == 4u);  // sph_laplacian, sph_heat, sph_cutting, sph_cutting_inputs
  const auto* spec = reg.find("sph_heat");
  BOOST_REQUIRE(spec);
  cutbench::Values v;
  for (const auto& p : spec->params) v[p.name] = *p.default_value;
  const auto mode = spec->run(v, nullptr);
  BOOST_TEST(mode.scalars.at("max_rel_error") < 2e-3);
  BOOST_TEST(mode.tables.at(0).rows() == 20u);
  v["problem"] = 1.0;
  v["scheme"] = 1.0;
  v["n"] = 10.0;
  v["t_end"] = 0.05;
  const auto cool = spec->run(v, nullptr);
  BOOST_TEST(std::abs(cool.scalars.at("energy_imbalance")) < 1e-10);
  BOOST_TEST(cool.scalars.at("energy_lost") > 0.0);
}

BOOST_AUTO_TEST_SUITE(two_body_conduction)

// Bodies A (k = 1) on [0, 1] and B (k = 3) on [1, 2], strips of height 0.3 with adiabatic free top
// and bottom, Dirichlet layers T = 0 left of A and T = 1 right of B, coupled only by the cross-body
// Brookshaw terms (harmonic-mean k). Steady state: T = 0.75 x in A, 0.75 + 0.25 (x - 1) in B.
// Marches to t = 6 with spacing dx, variant 0 the paper's mixed operator, 1 the Brookshaw band;
// returns max |T - T_exact| and checks that the cross term alone conserves energy exactly.
static double two_material_bar_error(int variant, double dx) {
  const CubicSpline2D kern(1.5 * dx);
  auto a = make_block(1.0, 0.3, dx, 3, 0), b = make_block(1.0, 0.3, dx, 3, 0);
  // keep only the outer Dirichlet layers: A's at x < 0, B's at x > 2
  auto trim = [](Block& blk, bool keep_left) {
    Block out;
    for (std::size_t i = 0; i < blk.x.size(); ++i) {
      const bool left = blk.x[i].x() < 0.0, right = blk.x[i].x() > 1.0;
      if ((keep_left && right) || (!keep_left && left)) continue;
      out.x.push_back(blk.x[i]);
      out.v.push_back(blk.v[i]);
      out.fixed.push_back(blk.fixed[i]);
    }
    blk = out;
  };
  trim(a, true);
  trim(b, false);
  for (auto& p : b.x) p.x() += 1.0;
  const HeatMaterial ma{1.0, 1.0, 1.0}, mb{3.0, 1.0, 1.0};
  const HeatBoundary none{0.0, 0.0, 0.0};
  const auto nla = build_neighbours(a.x, kern.support()), nlb = build_neighbours(b.x, kern.support());
  const ParticleView va{a.x, a.v, nla, kern}, vb{b.x, b.v, nlb, kern};
  const auto sa = detect_free_surface(va), sb = detect_free_surface(vb);
  std::vector<char> ua, la, ub, lb;
  heat_masks(nla, sa, a.fixed, variant == 1, SurfaceOptions{}.lambda_interior, ua, la);
  heat_masks(nlb, sb, b.fixed, variant == 1, SurfaceOptions{}.lambda_interior, ub, lb);
  FmfsLaplacian fa, fb;
  fa.update(va);
  fb.update(vb);
  const auto cross = build_cross_neighbours(a.x, b.x, kern.support());
  std::vector<double> ta(a.x.size(), 0.0), tb(b.x.size(), 0.0);
  for (std::size_t i = 0; i < b.x.size(); ++i) tb[i] = b.fixed[i] ? 1.0 : 0.5;
  const double dt = 0.1 * kern.h() * kern.h() / 3.0;
  std::vector<double> ra, rb;
  for (int step = 0; step < static_cast<int>(6.0 / dt); ++step) {
    heat_rates(va, ta, &fa, ua, a.fixed, la, ma, none, ra);
    heat_rates(vb, tb, &fb, ub, b.fixed, lb, mb, none, rb);
    cross_body_conduction(a.x, a.v, ta, ma, b.x, b.v, tb, mb, cross, kern, ra, rb);
    for (std::size_t i = 0; i < ta.size(); ++i)
      if (!a.fixed[i]) ta[i] += dt * ra[i];
    for (std::size_t i = 0; i < tb.size(); ++i)
      if (!b.fixed[i]) tb[i] += dt * rb[i];
  }
  double err = 0.0;
  for (std::size_t i = 0; i < ta.size(); ++i)
    if (!a.fixed[i]) err = std::max(err, std::abs(ta[i] - 0.75 * a.x[i].x()));
  for (std::size_t i = 0; i < tb.size(); ++i)
    if (!b.fixed[i]) err = std::max(err, std::abs(tb[i] - (0.75 + 0.25 * (b.x[i].x() - 1.0))));
  std::cout << "two-material bar dx " << dx << " (" << (variant ? "Brookshaw band" : "paper mixed")
            << "): max |T - T_exact| = " << err << " (interface jump 1)\n";
  // the cross term alone conserves energy exactly
  std::vector<double> qa(ta.size(), 0.0), qb(tb.size(), 0.0);
  cross_body_conduction(a.x, a.v, ta, ma, b.x, b.v, tb, mb, cross, kern, qa, qb);
  double ea = 0.0, eb = 0.0;
  for (std::size_t i = 0; i < qa.size(); ++i) ea += qa[i] * a.v[i];
  for (std::size_t i = 0; i < qb.size(); ++i) eb += qb[i] * b.v[i] * 1.0;
  BOOST_TEST(std::abs(ea + eb) < 1e-12 * std::abs(ea));
  BOOST_TEST(ea > 0.0);  // heat flows from B (hot) into A
  return err;
}

BOOST_AUTO_TEST_CASE(steady_two_material_bar) {
  for (int variant = 0; variant < 2; ++variant) BOOST_TEST(two_material_bar_error(variant, 0.1) < 0.05);
}

// first order in dx (interface rows use Brookshaw with a truncated own-body support)
BOOST_AUTO_TEST_CASE(steady_two_material_bar_first_order,
                     CUTBENCH_RELEASE_ONLY("paths covered by steady_two_material_bar (dx = 0.1)")) {
  for (int variant = 0; variant < 2; ++variant) {
    const double coarse = two_material_bar_error(variant, 0.1), fine = two_material_bar_error(variant, 0.05);
    BOOST_TEST(fine < 0.05);
    BOOST_TEST(fine < 0.6 * coarse);
  }
}

BOOST_AUTO_TEST_SUITE_END()
