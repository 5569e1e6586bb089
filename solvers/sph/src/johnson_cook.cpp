#include "cutbench/sph/johnson_cook.hpp"

#include <algorithm>
#include <cmath>

#include "cutbench/common/errors.hpp"

namespace cutbench::sph {

namespace {
double thermal_factor(const JohnsonCook& jc, double T) {
  const double ts = std::clamp((T - jc.T_ref) / (jc.T_melt - jc.T_ref), 0.0, 1.0);
  return ts > 0.0 ? 1.0 - std::pow(ts, jc.m) : 1.0;  // pow(0, m) = 0: skip the call (cold particles)
}
double rate_factor(const JohnsonCook& jc, double rate) {
  const double r = rate / jc.eps_rate_ref;
  return r > 1.0 ? 1.0 + jc.C * std::log(r) : 1.0;
}
// The strain-dependent part of the flow stress and its derivative in eps: g = A + B e^n, or with
// softening g = [A + B e^n exp(-e^a)] h(e, T), h = D + (1 - D) tanh(u)^s, u = (e + S)^-c;
// e_n = e^n and e_n1 = e^(n-1) (floored by the caller).
struct StrainPart {
  double g, dg;
};
StrainPart strain_part(const JohnsonCook& jc, double e, double e_n, double e_n1, double T) {
  if (!jc.softening) return {jc.A + jc.B * e_n, jc.B * jc.n * e_n1};
  const double ea = e > 0.0 ? std::pow(e, jc.sa) : 0.0, ex = std::exp(-ea);
  const double g1 = jc.A + jc.B * e_n * ex;
  // d/de [e^n exp(-e^a)] = (n e^(n-1) - a e^(n-1) e^a) exp(-e^a)
  const double dg1 = jc.B * (jc.n * e_n1 - jc.sa * e_n1 * ea) * ex;
  const double tr = std::max(T, 0.0) / jc.T_melt;
  const double D = 1.0 - std::pow(tr, jc.sd), S = std::pow(tr, jc.sb);
  const double base = e + S;
  if (!(base > 0.0)) return {g1, dg1};  // T = 0 and e = 0: tanh(inf) = 1, no softening
  const double u = std::pow(base, -jc.sc), th = std::tanh(u);
  const double ths = std::pow(th, jc.ss);
  const double h = D + (1.0 - D) * ths;
  // dh/de = (1 - D) s tanh(u)^(s-1) sech^2(u) du/de, du/de = -c u / (e + S)
  const double sech2 = 1.0 - th * th;
  const double dh = th > 0.0 ? (1.0 - D) * jc.ss * (ths / th) * sech2 * (-jc.sc * u / base) : 0.0;
  return {g1 * h, dg1 * h + g1 * dh};
}
double e_pow_n(const JohnsonCook& jc, double e) { return e > 0.0 ? std::pow(e, jc.n) : 0.0; }
}  // namespace

JohnsonCook sima_ozel_ti6al4v() {
  JohnsonCook jc;
  jc.A = 724.7e6;
  jc.B = 683.1e6;
  jc.C = 0.035;
  jc.m = 1.0;
  jc.n = 0.47;
  jc.T_ref = 300.0;
  jc.T_melt = 1878.0;
  jc.eps_rate_ref = 1.0;
  jc.softening = true;
  jc.sa = 2.0;
  jc.sb = 5.0;
  jc.sc = 2.0;
  jc.sd = 1.0;
  jc.ss = 0.05;
  return jc;
}

double JohnsonCook::flow_stress(double eps_p, double eps_rate_p, double T) const {
  return strain_part(*this, eps_p, e_pow_n(*this, eps_p), 0.0, T).g * rate_factor(*this, eps_rate_p) *
         thermal_factor(*this, T);
}

double JohnsonCook::d_strain(double eps_p, double eps_rate_p, double T) const {
  // n < 1: infinite slope at eps = 0; use a tiny floor so Newton stays finite.
  const double e = std::max(eps_p, 1e-12);
  return strain_part(*this, e, std::pow(e, n), std::pow(e, n - 1.0), T).dg * rate_factor(*this, eps_rate_p) *
         thermal_factor(*this, T);
}

double JohnsonCook::d_rate(double eps_p, double eps_rate_p, double T) const {
  if (eps_rate_p <= eps_rate_ref) return 0.0;
  return strain_part(*this, eps_p, e_pow_n(*this, eps_p), 0.0, T).g * C / eps_rate_p * thermal_factor(*this, T);
}

double JohnsonCook::eps_pow_n(double eps_p) const { return e_pow_n(*this, eps_p); }

double von_mises(const Stress3& s) { return std::sqrt(1.5 * (s.array() * s.array()).sum()); }

ReturnResult radial_return(const JohnsonCook& jc, const Stress3& trial, double G, double eps_p, double dt,
                           double T, double guess, double eps_p_pow_n) {
  if (!(G > 0.0) || !(dt > 0.0)) throw InputError("radial_return", "G and dt must be positive");
  ReturnResult res;
  res.deviator = trial;
  const double q = von_mises(trial);
  // The thermal factor is fixed during the return; per iterate one pow (eps^n, with
  // eps^(n-1) = eps^n / eps) and one log give sigma_y and both derivatives (same formulas as
  // flow_stress, d_strain and d_rate).
  const double tf = thermal_factor(jc, T);
  const double en0 = eps_p_pow_n >= 0.0 ? eps_p_pow_n : e_pow_n(jc, eps_p);
  res.eps_p_pow_n = en0;
  const double y0 = strain_part(jc, eps_p, en0, 0.0, T).g * tf;  // rate factor 1 at zero rate
  res.flow_stress = y0;
  if (q <= y0) return res;
  res.plastic = true;
  struct Eval {
    double y, slope, en;  // sigma_y, d sigma_y / d(d) (strain and rate terms), (eps_p + d)^n
  };
  auto eval = [&](double d) {
    const double e = eps_p + d, rate = d / dt;
    const double en = e_pow_n(jc, e);
    const double rr = rate / jc.eps_rate_ref;
    const double rf = rr > 1.0 ? 1.0 + jc.C * std::log(rr) : 1.0;
    const double e_min = 1e-12;
    const double en1 = e > e_min ? en / e : std::pow(e_min, jc.n - 1.0);
    const StrainPart sp = strain_part(jc, e, en, en1, T);
    const double dr = rate <= jc.eps_rate_ref ? 0.0 : sp.g * jc.C / rate * tf;
    return Eval{sp.g * rf * tf, sp.dg * rf * tf + dr / dt, en};
  };
  // Bracket: residual(0) > 0, residual(q / 3G) <= 0 since sigma_y >= 0.
  const double d_max = q / (3.0 * G);
  double lo = 0.0, hi = d_max;
  // first iterate: the caller's guess inside the bracket, else the perfectly plastic increment
  double d = guess > 0.0 && guess < hi ? guess : std::min(hi, (q - y0) / (3.0 * G));
  Eval ev{};
  bool done = false;
  for (int it = 1; it <= 100 && !done; ++it) {
    ev = eval(d);
    const double r = q - 3.0 * G * d - ev.y;
    res.iterations = it;
    if (r > 0.0) lo = d; else hi = d;
    const double slope = -3.0 * G - ev.slope;
    const double next = d - r / slope;
    // Converged when the correction moves the returned stress by at most 2e-15 q (3 G |dd| <=
    // 2e-15 q): the residual is then near its round-off floor, a few 1e-16 q, whatever the size of
    // d (a tolerance relative to d cannot be met by small increments, which then ran on to the
    // collapse of the bracket). Tested before the bracket safeguard: at convergence the correction
    // can land on the bracket end d has just become, and a bisection there would throw the
    // iterate back across the bracket.
    done = std::abs(next - d) <= 2e-15 * d_max || hi - lo <= 1e-15 * hi;
    if (!done) d = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  if (!done) ev = eval(d);  // the iteration limit: d is a new iterate
  // at convergence d was evaluated last: its flow stress and eps^n need no further call
  res.delta_eps_p = d;
  res.flow_stress = ev.y;
  res.eps_p_pow_n = ev.en;
  res.deviator = trial * (1.0 - 3.0 * G * d / q);
  return res;
}

}  // namespace cutbench::sph
