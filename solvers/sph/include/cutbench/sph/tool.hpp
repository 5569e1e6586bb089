#pragma once
// Rigid tool geometry as a signed distance (positive outside, normal pointing out of the tool) and
// the contact law between SPH particles and a translating rigid tool.
#include <memory>
#include <vector>

#include "cutbench/sph/kernel.hpp"

namespace cutbench::sph {

struct SignedDistance {
  double distance = 0.0;  // > 0 outside the tool
  Vec2 normal = Vec2::Zero();  // unit, out of the tool
};

class ToolGeometry {
public:
  virtual ~ToolGeometry() = default;
  virtual SignedDistance at(const Vec2& x) const = 0;  // in the tool frame
};

// Half-plane {x : n . (x - p) <= 0} (the solid side is opposite to n).
class HalfPlane final : public ToolGeometry {
public:
  HalfPlane(const Vec2& point, const Vec2& outward_normal);
  SignedDistance at(const Vec2& x) const override;

private:
  Vec2 p_, n_;
};

// Convex polygon (vertices counter-clockwise) grown by a radius: rounded corners of that radius.
class RoundedPolygon final : public ToolGeometry {
public:
  RoundedPolygon(std::vector<Vec2> vertices, double radius);
  SignedDistance at(const Vec2& x) const override;
  const std::vector<Vec2>& vertices() const { return v_; }
  double radius() const { return r_; }

private:
  std::vector<Vec2> v_;
  double r_;
};

// Orthogonal-cutting tool (paper Fig 4) cutting in the -x direction: rake face facing -x, tilted
// by the rake angle; clearance face facing down, rising at the clearance angle towards +x; edge
// rounded with edge_radius. `lowest` is the lowest point of the rounded edge (it sits on the
// machined surface); `extent` is the size of the tool body.
std::unique_ptr<RoundedPolygon> cutting_tool(double rake, double clearance, double edge_radius, const Vec2& lowest,
                                             double extent);

// Particle-tool contact (velocity level, applied after each step): a particle whose gap
// g = d - offset is negative and that approaches the tool gets the normal impulse that removes the
// approach and pushes it out at -kappa g / dt; the tangential impulse sticks it or, beyond
// mu times the normal impulse, lets it slip (Coulomb). Friction heat per particle:
// eta |f_t| |v_slip| (Eq. 6 with v_rel the slip velocity after the impulse).
//
// Alternative (model = penalty): a force-level penalty contact, f_N = -alpha m g / dt^2 n for g < 0,
// with the elastic-plastic (stick-slip) friction of the LS-DYNA theory manual: trial force
// f* = f_t,old - alpha m v_t / dt, f_t = f* if |f*| <= mu |f_N| else mu |f_N| f*/|f*|; the
// friction force is remembered per particle. Applied with the other forces (in a^{n+1}). Friction
// heat = f_y x plastic slip, slip = (|f*| - f_y) / k_t, k_t = alpha m / dt^2 (elastic stick stores).
enum class ContactModel { velocity, penalty };

struct ContactOptions {
  ContactModel model = ContactModel::velocity;
  double friction = 0.35;   // mu
  double heat_fraction = 1.0;  // eta
  // Share of the friction heat that goes to the tool (when the tool conducts, set_tool_thermal).
  // Negative (default): the effusivity partition beta = e_tool / (e_tool + e_work), e = sqrt(k rho c)
  // -- the split for two bodies in perfect thermal contact that gives both faces the same
  // temperature rise under a common plane source (Carslaw & Jaeger; Blok's partition for a
  // stationary source). With Table 1 (and the assumed tool density) beta = 0.82. The tool share is
  // deposited on the tool particles within the kernel support of the heated workpiece particle,
  // kernel-weighted, at the next conduction update. Without tool conduction all heat goes to the
  // workpiece particle.
  double tool_heat_share = -1.0;
  // Zorev-type cap of the friction stress by the shear flow stress of the chip: |f_t| <= k(T) l,
  // k = sigma_y(eps_p, T) / sqrt(3), l = dx (the face length a particle covers). Off by default (the
  // paper states a constant Coulomb mu).
  bool shear_cap = false;
  double kappa = 0.5;            // velocity model: push-out rate
  double alpha = 0.1;            // penalty model: stiffness scale
  double offset_fraction = 0.5;  // offset = fraction * dx (particles represent a cell of side dx)
};

}  // namespace cutbench::sph
