#include "cutbench/sph/lattice.hpp"

#include <cmath>

#include "cutbench/common/errors.hpp"

namespace cutbench::sph {

std::vector<Vec2> rectangle_lattice(std::size_t nx, std::size_t ny, double x0, double x1, double y0,
                                    double y1) {
  if (nx < 2 || ny < 2) throw InputError("n", "a lattice needs at least 2 particles per side");
  std::vector<Vec2> x;
  x.reserve(nx * ny);
  const double dx = (x1 - x0) / static_cast<double>(nx - 1);
  const double dy = (y1 - y0) / static_cast<double>(ny - 1);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      x.emplace_back(x0 + dx * static_cast<double>(i), y0 + dy * static_cast<double>(j));
  return x;
}

std::vector<Vec2> disc_rings(std::size_t rings, double dx, const Vec2& centre, std::vector<double>& volume) {
  constexpr double kPi = 3.14159265358979323846;
  std::vector<Vec2> x{centre};
  volume.assign(1, kPi * 0.25 * dx * dx);
  for (std::size_t k = 1; k <= rings; ++k) {
    const double r = dx * static_cast<double>(k);
    const auto m = static_cast<std::size_t>(std::lround(2.0 * kPi * static_cast<double>(k)));
    const double area = kPi * ((r + 0.5 * dx) * (r + 0.5 * dx) - (r - 0.5 * dx) * (r - 0.5 * dx));
    const double phase = 0.5 * static_cast<double>(k % 2) * 2.0 * kPi / static_cast<double>(m);
    for (std::size_t q = 0; q < m; ++q) {
      const double t = phase + 2.0 * kPi * static_cast<double>(q) / static_cast<double>(m);
      x.push_back(centre + r * Vec2(std::cos(t), std::sin(t)));
      volume.push_back(area / static_cast<double>(m));
    }
  }
  return x;
}

void jitter(std::vector<Vec2>& x, double amplitude, std::uint64_t seed) {
  std::uint64_t state = seed;
  auto next = [&state]() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;  // [0, 1)
  };
  for (auto& p : x) {
    const double u = next(), v = next();
    p += amplitude * Vec2(2.0 * u - 1.0, 2.0 * v - 1.0);
  }
}

}  // namespace cutbench::sph
