#pragma once
// Six-node triangle (T6) meshes and a simple structured triangulator.
//
// Node numbering of an element: vertices 0, 1, 2 counter-clockwise, then the mid-side nodes
// 3 (edge 0-1), 4 (edge 1-2), 5 (edge 2-0). Mid-side nodes lie at the edge midpoints.
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/StdVector>

namespace cutbench::limit {

struct Mesh {
  std::vector<Eigen::Vector2d> nodes;
  std::vector<std::array<int, 6>> elements;
  std::vector<bool> is_vertex;  // per node: a triangle vertex (true) or a mid-side node

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_elements() const { return static_cast<int>(elements.size()); }
  double area(int e) const;
};

// A boundary edge (one element only): end nodes a, b and mid node m, oriented so that the
// element lies on the left of a→b (the outward normal is the a→b direction rotated clockwise).
struct BoundaryEdge {
  int a, m, b, element;
};
std::vector<BoundaryEdge> boundary_edges(const Mesh& mesh);
Eigen::Vector2d boundary_normal(const Mesh& mesh, const BoundaryEdge& e);

// Promote a linear triangulation (vertices + CCW triangles) to T6 by adding mid-side nodes.
Mesh make_t6(const std::vector<Eigen::Vector2d>& vertices, const std::vector<std::array<int, 3>>& triangles);

enum class Pattern { alternating, union_jack, crossed };

// Structured mesh of the quadrilateral with corners p00 (ξ=0,η=0), p10, p11, p01 (CCW),
// bilinearly mapped from the parameter grid xi × eta (both increasing from 0 to 1).
// alternating / union_jack: two triangles per cell; crossed: four per cell (centre node).
Mesh structured_quad(const Eigen::Vector2d& p00, const Eigen::Vector2d& p10, const Eigen::Vector2d& p11,
                     const Eigen::Vector2d& p01, const std::vector<double>& xi, const std::vector<double>& eta,
                     Pattern pattern = Pattern::union_jack);

// 1D parameter distributions on [0, 1].
std::vector<double> uniform_grid(int n);
// n intervals whose sizes grow geometrically by `ratio` away from `toward` (0 or 1).
std::vector<double> graded_grid(int n, double ratio, double toward);
// Concatenate distributions of sub-intervals [b_i, b_{i+1}] (breakpoints in [0,1]).
std::vector<double> piecewise_grid(const std::vector<double>& breaks, const std::vector<std::vector<double>>& parts);

// Merge meshes, identifying nodes closer than tol.
Mesh merge(const Mesh& a, const Mesh& b, double tol = 1e-10);

// Conforming longest-edge bisection: every marked element has its longest edge bisected; the
// closure also bisects the longest edge of any element that has a bisected edge, so the result
// is conforming; elements end up split into 2, 3 or 4. Mid-side nodes are rebuilt (straight
// edges). Returns the refined mesh.
Mesh refine(const Mesh& mesh, const std::vector<int>& marked);

// ---- Anisotropic (metric-directed) refinement -------------------------------------------------
// A metric per element is a symmetric positive semi-definite 2×2 matrix M; the metric length of
// an edge e is √(eᵀ M e).
using Metrics = std::vector<Eigen::Matrix2d, Eigen::aligned_allocator<Eigen::Matrix2d>>;

// Recovered Hessian of a piecewise-constant element field f (e.g. the plastic dissipation
// density): nodal values at the vertices by area-weighted averaging, element gradients of their
// linear interpolant, nodal gradients by area-weighted averaging, element Hessian = gradient of
// the linear interpolant of the nodal gradients (symmetrised). Vertex triangle only.
Metrics recovered_hessian(const Mesh& mesh, const Eigen::VectorXd& element_field);

// Shape metric of a Hessian H: the eigenvectors of H with the ratio of the eigenvalues of |H|
// (largest first) capped at max_aspect², normalised so that the largest eigenvalue is 1. The unit
// ball is an ellipse stretched along the direction of small curvature (along a shear band), at
// most max_aspect times. H = 0 gives the identity (isotropic).
Eigen::Matrix2d shape_metric(const Eigen::Matrix2d& hessian, double max_aspect);

// Bisect the given edges (pairs of vertex node ids of `mesh`), without closure: each element is
// split according to its own bisected edges (1 edge: 2
// children, 2 edges: 3 children, the quadrilateral cut along the diagonal that is shorter in the
// element's metric (Euclidean when `metric` is null), 3 edges: 4 children). The result is
// conforming because both neighbours of a bisected edge see it. Mid-side nodes are rebuilt.
Mesh bisect_edges(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges, const Metrics* metric = nullptr);

// Metric-directed refinement of the marked elements: in a marked element e, every edge whose
// metric length is at least `theta` times the element's largest metric edge length is bisected
// (with metric[e] = identity and theta = 1 this is longest-edge bisection without closure).
// With the shape metric of the dissipation Hessian the edges crossing a shear band are cut and
// the edges along it kept, so the children are stretched along the band (up to max_aspect).
// Then `swap_passes` passes of edge swapping toward the metric (see swap_edges; children inherit
// the metric of their parent).
Mesh refine_anisotropic(const Mesh& mesh, const std::vector<int>& marked, const Metrics& metric, double theta = 0.75,
                        int swap_passes = 0);

// Edge swapping toward a metric per element: an interior edge of two triangles forming a convex
// quadrilateral is replaced by the other diagonal when that raises the smaller of the two metric
// qualities 4√3 A_M / Σ l_M² by more than 5% (mean metric of the pair). Boundary edges and
// vertices are kept, so boundary tags and breakpoints survive.
Mesh swap_edges(const Mesh& mesh, const Metrics& metric, int passes = 3);

// Shape of an element (vertex triangle): aspect = √(I_max/I_min) of the second moment of area
// about the centroid (1 for an equilateral triangle), angle of the long axis in
// (−π/2, π/2] from the x axis.
struct ElementShape {
  double aspect = 1.0;
  double angle = 0.0;
};
ElementShape element_shape(const Mesh& mesh, int e);

// Nodes on the boundary whose coordinates satisfy pred (vertex and mid-side nodes).
std::vector<int> boundary_nodes(const Mesh& mesh, const std::function<bool(const Eigen::Vector2d&)>& pred);

}  // namespace cutbench::limit
