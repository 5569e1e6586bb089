#pragma once
// Particle arrangements used by the verification runners and tests.
#include <cstdint>
#include <vector>

#include "cutbench/sph/kernel.hpp"

namespace cutbench::sph {

// n_x x n_y particles on [x0, x1] x [y0, y1] including the end points (spacing (x1-x0)/(n_x-1)),
// row-major with x fastest.
std::vector<Vec2> rectangle_lattice(std::size_t nx, std::size_t ny, double x0, double x1, double y0,
                                    double y1);

// Concentric rings of spacing dx about `centre`: a centre particle, then ring k (radius k dx)
// holding round(2 pi k) particles, k = 1..rings. Volumes (annulus area / count) in `volume`.
std::vector<Vec2> disc_rings(std::size_t rings, double dx, const Vec2& centre, std::vector<double>& volume);

// Uniform random displacement in [-amplitude, amplitude]^2 from a splitmix64 stream (identical
// on every platform for the same seed).
void jitter(std::vector<Vec2>& x, double amplitude, std::uint64_t seed);

}  // namespace cutbench::sph
