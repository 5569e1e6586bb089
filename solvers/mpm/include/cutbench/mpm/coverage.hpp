#pragma once
// Fig 2 metric: how well the deformed particle domains fill space. Each particle's domain is the
// parallelogram F * (square of side `size`) about its centre. On a raster (pixel = size/res) over
// the bounding box of the selected particles:
//   overlap fraction = pixels covered twice or more / pixels covered at least once,
//   gap fraction     = uncovered pixels enclosed by material (covered at distance `size` on both
//                      sides, left-right or up-down) / pixels covered at least once.
// A good update fills space with no gaps and no overlaps (both 0 for an affine deformation).
#include <cstddef>
#include <vector>

namespace cutbench::mpm {

struct DomainCoverage {
  double gap_fraction = 0.0;
  double overlap_fraction = 0.0;
  std::size_t particles = 0;
};

// x, y, F (xx, xy, yx, yy per particle), `use` selects particles (empty: all).
DomainCoverage domain_coverage(const std::vector<double>& x, const std::vector<double>& y,
                               const std::vector<double>& Fxx, const std::vector<double>& Fxy,
                               const std::vector<double>& Fyx, const std::vector<double>& Fyy,
                               const std::vector<bool>& use, double size, int res = 8);

}  // namespace cutbench::mpm
