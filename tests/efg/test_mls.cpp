// MLS shape functions (Kahwash 2018 Eqs 17-21): partition of unity, linear reproduction of the
// functions and their derivatives, derivatives against finite differences, near-interpolation of
// the Most-Bucher regularised weight, cell-list neighbour search.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "cutbench/common/errors.hpp"
#include "cutbench/efg/discretisation.hpp"

using namespace cutbench::efg;

namespace {

struct Case {
  const char* name;
  WeightKind kind;
  double jitter;
};

const Case kCases[] = {{"regularised, regular", WeightKind::regularized, 0.0},
                       {"regularised, jittered", WeightKind::regularized, 0.3},
                       {"spline, regular", WeightKind::cubic_spline, 0.0},
                       {"spline, jittered", WeightKind::cubic_spline, 0.3}};

// Evaluation points: the Gauss points plus random points in the domain.
std::vector<Vec2> eval_points(const Discretisation& d, double Lx, double Ly) {
  std::vector<Vec2> pts;
  for (const auto& g : d.gauss) pts.push_back(g.x);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 200; ++k) pts.emplace_back(Lx * u(gen), Ly * u(gen));
  return pts;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mls)

BOOST_AUTO_TEST_CASE(partition_of_unity_and_linear_reproduction) {
  const double Lx = 2.0, Ly = 1.0;
  for (const auto& c : kCases) {
    const Discretisation d = rectangle(Lx, Ly, 21, 11, 2.5, c.jitter, 3);
    WeightParams wp;
    wp.kind = c.kind;
    const auto pts = eval_points(d, Lx, Ly);
    const auto sf = shape_functions(pts, d.nodes, d.support, wp);
    double e0 = 0, e1 = 0, e2 = 0, eg = 0;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const ShapeData& s = sf[k];
      double sum = 0, sx = 0, sy = 0, dx = 0, dy = 0, dxx = 0, dxy = 0, dyx = 0, dyy = 0;
      for (std::size_t a = 0; a < s.nodes.size(); ++a) {
        const Vec2& xi = d.nodes[s.nodes[a]];
        sum += s.phi[a];
        sx += s.phi[a] * xi.x();
        sy += s.phi[a] * xi.y();
        dx += s.dphidx[a];
        dy += s.dphidy[a];
        dxx += s.dphidx[a] * xi.x();
        dxy += s.dphidx[a] * xi.y();
        dyx += s.dphidy[a] * xi.x();
        dyy += s.dphidy[a] * xi.y();
      }
      e0 = std::max(e0, std::abs(sum - 1.0));
      e1 = std::max({e1, std::abs(sx - pts[k].x()), std::abs(sy - pts[k].y())});
      e2 = std::max({e2, std::abs(dx), std::abs(dy)});
      eg = std::max({eg, std::abs(dxx - 1.0), std::abs(dxy), std::abs(dyx), std::abs(dyy - 1.0)});
    }
    BOOST_TEST_MESSAGE(c.name << ": |sum phi - 1| " << e0 << ", linear " << e1 << ", sum dphi " << e2
                              << ", grad of x " << eg);
    // Exact in exact arithmetic; what remains is round-off, amplified for the derivatives by the
    // conditioning of the regularised weight's moment matrix: measured sum dphi 3e-11 with GCC 12
    // -O3 and 1.7e-10 with Clang 14 (the ThreadSanitizer build), hence 1e-9 for the derivatives,
    // six orders below any discretisation error of the EFG solutions.
    BOOST_TEST(e0 < 1e-10, c.name);
    BOOST_TEST(e1 < 1e-10, c.name);
    BOOST_TEST(e2 < 1e-9, c.name);
    BOOST_TEST(eg < 1e-9, c.name);
  }
}

BOOST_AUTO_TEST_CASE(derivatives_match_finite_differences) {
  for (const auto& c : kCases) {
    const Discretisation d = rectangle(1.0, 1.0, 11, 11, 2.5, c.jitter, 5);
    WeightParams wp;
    wp.kind = c.kind;
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> u(0.05, 0.95);
    double worst = 0.0;
    for (int k = 0; k < 40; ++k) {
      const Vec2 x(u(gen), u(gen));
      const double eps = 1e-6;
      const auto sf = shape_functions({x, x + Vec2(eps, 0), x - Vec2(eps, 0), x + Vec2(0, eps), x - Vec2(0, eps)},
                                      d.nodes, d.support, wp);
      const auto phi_of = [&](const ShapeData& s, int node) {
        for (std::size_t a = 0; a < s.nodes.size(); ++a) {
          if (s.nodes[a] == node) return s.phi[a];
        }
        return 0.0;
      };
      double scale = 0.0;
      for (std::size_t a = 0; a < sf[0].nodes.size(); ++a) {
        scale = std::max({scale, std::abs(sf[0].dphidx[a]), std::abs(sf[0].dphidy[a])});
      }
      for (std::size_t a = 0; a < sf[0].nodes.size(); ++a) {
        const int I = sf[0].nodes[a];
        const double fx = (phi_of(sf[1], I) - phi_of(sf[2], I)) / (2 * eps);
        const double fy = (phi_of(sf[3], I) - phi_of(sf[4], I)) / (2 * eps);
        worst = std::max({worst, std::abs(fx - sf[0].dphidx[a]) / scale, std::abs(fy - sf[0].dphidy[a]) / scale});
      }
    }
    BOOST_TEST_MESSAGE(c.name << ": max relative FD error of dphi " << worst);
    BOOST_TEST(worst < 1e-5, c.name);
  }
}

BOOST_AUTO_TEST_CASE(regularised_weight_is_nearly_interpolating) {
  // Most-Bucher weight (omega = 1e-5): phi_I(x_J) ~ delta_IJ; the cubic spline is not.
  const Discretisation d = rectangle(1.0, 1.0, 11, 11, 2.5, 0.3, 9);
  WeightParams reg, spl;
  spl.kind = WeightKind::cubic_spline;
  const auto sr = shape_functions(d.nodes, d.nodes, d.support, reg, false);
  const auto ss = shape_functions(d.nodes, d.nodes, d.support, spl, false);
  double worst_reg = 0.0, best_spl = 1.0;
  for (std::size_t J = 0; J < d.nodes.size(); ++J) {
    for (std::size_t a = 0; a < sr[J].nodes.size(); ++a) {
      const double delta = sr[J].nodes[a] == static_cast<int>(J) ? 1.0 : 0.0;
      worst_reg = std::max(worst_reg, std::abs(sr[J].phi[a] - delta));
    }
    double dev = 0.0;
    for (std::size_t a = 0; a < ss[J].nodes.size(); ++a) {
      const double delta = ss[J].nodes[a] == static_cast<int>(J) ? 1.0 : 0.0;
      dev = std::max(dev, std::abs(ss[J].phi[a] - delta));
    }
    best_spl = std::min(best_spl, dev);
  }
  BOOST_TEST_MESSAGE("max |phi_I(x_J) - delta_IJ|: regularised " << worst_reg
                                                                  << "; cubic spline: smallest per-node max |phi_I(x_J) - delta_IJ| " << best_spl);
  BOOST_TEST(worst_reg < 1e-6);
  BOOST_TEST(best_spl > 0.05);
  // Weight itself: w(0) = 1, w(1) = 0, monotone.
  double w0, dw, w1, w5, w6;
  weight_function(reg, 0.0, w0, dw);
  weight_function(reg, 1.0, w1, dw);
  weight_function(reg, 0.5, w5, dw);
  weight_function(reg, 0.6, w6, dw);
  BOOST_TEST(std::abs(w0 - 1.0) < 1e-15);
  BOOST_TEST(w1 == 0.0);
  BOOST_TEST(w5 > w6);
}

BOOST_AUTO_TEST_CASE(cell_list_matches_brute_force) {
  const Discretisation d = rectangle(3.0, 1.0, 31, 11, 2.0, 0.4, 2);
  CellList cl;
  cl.build(d.nodes, 0.25);
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> u(-0.2, 3.2);
  std::vector<int> got;
  for (int k = 0; k < 100; ++k) {
    const Vec2 x(u(gen), u(gen) / 3.0);
    const double r = 0.05 + 0.003 * k;
    cl.query(x, r, got);
    std::sort(got.begin(), got.end());
    std::vector<int> want;
    for (std::size_t I = 0; I < d.nodes.size(); ++I) {
      if ((d.nodes[I] - x).norm() <= r) want.push_back(static_cast<int>(I));
    }
    BOOST_TEST((got == want));
  }
  double brute = 1e300;
  for (std::size_t a = 0; a < d.nodes.size(); ++a) {
    for (std::size_t b = a + 1; b < d.nodes.size(); ++b) brute = std::min(brute, (d.nodes[a] - d.nodes[b]).norm());
  }
  BOOST_TEST(std::abs(cl.min_pair_distance() - brute) < 1e-15);
}

// A node thrown far off the model (a blow-up) or a non-finite position is reported as a numerical
// fault instead of sizing a grid of cells to it (which ran out of memory).
BOOST_AUTO_TEST_CASE(cell_list_refuses_blown_up_points) {
  std::vector<Vec2> pts;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) pts.emplace_back(1e-4 * i, 1e-4 * j);
  }
  CellList cl;
  BOOST_CHECK_NO_THROW(cl.build(pts, 1e-4));
  pts.back() = Vec2(900.0, -200.0);
  BOOST_CHECK_THROW(cl.build(pts, 1e-4), cutbench::NumericalError);
  pts.back() = Vec2(std::nan(""), 0.0);
  BOOST_CHECK_THROW(cl.build(pts, 1e-4), cutbench::NumericalError);
}

BOOST_AUTO_TEST_CASE(background_quadrature_integrates_area) {
  const Discretisation d = rectangle(2.0, 0.5, 9, 5, 2.5);
  double area = 0.0;
  for (const auto& g : d.gauss) area += g.weight;
  BOOST_TEST(std::abs(area - 1.0) < 1e-14);
  BOOST_TEST(d.gauss.size() == 8u * 4u * 4u);
}

BOOST_AUTO_TEST_SUITE_END()
