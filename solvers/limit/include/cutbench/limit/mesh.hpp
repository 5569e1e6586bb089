#pragma once
// Six-node triangle (T6) meshes and a simple structured triangulator.
//
// Node numbering of an element: vertices 0, 1, 2 counter-clockwise, then the mid-side nodes
// 3 (edge 0-1), 4 (edge 1-2), 5 (edge 2-0). Mid-side nodes lie at the edge midpoints.
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

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

// Nodes on the boundary whose coordinates satisfy pred (vertex and mid-side nodes).
std::vector<int> boundary_nodes(const Mesh& mesh, const std::function<bool(const Eigen::Vector2d&)>& pred);

}  // namespace cutbench::limit
