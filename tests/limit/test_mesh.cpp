#include <boost/test/unit_test.hpp>

#include <cmath>

#include "cutbench/limit/mesh.hpp"
#include "cutbench/limit/socp.hpp"

using namespace cutbench::limit;

BOOST_AUTO_TEST_SUITE(limit_mesh)

BOOST_AUTO_TEST_CASE(structured_quad_areas_and_boundary) {
  for (auto pat : {Pattern::alternating, Pattern::union_jack, Pattern::crossed}) {
    const Mesh m = structured_quad({0, 0}, {2, 0}, {2.5, 1}, {0, 1}, graded_grid(5, 1.2, 1.0), uniform_grid(3), pat);
    double area = 0.0;
    for (int e = 0; e < m.num_elements(); ++e) {
      BOOST_TEST(m.area(e) > 0.0);
      area += m.area(e);
    }
    BOOST_TEST(std::abs(area - 2.25) < 1e-12);  // trapezoid
    double perimeter = 0.0;
    for (const auto& e : boundary_edges(m)) perimeter += (m.nodes[static_cast<std::size_t>(e.b)] - m.nodes[static_cast<std::size_t>(e.a)]).norm();
    BOOST_TEST(std::abs(perimeter - (2.0 + std::sqrt(1.25) + 2.5 + 1.0)) < 1e-12);
    // mid-side nodes at the edge midpoints
    for (const auto& el : m.elements) {
      for (int k = 0; k < 3; ++k) {
        const auto mid = 0.5 * (m.nodes[static_cast<std::size_t>(el[k])] + m.nodes[static_cast<std::size_t>(el[(k + 1) % 3])]);
        BOOST_TEST((m.nodes[static_cast<std::size_t>(el[3 + k])] - mid).norm() < 1e-14);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(merge_identifies_shared_nodes) {
  const Mesh a = structured_quad({0, 0}, {1, 0}, {1, 1}, {0, 1}, uniform_grid(2), uniform_grid(2));
  const Mesh b = structured_quad({1, 0}, {2, 0}, {2, 1}, {1, 1}, uniform_grid(2), uniform_grid(2));
  const Mesh m = merge(a, b, 1e-9);
  BOOST_TEST(m.num_nodes() == a.num_nodes() + b.num_nodes() - 5);  // 3 vertices + 2 mid-side nodes
  BOOST_TEST(boundary_edges(m).size() == 12u);  // 4 + 4 along x, 2 + 2 along y
}

BOOST_AUTO_TEST_CASE(graded_grid_ends_and_ratio) {
  const auto g = graded_grid(4, 2.0, 0.0);
  BOOST_TEST(g.front() == 0.0);
  BOOST_TEST(g.back() == 1.0);
  BOOST_TEST(std::abs((g[2] - g[1]) / (g[1] - g[0]) - 2.0) < 1e-12);
  const auto h = graded_grid(4, 2.0, 1.0);
  BOOST_TEST(std::abs((h[3] - h[2]) / (h[4] - h[3]) - 2.0) < 1e-12);
}

BOOST_AUTO_TEST_CASE(refine_is_conforming) {
  const Mesh m0 = structured_quad({0, 0}, {2, 0}, {2, 1}, {0, 1}, uniform_grid(4), uniform_grid(2));
  const Mesh m1 = refine(m0, {0, 5, 6, 11});
  const Mesh m2 = refine(m1, {0, 1, 2, 3, 4});
  for (const Mesh* m : {&m1, &m2}) {
    double area = 0.0, perimeter = 0.0;
    for (int e = 0; e < m->num_elements(); ++e) {
      BOOST_TEST(m->area(e) > 0.0);
      area += m->area(e);
    }
    for (const auto& e : boundary_edges(*m)) perimeter += (m->nodes[static_cast<std::size_t>(e.b)] - m->nodes[static_cast<std::size_t>(e.a)]).norm();
    BOOST_TEST(std::abs(area - 2.0) < 1e-12);
    BOOST_TEST(std::abs(perimeter - 6.0) < 1e-12);  // no hanging nodes: interior edges are shared
  }
  BOOST_TEST(m1.num_elements() > m0.num_elements());
  BOOST_TEST(m2.num_elements() > m1.num_elements());
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(socp_singular)

BOOST_AUTO_TEST_CASE(free_variable_in_no_constraint_row_and_dependent_rows) {
  // min −x0 s.t. ‖(x0, x1)‖ ≤ 1 (cone), x1 + x2 = 0, 2x1 + 2x2 = 0 (dependent), x3 free and unused:
  // the KKT matrix without regularisation is singular twice (unused free variable, rank-deficient A).
  SpMat A(2, 4);
  A.insert(0, 1) = 1.0;
  A.insert(0, 2) = 1.0;
  A.insert(1, 1) = 2.0;
  A.insert(1, 2) = 2.0;
  SpMat G(3, 4);
  G.insert(1, 0) = -1.0;
  G.insert(2, 1) = -1.0;
  SocpProblem p;
  p.c = Eigen::Vector4d(-1.0, 0.0, 0.0, 0.0);
  p.A = A;
  p.b = Eigen::Vector2d::Zero();
  p.G = G;
  p.h = Eigen::Vector3d(1.0, 0.0, 0.0);
  p.cones.soc = {3};
  const auto r = solve_socp(p);
  BOOST_TEST((r.status == SocpStatus::optimal || r.status == SocpStatus::optimal_inaccurate));
  BOOST_TEST(std::abs(r.pcost + 1.0) < 1e-7);
}

BOOST_AUTO_TEST_SUITE_END()
