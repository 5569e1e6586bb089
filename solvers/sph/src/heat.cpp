#include "cutbench/sph/heat.hpp"

#include <cmath>

#include "cutbench/common/errors.hpp"
#include "parallel.hpp"

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
  heat_masks(nl_, surface_, fixed_, opt_.brookshaw_band, opt_.surface.lambda_interior, use_fmfs_, loss_);
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

double surface_flux(const HeatBoundary& bc, double T) {
  const double t4 = T * T * T * T, a4 = bc.T_ambient * bc.T_ambient * bc.T_ambient * bc.T_ambient;
  return bc.h_conv * (T - bc.T_ambient) + bc.emissivity * kStefanBoltzmann * (t4 - a4);
}

double HeatConduction::surface_flux(double T) const { return sph::surface_flux(bc_, T); }

void heat_masks(const NeighbourList& nl, const SurfaceDetection& surface, const std::vector<char>& fixed,
                bool band, double lambda_interior, std::vector<char>& use_fmfs, std::vector<char>& loss) {
  const std::size_t n = nl.size();
  loss.assign(n, 0);
  use_fmfs.assign(n, 0);
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    loss[i] = surface.surface[i] && !fixed[i];
    use_fmfs[i] = !surface.surface[i] && surface.lambda[i] > lambda_interior;
    if (band)
      for (std::size_t k = nl.begin(i); k < nl.end(i); ++k)
        if (surface.surface[nl.index[k]]) use_fmfs[i] = 0;
  }
}

double heat_rates(const ParticleView& p, const std::vector<double>& T, const FmfsLaplacian* fmfs,
                  const std::vector<char>& use_fmfs, const std::vector<char>& fixed,
                  const std::vector<char>& loss, const HeatMaterial& mat, const HeatBoundary& bc,
                  std::vector<double>& rate, std::vector<char>* fmfs_used, double* fixed_inflow) {
  if (fmfs) {
    rate = fmfs->laplacian(p, T, &use_fmfs, fmfs_used);
  } else {
    rate = laplacian_brookshaw(p, T);
    if (fmfs_used) fmfs_used->assign(p.x.size(), 0);
  }
  const double alpha = mat.diffusivity(), rc = mat.density * mat.specific_heat;
  double total = 0.0, inflow = 0.0;
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    if (fixed[i]) {
      inflow += mat.conductivity * rate[i] * p.volume[i];
      rate[i] = 0.0;
      continue;
    }
    double d = alpha * rate[i];
    if (loss[i]) {
      const double l = std::sqrt(p.volume[i]);
      const double q = surface_flux(bc, T[i]);
      d -= q * l / (p.volume[i] * rc);
      total += q * l;
    }
    rate[i] = d;
  }
  if (fixed_inflow) *fixed_inflow = inflow;
  return total;
}

void cross_body_conduction(const std::vector<Vec2>& xa, const std::vector<double>& Va,
                           const std::vector<double>& Ta, const HeatMaterial& ma, const std::vector<Vec2>& xb,
                           const std::vector<double>& Vb, const std::vector<double>& Tb, const HeatMaterial& mb,
                           const NeighbourList& cross, const CubicSpline2D& kernel, std::vector<double>& rate_a,
                           std::vector<double>& rate_b) {
  const double kab = 2.0 * ma.conductivity * mb.conductivity / (ma.conductivity + mb.conductivity);
  const double rca = ma.density * ma.specific_heat, rcb = mb.density * mb.specific_heat;
  for (std::size_t i = 0; i < xa.size(); ++i) {
    for (std::size_t k = cross.begin(i); k < cross.end(i); ++k) {
      const std::size_t j = cross.index[k];
      const double r = (xa[i] - xb[j]).norm();
      const double g = 2.0 * kab * (Ta[i] - Tb[j]) / r * kernel.dwdr(r);  // W/m^3 per unit volume pair
      rate_a[i] += g * Vb[j] / rca;
      rate_b[j] -= g * Va[i] / rcb;
    }
  }
}

std::vector<double> HeatConduction::rate(double& heat_loss_rate) {
  if (!ready_) throw InputError("heat", "setup() must be called before stepping");
  const ParticleView view{x_, V_, nl_, kernel_};
  std::vector<double> r;
  heat_loss_rate = heat_rates(view, T_, opt_.scheme == HeatScheme::fmfs ? &fmfs_ : nullptr, use_fmfs_, fixed_,
                              loss_, mat_, bc_, r, &fmfs_used_);
  return r;
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
