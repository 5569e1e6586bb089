#include "cutbench/sph/tool.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cutbench/common/errors.hpp"

namespace cutbench::sph {

HalfPlane::HalfPlane(const Vec2& point, const Vec2& outward_normal) : p_(point), n_(outward_normal.normalized()) {}

SignedDistance HalfPlane::at(const Vec2& x) const { return {n_.dot(x - p_), n_}; }

RoundedPolygon::RoundedPolygon(std::vector<Vec2> vertices, double radius) : v_(std::move(vertices)), r_(radius) {
  if (v_.size() < 3) throw InputError("tool", "a polygon needs at least three vertices");
  if (!(r_ >= 0.0)) throw InputError("edge_radius", "must be >= 0");
  for (std::size_t k = 0; k < v_.size(); ++k) {
    const Vec2 a = v_[(k + 1) % v_.size()] - v_[k], b = v_[(k + 2) % v_.size()] - v_[(k + 1) % v_.size()];
    if (a.x() * b.y() - a.y() * b.x() <= 0.0)
      throw InputError("tool", "polygon must be convex with counter-clockwise vertices");
  }
}

SignedDistance RoundedPolygon::at(const Vec2& x) const {
  const std::size_t m = v_.size();
  double best = std::numeric_limits<double>::infinity();
  Vec2 closest = Vec2::Zero();
  bool inside = true;
  double max_plane = -std::numeric_limits<double>::infinity();
  Vec2 plane_normal = Vec2::Zero();
  for (std::size_t k = 0; k < m; ++k) {
    const Vec2 a = v_[k], b = v_[(k + 1) % m];
    const Vec2 e = b - a;
    const Vec2 out(e.y(), -e.x());  // outward for CCW
    const Vec2 on = out.normalized();
    const double plane = on.dot(x - a);
    if (plane > 0.0) inside = false;
    if (plane > max_plane) {
      max_plane = plane;
      plane_normal = on;
    }
    const double t = std::clamp((x - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const Vec2 c = a + t * e;
    const double d = (x - c).squaredNorm();
    if (d < best) {
      best = d;
      closest = c;
    }
  }
  SignedDistance s;
  if (inside) {
    s.distance = max_plane - r_;
    s.normal = plane_normal;
  } else {
    const double d = std::sqrt(best);
    s.distance = d - r_;
    s.normal = d > 0.0 ? Vec2((x - closest) / d) : plane_normal;
  }
  return s;
}

std::unique_ptr<RoundedPolygon> cutting_tool(double rake, double clearance, double edge_radius, const Vec2& lowest,
                                             double extent) {
  if (!(clearance > 0.0 && clearance < 1.5) || !(std::abs(rake) < 1.2))
    throw InputError("tool", "clearance must be in (0, 86 deg) and |rake| < 69 deg");
  if (!(extent > 10.0 * edge_radius)) throw InputError("extent", "tool body must be much larger than the edge radius");
  // Inner wedge apex q (faces offset inwards by r): the lowest point of the rounded edge is q - r e_y
  // as long as -e_y lies between the two face normals (true for the admissible angles).
  const Vec2 q = lowest + Vec2(0.0, edge_radius);
  const Vec2 d_rake(std::sin(rake), std::cos(rake));          // up along the rake face
  const Vec2 d_clear(std::cos(clearance), std::sin(clearance));  // right along the clearance face
  const Vec2 a = q;
  const Vec2 b = q + extent * d_clear;
  const Vec2 c = b + Vec2(0.0, extent);
  const Vec2 top = q + extent * d_rake;
  const Vec2 d(c.x(), std::max(c.y(), top.y()));
  std::vector<Vec2> poly{a, b, d, top};
  return std::make_unique<RoundedPolygon>(std::move(poly), edge_radius);
}

}  // namespace cutbench::sph
