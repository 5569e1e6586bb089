#include "cutbench/efg/verification.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>

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

WaveResult bar_wave(const Orthotropic& m, double theta, double L, int nx, int ny, double cfl,
                    Kinematics kin, const WeightParams& w, int update_interval) {
  const double H = L * (ny - 1) / (nx - 1);
  const Discretisation d = rectangle(L, H, nx, ny, 2.5);
  ExplicitOptions opt;
  opt.kinematics = kin;
  opt.cfl = cfl;
  opt.weight = w;
  opt.update_interval = update_interval;
  ExplicitEFG s(d, m, theta, opt);
  const double v0 = 1.0;
  for (int j = 0; j < ny; ++j) {
    s.add_velocity_bc(j * nx, 0, [v0](double) { return v0; });
    for (int i = 0; i < nx; ++i) s.add_velocity_bc(j * nx + i, 1, [](double) { return 0.0; });
  }
  const int row = ny / 2, i1 = (nx - 1) / 4, i2 = 3 * (nx - 1) / 4;
  const int n1 = row * nx + i1, n2 = row * nx + i2;
  WaveResult r;
  r.c_exact = std::sqrt(m.Qbar(theta)(0, 0) / m.rho);
  double t1 = -1, t2 = -1, v1p = 0, v2p = 0, tp = 0;
  while (s.time() < 0.9 * L / r.c_exact) {
    s.step();
    const double v1 = s.velocities()[n1].x(), v2 = s.velocities()[n2].x(), t = s.time();
    if (t1 < 0 && v1 >= 0.5 * v0) t1 = tp + (t - tp) * (0.5 * v0 - v1p) / (v1 - v1p);
    if (t2 < 0 && v2 >= 0.5 * v0) t2 = tp + (t - tp) * (0.5 * v0 - v2p) / (v2 - v2p);
    v1p = v1;
    v2p = v2;
    tp = t;
    r.t.push_back(t);
    r.v1.push_back(v1);
    r.v2.push_back(v2);
  }
  r.steps = s.steps();
  if (t1 > 0 && t2 > t1) {
    r.c_measured = (d.nodes[n2].x() - d.nodes[n1].x()) / (t2 - t1);
    r.rel_error = r.c_measured / r.c_exact - 1.0;
  } else {
    r.c_measured = r.rel_error = std::numeric_limits<double>::quiet_NaN();
  }
  return r;
}

PatchResult patch_test(const Orthotropic& m, double theta, int nx, int ny, double jitter, int gauss_per_dir,
                       const WeightParams& w) {
  PatchResult r;
  const double Lx = 1.0, Ly = 1.0 * (ny - 1) / (nx - 1);
  const Discretisation d = rectangle(Lx, Ly, nx, ny, 2.5, jitter, 8, gauss_per_dir);
  Mat2 H;
  H << 1e-3, 2e-3, -1e-3, 0.5e-3;
  // (a) homogeneous finite deformation, total Lagrangian.
  {
    Mat2 Hf = 50.0 * H;  // finite: |H| ~ 0.1
    const Mat2 F = Mat2::Identity() + Hf;
    ExplicitOptions opt;
    opt.weight = w;
    ExplicitEFG s(d, m, theta, opt);
    std::vector<Vec2> u(d.nodes.size());
    for (std::size_t I = 0; I < u.size(); ++I) u[I] = Hf * d.nodes[I] + Vec2(1e-3, -2e-3);
    s.set_displacement(u);
    const Mat2 C = F.transpose() * F;
    const Eigen::Vector3d E(0.5 * (C(0, 0) - 1), 0.5 * (C(1, 1) - 1), C(0, 1));
    const Eigen::Vector3d S = m.Qbar(theta) * E;
    for (std::size_t g = 0; g < s.num_gauss(); ++g) {
      r.max_F_error = std::max(r.max_F_error, (s.deformation_gradient(g) - F).cwiseAbs().maxCoeff());
      r.max_stress_rel_error =
          std::max(r.max_stress_rel_error, (s.pk2(g) - S).cwiseAbs().maxCoeff() / S.cwiseAbs().maxCoeff());
    }
  }
  // (b) static patch test.
  std::vector<NodalDirichlet> fixed;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (i == 0 || j == 0 || i == nx - 1 || j == ny - 1) {
        const int I = j * nx + i;
        const Vec2 u = H * d.nodes[I];
        fixed.push_back({I, 0, u.x()});
        fixed.push_back({I, 1, u.y()});
      }
    }
  }
  const auto u = solve_linear_static(d, m.Qbar(theta), 1.0, w, fixed, std::vector<Vec2>(d.nodes.size(), Vec2::Zero()));
  double e = 0.0;
  for (std::size_t I = 0; I < d.nodes.size(); ++I) e = std::max(e, (u[I] - H * d.nodes[I]).norm());
  r.static_rel_error = e / (H.norm() * Lx);
  return r;
}

}  // namespace cutbench::efg
