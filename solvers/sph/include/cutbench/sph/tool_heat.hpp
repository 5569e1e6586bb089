#pragma once
// Tool conduction, a component of SolidSph (set_tool_thermal): the tool discretised as a
// heat-conducting body of particles in its own frame, with a far boundary held at the ambient
// temperature (heat sink), its own surface masks, neighbour list and FMFS geometry. It receives its
// share of the friction heat from the workpiece particles in contact and exchanges heat with the
// workpiece through cross_body_conduction() (heat.hpp).
#include <cstddef>
#include <vector>

#include "cutbench/sph/heat.hpp"
#include "cutbench/sph/neighbours.hpp"
#include "cutbench/sph/operators.hpp"
#include "cutbench/sph/surface.hpp"
#include "cutbench/sph/tool.hpp"

namespace cutbench::sph {

struct ToolHeatBody {
  bool active = false;
  HeatMaterial heat;
  std::vector<Vec2> x;                      // tool frame
  std::vector<double> V, T;                 // volume (dx^2), temperature
  std::vector<char> fixed, use_fmfs, loss;  // sink; FMFS / Brookshaw; loses heat to the air
  NeighbourList nl;
  FmfsLaplacian fmfs;

  // Particles on the dx lattice aligned with the tool frame's origin (the lowest edge point) inside
  // the tool and within `depth` of the origin; those within 3 dx of that boundary are sinks.
  // Surface masks as the workpiece's (surface detection options, Brookshaw band); temperatures
  // start at T_ambient.
  void build(const ToolGeometry& tool, const HeatMaterial& material, double depth, double dx,
             const CubicSpline2D& kernel, const SurfaceOptions& surface, bool brookshaw_band, double T_ambient);
  // sum rho c V (T - T_ambient), J per metre of depth
  double heat_content(double T_ambient) const;
  std::vector<Vec2> world(const Vec2& tool_position) const;
  // Friction heat q of workpiece particle i at xi onto the non-sink tool particles in its support
  // (cross neighbours of row i, kernel-weighted). False (nothing deposited) when there are none.
  bool receive(std::size_t i, const Vec2& xi, double q, const NeighbourList& cross, const std::vector<Vec2>& world,
               const CubicSpline2D& kernel);
};

}  // namespace cutbench::sph
