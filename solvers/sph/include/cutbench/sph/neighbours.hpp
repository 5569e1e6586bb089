#pragma once
// Cell-list neighbour search. The list is stored in compressed rows: the neighbours of i are
// index[offset[i] .. offset[i+1]), sorted by ascending j, j != i, |x_i - x_j| < radius. The order
// does not depend on the thread count, so sums over neighbours are bitwise reproducible.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cutbench/sph/kernel.hpp"

namespace cutbench::sph {

struct NeighbourList {
  std::vector<std::size_t> offset;   // size n + 1
  std::vector<std::uint32_t> index;  // neighbour ids

  std::size_t size() const { return offset.empty() ? 0 : offset.size() - 1; }
  std::size_t begin(std::size_t i) const { return offset[i]; }
  std::size_t end(std::size_t i) const { return offset[i + 1]; }
  std::size_t count(std::size_t i) const { return offset[i + 1] - offset[i]; }
};

// Square cells of side `radius` over the bounding box of x; each particle scans the 3x3 block.
NeighbourList build_neighbours(const std::vector<Vec2>& x, double radius);

// Neighbours of each particle of `a` among the particles of `b` (rows for a, ids into b, sorted).
NeighbourList build_cross_neighbours(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double radius);

// O(n^2) reference used by the tests.
NeighbourList build_neighbours_brute_force(const std::vector<Vec2>& x, double radius);

}  // namespace cutbench::sph
