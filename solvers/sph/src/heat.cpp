#include "cutbench/sph/heat.hpp"

#include <cmath>

#include "cutbench/common/errors.hpp"

namespace cutbench::sph {

HeatConduction::HeatConduction(std::vector<Vec2> x, std::vector<double> volume, double h,
                               HeatMaterial material, HeatBoundary boundary, HeatOptions options)
    : x_(std::move(x)), V_(std::move(volume)), kernel_(h), mat_(material), bc_(boundary), opt_(options) {
  if (V_.size() != x_.size()) throw InputError("volume", "size differs from the particle count");
  if (!(mat_.conductivity > 0.0) || !(mat_.density > 0.0) || !(mat_.specific_heat > 0.0))
    throw InputError("material", "k, rho and c_p must be positive");
  if (!(bc_.h_conv >= 0.0) || !(bc_.emissivity >= 0.0 && bc_.emissivity <= 1.0))
    throw InputError("boundary", "h_c must be >= 0 and the emissivity in [0, 1]");
  if (!(opt_.cfl > 0.0)) throw InputError("cfl", "must be positive");
  fixed_.assign(x_.size(), 0);
  T_.assign(x_.size(), bc_.T_ambient);
}

void HeatConduction::set_dirichlet(std::vector<char> fixed, Field value) {
  if (fixed.size() != x_.size()) throw InputError("dirichlet", "mask size differs from the particle count");
  fixed_ = std::move(fixed);
  dirichlet_value_ = std::move(value);
  ready_ = false;
}

void HeatConduction::set_temperature(std::vector<double> T) {
  if (T.size() != x_.size()) throw InputError("temperature", "size differs from the particle count");
  T_ = std::move(T);
}

void HeatConduction::set_temperature(const Field& initial) {
  for (std::size_t i = 0; i < x_.size(); ++i) T_[i] = initial(x_[i], time_);
}

void HeatConduction::setup() {
  nl_ = build_neighbours(x_, kernel_.support());
  const ParticleView view{x_, V_, nl_, kernel_};
  surface_ = detect_free_surface(view, opt_.surface);
  if (opt_.scheme == HeatScheme::fmfs) fmfs_.update(view);
  const std::size_t n = x_.size();
  loss_.assign(n, 0);
  use_fmfs_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    loss_[i] = surface_.surface[i] && !fixed_[i];
    use_fmfs_[i] = !surface_.surface[i];
    if (opt_.brookshaw_band)
      for (std::size_t k = nl_.begin(i); k < nl_.end(i); ++k)
        if (surface_.surface[nl_.index[k]]) use_fmfs_[i] = 0;
  }
  ready_ = true;
  apply_dirichlet();
}

void HeatConduction::apply_dirichlet() {
  if (!dirichlet_value_) return;
  for (std::size_t i = 0; i < x_.size(); ++i)
    if (fixed_[i]) T_[i] = dirichlet_value_(x_[i], time_);
}

double HeatConduction::stable_time_step() const {
  return opt_.cfl * kernel_.h() * kernel_.h() / mat_.diffusivity();
}

double HeatConduction::surface_flux(double T) const {
  const double t4 = T * T * T * T, a4 = bc_.T_ambient * bc_.T_ambient * bc_.T_ambient * bc_.T_ambient;
  return bc_.h_conv * (T - bc_.T_ambient) + bc_.emissivity * kStefanBoltzmann * (t4 - a4);
}

std::vector<double> HeatConduction::rate(double& heat_loss_rate) {
  if (!ready_) throw InputError("heat", "setup() must be called before stepping");
  const ParticleView view{x_, V_, nl_, kernel_};
  std::vector<double> lap;
  if (opt_.scheme == HeatScheme::fmfs) {
    lap = fmfs_.laplacian(view, T_, &use_fmfs_, &fmfs_used_);
  } else {
    lap = laplacian_brookshaw(view, T_);
    fmfs_used_.assign(x_.size(), 0);
  }
  const double alpha = mat_.diffusivity(), rc = mat_.density * mat_.specific_heat;
  double loss = 0.0;
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (fixed_[i]) {
      lap[i] = 0.0;
      continue;
    }
    double d = alpha * lap[i];
    if (loss_[i]) {
      const double l = std::sqrt(V_[i]);
      const double q = surface_flux(T_[i]);
      d -= q * l / (V_[i] * rc);
      loss += q * l;
    }
    lap[i] = d;
  }
  heat_loss_rate = loss;
  return lap;
}

void HeatConduction::step(double dt) {
  if (!(dt > 0.0)) throw InputError("dt", "time step must be positive");
  double loss = 0.0;
  const std::vector<double> d = rate(loss);
  for (std::size_t i = 0; i < x_.size(); ++i) T_[i] += dt * d[i];
  for (double t : T_)
    if (!std::isfinite(t)) throw NumericalError("sph heat: non-finite temperature (time step too large?)");
  lost_ += dt * loss;
  time_ += dt;
  ++steps_;
  apply_dirichlet();
}

void HeatConduction::advance_to(double t_end) {
  const double dt = stable_time_step();
  while (time_ < t_end * (1.0 - 1e-12)) step(std::min(dt, t_end - time_));
}

double HeatConduction::thermal_energy() const {
  const double rc = mat_.density * mat_.specific_heat;
  double e = 0.0;
  for (std::size_t i = 0; i < x_.size(); ++i)
    if (!fixed_[i]) e += rc * V_[i] * T_[i];
  return e;
}

}  // namespace cutbench::sph
