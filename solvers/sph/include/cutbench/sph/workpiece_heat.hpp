#pragma once
// Heat in the workpiece, a component of SolidSph (enable_thermal): plastic and friction heating,
// conduction with FMFS inside and Brookshaw at the surface (or the Brookshaw band), convection and
// radiation from the detected surface, fixed-temperature particles as sinks, the coupling to the
// conducting tool (ToolHeatBody) and the heat audit.
#include <cstddef>
#include <vector>

#include "cutbench/sph/heat.hpp"
#include "cutbench/sph/neighbours.hpp"
#include "cutbench/sph/operators.hpp"
#include "cutbench/sph/surface.hpp"
#include "cutbench/sph/tool_heat.hpp"

namespace cutbench::sph {

// Heat equation on the moving particles (Eq. 4): conduction with V_j = m_j / rho_j, surface
// detection and FMFS geometry recomputed every step, plastic heating chi sigma_y d(eps_p) / (rho c_p)
// per step (Eq. 5), convection and radiation on the detected surface, fixed-temperature particles.
struct ThermalOptions {
  HeatMaterial heat{7.3, 4430.0, 580.0};  // Ti6Al4V, paper Table 1
  HeatBoundary boundary{50.0, 0.3, 300.0};
  HeatScheme scheme = HeatScheme::fmfs;
  bool brookshaw_band = false;
  SurfaceOptions surface;
  double taylor_quinney = 0.9;  // chi
  // Conduction, surface detection and FMFS geometry are updated every `conduction_interval`
  // mechanical steps with the accumulated step (the thermal limit 0.1 h^2/alpha is ~1e4 times the
  // mechanical CFL step in cutting); plastic and friction heat are added every step.
  int conduction_interval = 10;
};

class WorkpieceHeat {
public:
  bool active = false;
  ThermalOptions options;
  std::vector<char> fixed;  // fixed-temperature particles (sinks)
  SurfaceDetection surface;  // of the last conduction update
  // Heat accounts, J per metre of depth, accumulated: plastic, lost to the air, friction (all of
  // it), sunk into fixed-temperature particles, friction heat put into the tool.
  double plastic_heat = 0.0, heat_lost = 0.0, friction_heat = 0.0, heat_sunk = 0.0, friction_heat_tool = 0.0;
  double tool_share = 0.0;                // beta: share of the friction heat for the tool
  std::vector<double> plastic_at;         // plastic heat per particle, J/m
  std::vector<double> pending_tool;       // friction heat per particle for the tool, deposited at the next conduction update
  double dt_acc = 0.0;                    // time since the last conduction update
  int steps = 0;                          // mechanical steps since then

  // Friction heat of one contact at particle i (rho_i, m_i): the tool's share is kept for the next
  // conduction update, the rest raises T_i (nothing for a fixed-temperature particle).
  void deposit_friction(std::size_t i, double heat, double rho_i, double m_i, double& T_i, bool tool_active);
  // The plastic heat of one step, then, every `conduction_interval` steps or at the stability limit
  // 0.1 h^2/alpha, the conduction sub-steps of the workpiece (x, m, rho, T at the start of the step,
  // neighbour list nl) and of the tool with their coupling. time and step_count name a fault.
  void update(double dt, const std::vector<double>& plastic_dT, const std::vector<Vec2>& x,
              const std::vector<double>& m, const std::vector<double>& rho, std::vector<double>& T,
              const NeighbourList& nl, const CubicSpline2D& kernel, double dx, ToolHeatBody& tool,
              const Vec2& tool_position, double time, std::size_t step_count);
  // sum rho0 c V_i (T_i - T_ambient) over the free (not fixed-temperature) particles, J/m
  double content(const std::vector<double>& m, const std::vector<double>& rho, const std::vector<double>& T) const;

private:
  FmfsLaplacian fmfs_;
  PairCache pairs_;  // the pairs inside the support in the conduction update
  std::vector<double> dT_q_;
};

}  // namespace cutbench::sph
