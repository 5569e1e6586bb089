#include "cutbench/efg/static.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "cutbench/common/errors.hpp"

namespace cutbench::efg {

std::vector<Vec2> traction_forces(const std::vector<Vec2>& nodes, const std::vector<double>& support,
                                  const WeightParams& weight, const std::vector<GaussPoint>& line,
                                  const std::function<Vec2(const Vec2&)>& traction, double thickness) {
  std::vector<Vec2> pts;
  for (const auto& g : line) pts.push_back(g.x);
  const auto sf = shape_functions(pts, nodes, support, weight, false);
  std::vector<Vec2> f(nodes.size(), Vec2::Zero());
  for (std::size_t k = 0; k < line.size(); ++k) {
    const Vec2 t = traction(line[k].x) * (line[k].weight * thickness);
    for (std::size_t a = 0; a < sf[k].nodes.size(); ++a) f[sf[k].nodes[a]] += sf[k].phi[a] * t;
  }
  return f;
}

std::vector<Vec2> solve_linear_static(const Discretisation& d, const Eigen::Matrix3d& D, double thickness,
                                      const WeightParams& weight, const std::vector<NodalDirichlet>& fixed,
                                      const std::vector<Vec2>& f) {
  const int n = static_cast<int>(d.nodes.size());
  std::vector<Vec2> pts;
  for (const auto& g : d.gauss) pts.push_back(g.x);
  const auto sf = shape_functions(pts, d.nodes, d.support, weight, true);
  // Dof numbering: free dofs first.
  std::vector<int> map(2 * n, 0);
  std::vector<double> uval(2 * n, 0.0);
  std::vector<char> isfixed(2 * n, 0);
  for (const auto& b : fixed) {
    isfixed[2 * b.node + b.dof] = 1;
    uval[2 * b.node + b.dof] = b.value;
  }
  int nf = 0;
  for (int k = 0; k < 2 * n; ++k) map[k] = isfixed[k] ? -1 : nf++;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nf);
  for (int k = 0; k < 2 * n; ++k) {
    if (map[k] >= 0) rhs(map[k]) = f[k / 2](k % 2);
  }
  for (std::size_t g = 0; g < pts.size(); ++g) {
    const ShapeData& s = sf[g];
    const std::size_t m = s.nodes.size();
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(3, 2 * m);
    for (std::size_t a = 0; a < m; ++a) {
      B(0, 2 * a) = s.dphidx[a];
      B(1, 2 * a + 1) = s.dphidy[a];
      B(2, 2 * a) = s.dphidy[a];
      B(2, 2 * a + 1) = s.dphidx[a];
    }
    const Eigen::MatrixXd Ke = (d.gauss[g].weight * thickness) * (B.transpose() * D * B);
    for (std::size_t a = 0; a < 2 * m; ++a) {
      const int ga = 2 * s.nodes[a / 2] + static_cast<int>(a % 2);
      if (map[ga] < 0) continue;
      for (std::size_t b = 0; b < 2 * m; ++b) {
        const int gb = 2 * s.nodes[b / 2] + static_cast<int>(b % 2);
        if (map[gb] >= 0) {
          trip.emplace_back(map[ga], map[gb], Ke(a, b));
        } else {
          rhs(map[ga]) -= Ke(a, b) * uval[gb];
        }
      }
    }
  }
  Eigen::SparseMatrix<double> K(nf, nf);
  K.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(K);
  if (solver.info() != Eigen::Success) throw NumericalError("EFG static: stiffness factorisation failed");
  const Eigen::VectorXd uf = solver.solve(rhs);
  if (solver.info() != Eigen::Success) throw NumericalError("EFG static: solve failed");
  std::vector<Vec2> u(n, Vec2::Zero());
  for (int k = 0; k < 2 * n; ++k) u[k / 2](k % 2) = map[k] >= 0 ? uf(map[k]) : uval[k];
  return u;
}

std::vector<FieldSample> sample_field(const std::vector<Vec2>& points, const std::vector<Vec2>& nodes,
                                      const std::vector<double>& support, const WeightParams& weight,
                                      const std::vector<Vec2>& u) {
  const auto sf = shape_functions(points, nodes, support, weight, true);
  std::vector<FieldSample> out(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const ShapeData& s = sf[k];
    for (std::size_t a = 0; a < s.nodes.size(); ++a) {
      const Vec2& uI = u[s.nodes[a]];
      out[k].u += s.phi[a] * uI;
      out[k].strain(0) += s.dphidx[a] * uI.x();
      out[k].strain(1) += s.dphidy[a] * uI.y();
      out[k].strain(2) += s.dphidy[a] * uI.x() + s.dphidx[a] * uI.y();
    }
  }
  return out;
}

}  // namespace cutbench::efg
