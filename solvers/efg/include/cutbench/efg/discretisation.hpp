#pragma once
// EFG discretisation: nodes with their support radii, background quadrilateral cells with
// 2 x 2 Gauss points (Kahwash 2018, section 3.1, Eq 54), and the shape functions at those points.
#include <array>
#include <vector>

#include "cutbench/efg/mls.hpp"

namespace cutbench::efg {

struct GaussPoint {
  Vec2 x = Vec2::Zero();
  double weight = 0.0;  // Gauss weight x |J| (area per unit thickness)
  int cell = -1;
};

struct Discretisation {
  std::vector<Vec2> nodes;
  std::vector<double> support;                 // D_I, domain-of-influence radius per node
  std::vector<std::array<int, 4>> cells;       // background cells (counter-clockwise vertices)
  std::vector<Vec2> cell_vertices;             // cell vertex coordinates
  std::vector<GaussPoint> gauss;
  double spacing = 0.0;                        // characteristic nodal spacing h
};

// Regular nx x ny node grid on [0,Lx] x [0,Ly]; support D_I = support_factor * max(hx, hy);
// interior nodes jittered by up to `jitter` * h (uniform, deterministic seed). Background cells:
// the regular (nx-1) x (ny-1) grid of the unjittered lattice, ng x ng Gauss points per cell.
Discretisation rectangle(double Lx, double Ly, int nx, int ny, double support_factor,
                         double jitter = 0.0, unsigned seed = 1, int ng = 2);

// Gauss points of a straight boundary segment [a, b] split into nseg pieces with ng points each
// (weights are lengths), for traction integrals.
std::vector<GaussPoint> line_gauss(const Vec2& a, const Vec2& b, int nseg, int ng = 2);

// Rectangle with a rectangular notch removed from its top-left corner: the lattice of
// `rectangle` without the nodes strictly inside {x < notch_x, y > notch_y} and without the cells
// that have a vertex there (the already-cut part of a cutting workpiece, Kahwash 2018 section 5.1:
// the cut starts inside the workpiece). Node spacings hx = Lx/(nx-1), hy = Ly/(ny-1).
Discretisation notched_rectangle(double Lx, double Ly, int nx, int ny, double support_factor, double notch_x,
                                 double notch_y, int ng = 2);

// Where the visibility criterion is decided: material positions of the points and nodes (the
// configuration in which the opaque segments are given), when these differ from the positions the
// shape functions are built on (updated Lagrangian: a crack is a material surface).
struct VisibilityFrame {
  const std::vector<Vec2>* points = nullptr;
  const std::vector<Vec2>* nodes = nullptr;
};

// Shape functions at each point; throws NumericalError naming the point when the MLS fit fails.
// With opaque segments the visibility criterion removes hidden nodes from each support, tested
// between `frame`'s positions when given, else between `points` and `nodes`.
std::vector<ShapeData> shape_functions(const std::vector<Vec2>& points, const std::vector<Vec2>& nodes,
                                       const std::vector<double>& support, const WeightParams& weight,
                                       bool derivatives = true, const std::vector<Segment>& opaque = {},
                                       const VisibilityFrame& frame = {});
// The same into `out` (resized to the points): each entry's storage is reused, so a rebuild of
// shape functions already held allocates nothing (the updated-Lagrangian reference updates).
void shape_functions_into(const std::vector<Vec2>& points, const std::vector<Vec2>& nodes,
                          const std::vector<double>& support, const WeightParams& weight, bool derivatives,
                          const std::vector<Segment>& opaque, const VisibilityFrame& frame,
                          std::vector<ShapeData>& out);

// Gauss-Legendre points and weights on [-1, 1] for n = 1..4.
void gauss_legendre(int n, std::vector<double>& xi, std::vector<double>& w);

}  // namespace cutbench::efg
