// Kernel normalisation and derivative, neighbour search against brute force.
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "cutbench/sph/kernel.hpp"
#include "cutbench/sph/lattice.hpp"
#include "cutbench/sph/neighbours.hpp"

using namespace cutbench::sph;
namespace tt = boost::test_tools;

BOOST_AUTO_TEST_SUITE(kernel_and_neighbours)

BOOST_AUTO_TEST_CASE(cubic_spline_normalised_and_smooth) {
  const double h = 0.37;
  const CubicSpline2D w(h);
  // integral of W over the plane by the radial rule: 2 pi int_0^{2h} W(r) r dr (Simpson)
  const int m = 20000;
  const double dr = w.support() / m;
  double s = 0.0;
  for (int k = 0; k <= m; ++k) {
    const double r = k * dr;
    const double c = (k == 0 || k == m) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    s += c * w.value(r) * r;
  }
  s *= dr / 3.0 * 2.0 * 3.14159265358979323846;
  BOOST_TEST(s == 1.0, tt::tolerance(1e-10));
  BOOST_TEST(w.value(2.0 * h) == 0.0);
  BOOST_TEST(w.value(2.5 * h) == 0.0);
  BOOST_TEST(w.value(0.0) == 10.0 / (7.0 * 3.14159265358979323846 * h * h), tt::tolerance(1e-14));
  // continuity at q = 1 and derivative against central differences
  BOOST_TEST(w.value(h * (1 - 1e-12)) == w.value(h * (1 + 1e-12)), tt::tolerance(1e-9));
  for (double q : {0.1, 0.5, 0.99, 1.01, 1.5, 1.9}) {
    const double r = q * h, e = 1e-6 * h;
    const double fd = (w.value(r + e) - w.value(r - e)) / (2 * e);
    BOOST_TEST(w.dwdr(r) == fd, tt::tolerance(1e-7));
  }
}

BOOST_AUTO_TEST_CASE(cell_list_matches_brute_force) {
  auto x = rectangle_lattice(23, 17, -1.0, 1.2, 0.0, 0.8);
  jitter(x, 0.03, 7);
  for (double radius : {0.1, 0.15, 0.31}) {
    const auto a = build_neighbours(x, radius);
    const auto b = build_neighbours_brute_force(x, radius);
    BOOST_TEST(a.offset == b.offset, tt::per_element());
    BOOST_TEST(a.index == b.index, tt::per_element());
  }
  const auto empty = build_neighbours({}, 1.0);
  BOOST_TEST(empty.size() == 0u);
}

BOOST_AUTO_TEST_CASE(cross_neighbours_match_brute_force) {
  auto a = rectangle_lattice(15, 9, 0.0, 1.0, 0.0, 0.6);
  auto b = rectangle_lattice(11, 11, 0.7, 1.5, 0.3, 1.1);
  jitter(a, 0.02, 1);
  jitter(b, 0.02, 2);
  const double radius = 0.2;
  const auto nl = build_cross_neighbours(a, b, radius);
  BOOST_REQUIRE(nl.size() == a.size());
  std::size_t total = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::vector<std::uint32_t> expect;
    for (std::size_t j = 0; j < b.size(); ++j)
      if ((a[i] - b[j]).squaredNorm() < radius * radius) expect.push_back(static_cast<std::uint32_t>(j));
    const std::vector<std::uint32_t> got(nl.index.begin() + static_cast<std::ptrdiff_t>(nl.begin(i)),
                                         nl.index.begin() + static_cast<std::ptrdiff_t>(nl.end(i)));
    BOOST_TEST(got == expect, tt::per_element());
    total += got.size();
  }
  BOOST_TEST(total > 0u);
  BOOST_TEST(build_cross_neighbours(a, {}, radius).index.empty());
}

BOOST_AUTO_TEST_SUITE_END()
