#pragma once
// Tool contact, a component of SolidSph (set_tool): the rigid tool's geometry, position, velocity
// and the contact force on it; the velocity-level contact (impulses) or the penalty contact with
// stick-slip Coulomb friction (forces), each limited by an optional shear cap and depositing the
// friction heat through the caller (SolidSph splits it between workpiece and tool).
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "cutbench/sph/tool.hpp"

namespace cutbench::sph {

// One contact of the last step: forces act on the particle (N/m); `limit` is the Coulomb bound
// mu |f_n| in force (the velocity model's impulse bound over dt).
struct ContactRecord {
  std::size_t particle = 0;
  Vec2 normal = Vec2::Zero();  // out of the tool
  Vec2 fn = Vec2::Zero(), ft = Vec2::Zero();
  double limit = 0.0;
};

class ToolContact {
public:
  using CapFn = std::function<double(std::size_t)>;           // bound of |f_t| of particle i, N/m
  using HeatFn = std::function<void(std::size_t, double)>;    // friction heat of particle i, J/m

  void set(std::shared_ptr<const ToolGeometry> tool, const Vec2& start, const Vec2& tool_velocity,
           ContactOptions options);
  bool active() const { return static_cast<bool>(tool_); }
  const ToolGeometry& geometry() const { return *tool_; }
  const ContactOptions& options() const { return options_; }

  // Velocity level: the tool moves by dt first, then penetrating particles get impulses (normal
  // to the gap-closing velocity, tangential up to mu j_n and the cap).
  void velocity_level(double dt, double dx, const std::vector<Vec2>& x, std::vector<Vec2>& v,
                      const std::vector<double>& m, const std::vector<char>& fixed, const CapFn& cap,
                      const HeatFn& heat);
  // Penalty at the positions x^{n+1} with the tool at its position of the end of the step (it
  // moves by dt afterwards, advance()): normal force alpha m g / dt^2, stick-slip friction with
  // history; the forces are added to a.
  void penalty(double dt, double dx, const std::vector<Vec2>& x, const std::vector<Vec2>& v,
               const std::vector<double>& m, const std::vector<char>& fixed, std::vector<Vec2>& a, const CapFn& cap,
               const HeatFn& heat);
  void advance(double dt) { position += dt * velocity; }

  const std::vector<ContactRecord>& contacts() const { return contacts_; }

  // State carried from step to step (checkpoints): screening memory and friction history.
  Vec2 position = Vec2::Zero(), velocity = Vec2::Zero(), force = Vec2::Zero();  // force on the tool
  std::vector<Vec2> screen_p, friction_history;
  std::vector<double> screen_gap;

private:
  std::shared_ptr<const ToolGeometry> tool_;
  ContactOptions options_;
  std::vector<ContactRecord> contacts_;  // reused every step (capacity kept)
  // contact screening: relative position (particle - tool) and gap at the last evaluation of the
  // tool's signed distance; the distance is 1-Lipschitz, so while |p - p_last| < gap_last the
  // particle cannot touch the tool and the evaluation is skipped (exact)
  std::vector<SignedDistance> sd_;  // per step: the tool's signed distance where evaluated
  std::vector<char> eval_;
};

}  // namespace cutbench::sph
