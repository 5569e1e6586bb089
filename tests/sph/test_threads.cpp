// Results do not depend on the OpenMP thread count: per-particle loops are bitwise identical;
// the pair-force reduction differs only by round-off.
#include <boost/test/unit_test.hpp>
#include <omp.h>

#include <cmath>

#include "cutbench/sph/lattice.hpp"
#include "cutbench/sph/operators.hpp"
#include "cutbench/sph/solid.hpp"

using namespace cutbench::sph;

BOOST_AUTO_TEST_SUITE(thread_independence)

BOOST_AUTO_TEST_CASE(operators_and_solid_with_one_and_two_threads) {
  const int saved = omp_get_max_threads();
  const std::size_t n = 75;  // 5625 particles: above the serial threshold
  const double dx = 1.0 / static_cast<double>(n - 1);
  auto x = rectangle_lattice(n, n, 0.0, 1.0, 0.0, 1.0);
  jitter(x, 0.2 * dx, 11);
  const std::vector<double> v(x.size(), dx * dx);
  std::vector<double> f(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) f[i] = std::sin(3.0 * x[i].x()) * std::cos(2.0 * x[i].y());
  std::vector<double> lap[2], brook[2];
  std::vector<Vec2> pos[2], vel[2];
  for (int threads = 1; threads <= 2; ++threads) {
    omp_set_num_threads(threads);
    const CubicSpline2D k(1.5 * dx);
    const auto nl = build_neighbours(x, k.support());
    const ParticleView p{x, v, nl, k};
    FmfsLaplacian fm;
    fm.update(p);
    lap[threads - 1] = fm.laplacian(p, f);
    brook[threads - 1] = laplacian_brookshaw(p, f);
    SolidMaterial mat;
    mat.plastic = true;
    SolidSph solid(rectangle_lattice(n, n, 0.0, (n - 1) * 1e-5, 0.0, (n - 1) * 1e-5), 1e-5, mat);
    for (std::size_t i = 0; i < x.size(); ++i)
      solid.velocity()[i] = Vec2(10.0 * std::sin(7.0 * x[i].y()), -10.0 * std::cos(5.0 * x[i].x()));
    for (int step = 0; step < 5; ++step) solid.step(solid.stable_time_step());
    pos[threads - 1] = solid.positions();
    vel[threads - 1] = solid.velocity();
  }
  omp_set_num_threads(saved);
  BOOST_TEST(lap[0] == lap[1]);    // bitwise
  BOOST_TEST(brook[0] == brook[1]);
  double dv = 0.0, vmax = 0.0;
  for (std::size_t i = 0; i < vel[0].size(); ++i) {
    dv = std::max(dv, (vel[0][i] - vel[1][i]).norm());
    vmax = std::max(vmax, vel[0][i].norm());
  }
  BOOST_TEST(dv < 1e-10 * vmax);
}

BOOST_AUTO_TEST_SUITE_END()
