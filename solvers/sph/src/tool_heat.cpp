#include "cutbench/sph/tool_heat.hpp"

#include <cmath>

#include "cutbench/sph/surface.hpp"

namespace cutbench::sph {

void ToolHeatBody::build(const ToolGeometry& tool, const HeatMaterial& material, double depth, double dx,
                         const CubicSpline2D& kernel, const SurfaceOptions& surface, bool brookshaw_band,
                         double T_ambient) {
  heat = material;
  x.clear();
  // lattice aligned with the lowest edge point (tool-frame origin of cutting_tool(...) is arbitrary:
  // use the current world frame relative to the tool position)
  const int m = static_cast<int>(std::ceil(depth / dx)) + 1;
  for (int j = -m; j <= m; ++j)
    for (int i = -m; i <= m; ++i) {
      const Vec2 p((i + 0.5) * dx, (j + 0.5) * dx);
      if (p.norm() > depth) continue;
      if (tool.at(p).distance <= -0.45 * dx) x.push_back(p);
    }
  const std::size_t n = x.size();
  V.assign(n, dx * dx);
  T.assign(n, T_ambient);
  fixed.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) fixed[i] = x[i].norm() > depth - 3.0 * dx;
  nl = build_neighbours(x, kernel.support());
  const ParticleView view{x, V, nl, kernel};
  const SurfaceDetection s = detect_free_surface(view, surface);
  heat_masks(nl, s, fixed, brookshaw_band, surface.lambda_interior, use_fmfs, loss);
  fmfs.update(view);
  active = true;
}

double ToolHeatBody::heat_content(double T_ambient) const {
  double e = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) e += heat.density * heat.specific_heat * V[i] * (T[i] - T_ambient);
  return e;
}

std::vector<Vec2> ToolHeatBody::world(const Vec2& tool_position) const {
  std::vector<Vec2> w(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) w[k] = x[k] + tool_position;
  return w;
}

bool ToolHeatBody::receive(std::size_t i, const Vec2& xi, double q, const NeighbourList& cross,
                           const std::vector<Vec2>& world, const CubicSpline2D& kernel) {
  const double rc_tool = heat.density * heat.specific_heat;
  double wsum = 0.0;
  for (std::size_t k = cross.begin(i); k < cross.end(i); ++k)
    if (!fixed[cross.index[k]]) wsum += kernel.value((xi - world[cross.index[k]]).norm());
  if (!(wsum > 0.0)) return false;
  for (std::size_t k = cross.begin(i); k < cross.end(i); ++k) {
    const std::size_t j = cross.index[k];
    if (fixed[j]) continue;
    const double w = kernel.value((xi - world[j]).norm()) / wsum;
    T[j] += q * w / (rc_tool * V[j]);
  }
  return true;
}

}  // namespace cutbench::sph
