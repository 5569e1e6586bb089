#include "cutbench/sph/workpiece_heat.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cutbench/common/errors.hpp"
#include "parallel.hpp"

namespace cutbench::sph {

void WorkpieceHeat::deposit_friction(std::size_t i, double heat, double rho_i, double m_i, double& T_i,
                                     bool tool_active) {
  friction_heat += heat;
  if (!active || fixed[i]) return;
  double to_tool = 0.0;
  if (tool_active && tool_share > 0.0) {
    to_tool = tool_share * heat;
    pending_tool[i] += to_tool;
  }
  // in the audit metric rho0 c V_i T_i this adds exactly heat - to_tool
  T_i += (heat - to_tool) * rho_i / (options.heat.density * options.heat.specific_heat * m_i);
}

double WorkpieceHeat::content(const std::vector<double>& m, const std::vector<double>& rho,
                              const std::vector<double>& T) const {
  if (!active) return 0.0;
  double e = 0.0;
  const double rc = options.heat.density * options.heat.specific_heat;
  for (std::size_t i = 0; i < T.size(); ++i)
    if (!fixed[i]) e += rc * m[i] / rho[i] * (T[i] - options.boundary.T_ambient);
  return e;
}

void WorkpieceHeat::update(double dt, const std::vector<double>& plastic_dT, const std::vector<Vec2>& x,
                           const std::vector<double>& m, const std::vector<double>& rho, std::vector<double>& T,
                           const NeighbourList& nl, const CubicSpline2D& kernel, double dx, ToolHeatBody& tool,
                           const Vec2& tool_position, double time, std::size_t step_count) {
  // Called with nl, x and rho of the start of the step.
  const std::size_t n = x.size();
  const double rc = options.heat.density * options.heat.specific_heat;
  if (plastic_at.size() != n) plastic_at.assign(n, 0.0);
  // plastic heat of this step: per particle in parallel, the total summed in index order (as a
  // serial loop over every particle would: the elastic ones add exact zeros)
  dT_q_.resize(n);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    if (fixed[i] || plastic_dT[i] == 0.0) {
      dT_q_[i] = 0.0;
      continue;
    }
    T[i] += plastic_dT[i];
    const double q = plastic_dT[i] * rc * (m[i] / rho[i]);
    dT_q_[i] = q;
    plastic_at[i] += q;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (dT_q_[i] != 0.0) plastic_heat += dT_q_[i];
  dt_acc += dt;
  ++steps;
  const double alpha_max = tool.active ? std::max(options.heat.diffusivity(), tool.heat.diffusivity())
                                             : options.heat.diffusivity();
  const double dt_limit = 0.1 * kernel.h() * kernel.h() / alpha_max;
  if (steps < options.conduction_interval && dt_acc + dt < dt_limit) return;
  const int sub = std::max(1, static_cast<int>(std::ceil(dt_acc / dt_limit)));
  const double dt_th = dt_acc / sub;
  dt_acc = 0.0;
  steps = 0;
  std::vector<double> vol(n);
  for (std::size_t i = 0; i < n; ++i) vol[i] = m[i] / rho[i];
  fill_pair_cache(ParticleView{x, vol, nl, kernel}, pairs_);
  const ParticleView view{x, vol, nl, kernel, &pairs_};
  surface = detect_free_surface(view, options.surface);
  std::vector<char> use_fmfs, loss;
  heat_masks(nl, surface, fixed, options.brookshaw_band, options.surface.lambda_interior, use_fmfs, loss);
  const FmfsLaplacian* fm = nullptr;
  if (options.scheme == HeatScheme::fmfs) {
    fmfs_.update(view, &use_fmfs);  // FMFS geometry only where FMFS is used
    fm = &fmfs_;
  }
  std::vector<double> rate, tool_rate;
  std::vector<Vec2> tool_world;
  NeighbourList cross;
  ToolHeatBody& tb = tool;
  std::vector<char> tool_loss = tb.loss;
  if (tb.active) {
    tool_world = tb.world(tool_position);
    cross = build_cross_neighbours(x, tool_world, kernel.support());
    const double c2 = 2.25 * dx * dx;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = cross.begin(i); k < cross.end(i); ++k)
        if ((x[i] - tool_world[cross.index[k]]).squaredNorm() < c2) {
          loss[i] = 0;
          tool_loss[cross.index[k]] = 0;
        }
    // friction heat share of the tool: onto the (non-sink) tool particles in the support of the
    // heated workpiece particle, kernel-weighted; back to the workpiece particle if there are none
    for (std::size_t i = 0; i < n; ++i) {
      const double q = pending_tool[i];
      if (q == 0.0) continue;
      pending_tool[i] = 0.0;
      if (tb.receive(i, x[i], q, cross, tool_world, kernel)) {
        friction_heat_tool += q;
      } else {
        T[i] += q / (rc * vol[i]);
      }
    }
  }
  const ParticleView tool_view{tb.x, tb.V, tb.nl, kernel};
  for (int k = 0; k < sub; ++k) {
    double sunk = 0.0, tool_sunk = 0.0;
    const double lost = heat_rates(view, T, fm, use_fmfs, fixed, loss, options.heat, options.boundary, rate, nullptr, &sunk);
    heat_lost += dt_th * lost;
    heat_sunk += dt_th * sunk;
    if (tb.active) {
      const double tool_lost =
          heat_rates(tool_view, tb.T, options.scheme == HeatScheme::fmfs ? &tb.fmfs : nullptr, tb.use_fmfs, tb.fixed,
                     tool_loss, tb.heat, options.boundary, tool_rate, nullptr, &tool_sunk);
      heat_lost += dt_th * tool_lost;
      heat_sunk += dt_th * tool_sunk;
      cross_body_conduction(x, vol, T, options.heat, tool_world, tb.V, tb.T, tb.heat, cross, kernel, rate, tool_rate);
      // cross-body heat into fixed particles (their rates were zeroed before the cross term)
      const double rcw = options.heat.density * options.heat.specific_heat;
      const double rct = tb.heat.density * tb.heat.specific_heat;
      for (std::size_t i = 0; i < n; ++i)
        if (fixed[i]) heat_sunk += dt_th * rate[i] * rcw * vol[i];
      for (std::size_t i = 0; i < tb.T.size(); ++i)
        if (tb.fixed[i]) heat_sunk += dt_th * tool_rate[i] * rct * tb.V[i];
      for (std::size_t i = 0; i < tb.T.size(); ++i)
        if (!tb.fixed[i]) tb.T[i] += dt_th * tool_rate[i];
    }
    for (std::size_t i = 0; i < n; ++i)
      if (!fixed[i]) T[i] += dt_th * rate[i];
  }
  // A non-finite temperature would silently switch off J-C yielding (NaN flow stress) and the run
  // would go on with garbage: stop it here with the place and time.
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(T[i]))
      throw NumericalError("sph: non-finite temperature at workpiece particle " + std::to_string(i) + " (x " +
                           std::to_string(x[i].x()) + " m, y " + std::to_string(x[i].y()) + " m) at t = " +
                           std::to_string(time) + " s, step " + std::to_string(step_count));
  for (std::size_t i = 0; i < tb.T.size(); ++i)
    if (!std::isfinite(tb.T[i]))
      throw NumericalError("sph: non-finite temperature at tool particle " + std::to_string(i) + " at t = " +
                           std::to_string(time) + " s, step " + std::to_string(step_count));
}

}  // namespace cutbench::sph
