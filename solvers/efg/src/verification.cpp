#include "cutbench/efg/verification.hpp"

#include <Eigen/LU>
#include <cmath>

namespace cutbench::efg {

CantileverResult timoshenko_cantilever(int nx, int ny, double support_factor, const WeightParams& w,
                                       double L, double H, double E, double nu, double P) {
  const double I = H * H * H / 12.0;
  const auto exact_u = [&](const Vec2& p) {
    const double x = p.x(), y = p.y();
    return Vec2(-P * y / (6 * E * I) * ((6 * L - 3 * x) * x + (2 + nu) * (y * y - H * H / 4)),
                P / (6 * E * I) * (3 * nu * y * y * (L - x) + (4 + 5 * nu) * H * H * x / 4 + (3 * L - x) * x * x));
  };
  const auto exact_s = [&](const Vec2& p) {
    return Eigen::Vector3d(-P * (L - p.x()) * p.y() / I, 0.0, P / (2 * I) * (H * H / 4 - p.y() * p.y()));
  };
  Discretisation d = rectangle(L, H, nx, ny, support_factor);
  for (auto& p : d.nodes) p.y() -= H / 2;
  for (auto& p : d.cell_vertices) p.y() -= H / 2;
  for (auto& g : d.gauss) g.x.y() -= H / 2;
  const Orthotropic mat = Orthotropic::isotropic(E, nu, 1.0);
  const Eigen::Matrix3d D = mat.Q();
  std::vector<NodalDirichlet> fixed;
  for (int j = 0; j < ny; ++j) {
    const int n = j * nx;
    const Vec2 u = exact_u(d.nodes[n]);
    fixed.push_back({n, 0, u.x()});
    fixed.push_back({n, 1, u.y()});
  }
  const auto line = line_gauss(Vec2(L, -H / 2), Vec2(L, H / 2), ny - 1, 4);
  const auto f = traction_forces(d.nodes, d.support, w, line,
                                 [&](const Vec2& p) { return Vec2(0.0, exact_s(p)(2)); }, 1.0);
  const auto u = solve_linear_static(d, D, 1.0, w, fixed, f);
  CantileverResult r;
  r.nodes = nx * ny;
  r.h = L / (nx - 1);
  r.tip_exact = exact_u(Vec2(L, 0.0)).y();
  r.tip = sample_field({Vec2(L, 0.0)}, d.nodes, d.support, w, u)[0].u.y();
  r.tip_rel_error = std::abs(r.tip / r.tip_exact - 1.0);
  std::vector<Vec2> pts;
  for (const auto& g : d.gauss) pts.push_back(g.x);
  const auto fs = sample_field(pts, d.nodes, d.support, w, u);
  double eu = 0, nu2 = 0, ee = 0, ne = 0;
  const Eigen::Matrix3d C = D.inverse();
  for (std::size_t g = 0; g < pts.size(); ++g) {
    const Vec2 ue = exact_u(pts[g]);
    eu += d.gauss[g].weight * (fs[g].u - ue).squaredNorm();
    nu2 += d.gauss[g].weight * ue.squaredNorm();
    const Eigen::Vector3d se = exact_s(pts[g]);
    const Eigen::Vector3d de = fs[g].strain - C * se;
    ee += d.gauss[g].weight * de.dot(D * de);
    ne += d.gauss[g].weight * se.dot(C * se);
  }
  r.l2_rel_error = std::sqrt(eu / nu2);
  r.energy_rel_error = std::sqrt(ee / ne);
  // The explicit solver's internal forces at the static solution balance the traction forces.
  ExplicitOptions opt;
  opt.kinematics = Kinematics::small_strain;
  opt.weight = w;
  ExplicitEFG s(d, mat, 0.0, opt);
  s.set_displacement(u);
  double res = 0, fmax = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 1; i < nx; ++i) {
      const int n = j * nx + i;
      res = std::max(res, (s.internal_forces()[n] - f[n]).norm());
    }
  }
  for (const auto& fi : f) fmax = std::max(fmax, fi.norm());
  r.max_fint_residual = res / fmax;
  return r;
}

}  // namespace cutbench::efg
