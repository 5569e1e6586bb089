#include "cutbench/sph/neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cutbench/common/errors.hpp"
#include "parallel.hpp"

namespace cutbench::sph {

NeighbourList build_neighbours(const std::vector<Vec2>& x, double radius) {
  if (!(radius > 0.0)) throw InputError("radius", "neighbour radius must be positive");
  if (x.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InputError("particles", "too many particles for 32-bit neighbour ids");
  const std::size_t n = x.size();
  NeighbourList nl;
  nl.offset.assign(n + 1, 0);
  if (n == 0) return nl;

  Vec2 lo = x[0], hi = x[0];
  for (const auto& p : x) {
    if (!p.allFinite()) throw NumericalError("sph neighbour search: non-finite particle position");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double span_x = (hi.x() - lo.x()) / radius, span_y = (hi.y() - lo.y()) / radius;
  if (span_x * span_y > 1e8)
    throw NumericalError("sph neighbour search: bounding box too large for a dense cell grid");
  const long nx = static_cast<long>(std::floor(span_x)) + 1;
  const long ny = static_cast<long>(std::floor(span_y)) + 1;
  auto cell_of = [&](const Vec2& p, long& cx, long& cy) {
    cx = std::min(nx - 1, static_cast<long>(std::floor((p.x() - lo.x()) / radius)));
    cy = std::min(ny - 1, static_cast<long>(std::floor((p.y() - lo.y()) / radius)));
  };

  // Counting sort of particles into cells (ascending id inside each cell).
  std::vector<std::size_t> cell_start(static_cast<std::size_t>(nx * ny) + 1, 0);
  std::vector<std::size_t> cell_id(n);
  for (std::size_t i = 0; i < n; ++i) {
    long cx, cy;
    cell_of(x[i], cx, cy);
    cell_id[i] = static_cast<std::size_t>(cy * nx + cx);
    ++cell_start[cell_id[i] + 1];
  }
  for (std::size_t c = 1; c < cell_start.size(); ++c) cell_start[c] += cell_start[c - 1];
  std::vector<std::uint32_t> sorted(n);
  {
    std::vector<std::size_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) sorted[fill[cell_id[i]]++] = static_cast<std::uint32_t>(i);
  }

  const double r2 = radius * radius;
  // Two passes over the 3x3 cell blocks: count, then fill (no per-row allocations).
  auto visit = [&](std::size_t i, auto&& emit) {
    long cx, cy;
    cell_of(x[i], cx, cy);
    for (long dy = -1; dy <= 1; ++dy) {
      const long yy = cy + dy;
      if (yy < 0 || yy >= ny) continue;
      for (long dx = -1; dx <= 1; ++dx) {
        const long xx = cx + dx;
        if (xx < 0 || xx >= nx) continue;
        const auto c = static_cast<std::size_t>(yy * nx + xx);
        for (std::size_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
          const std::uint32_t j = sorted[k];
          if (j != i && (x[i] - x[j]).squaredNorm() < r2) emit(j);
        }
      }
    }
  };
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t count = 0;
    visit(i, [&count](std::uint32_t) { ++count; });
    nl.offset[i + 1] = count;
  }
  for (std::size_t i = 0; i < n; ++i) nl.offset[i + 1] += nl.offset[i];
  nl.index.resize(nl.offset[n]);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t pos = nl.offset[i];
    visit(i, [&](std::uint32_t j) { nl.index[pos++] = j; });
    std::sort(nl.index.begin() + static_cast<std::ptrdiff_t>(nl.offset[i]),
              nl.index.begin() + static_cast<std::ptrdiff_t>(nl.offset[i + 1]));
  }
  return nl;
}

NeighbourList build_cross_neighbours(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double radius) {
  // Simple and sufficient for the tool band: index b by cells, query every a.
  NeighbourList nl;
  nl.offset.assign(a.size() + 1, 0);
  if (a.empty() || b.empty()) return nl;
  if (!(radius > 0.0)) throw InputError("radius", "neighbour radius must be positive");
  Vec2 lo = b[0], hi = b[0];
  for (const auto& p : b) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const long nx = static_cast<long>(std::floor((hi.x() - lo.x()) / radius)) + 1;
  const long ny = static_cast<long>(std::floor((hi.y() - lo.y()) / radius)) + 1;
  if (static_cast<double>(nx) * static_cast<double>(ny) > 1e8)
    throw NumericalError("sph cross neighbour search: bounding box too large");
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(nx * ny));
  for (std::size_t j = 0; j < b.size(); ++j) {
    const long cx = std::min(nx - 1, static_cast<long>(std::floor((b[j].x() - lo.x()) / radius)));
    const long cy = std::min(ny - 1, static_cast<long>(std::floor((b[j].y() - lo.y()) / radius)));
    cells[static_cast<std::size_t>(cy * nx + cx)].push_back(static_cast<std::uint32_t>(j));
  }
  const double r2 = radius * radius;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const long cx = static_cast<long>(std::floor((a[i].x() - lo.x()) / radius));
    const long cy = static_cast<long>(std::floor((a[i].y() - lo.y()) / radius));
    const std::size_t start = nl.index.size();
    for (long yy = cy - 1; yy <= cy + 1; ++yy) {
      if (yy < 0 || yy >= ny) continue;
      for (long xx = cx - 1; xx <= cx + 1; ++xx) {
        if (xx < 0 || xx >= nx) continue;
        for (std::uint32_t j : cells[static_cast<std::size_t>(yy * nx + xx)])
          if ((a[i] - b[j]).squaredNorm() < r2) nl.index.push_back(j);
      }
    }
    std::sort(nl.index.begin() + static_cast<std::ptrdiff_t>(start), nl.index.end());
    nl.offset[i + 1] = nl.index.size();
  }
  return nl;
}

NeighbourList build_neighbours_brute_force(const std::vector<Vec2>& x, double radius) {
  const std::size_t n = x.size();
  NeighbourList nl;
  nl.offset.assign(n + 1, 0);
  const double r2 = radius * radius;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (j != i && (x[i] - x[j]).squaredNorm() < r2) nl.index.push_back(static_cast<std::uint32_t>(j));
    }
    nl.offset[i + 1] = nl.index.size();
  }
  return nl;
}

}  // namespace cutbench::sph
