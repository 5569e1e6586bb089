#pragma once
// Small-strain static solve of the same EFG discretisation (stiffness K = sum_G V B^T Qbar B,
// 2 x 2 Gauss points per background cell), for verification against static closed forms
// (patch test, Timoshenko cantilever). Dirichlet values are imposed on nodal values.
#include <functional>
#include <vector>

#include "cutbench/efg/discretisation.hpp"

namespace cutbench::efg {

struct NodalDirichlet {
  int node = 0;
  int dof = 0;
  double value = 0.0;
};

// Consistent nodal forces of a traction t(x) over boundary Gauss points: f_I = sum t phi_I w.
std::vector<Vec2> traction_forces(const std::vector<Vec2>& nodes, const std::vector<double>& support,
                                  const WeightParams& weight, const std::vector<GaussPoint>& line,
                                  const std::function<Vec2(const Vec2&)>& traction, double thickness);

// Solves K u = f with the given nodal Dirichlet values (sparse LDL^T). Throws NumericalError if
// the reduced stiffness is singular.
std::vector<Vec2> solve_linear_static(const Discretisation& d, const Eigen::Matrix3d& D, double thickness,
                                      const WeightParams& weight, const std::vector<NodalDirichlet>& fixed,
                                      const std::vector<Vec2>& f);

// u^h and its gradient at points: value (ux, uy) and small strain (xx, yy, 2xy).
struct FieldSample {
  Vec2 u = Vec2::Zero();
  Eigen::Vector3d strain = Eigen::Vector3d::Zero();
};
std::vector<FieldSample> sample_field(const std::vector<Vec2>& points, const std::vector<Vec2>& nodes,
                                      const std::vector<double>& support, const WeightParams& weight,
                                      const std::vector<Vec2>& u);

}  // namespace cutbench::efg
