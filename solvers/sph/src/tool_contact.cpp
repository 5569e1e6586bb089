#include "cutbench/sph/tool_contact.hpp"

#include <algorithm>
#include <cmath>

#include "cutbench/common/errors.hpp"
#include "parallel.hpp"

namespace cutbench::sph {

void ToolContact::set(std::shared_ptr<const ToolGeometry> tool, const Vec2& start, const Vec2& tool_velocity,
                      ContactOptions options) {
  if (!tool) throw InputError("tool", "null tool geometry");
  if (!(options.friction >= 0.0) || !(options.kappa > 0.0 && options.kappa <= 1.0) ||
      !(options.alpha > 0.0 && options.alpha <= 1.0))
    throw InputError("contact", "mu >= 0, 0 < kappa <= 1 and 0 < alpha <= 1 required");
  tool_ = std::move(tool);
  position = start;
  velocity = tool_velocity;
  options_ = options;
}

void ToolContact::velocity_level(double dt, double dx, const std::vector<Vec2>& x, std::vector<Vec2>& v,
                                 const std::vector<double>& m, const std::vector<char>& fixed, const CapFn& cap,
                                 const HeatFn& heat) {
  position += dt * velocity;
  const double offset = options_.offset_fraction * dx;
  Vec2 total = Vec2::Zero();
  contacts_.clear();
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (fixed[i]) continue;
    const SignedDistance sd = tool_->at(x[i] - position);
    const double g = sd.distance - offset;
    if (g >= 0.0) continue;
    const Vec2 vrel = v[i] - velocity;
    const double vn = vrel.dot(sd.normal);
    const double target = std::max(vn, -options_.kappa * g / dt);
    const double jn = m[i] * (target - vn);
    if (jn <= 0.0) continue;
    const Vec2 vt = vrel - vn * sd.normal;
    Vec2 jt = -m[i] * vt;
    const double limit = std::min(options_.friction * jn, cap(i) * dt);
    if (jt.norm() > limit) jt *= limit / jt.norm();
    const Vec2 impulse = jn * sd.normal + jt;
    v[i] += impulse / m[i];
    total -= impulse / dt;
    contacts_.push_back({i, sd.normal, (jn / dt) * sd.normal, jt / dt, limit / dt});
    const Vec2 vrel_after = v[i] - velocity;
    const double slip = (vrel_after - vrel_after.dot(sd.normal) * sd.normal).norm();
    heat(i, options_.heat_fraction * jt.norm() * slip);  // J/m over this step
  }
  force = total;
}

void ToolContact::penalty(double dt, double dx, const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                          const std::vector<double>& m, const std::vector<char>& fixed, std::vector<Vec2>& a,
                          const CapFn& cap, const HeatFn& heat) {
  // positions are x^{n+1}; the tool is at its position of time + dt
  const Vec2 tool_pos = position + dt * velocity;
  const double offset = options_.offset_fraction * dx;
  if (friction_history.size() != x.size()) friction_history.assign(x.size(), Vec2::Zero());
  Vec2 total = Vec2::Zero();
  contacts_.clear();
  if (screen_gap.size() != x.size()) {
    screen_gap.assign(x.size(), 0.0);
    screen_p.assign(x.size(), Vec2::Zero());
  }
  // Screening and the tool's signed distance per particle in parallel (pure), then the contacts
  // in index order on one thread (forces, friction heat and the contact list in the same order as
  // a serial loop).
  const std::size_t n = x.size();
  sd_.resize(n);
  eval_.resize(n);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    eval_[i] = 0;
    if (fixed[i]) continue;
    const Vec2 p = x[i] - tool_pos;
    // screening: the signed distance is 1-Lipschitz, so g(p) >= gap_last - |p - p_last| > 0
    // (friction history already zero from that evaluation); margin against round-off
    const double gl = screen_gap[i];
    if (gl > 0.0 && (p - screen_p[i]).squaredNorm() < 0.81 * gl * gl) continue;
    sd_[i] = tool_->at(p);
    eval_[i] = 1;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!eval_[i]) continue;
    const Vec2 p = x[i] - tool_pos;
    const SignedDistance& sd = sd_[i];
    const double g = sd.distance - offset;
    screen_p[i] = p;
    screen_gap[i] = g;
    if (g >= 0.0) {
      friction_history[i] = Vec2::Zero();
      continue;
    }
    const Vec2 fn = (-options_.alpha * m[i] * g / (dt * dt)) * sd.normal;
    const Vec2 vrel = v[i] - velocity;
    const Vec2 vt = vrel - vrel.dot(sd.normal) * sd.normal;
    Vec2 ft = friction_history[i] - (options_.alpha * m[i] / dt) * vt;
    const double fy = std::min(options_.friction * fn.norm(), cap(i));
    // Only the plastic (slip) part of the tangential motion dissipates: slip = (|f*| - f_y) / k_t
    // with the tangential stiffness k_t = alpha m / dt^2; the elastic stick part is stored.
    double q = 0.0;
    const double ftrial = ft.norm();
    if (ftrial > fy) {
      const double kt = options_.alpha * m[i] / (dt * dt);
      q = options_.heat_fraction * fy * (ftrial - fy) / kt;  // J/m over this step
      ft *= fy / ftrial;
    }
    friction_history[i] = ft;
    a[i] += (fn + ft) / m[i];
    total -= fn + ft;
    contacts_.push_back({i, sd.normal, fn, ft, fy});
    heat(i, q);
  }
  force = total;
}

}  // namespace cutbench::sph
