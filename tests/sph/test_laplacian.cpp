// Fig. 3 of Afrasiabi et al. (2021): Laplacian of x^2 + y^2 on 21 x 21 particles in [-1,1]^2.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <iostream>

#include "cutbench/sph/runners.hpp"

using namespace cutbench::sph;
namespace tt = boost::test_tools;

BOOST_AUTO_TEST_SUITE(fig03_laplacian)

BOOST_AUTO_TEST_CASE(brookshaw_and_fmfs_on_regular_lattice) {
  const auto r = laplacian_reconstruction(21, 1.5, 0.0);
  std::cout << "Fig3 regular: Brookshaw interior mean " << r.brookshaw_interior_mean << " corner "
            << r.brookshaw_corner << " FMFS max |err| " << r.fmfs_max_abs_error << "\n";
  BOOST_TEST(std::abs(r.brookshaw_interior_mean - 4.027) < 0.01);
  BOOST_TEST(std::abs(r.brookshaw_corner - (-22.12)) < 0.01);
  BOOST_TEST(r.fmfs_irregular == 0.0);
  BOOST_TEST(r.fmfs_max_abs_error < 1e-8);
}

BOOST_AUTO_TEST_CASE(fmfs_exact_on_jittered_lattice) {
  for (double amp : {0.1, 0.25}) {
    const auto r = laplacian_reconstruction(21, 1.5, amp, 42);
    std::cout << "Fig3 jitter " << amp << ": FMFS max |err| " << r.fmfs_max_abs_error
              << ", Brookshaw max |err| " << r.brookshaw_max_abs_error << "\n";
    BOOST_TEST(r.fmfs_irregular == 0.0);
    BOOST_TEST(r.fmfs_max_abs_error < 1e-8);
  }
}

BOOST_AUTO_TEST_SUITE_END()

#include "cutbench/sph/lattice.hpp"
#include "cutbench/sph/operators.hpp"
#include "cutbench/sph/surface.hpp"

BOOST_AUTO_TEST_SUITE(operators)

BOOST_AUTO_TEST_CASE(renormalisation_matrix_is_identity_inside) {
  const std::size_t n = 21;
  const double dx = 0.1;
  const auto x = rectangle_lattice(n, n, 0.0, 2.0, 0.0, 2.0);
  const std::vector<double> v(x.size(), dx * dx);
  const CubicSpline2D k(1.5 * dx);
  const auto nl = build_neighbours(x, k.support());
  const ParticleView p{x, v, nl, k};
  const auto l = renormalisation_matrices(p);
  const std::size_t centre = 10 * n + 10;
  BOOST_TEST(l[centre](0, 0) == 1.0, tt::tolerance(1e-2));  // lattice sum 1.0067 (same ratio as 4.027/4)
  BOOST_TEST(l[centre](1, 1) == 1.0, tt::tolerance(1e-2));  // lattice sum 1.0067 (same ratio as 4.027/4)
  BOOST_TEST(std::abs(l[centre](0, 1)) < 1e-12);
  // corner: a quarter of the support, lambda well below the 0.75 threshold
  BOOST_TEST(smallest_eigenvalue(l[0]) < 0.5);
  BOOST_TEST(smallest_eigenvalue(l[centre]) > 0.99);
  Mat2 m;
  m << 2.0, 1.0, 1.0, 2.0;
  BOOST_TEST(smallest_eigenvalue(m) == 1.0, tt::tolerance(1e-14));
}

// The pair cache (used by the cutting solver's conduction update) must give the values of the
// uncached operators bit for bit: the same pairs, in the same order, with the same numbers.
BOOST_AUTO_TEST_CASE(pair_cache_gives_identical_values) {
  const std::size_t n = 70;  // 4,900 particles: above the OpenMP threshold
  const double dx = 0.01;
  auto x = rectangle_lattice(n, n, 0.0, (n - 1) * dx, 0.0, (n - 1) * dx);
  jitter(x, 0.2 * dx, 7);
  std::vector<double> v(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) v[i] = dx * dx * (1.0 + 0.01 * static_cast<double>(i % 7));
  const CubicSpline2D k(1.5 * dx);
  const auto nl = build_neighbours(x, 1.3 * k.support());  // a skin: about 40 % of the pairs outside
  std::vector<double> f(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) f[i] = std::sin(30.0 * x[i].x()) * std::exp(x[i].y());
  const ParticleView plain{x, v, nl, k};
  PairCache cache;
  fill_pair_cache(plain, cache);
  const ParticleView cached{x, v, nl, k, &cache};
  std::size_t inside = 0;
  for (std::size_t i = 0; i < x.size(); ++i) inside += cache.count[i];
  BOOST_TEST(inside < nl.index.size());
  BOOST_TEST(inside > nl.index.size() / 2);

  const auto l0 = renormalisation_matrices(plain), l1 = renormalisation_matrices(cached);
  const auto s0 = detect_free_surface(plain, SurfaceOptions{}), s1 = detect_free_surface(cached, SurfaceOptions{});
  const auto b0 = laplacian_brookshaw(plain, f), b1 = laplacian_brookshaw(cached, f);
  FmfsLaplacian m0, m1;
  m0.update(plain);
  m1.update(cached);
  const auto f0 = m0.laplacian(plain, f), f1 = m1.laplacian(cached, f);
  const auto g0 = m0.gradient(plain, f), g1 = m1.gradient(cached, f);
  std::size_t differ = 0, surface = 0, regular = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    differ += l0[i] != l1[i] || s0.lambda[i] != s1.lambda[i] || s0.normal[i] != s1.normal[i] ||
              s0.surface[i] != s1.surface[i] || b0[i] != b1[i] || f0[i] != f1[i] || g0[i] != g1[i] ||
              m0.regular(i) != m1.regular(i) || m0.laplacian_correction(i) != m1.laplacian_correction(i);
    surface += s0.surface[i];
    regular += m0.regular(i) ? 1 : 0;
  }
  BOOST_TEST(differ == 0u);
  BOOST_TEST(surface >= 4 * (n - 1));  // the outer layer at least
  BOOST_TEST(regular > x.size() / 2);
}

// FMFS must be exact for any quadratic (cross term included), with unequal volumes and a jittered
// lattice, at every particle including corners; the FMFS gradient exact for linear fields.
BOOST_AUTO_TEST_CASE(fmfs_exact_for_general_quadratics) {
  const std::size_t n = 17;
  auto x = rectangle_lattice(n, n + 4, -0.3, 1.3, 0.2, 2.2);
  const double dx = 1.6 / static_cast<double>(n - 1);
  jitter(x, 0.2 * dx, 3);
  std::vector<double> v(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) v[i] = dx * dx * (0.8 + 0.4 * static_cast<double>(i % 5) / 4.0);
  const CubicSpline2D k(1.5 * dx);
  const auto nl = build_neighbours(x, k.support());
  const ParticleView p{x, v, nl, k};
  FmfsLaplacian fm;
  fm.update(p);
  std::vector<double> quad(x.size()), lin(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double a = x[i].x(), b = x[i].y();
    quad[i] = 3.0 * a * a - 1.7 * a * b + 0.4 * b * b + 2.0 * a - b + 5.0;  // lap = 6.8
    lin[i] = 2.5 * a - 0.75 * b + 1.0;
  }
  const auto lap = fm.laplacian(p, quad);
  const auto g = fm.gradient(p, lin);
  double err_lap = 0.0, err_g = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    BOOST_REQUIRE(fm.regular(i));
    err_lap = std::max(err_lap, std::abs(lap[i] - 6.8));
    err_g = std::max(err_g, (g[i] - Vec2(2.5, -0.75)).norm());
  }
  BOOST_TEST(err_lap < 1e-8);
  BOOST_TEST(err_g < 1e-10);
}

BOOST_AUTO_TEST_CASE(registered_runner_reproduces_fig03) {
  cutbench::SolverRegistry reg;
  register_solvers(reg);
  register_solvers(reg);
  std::size_t count = 0;
  for (const auto& s : reg.all()) count += s.name == "sph_laplacian";
  BOOST_TEST(count == 1u);
  const auto* spec = reg.find("sph_laplacian");
  BOOST_REQUIRE(spec);
  cutbench::Values v;
  for (const auto& prm : spec->params) v[prm.name] = *prm.default_value;
  const auto out = spec->run(v, nullptr);
  BOOST_REQUIRE(out.tables.size() == 1u);
  BOOST_TEST(out.tables[0].name == "laplacian");
  BOOST_TEST(out.tables[0].rows() == 441u);
  BOOST_TEST(out.scalars.at("brookshaw_interior_mean") == 4.027, tt::tolerance(0.01 / 4.027));
  BOOST_TEST(out.scalars.at("brookshaw_corner") == -22.12, tt::tolerance(0.01 / 22.12));
  BOOST_TEST(out.scalars.at("fmfs_max_abs_error") < 1e-8);
}

BOOST_AUTO_TEST_SUITE_END()
