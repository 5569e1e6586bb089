// Verification of the interior-point SOCP solver on problems with known optima.
#define BOOST_TEST_MODULE test_limit
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iostream>
#include <random>

#include "cutbench/limit/socp.hpp"

using namespace cutbench::limit;
using Eigen::VectorXd;

namespace {

SpMat dense_to_sparse(const Eigen::MatrixXd& d) {
  SpMat s = d.sparseView();
  s.makeCompressed();
  return s;
}

SocpProblem make(const Eigen::MatrixXd& A, const VectorXd& b, const Eigen::MatrixXd& G, const VectorXd& h,
                 const VectorXd& c, ConeDims k) {
  SocpProblem p;
  p.c = c;
  p.A = A.rows() ? dense_to_sparse(A) : SpMat(0, c.size());
  p.b = b;
  p.G = dense_to_sparse(G);
  p.h = h;
  p.cones = std::move(k);
  return p;
}

bool in_cone(const ConeDims& k, const VectorXd& u, double tol) { return cone::min_eig(k, u) >= -tol; }

// KKT residuals of a returned solution.
void check_kkt(const SocpProblem& p, const SocpResult& r, double tol) {
  const double pres = std::max((p.A * r.x - p.b).norm(), (p.G * r.x + r.s - p.h).norm());
  const double dres = (p.A.transpose() * r.y + p.G.transpose() * r.z + p.c).norm();
  const double gap = r.s.dot(r.z);
  BOOST_TEST_MESSAGE("  pres " << pres << " dres " << dres << " sᵀz " << gap << " it " << r.iterations);
  BOOST_TEST(pres < tol);
  BOOST_TEST(dres < tol);
  BOOST_TEST(std::abs(gap) < tol * (1.0 + std::abs(r.pcost)));
  BOOST_TEST(in_cone(p.cones, r.s, 1e-10));
  BOOST_TEST(in_cone(p.cones, r.z, 1e-10));
  BOOST_TEST(std::abs(r.pcost - p.c.dot(r.x)) < 1e-12 * (1.0 + std::abs(r.pcost)));
}

SocpSettings settings(KktBackend b = KktBackend::cholmod) {
  SocpSettings s;
  s.backend = b;
  s.log = [](const std::string& l) { BOOST_TEST_MESSAGE(l); };
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(socp)

BOOST_AUTO_TEST_CASE(nt_scaling_identity) {
  ConeDims k;
  k.nonneg = 2;
  k.soc = {3, 4, 1};
  VectorXd s(10), z(10);
  s << 1.0, 2.0, 3.0, 1.0, -2.0, 2.0, 0.5, 0.3, 0.1, 0.7;
  z << 0.5, 4.0, 1.5, -0.5, 0.2, 1.0, -0.1, 0.2, 0.3, 2.0;
  BOOST_REQUIRE(cone::min_eig(k, s) > 0.0);
  BOOST_REQUIRE(cone::min_eig(k, z) > 0.0);
  const auto w = cone::nt_scaling(k, s, z);
  const VectorXd wz = cone::apply_w(k, w, z, false);
  const VectorXd wis = cone::apply_w(k, w, s, true);
  BOOST_TEST((wz - wis).norm() < 1e-12);
  // W W⁻¹ = I
  const VectorXd v = VectorXd::LinSpaced(10, -1.0, 2.0);
  BOOST_TEST((cone::apply_w(k, w, cone::apply_w(k, w, v, true), false) - v).norm() < 1e-12);
}

BOOST_AUTO_TEST_CASE(max_step_to_boundary) {
  ConeDims k;
  k.soc = {3};
  VectorXd u(3), d(3);
  u << 2.0, 0.0, 0.0;
  d << 0.0, 1.0, 0.0;  // boundary at α = 2
  BOOST_TEST(std::abs(cone::max_step(k, u, d, 1e30) - 2.0) < 1e-14);
  d << -1.0, 0.0, 0.0;  // apex at α = 2
  BOOST_TEST(std::abs(cone::max_step(k, u, d, 1e30) - 2.0) < 1e-14);
  d << 1.0, 0.5, 0.0;  // stays inside
  BOOST_TEST(cone::max_step(k, u, d, 1e30) == 1e30);
}

BOOST_AUTO_TEST_CASE(lp_vertex) {
  // min −x1 − x2 s.t. x1 + 2x2 ≤ 4, 3x1 + x2 ≤ 6, x ≥ 0: optimum −14/5 at (8/5, 6/5).
  Eigen::MatrixXd G(4, 2);
  G << 1, 2, 3, 1, -1, 0, 0, -1;
  VectorXd h(4);
  h << 4, 6, 0, 0;
  VectorXd c(2);
  c << -1, -1;
  ConeDims k;
  k.nonneg = 4;
  for (auto be : {KktBackend::cholmod, KktBackend::eigen}) {
    const auto p = make(Eigen::MatrixXd(0, 2), VectorXd(0), G, h, c, k);
    const auto r = solve_socp(p, settings(be));
    BOOST_TEST(r.status == SocpStatus::optimal);
    BOOST_TEST(std::abs(r.pcost + 14.0 / 5.0) < 1e-7);
    BOOST_TEST(std::abs(r.x[0] - 1.6) < 1e-6);
    BOOST_TEST(std::abs(r.x[1] - 1.2) < 1e-6);
    check_kkt(p, r, 1e-7);
  }
}

BOOST_AUTO_TEST_CASE(lp_degenerate_vertex_and_redundant_equalities) {
  // min −x1 − x2 s.t. x1 ≤ 1, x2 ≤ 1, x1 + x2 ≤ 2, x ≥ 0 (three active constraints at (1,1)),
  // plus the equality x1 − x2 = 0 stated twice (rank-deficient A).
  Eigen::MatrixXd G(5, 2);
  G << 1, 0, 0, 1, 1, 1, -1, 0, 0, -1;
  VectorXd h(5);
  h << 1, 1, 2, 0, 0;
  Eigen::MatrixXd A(2, 2);
  A << 1, -1, 2, -2;
  VectorXd b = VectorXd::Zero(2);
  VectorXd c(2);
  c << -1, -1;
  ConeDims k;
  k.nonneg = 5;
  const auto p = make(A, b, G, h, c, k);
  const auto r = solve_socp(p, settings());
  BOOST_TEST(r.status == SocpStatus::optimal);
  BOOST_TEST(std::abs(r.pcost + 2.0) < 1e-7);
  BOOST_TEST((r.x - VectorXd::Ones(2)).norm() < 1e-6);
  check_kkt(p, r, 1e-7);
}

BOOST_AUTO_TEST_CASE(min_norm_on_hyperplane) {
  // min ‖x‖ s.t. aᵀx = 1, x ∈ R⁴: variables (t, x), min t, (t, x) ∈ Q⁵. Optimum 1/‖a‖, x = a/‖a‖².
  VectorXd a(4);
  a << 1.0, -2.0, 0.5, 3.0;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(1, 5);
  A.block(0, 1, 1, 4) = a.transpose();
  VectorXd b(1);
  b << 1.0;
  VectorXd c = VectorXd::Zero(5);
  c[0] = 1.0;
  ConeDims k;
  k.soc = {5};
  const auto p = standard_form(c, dense_to_sparse(A), b, k);
  const auto r = solve_socp(p, settings());
  BOOST_TEST(r.status == SocpStatus::optimal);
  BOOST_TEST(std::abs(r.pcost - 1.0 / a.norm()) < 1e-8);
  BOOST_TEST((r.x.tail(4) - a / a.squaredNorm()).norm() < 1e-6);
  check_kkt(p, r, 1e-7);
}

BOOST_AUTO_TEST_CASE(free_variables) {
  // min −x s.t. ‖(x, y)‖ ≤ 2, y = 1, x and y free: optimum −√3.
  Eigen::MatrixXd A(1, 2);
  A << 0, 1;
  VectorXd b(1);
  b << 1;
  Eigen::MatrixXd G(3, 2);
  G << 0, 0, -1, 0, 0, -1;
  VectorXd h(3);
  h << 2, 0, 0;
  VectorXd c(2);
  c << -1, 0;
  ConeDims k;
  k.soc = {3};
  const auto p = make(A, b, G, h, c, k);
  const auto r = solve_socp(p, settings());
  BOOST_TEST(r.status == SocpStatus::optimal);
  BOOST_TEST(std::abs(r.pcost + std::sqrt(3.0)) < 1e-8);
  check_kkt(p, r, 1e-7);
}

BOOST_AUTO_TEST_CASE(primal_infeasible) {
  // x ≥ 0 and x ≤ −1.
  Eigen::MatrixXd G(2, 1);
  G << -1, 1;
  VectorXd h(2);
  h << 0, -1;
  VectorXd c(1);
  c << 1;
  ConeDims k;
  k.nonneg = 2;
  const auto p = make(Eigen::MatrixXd(0, 1), VectorXd(0), G, h, c, k);
  const auto r = solve_socp(p, settings());
  BOOST_TEST(r.status == SocpStatus::primal_infeasible);
  // certificate: hᵀz = −1, Gᵀz ≈ 0, z ∈ K
  BOOST_TEST(std::abs(p.h.dot(r.z) + 1.0) < 1e-9);
  BOOST_TEST((p.G.transpose() * r.z).norm() < 1e-7);
}

BOOST_AUTO_TEST_CASE(dual_infeasible) {
  // min −x1 s.t. ‖(x2, x3)‖ ≤ x1, x2 = 1: unbounded below.
  Eigen::MatrixXd A(1, 3);
  A << 0, 1, 0;
  VectorXd b(1);
  b << 1;
  VectorXd c(3);
  c << -1, 0, 0;
  ConeDims k;
  k.soc = {3};
  const auto p = standard_form(c, dense_to_sparse(A), b, k);
  const auto r = solve_socp(p, settings());
  BOOST_TEST(r.status == SocpStatus::dual_infeasible);
  BOOST_TEST(std::abs(p.c.dot(r.x) + 1.0) < 1e-9);
}

BOOST_AUTO_TEST_CASE(random_feasible_socp) {
  // Strictly feasible primal and dual by construction; check the KKT conditions of the answer
  // and that both KKT backends agree.
  std::mt19937 rng(42);
  std::normal_distribution<double> nd;
  const int n = 40, np = 10;
  ConeDims k;
  k.nonneg = 15;
  for (int i = 0; i < 20; ++i) k.soc.push_back(3);
  k.soc.push_back(6);
  const int m = k.size();
  Eigen::MatrixXd A(np, n), G(m, n);
  for (int i = 0; i < np; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = (rng() % 4 == 0) ? nd(rng) : 0.0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) G(i, j) = (rng() % 3 == 0) ? nd(rng) : 0.0;
  auto interior = [&]() {
    VectorXd u(m);
    for (int i = 0; i < m; ++i) u[i] = nd(rng);
    for (int i = 0; i < k.nonneg; ++i) u[i] = std::abs(u[i]) + 0.1;
    int o = k.nonneg;
    for (int d : k.soc) {
      u[o] = u.segment(o + 1, d - 1).norm() + 0.1 + std::abs(nd(rng));
      o += d;
    }
    return u;
  };
  VectorXd x0(n), y0(np);
  for (int i = 0; i < n; ++i) x0[i] = nd(rng);
  for (int i = 0; i < np; ++i) y0[i] = nd(rng);
  const VectorXd s0 = interior(), z0 = interior();
  const VectorXd b = A * x0, h = G * x0 + s0, c = -A.transpose() * y0 - G.transpose() * z0;
  const auto p = make(A, b, G, h, c, k);
  const auto r1 = solve_socp(p, settings(KktBackend::cholmod));
  const auto r2 = solve_socp(p, settings(KktBackend::eigen));
  BOOST_TEST(r1.status == SocpStatus::optimal);
  BOOST_TEST(r2.status == SocpStatus::optimal);
  check_kkt(p, r1, 1e-6);
  check_kkt(p, r2, 1e-6);
  BOOST_TEST(std::abs(r1.pcost - r2.pcost) < 1e-7 * (1.0 + std::abs(r1.pcost)));
  // weak duality against the constructed feasible points
  BOOST_TEST(r1.pcost <= c.dot(x0) + 1e-9);
  BOOST_TEST(r1.dcost >= -b.dot(y0) - h.dot(z0) - 1e-9);
  BOOST_TEST(r1.iterations < 40);
}

BOOST_AUTO_TEST_SUITE_END()
