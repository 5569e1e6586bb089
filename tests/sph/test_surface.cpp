// Marrone free-surface detection: exactly the outer layer of a rectangle and of a disc.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <iostream>

#include "cutbench/sph/lattice.hpp"
#include "cutbench/sph/surface.hpp"

using namespace cutbench::sph;
namespace tt = boost::test_tools;

BOOST_AUTO_TEST_SUITE(surface_detection)

BOOST_AUTO_TEST_CASE(rectangle_outer_layer) {
  const std::size_t nx = 31, ny = 13;
  const double dx = 0.01;
  const auto x = rectangle_lattice(nx, ny, 0.0, dx * (nx - 1), 0.0, dx * (ny - 1));
  const std::vector<double> v(x.size(), dx * dx);
  const CubicSpline2D k(1.5 * dx);
  const auto nl = build_neighbours(x, k.support());
  const ParticleView p{x, v, nl, k};
  const auto s = detect_free_surface(p);
  std::size_t wrong = 0;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const bool outer = i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
      const std::size_t id = j * nx + i;
      if (outer != static_cast<bool>(s.surface[id])) ++wrong;
      if (j == 0 && i >= 3 && i + 3 < nx) {  // bottom edge, full tangential support: normal points down
        BOOST_TEST(s.normal[id].y() == -1.0, tt::tolerance(1e-12));
      }
    }
  BOOST_TEST(wrong == 0u);
  BOOST_TEST(s.count() == 2 * (nx + ny) - 4);
  // On this lattice (h = 1.5 dx) lambda alone already isolates one layer (second row lambda ~ 0.82).
  SurfaceOptions lam_only;
  lam_only.scan_test = false;
  const auto s2 = detect_free_surface(p, lam_only);
  std::cout << "rectangle: scan test " << s.count() << " surface particles, lambda<0.75 alone "
            << s2.count() << ", lambda edge " << s.lambda[nx / 2] << ", second row " << s.lambda[nx + nx / 2]
            << ", third row " << s.lambda[2 * nx + nx / 2] << "\n";
  BOOST_TEST(s2.count() >= s.count());
}

BOOST_AUTO_TEST_CASE(disc_outer_ring) {
  const std::size_t rings = 12;
  const double dx = 0.02;
  std::vector<double> v;
  const auto x = disc_rings(rings, dx, Vec2(0.3, -0.1), v);
  const CubicSpline2D k(1.5 * dx);
  const auto nl = build_neighbours(x, k.support());
  const ParticleView p{x, v, nl, k};
  const auto s = detect_free_surface(p);
  std::size_t wrong = 0, outer_count = 0;
  double worst_normal = 1.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = (x[i] - Vec2(0.3, -0.1)).norm();
    const bool outer = r > (static_cast<double>(rings) - 0.5) * dx;
    outer_count += outer;
    if (outer != static_cast<bool>(s.surface[i])) ++wrong;
    if (outer) worst_normal = std::min(worst_normal, s.normal[i].dot((x[i] - Vec2(0.3, -0.1)) / r));
  }
  std::cout << "disc: " << s.count() << " flagged, outer ring " << outer_count << ", misclassified " << wrong
            << ", min n.e_r on the ring " << worst_normal << "\n";
  BOOST_TEST(wrong == 0u);
  BOOST_TEST(worst_normal > 0.99);
}

BOOST_AUTO_TEST_CASE(lattice_cut_disc_and_isolated_particle) {
  // A disc cut from a square lattice: every flagged particle must have an empty lattice site
  // among its 8 neighbours, and every particle with an empty 4-neighbour site must be flagged.
  const double dx = 0.05, radius = 0.62;
  const int m = 15;
  std::vector<Vec2> x;
  auto inside = [&](int a, int b) { return std::hypot(a * dx, b * dx) <= radius; };
  std::vector<std::pair<int, int>> ij;
  for (int b = -m; b <= m; ++b)
    for (int a = -m; a <= m; ++a)
      if (inside(a, b)) {
        x.emplace_back(a * dx, b * dx);
        ij.emplace_back(a, b);
      }
  x.emplace_back(2.0, 2.0);  // isolated particle: lambda = 0, surface
  const std::vector<double> v(x.size(), dx * dx);
  const CubicSpline2D k(1.5 * dx);
  const auto nl = build_neighbours(x, k.support());
  const ParticleView p{x, v, nl, k};
  const auto s = detect_free_surface(p);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < ij.size(); ++i) {
    const auto [a, b] = ij[i];
    const bool four_open = !inside(a + 1, b) || !inside(a - 1, b) || !inside(a, b + 1) || !inside(a, b - 1);
    const bool eight_open = four_open || !inside(a + 1, b + 1) || !inside(a - 1, b + 1) ||
                            !inside(a + 1, b - 1) || !inside(a - 1, b - 1);
    if (four_open && !s.surface[i]) ++bad;
    if (s.surface[i] && !eight_open) ++bad;
  }
  BOOST_TEST(bad == 0u);
  BOOST_TEST(s.surface.back() == 1);
}

BOOST_AUTO_TEST_SUITE_END()
