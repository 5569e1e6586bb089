#include "cutbench/sph/solid.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "cutbench/common/errors.hpp"
#include "parallel.hpp"

#ifdef _OPENMP
#include <omp.h>
#else
namespace {
int omp_get_num_threads() { return 1; }
int omp_get_thread_num() { return 0; }
}  // namespace
#endif

namespace cutbench::sph {

SolidSph::SolidSph(std::vector<Vec2> x, double dx, SolidMaterial material, SolidOptions options,
                   double h_over_dx)
    : x_(std::move(x)), mat_(material), opt_(options), kernel_(h_over_dx * dx), dx_(dx) {
  if (!(dx > 0.0)) throw InputError("dx", "particle spacing must be positive");
  if (!(mat_.density > 0.0) || !(mat_.young > 0.0) || !(mat_.poisson > -1.0 && mat_.poisson < 0.5))
    throw InputError("material", "rho > 0, E > 0 and -1 < nu < 0.5 required");
  const std::size_t n = x_.size();
  v_.assign(n, Vec2::Zero());
  a_.assign(n, Vec2::Zero());
  m_.assign(n, mat_.density * dx * dx);
  rho_.assign(n, mat_.density);
  eps_p_.assign(n, 0.0);
  T_.assign(n, mat_.jc.T_ref);
  S_.assign(n, Stress3::Zero());
  fixed_.assign(n, 0);
  w_dx_ = kernel_.value(dx);
}

void SolidSph::set_fixed(std::vector<char> fixed) {
  if (fixed.size() != x_.size()) throw InputError("fixed", "mask size differs from the particle count");
  fixed_ = std::move(fixed);
}

void SolidSph::enable_thermal(ThermalOptions options, std::vector<char> fixed_temperature) {
  if (fixed_temperature.size() != x_.size())
    throw InputError("fixed_temperature", "mask size differs from the particle count");
  if (!(options.heat.conductivity > 0.0) || !(options.heat.density > 0.0) || !(options.heat.specific_heat > 0.0))
    throw InputError("thermal", "k, rho and c_p must be positive");
  if (options.conduction_interval < 1) throw InputError("conduction_interval", "must be >= 1");
  heat_.options = options;
  heat_.fixed = std::move(fixed_temperature);
  heat_.active = true;
}

void SolidSph::set_tool_thermal(HeatMaterial tool_heat, double depth) {
  if (!contact_.active() || !heat_.active) throw InputError("tool", "set_tool and enable_thermal must come first");
  if (!(depth > 6.0 * dx_)) throw InputError("depth", "tool band must be deeper than 6 particle spacings");
  tool_body_.build(contact_.geometry(), tool_heat, depth, dx_, kernel_, heat_.options.surface, heat_.options.brookshaw_band, heat_.options.boundary.T_ambient);
  if (contact_.options().tool_heat_share >= 0.0) {
    heat_.tool_share = contact_.options().tool_heat_share;
  } else {  // effusivity partition
    const HeatMaterial& tool = tool_body_.heat;
    const double e_tool = std::sqrt(tool.conductivity * tool.density * tool.specific_heat);
    const double e_work = std::sqrt(heat_.options.heat.conductivity * heat_.options.heat.density * heat_.options.heat.specific_heat);
    heat_.tool_share = e_tool / (e_tool + e_work);
  }
  heat_.pending_tool.assign(x_.size(), 0.0);
}

void SolidSph::deposit_friction_heat(std::size_t i, double heat) {
  const double eta = contact_.options().heat_fraction;
  if (eta > 0.0) energy_.friction += heat / eta;
  heat_.deposit_friction(i, heat, rho_[i], m_[i], T_[i], tool_body_.active);
}

double SolidSph::shear_cap(std::size_t i) const {
  if (!contact_.options().shear_cap || !mat_.plastic) return std::numeric_limits<double>::infinity();
  // shear flow stress at the particle's state (reference rate: the cap is a stress bound) times
  // the face length dx it covers (per unit depth)
  return mat_.jc.flow_stress(eps_p_[i], 0.0, T_[i]) / std::sqrt(3.0) * dx_;
}

double SolidSph::tool_heat_content() const {
  double e = tool_body_.heat_content(heat_.options.boundary.T_ambient);
  for (double q : heat_.pending_tool) e += q;  // friction heat not yet deposited on tool particles
  return e;
}

double SolidSph::workpiece_heat_content() const { return heat_.content(m_, rho_, T_); }


std::vector<double> SolidSph::pressure() const {
  std::vector<double> p(x_.size());
  for (std::size_t i = 0; i < x_.size(); ++i) p[i] = mat_.bulk() * (rho_[i] / mat_.density - 1.0);
  return p;
}

double SolidSph::stable_time_step() const {
  double vmax = 0.0;  // a maximum: the same in any order
  bool finite = true;
  const std::size_t np = v_.size();
#pragma omp parallel for schedule(static) reduction(max : vmax) reduction(&& : finite) if (np >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < np; ++i) {
    const double n = v_[i].norm();
    finite = finite && std::isfinite(n);
    vmax = std::max(vmax, n);
  }
  if (!finite)
    throw NumericalError("sph: non-finite particle velocity at t = " + std::to_string(time_) + " s, step " +
                         std::to_string(steps_));
  double dt = opt_.cfl * kernel_.h() / (mat_.p_wave_speed() + vmax);
  if (heat_.active) dt = std::min(dt, 0.1 * kernel_.h() * kernel_.h() / heat_.options.heat.diffusivity());
  return dt;
}

void SolidSph::update_neighbours() {
  const double skin = opt_.neighbour_skin * kernel_.h();
  bool rebuild = x_listed_.size() != x_.size() || skin <= 0.0;
  if (!rebuild) {
    const double lim2 = 0.25 * skin * skin;
    const std::size_t n = x_.size();
    bool moved = false;
#pragma omp parallel for schedule(static) reduction(|| : moved) if (n >= detail::kOmpMinParticles)
    for (std::size_t i = 0; i < n; ++i) moved = moved || (x_[i] - x_listed_[i]).squaredNorm() > lim2;
    rebuild = moved;
  }
  if (!rebuild) return;
  rebuild_neighbours(x_);
}

void SolidSph::rebuild_neighbours(const std::vector<Vec2>& at) {
  const double skin = opt_.neighbour_skin * kernel_.h();
  nl_ = build_neighbours(at, kernel_.support() + std::max(skin, 0.0));
  // half list: the tail j > i of every (sorted) row
  const std::size_t n = x_.size();
  half_offset_.assign(n + 1, 0);
  half_index_.clear();
  half_index_.reserve(nl_.index.size() / 2 + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const auto first = nl_.index.begin() + static_cast<std::ptrdiff_t>(nl_.begin(i));
    const auto last = nl_.index.begin() + static_cast<std::ptrdiff_t>(nl_.end(i));
    half_index_.insert(half_index_.end(), std::upper_bound(first, last, static_cast<std::uint32_t>(i)), last);
    half_offset_[i + 1] = half_index_.size();
  }
  pair_gx_.resize(half_index_.size());
  pair_gy_.resize(half_index_.size());
  pair_wr_.resize(half_index_.size());
  pair_j_.resize(half_index_.size());
  pair_count_.resize(n);
  x_listed_ = at;
  ++builds_;
}

void SolidSph::save_state(BinaryWriter& w) const {
  w.u64(x_.size());
  w.pods(x_);
  w.pods(v_);
  w.pods(a_);
  w.pods(m_);
  w.pods(rho_);
  w.pods(eps_p_);
  w.pods(T_);
  w.pods(S_);
  w.pods(last_dep_);
  w.pods(x_listed_);
  w.pods(contact_.screen_p);
  w.pods(contact_.screen_gap);
  w.pods(contact_.friction_history);
  w.pods(heat_.pending_tool);
  w.pods(heat_.plastic_at);
  w.pods(tool_body_.T);
  w.pods(heat_.surface.surface);
  w.pods(heat_.surface.lambda);
  w.pods(heat_.surface.normal);
  w.u64(builds_);
  w.u64(steps_);
  w.u64(static_cast<std::uint64_t>(heat_.steps));
  for (double d : {time_, heat_.plastic_heat, heat_.heat_lost, heat_.friction_heat, heat_.dt_acc, heat_.heat_sunk, heat_.friction_heat_tool,
                   heat_.tool_share, last_dt_, contact_.position.x(), contact_.position.y(), contact_.velocity.x(),
                   contact_.velocity.y(), contact_.force.x(), contact_.force.y(), energy_.tool_work, energy_.stress_work,
                   energy_.internal_work, energy_.plastic, energy_.viscous, energy_.artificial_stress, energy_.friction,
                   energy_.xsph_contact})
    w.f64(d);
}

void SolidSph::load_state(BinaryReader& r) {
  const std::size_t n = x_.size();
  if (r.u64() != n) throw NumericalError("sph checkpoint: particle count differs from the setup");
  auto per_particle = [n](auto v) {
    if (v.size() != n) throw NumericalError("sph checkpoint: array size differs from the setup");
    return v;
  };
  x_ = per_particle(r.pods<Vec2>());
  v_ = per_particle(r.pods<Vec2>());
  std::vector<Vec2> a = per_particle(r.pods<Vec2>());
  m_ = per_particle(r.pods<double>());
  rho_ = per_particle(r.pods<double>());
  eps_p_ = per_particle(r.pods<double>());
  eps_pn_.clear();  // recomputed from eps_p_ by the next step
  T_ = per_particle(r.pods<double>());
  S_ = per_particle(r.pods<Stress3>());
  last_dep_ = r.pods<double>();
  const std::vector<Vec2> listed = per_particle(r.pods<Vec2>());
  contact_.screen_p = r.pods<Vec2>();
  contact_.screen_gap = r.pods<double>();
  contact_.friction_history = r.pods<Vec2>();
  heat_.pending_tool = r.pods<double>();
  heat_.plastic_at = r.pods<double>();
  std::vector<double> tool_T = r.pods<double>();
  if (tool_T.size() != tool_body_.T.size()) throw NumericalError("sph checkpoint: tool particle count differs from the setup");
  tool_body_.T = std::move(tool_T);
  heat_.surface.surface = r.pods<char>();
  heat_.surface.lambda = r.pods<double>();
  heat_.surface.normal = r.pods<Vec2>();
  const auto builds = static_cast<std::size_t>(r.u64());
  steps_ = static_cast<std::size_t>(r.u64());
  heat_.steps = static_cast<int>(r.u64());
  time_ = r.f64();
  heat_.plastic_heat = r.f64();
  heat_.heat_lost = r.f64();
  heat_.friction_heat = r.f64();
  heat_.dt_acc = r.f64();
  heat_.heat_sunk = r.f64();
  heat_.friction_heat_tool = r.f64();
  heat_.tool_share = r.f64();
  last_dt_ = r.f64();
  contact_.position.x() = r.f64();
  contact_.position.y() = r.f64();
  contact_.velocity.x() = r.f64();
  contact_.velocity.y() = r.f64();
  contact_.force.x() = r.f64();
  contact_.force.y() = r.f64();
  for (double* d : {&energy_.tool_work, &energy_.stress_work, &energy_.internal_work, &energy_.plastic, &energy_.viscous,
                    &energy_.artificial_stress, &energy_.friction, &energy_.xsph_contact})
    *d = r.f64();
  // The neighbour lists as they were (built at x_listed_), then the pair geometry and packed
  // particle data of the current positions, which the next step's rate pass reuses; the
  // accelerations themselves (with the contact forces of the last step) are the stored ones.
  rebuild_neighbours(listed);
  accelerations();
  a_ = std::move(a);
  have_accel_ = true;
  builds_ = builds;
}

namespace {
int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}
}  // namespace

void SolidSph::accelerations() {
  update_neighbours();
  const std::size_t n = x_.size();
  const double K = mat_.bulk(), c0 = mat_.bulk_speed(), h = kernel_.h(), support = kernel_.support();
  const double support2 = support * support;
  pdata_.resize(n);
  const double eps_art = opt_.artificial_stress;
  // per particle, independent: parallel (the same values with any thread count)
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    const double p = K * (rho_[i] / mat_.density - 1.0);
    const double inv_r2 = 1.0 / (rho_[i] * rho_[i]);
    const double sxx = S_[i](0, 0) - p, syy = S_[i](1, 1) - p, sxy = S_[i](0, 1);
    ParticleData& f = pdata_[i];
    f.x = x_[i].x();
    f.y = x_[i].y();
    f.vx = v_[i].x();
    f.vy = v_[i].y();
    f.rho = rho_[i];
    f.m = m_[i];
    f.vol = m_[i] / rho_[i];
    f.sxx = sxx * inv_r2;
    f.sxy = sxy * inv_r2;
    f.syy = syy * inv_r2;
    f.axx = f.axy = f.ayy = 0.0;
    if (eps_art > 0.0) {
      // R = -eps/rho^2 sum_{s_k > 0} s_k e_k e_k^T over the in-plane principal stresses s1 >= s2.
      // Both positive: R = -eps/rho^2 sigma. Only s1 > 0: R = -eps/rho^2 s1 P1 with the projector
      // P1 = (sigma - s2 I) / (s1 - s2) (no angles needed).
      const double mean = 0.5 * (sxx + syy), rad = std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
      const double s1 = mean + rad, s2 = mean - rad;
      const double k = -eps_art * inv_r2;
      if (s2 > 0.0) {
        f.axx = k * sxx;
        f.axy = k * sxy;
        f.ayy = k * syy;
      } else if (s1 > 0.0) {
        const double c = k * s1 / (s1 - s2);
        f.axx = c * (sxx - s2);
        f.axy = c * sxy;
        f.ayy = c * (syy - s2);
      }
    }
  }
  // Each pair (i < j) is evaluated once: acc_i += m_j T_ij gradW_ij, acc_j -= m_i T_ij gradW_ij
  // (T_ij symmetric, gradW_ji = -gradW_ij). Threads accumulate into private buffers that are summed
  // in thread order: deterministic for a fixed thread count.
  //
  // Per row: a branch-free scalar loop picks the listed pairs inside the support (the Verlet skin
  // lists about 35 % more), then a SIMD loop without branches evaluates them (the j of a row are
  // distinct, so the lanes are independent): both kernel pieces are computed and selected with a
  // mask, and the viscosity is selected for approaching pairs. In a cut the inside/outside and
  // q < 1 outcomes follow no pattern, so branches there were mispredicted at a high rate
  // (solvers/sph/README.md, known problem 13). The SIMD loop writes each pair's force into small
  // buffers; a scalar loop then adds them to i (in pair order) and to j. Every operation is the
  // one of the scalar code with branches, in the same order, so the results are bit for bit those
  // of that code, whatever the vector width. The row's inside pairs (j, grad W, W / rhobar) are
  // kept, compacted, for the rate pass of the next step.
  const double vis = opt_.alpha_visc > 0.0 || opt_.beta_visc > 0.0 ? 1.0 : 0.0, artf = eps_art > 0.0 ? 1.0 : 0.0;
  const double inv_wdx = 1.0 / w_dx_;
  const double eta2 = 0.01 * h * h, minus_alpha_c0 = -opt_.alpha_visc * c0, beta = opt_.beta_visc;
  const double inv_h = kernel_.inv_h(), sig = kernel_.sigma(), sig_h = kernel_.sigma_inv_h();
  const double xs = opt_.xsph > 0.0 ? 1.0 : 0.0;
  const ParticleData* const pd = pdata_.data();
  const std::uint32_t* const hidx = half_index_.data();
  const std::size_t* const hoff = half_offset_.data();
  double* const pgx = pair_gx_.data();
  double* const pgy = pair_gy_.data();
  double* const pwr = pair_wr_.data();
  std::uint32_t* const cidx = pair_j_.data();
  std::uint32_t* const ccount = pair_count_.data();
  pow_stress_.resize(n);
  pow_visc_.resize(n);
  pow_art_.resize(n);
  double* const pst = pow_stress_.data();
  double* const pvi = pow_visc_.data();
  double* const par = pow_art_.data();
  auto row = [=](std::size_t i, Vec2* acc) {
    // the captured pointers as locals: GCC does not vectorise loads through the closure
    const ParticleData* const P = pd;
    const std::uint32_t* const J = hidx;
    double* const GX = pgx;
    double* const GY = pgy;
    double* const WR = pwr;
    std::uint32_t* const CJ = cidx;
    const ParticleData fi = P[i];
    double ax = 0.0, ay = 0.0, e_st = 0.0, e_vi = 0.0, e_ar = 0.0;
    constexpr std::size_t kChunk = 64;
    std::uint32_t sel[kChunk];
    double fx[kChunk], fy[kChunk], bx[kChunk], by[kChunk];
    std::size_t out = hoff[i];  // next slot of the row's compacted pair list
    for (std::size_t b0 = hoff[i]; b0 < hoff[i + 1]; b0 += kChunk) {
      const std::size_t b1 = std::min(hoff[i + 1], b0 + kChunk);
      // the listed pairs inside the support, in list order (branch-free compaction)
      std::size_t m = 0;
      for (std::size_t k = b0; k < b1; ++k) {
        const std::uint32_t j = J[k];
        const double xx = fi.x - P[j].x, xy = fi.y - P[j].y;
        sel[m] = j;
        m += xx * xx + xy * xy < support2 ? 1 : 0;
      }
#pragma omp simd reduction(+ : e_st, e_vi, e_ar)
      for (std::size_t u = 0; u < m; ++u) {
        const ParticleData& fj = P[sel[u]];
        const double xx = fi.x - fj.x, xy = fi.y - fj.y;
        const double r2 = xx * xx + xy * xy;
        const double r = std::sqrt(r2);
        const double q = r * inv_h;
        const double wij = CubicSpline2D::value_in_support(q, sig);
        const double dw = CubicSpline2D::dwdr_in_support(q, sig_h);
        const double dwr = dw / r;
        const double gx = dwr * xx, gy = dwr * xy;
        const double rhobar = 0.5 * (fi.rho + fj.rho);
        GX[out + u] = gx;
        GY[out + u] = gy;
        WR[out + u] = xs * (wij / rhobar);  // XSPH weight of the rate pass (xs = 1, or 0 without XSPH)
        CJ[out + u] = sel[u];
        double txx = fi.sxx + fj.sxx, txy = fi.sxy + fj.sxy, tyy = fi.syy + fj.syy;
        // energy ledger: the pair's power m_i m_j (T g).(v_i - v_j), its viscous and artificial-stress
        // parts (the stress part is the rest)
        const double dvx = fi.vx - fj.vx, dvy = fi.vy - fj.vy, mm = fi.m * fj.m;
        // Monaghan viscosity on approaching pairs (vr < 0)
        const double vr = (fi.vx - fj.vx) * xx + (fi.vy - fj.vy) * xy;
        const double mu = h * vr / (r2 + eta2);
        const double pi0 = (minus_alpha_c0 * mu + beta * mu * mu) / rhobar;
        const double pi = vr < 0.0 ? vis * pi0 : 0.0;  // vis = 1 or 0: exact
        txx -= pi;
        tyy -= pi;
        const double f = wij * inv_wdx;
        const double f2 = f * f;
        const double f4 = artf * (f2 * f2);  // artf = 1 or 0 (then R = 0 too): exact
        const double pv = mm * pi * dwr * vr;  // dissipated: -(power of the viscous pair force) >= 0
        const double rxx = f4 * (fi.axx + fj.axx), rxy = f4 * (fi.axy + fj.axy), ryy = f4 * (fi.ayy + fj.ayy);
        const double pa = mm * ((rxx * gx + rxy * gy) * dvx + (rxy * gx + ryy * gy) * dvy);
        txx += f4 * (fi.axx + fj.axx);
        txy += f4 * (fi.axy + fj.axy);
        tyy += f4 * (fi.ayy + fj.ayy);
        const double tgx = txx * gx + txy * gy, tgy = txy * gx + tyy * gy;
        fx[u] = fj.m * tgx;
        fy[u] = fj.m * tgy;
        e_st += mm * (tgx * dvx + tgy * dvy) + pv - pa;  // total + dissipated - artificial = stress part
        e_vi += pv;
        e_ar += pa;
        bx[u] = fi.m * tgx;
        by[u] = fi.m * tgy;
      }
      for (std::size_t u = 0; u < m; ++u) {
        ax += fx[u];
        ay += fy[u];
        Vec2& aj = acc[sel[u]];
        aj.x() -= bx[u];
        aj.y() -= by[u];
      }
      out += m;
    }
    ccount[i] = static_cast<std::uint32_t>(out - hoff[i]);
    pst[i] = e_st;
    pvi[i] = e_vi;
    par[i] = e_ar;
    acc[i].x() += ax;
    acc[i].y() += ay;
  };
  if (n < detail::kOmpMinParticles) {
    acc_.assign(n, Vec2::Zero());
    for (std::size_t i = 0; i < n; ++i) row(i, acc_.data());
    for (std::size_t i = 0; i < n; ++i) a_[i] = fixed_[i] ? Vec2::Zero() : Vec2(acc_[i] + opt_.body_force);
  } else {
    // Each thread zeroes its own buffer and accumulates its rows; the buffers are then summed per
    // particle in thread order, ((0 + b_0) + b_1) + ..., in parallel over the particles.
    const auto nt = static_cast<std::size_t>(max_threads());
    if (acc_part_.size() != nt) acc_part_.resize(nt);
#pragma omp parallel
    {
      auto& mine = acc_part_[static_cast<std::size_t>(omp_get_thread_num())];
      mine.assign(n, Vec2::Zero());
#pragma omp barrier
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) row(i, mine.data());
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        Vec2 sum = Vec2::Zero();
        for (std::size_t t = 0; t < nt; ++t) sum += acc_part_[t][i];
        a_[i] = fixed_[i] ? Vec2::Zero() : Vec2(sum + opt_.body_force);
      }
    }
  }
  have_accel_ = true;
}

void SolidSph::step(double dt) {
  if (!(dt > 0.0)) throw InputError("dt", "time step must be positive");
  const std::size_t n = x_.size();
  if (!have_accel_) accelerations();
  // kick, and the velocities after it into the packed particle data (positions, densities and
  // volumes are those of x^n, filled by accelerations())
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    v_[i] += 0.5 * dt * a_[i];
    pdata_[i].vx = v_[i].x();
    pdata_[i].vy = v_[i].y();
  }
  // rates on x^n with v^{n+1/2} (the pair geometry of accelerations() belongs to x^n)
  const double G = mat_.shear();
  rho_new_.resize(n);
  s_new_.resize(n);
  plastic_dT_.resize(n);  // set for every particle by the constitutive update
  work_int_.resize(n);
  work_plastic_.resize(n);
  auto& work_int = work_int_;
  auto& work_plastic = work_plastic_;
  const double K_bulk = mat_.bulk();
  auto& xsph = xsph_;
  auto& rho_new = rho_new_;
  auto& s_new = s_new_;
  auto& plastic_dT = plastic_dT_;
  const double chi_rc =
      heat_.active ? heat_.options.taylor_quinney / (heat_.options.heat.density * heat_.options.heat.specific_heat) : 0.0;
  const bool corr = opt_.correct_velocity_gradient;
  // Pair pass over the half list (symmetric): with dv = v_j - v_i and gradW_ji = -gradW_ij,
  //   (grad v)_i += V_j dv (x) gradW_ij,  (grad v)_j += V_i dv (x) gradW_ij,
  //   L_i -= V_j x_ij (x) gradW_ij,       L_j -= V_i x_ij (x) gradW_ij,
  //   xs_i += m_j / rhobar W dv,           xs_j -= m_i / rhobar W dv.
  const ParticleData* const pd = pdata_.data();
  const std::size_t* const hoff = half_offset_.data();
  const double* const pgx = pair_gx_.data();
  const double* const pgy = pair_gy_.data();
  const double* const pwr = pair_wr_.data();
  const std::uint32_t* const cidx = pair_j_.data();
  const std::uint32_t* const ccount = pair_count_.data();
  // As in accelerations(): a SIMD loop over the row's pairs inside the support (compacted by
  // accelerations()) writes the contributions to i and j into buffers, scalar loops add them in
  // pair order: bit for bit the results of the scalar loop that skipped the pairs outside. The
  // renormalisation matrix L (optional) is summed in a plain loop.
  auto row = [=](std::size_t i, RateAcc* ra, Mat2* lr) {
    const ParticleData* const P = pd;  // locals: see accelerations()
    const std::uint32_t* const J = cidx;  // the compacted inside pairs of accelerations()
    const std::uint32_t* const CN = ccount;
    const double* const GX = pgx;
    const double* const GY = pgy;
    const double* const WR = pwr;
    const ParticleData fi = P[i];
    RateAcc acc_i{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    constexpr std::size_t kChunk = 64;
    double b00[kChunk], b01[kChunk], b10[kChunk], b11[kChunk], bsx[kChunk], bsy[kChunk];
    double c00[kChunk], c01[kChunk], c10[kChunk], c11[kChunk], csx[kChunk], csy[kChunk];
    const std::size_t row_end = hoff[i] + CN[i];
    for (std::size_t b0 = hoff[i]; b0 < row_end; b0 += kChunk) {
      const std::size_t b1 = std::min(row_end, b0 + kChunk);
#pragma omp simd
      for (std::size_t k = b0; k < b1; ++k) {
        const ParticleData& fj = P[J[k]];
        const double gx = GX[k], gy = GY[k];
        const double dvx = fj.vx - fi.vx, dvy = fj.vy - fi.vy;
        const double o00 = dvx * gx, o01 = dvx * gy, o10 = dvy * gx, o11 = dvy * gy;
        const double c = WR[k];
        const double wx = c * dvx, wy = c * dvy;
        const std::size_t u = k - b0;
        c00[u] = fj.vol * o00;
        c01[u] = fj.vol * o01;
        c10[u] = fj.vol * o10;
        c11[u] = fj.vol * o11;
        csx[u] = fj.m * wx;  // wx = 0 without XSPH (weights stored as 0)
        csy[u] = fj.m * wy;
        b00[u] = fi.vol * o00;
        b01[u] = fi.vol * o01;
        b10[u] = fi.vol * o10;
        b11[u] = fi.vol * o11;
        bsx[u] = -(fi.m * wx);
        bsy[u] = -(fi.m * wy);
      }
      for (std::size_t k = b0; k < b1; ++k) {
        const std::size_t u = k - b0;
        acc_i += RateAcc{c00[u], c01[u], c10[u], c11[u], csx[u], csy[u]};
        ra[J[k]] += RateAcc{b00[u], b01[u], b10[u], b11[u], bsx[u], bsy[u]};
      }
    }
    ra[i] += acc_i;
    if (corr) {
      Mat2 lr_i = Mat2::Zero();
      for (std::size_t k = hoff[i]; k < row_end; ++k) {
        const std::size_t j = J[k];
        const Mat2 ol = Vec2(fi.x - pd[j].x, fi.y - pd[j].y) * Vec2(GX[k], GY[k]).transpose();
        lr_i.noalias() -= pd[j].vol * ol;
        lr[j].noalias() -= fi.vol * ol;
      }
      lr[i] += lr_i;
    }
  };
  if (last_dep_.size() != n) last_dep_.assign(n, 0.0);
  if (eps_pn_.size() != n) {  // after construction or a restart: the same pow radial_return takes
    eps_pn_.resize(n);
    for (std::size_t i = 0; i < n; ++i) eps_pn_[i] = mat_.jc.eps_pow_n(eps_p_[i]);
  }
  const RateAcc zero{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  racc_.resize(n);
  xsph_.resize(n);
  if (corr) lren_.resize(n);
  if (n < detail::kOmpMinParticles) {
    racc_.assign(n, zero);
    if (corr) lren_.assign(n, Mat2::Zero());
    for (std::size_t i = 0; i < n; ++i) row(i, racc_.data(), lren_.data());
  } else {
    // as in accelerations(): per-thread buffers zeroed by their thread, summed per particle in
    // thread order in parallel
    const auto nt = static_cast<std::size_t>(max_threads());
    if (racc_part_.size() != nt) racc_part_.resize(nt);
    if (lren_part_.size() != nt) lren_part_.resize(nt);
#pragma omp parallel
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      racc_part_[t].assign(n, zero);
      lren_part_[t].assign(corr ? n : 0, Mat2::Zero());
#pragma omp barrier
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) row(i, racc_part_[t].data(), lren_part_[t].data());
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        RateAcc ra = zero;
        for (std::size_t u = 0; u < nt; ++u) ra += racc_part_[u][i];
        racc_[i] = ra;
        if (corr) {
          Mat2 l = Mat2::Zero();
          for (std::size_t u = 0; u < nt; ++u) l += lren_part_[u][i];
          lren_[i] = l;
        }
      }
    }
  }
  // Constitutive update per particle. Plane strain: S has components xx, yy, zz, xy (the
  // out-of-plane shears stay zero); spin W = [[0, w], [-w, 0]] with w = (grad v)_[xy] antisymmetric part.
  // Chunks of 256 particles dealt round-robin: the yielding particles (radial return with pow and
  // log, ~10 % of a cutting step) lie in the chip and shear zone, one contiguous range of indices
  // that a plain static schedule gave to one thread. Per particle, so the same values either way.
#pragma omp parallel for schedule(static, 256) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    const RateAcc& ra = racc_[i];
    Mat2 gv;
    gv << ra.g00, ra.g01, ra.g10, ra.g11;
    if (corr && std::abs(lren_[i].determinant()) > 1e-6) gv = gv * lren_[i].inverse();
    xsph[i] = opt_.xsph * Vec2(ra.sx, ra.sy);
    const double dxx = gv(0, 0), dyy = gv(1, 1), dxy = 0.5 * (gv(0, 1) + gv(1, 0)), w = 0.5 * (gv(0, 1) - gv(1, 0));
    const double trd = dxx + dyy;
    rho_new[i] = rho_[i] * (1.0 - dt * trd);
    const double third = trd / 3.0;
    const Stress3& S = S_[i];
    const double sxx = S(0, 0), syy = S(1, 1), szz = S(2, 2), sxy = S(0, 1);
    {  // constitutive power V sigma:D over the step (plane strain, D_zz = 0), stress of x^n
      const double p = K_bulk * (rho_[i] / mat_.density - 1.0);
      work_int[i] = dt * m_[i] / rho_[i] * (sxx * dxx + syy * dyy + 2.0 * sxy * dxy - p * trd);
    }
    work_plastic[i] = 0.0;
    Stress3 s = Stress3::Zero();
    s(0, 0) = sxx + dt * (2.0 * G * (dxx - third) + 2.0 * w * sxy);
    s(1, 1) = syy + dt * (2.0 * G * (dyy - third) - 2.0 * w * sxy);
    s(2, 2) = szz + dt * (2.0 * G * (-third));
    s(0, 1) = s(1, 0) = sxy + dt * (2.0 * G * dxy + w * (syy - sxx));
    // Elastic without evaluating J-C: sigma_y >= A (1 - T*^m) >= A m (1 - T*) for m <= 1 (T*^m is
    // concave, below its tangent at 1) or A (1 - T*) for m > 1; the rate factor is >= 1.
    plastic_dT[i] = 0.0;
    if (mat_.plastic) {
      const double q = std::sqrt(1.5 * (s(0, 0) * s(0, 0) + s(1, 1) * s(1, 1) + s(2, 2) * s(2, 2) +
                                        2.0 * s(0, 1) * s(0, 1)));
      if (q > yield_floor(T_[i])) {
        // warm start from the particle's increment of its last plastic step
        const auto rr = radial_return(mat_.jc, s, G, eps_p_[i], dt, T_[i], last_dep_[i], eps_pn_[i]);
        s = rr.deviator;
        eps_p_[i] += rr.delta_eps_p;
        eps_pn_[i] = rr.eps_p_pow_n;  // (eps_p + d)^n with eps_p + d the value just stored
        last_dep_[i] = rr.delta_eps_p;
        plastic_dT[i] = chi_rc * rr.flow_stress * rr.delta_eps_p;
        work_plastic[i] = m_[i] / rho_[i] * rr.flow_stress * rr.delta_eps_p;
      }
    }
    s_new[i] = s;
  }
  for (std::size_t i = 0; i < n; ++i) {  // in index order: the same sums with any thread count
    energy_.internal_work += work_int_[i];
    energy_.plastic += work_plastic_[i];
  }
  if (heat_.active)
    heat_.update(dt, plastic_dT, x_, m_, rho_, T_, nl_, kernel_, dx_, tool_body_, contact_.position, time_, steps_);
  rho_.swap(rho_new);
  S_.swap(s_new);
  // drift
  bool finite = true;
#pragma omp parallel for schedule(static) reduction(&& : finite) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) {
    x_[i] += dt * (fixed_[i] ? v_[i] : Vec2(v_[i] + xsph[i]));  // prescribed particles follow v exactly
    finite = finite && x_[i].allFinite();
  }
  if (!finite) throw NumericalError("sph solid: non-finite particle position");
  accelerations();
  const auto cap = [this](std::size_t i) { return shear_cap(i); };
  const auto heat = [this](std::size_t i, double q) { deposit_friction_heat(i, q); };
  const bool penalty = contact_.active() && contact_.options().model == ContactModel::penalty;
  for (std::size_t i = 0; i < n; ++i) {  // pair powers at x^{n+1}, v^{n+1/2}, in index order
    energy_.stress_work += dt * pow_stress_[i];
    energy_.viscous += dt * pow_visc_[i];
    energy_.artificial_stress += dt * pow_art_[i];
  }
  if (penalty) {
    contact_.penalty(dt, dx_, x_, v_, m_, fixed_, a_, cap, heat);
    for (const auto& k : contact_.contacts()) energy_.xsph_contact += dt * (k.fn + k.ft).dot(xsph_[k.particle]);
  }
#pragma omp parallel for schedule(static) if (n >= detail::kOmpMinParticles)
  for (std::size_t i = 0; i < n; ++i) v_[i] += 0.5 * dt * a_[i];
  time_ += dt;
  if (contact_.active() && contact_.options().model == ContactModel::velocity)
    contact_.velocity_level(dt, dx_, x_, v_, m_, fixed_, cap, heat);
  if (penalty) contact_.advance(dt);
  if (contact_.active()) energy_.tool_work -= dt * contact_.force.dot(contact_.velocity);
  last_dt_ = dt;
  ++steps_;
}

void SolidSph::set_tool(std::shared_ptr<const ToolGeometry> tool, const Vec2& position, const Vec2& velocity,
                        ContactOptions contact) {
  contact_.set(std::move(tool), position, velocity, contact);
}

double SolidSph::yield_floor(double T) const {
  const auto& jc = mat_.jc;
  if (!(jc.A > 0.0) || !(jc.B >= 0.0) || !(jc.C >= 0.0)) return 0.0;  // no cheap bound: always return-map
  const double ts = std::clamp((T - jc.T_ref) / (jc.T_melt - jc.T_ref), 0.0, 1.0);
  // softening: the bracket D + (1 - D) tanh(.)^s is at least D = 1 - (T / T_m)^d
  const double soft = jc.softening ? std::max(0.0, 1.0 - std::pow(std::max(T, 0.0) / jc.T_melt, jc.sd)) : 1.0;
  return jc.A * (jc.m <= 1.0 ? jc.m : 1.0) * (1.0 - ts) * soft;
}

Vec2 SolidSph::momentum() const {
  Vec2 p = Vec2::Zero();
  for (std::size_t i = 0; i < x_.size(); ++i) p += m_[i] * v_[i];
  return p;
}

double SolidSph::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < x_.size(); ++i) e += 0.5 * m_[i] * v_[i].squaredNorm();
  return e;
}

double SolidSph::contact_spring_energy() const {
  if (!contact_.active() || contact_.options().model != ContactModel::penalty || !(last_dt_ > 0.0)) return 0.0;
  double e = 0.0;
  for (const auto& k : contact_.contacts()) {  // springs of stiffness alpha m / dt^2
    const double stiff = contact_.options().alpha * m_[k.particle] / (last_dt_ * last_dt_);
    e += 0.5 * (k.fn.squaredNorm() + k.ft.squaredNorm()) / stiff;
  }
  return e;
}

double SolidSph::strain_energy() const {
  const double K = mat_.bulk(), G = mat_.shear();
  double e = 0.0;
  for (std::size_t i = 0; i < x_.size(); ++i) {
    const double p = K * (rho_[i] / mat_.density - 1.0);
    e += m_[i] / rho_[i] * (p * p / (2.0 * K) + (S_[i].array() * S_[i].array()).sum() / (4.0 * G));
  }
  return e;
}

}  // namespace cutbench::sph
