#include "cutbench/efg/cutting.hpp"

#include <cmath>

#include "cutbench/common/errors.hpp"

namespace cutbench::efg {

CuttingResult run_cutting(const CuttingSetup& s, const std::function<void(double)>& progress) {
  if (s.depth >= s.work_height) throw InputError("depth", "must be smaller than the workpiece height");
  const int nx = static_cast<int>(std::lround(s.work_length / s.spacing)) + 1;
  const int ny = static_cast<int>(std::lround(s.work_height / s.spacing)) + 1;
  const Discretisation d = rectangle(s.work_length, s.work_height, nx, ny, s.support_factor);
  ExplicitOptions opt;
  opt.kinematics = s.kinematics;
  opt.update_interval = s.update_interval;
  opt.cfl = s.cfl;
  opt.failure.enabled = true;
  opt.failure.criterion = s.criterion;
  opt.failure.lamina = s.lamina;
  opt.failure.residual = s.residual;
  // Fibre direction (cos theta, -sin theta): clockwise from the cutting direction.
  ExplicitEFG solver(d, s.material, -s.theta, opt);
  // Workpiece held on its bottom and right-hand faces.
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (j == 0 || i == nx - 1) {
        solver.add_velocity_bc(j * nx + i, 0, [](double) { return 0.0; });
        solver.add_velocity_bc(j * nx + i, 1, [](double) { return 0.0; });
      }
    }
  }
  // Tool: cutting edge at (x_e, H - depth), rake face at angle `rake` from the vertical, clearance
  // face rising backwards at `clearance`; moves along +x.
  const double V = s.speed * s.time_scale;
  const double gap = 0.25 * s.spacing;
  const double yE = s.work_height - s.depth;
  const double T = 4.0 * s.work_height, W = 4.0 * s.work_height;
  const Vec2 E(-gap, yE);
  RigidTool tool;
  tool.vertices = {E, E + Vec2(-T * std::tan(s.rake), T), E + Vec2(-W, T), E + Vec2(-W, W * std::tan(s.clearance))};
  tool.velocity = Vec2(V, 0.0);
  tool.mu = s.mu;
  solver.set_tool(tool);

  CuttingResult r;
  r.nodes = nx * ny;
  r.gauss = solver.num_gauss();
  r.t_contact_expected = gap / V;
  r.dt_initial = solver.critical_time_step() * s.cfl;
  r.dt_min = r.dt_initial;
  const double t_end = r.t_contact_expected + s.travel / V;
  Vec2 acc = Vec2::Zero();
  double tacc = 0.0;
  int nacc = 0;
  while (solver.time() < t_end) {
    const double dt = solver.step();
    r.dt_min = std::min(r.dt_min, dt);
    if (r.t_dt_drop < 0 && dt < 0.5 * r.dt_initial) r.t_dt_drop = solver.time();
    if (dt < 0.05 * r.dt_initial) break;  // nodes collapsing: chip complete or run broken (Fig 10)
    if (r.t_contact < 0 && solver.contact_count() > 0) r.t_contact = solver.time();
    acc += solver.tool_force() * dt;
    tacc += dt;
    if (++nacc == s.record_every) {
      r.t.push_back(solver.time());
      r.Fc.push_back(-acc.x() / tacc);  // resistance of the workpiece to the tool's advance
      r.Ft.push_back(acc.y() / tacc);   // thrust: pushes the tool away from the workpiece (+y)
      r.dt.push_back(dt);
      acc.setZero();
      tacc = 0.0;
      nacc = 0;
      if (progress) progress(solver.time() / t_end);
    }
  }
  r.steps = solver.steps();
  const double t_half = r.t_contact_expected + 0.5 * s.travel / V;
  int n = 0;
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    if (r.t[k] >= t_half) {
      r.Fc_mean += r.Fc[k];
      r.Ft_mean += r.Ft[k];
      ++n;
    }
  }
  if (n > 0) {
    r.Fc_mean /= n;
    r.Ft_mean /= n;
  }
  for (std::size_t g = 0; g < solver.num_gauss(); ++g) {
    const auto dm = solver.damage(g);
    r.fibre_damaged += dm[0] > 0.5;
    r.matrix_damaged += dm[1] > 0.5;
    r.interface_damaged += dm[2] > 0.5;
    const Vec2 x = solver.gauss_position(g);
    r.gx.push_back(x.x());
    r.gy.push_back(x.y());
    r.dfibre.push_back(dm[0]);
    r.dmatrix.push_back(dm[1]);
  }
  return r;
}

}  // namespace cutbench::efg
