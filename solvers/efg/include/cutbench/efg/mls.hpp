#pragma once
// Moving least squares (MLS) shape functions of the element-free Galerkin method, as in Kahwash,
// Shyha, Maheri (2018), Compos. Struct. 198:156-173, section 2.2 (Eqs 10-21).
//
// Linear basis p = {1, (x - x_e)/h, (y - y_e)/h}, shifted to the evaluation point x_e and scaled
// by the local support size h, so that the moment matrix A stays well conditioned; with the
// shifted basis p(x_e) = e1 and phi_I = e1^T A^{-1} p_I w_I (Eq 17). Derivatives follow Eqs 18-19
// with the shift point frozen: gamma = A^{-1} e1, gamma_,i = A^{-1}(p_,i - A_,i gamma).
//
// Weights: the regularised weight of Most & Bucher (Eqs 20-21, EQUATIONS.md E4), normalised by
// the sum over the neighbours (which leaves the MLS shape functions unchanged mathematically but
// keeps A of order one), or a cubic spline. Each node has its own support radius D_I.
#include <Eigen/Core>
#include <utility>
#include <vector>

namespace cutbench::efg {

using Vec2 = Eigen::Vector2d;

enum class WeightKind { regularized, cubic_spline };

struct WeightParams {
  WeightKind kind = WeightKind::regularized;
  double omega = 1e-5;  // regularisation constant of Eq 21 (paper: 1e-5)
};

// Unnormalised weight w(s) and dw/ds for s = d/D >= 0 (zero for s >= 1).
void weight_function(const WeightParams& p, double s, double& w, double& dw_ds);

// Shape functions of the nodes supporting one point.
struct ShapeData {
  std::vector<int> nodes;
  std::vector<double> phi, dphidx, dphidy;
  void clear() {
    nodes.clear();
    phi.clear();
    dphidx.clear();
    dphidy.clear();
  }
};

// Uniform-grid cell list over a set of points for radius queries.
class CellList {
public:
  void build(const std::vector<Vec2>& points, double cell_size);
  // Indices of points within `radius` of x (unsorted order is deterministic: cell by cell).
  void query(const Vec2& x, double radius, std::vector<int>& out) const;
  // Smallest distance between two distinct points (requires cell_size >= that distance to be
  // exact; returns +inf when no pair is closer than cell_size).
  double min_pair_distance() const;
  // Every pair (i < j, indices into the points) closer than r (r <= cell_size), appended to out.
  void pairs_within(double r, std::vector<std::pair<int, int>>& out) const;
  double cell_size() const { return h_; }

private:
  long key(long i, long j) const { return i * ny_ + j; }
  const std::vector<Vec2>* pts_ = nullptr;
  double h_ = 1.0;
  Vec2 lo_ = Vec2::Zero();
  long nx_ = 0, ny_ = 0;
  std::vector<int> start_, items_;  // CSR layout of points per cell
};

// Visibility criterion (Belytschko et al. 1996; Kahwash 2018 section 3.5): an opaque segment (a
// crack, a cut or a non-convex boundary) hides a node from an evaluation point when the line of
// sight between them crosses it; the hidden node is dropped from the point's support, so its shape
// function and derivatives vanish there. Touching an end point or running along the segment
// counts as crossing only when the interiors properly intersect (collinear overlap: not hidden).
struct Segment {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
};
bool line_of_sight_blocked(const Vec2& x, const Vec2& xI, const Segment& s);
// Removes from `candidates` every node hidden from x by one of the opaque segments.
void visibility_filter(const Vec2& x, const std::vector<Vec2>& nodes, const std::vector<Segment>& opaque,
                       std::vector<int>& candidates);

// MLS shape functions at x from the candidate nodes (those with |x - x_I| < D_I are used).
// Returns false when fewer than three supporting nodes exist or A is singular.
bool mls_shape(const Vec2& x, const std::vector<Vec2>& nodes, const std::vector<double>& support,
               const std::vector<int>& candidates, const WeightParams& weight, ShapeData& out,
               bool derivatives = true);

}  // namespace cutbench::efg
