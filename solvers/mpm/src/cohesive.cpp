#include "cutbench/mpm/cohesive.hpp"

#include <algorithm>
#include <cmath>

namespace cutbench::mpm {

double TractionLaw::toughness() const {
  return type == TractionLawType::cubic ? 9.0 * sigma_c * delta_c / 16.0 : 0.5 * sigma_c * delta_c;
}

TractionLaw TractionLaw::from_toughness(TractionLawType t, double G_c, double sc) {
  TractionLaw law;
  law.type = t;
  law.sigma_c = sc;
  law.delta_c = t == TractionLawType::cubic ? 16.0 * G_c / (9.0 * sc) : 2.0 * G_c / sc;
  return law;
}

double TractionLaw::envelope(double d) const {
  if (d <= 0.0 || d >= delta_c) return 0.0;
  if (type == TractionLawType::cubic) {
    const double u = d / delta_c;
    return 6.75 * sigma_c * u * (1.0 - u) * (1.0 - u);
  }
  const double dp = peak_fraction * delta_c;
  return d <= dp ? sigma_c * d / dp : sigma_c * (delta_c - d) / (delta_c - dp);
}

double TractionLaw::area(double d) const {
  if (d <= 0.0) return 0.0;
  if (d >= delta_c) return toughness();
  if (type == TractionLawType::cubic) {
    const double u = d / delta_c;
    return toughness() * u * u * (6.0 - 8.0 * u + 3.0 * u * u);
  }
  const double dp = peak_fraction * delta_c;
  if (d <= dp) return 0.5 * sigma_c * d * d / dp;
  const double r = delta_c - d;
  return toughness() - 0.5 * sigma_c * r * r / (delta_c - dp);
}

double TractionLaw::traction(double d, double dmax) const {
  if (d <= 0.0 || dmax >= delta_c) return 0.0;
  if (d >= dmax) return envelope(d);
  // Secant to the origin from the envelope point at dmax.
  if (dmax <= 0.0) return 0.0;
  return envelope(dmax) * d / dmax;
}

CohesiveTraction cohesive_update(const TractionLaw& mode1, const TractionLaw& mode2, double dn, double dt,
                                 CohesiveState& s) {
  CohesiveTraction t;
  if (s.failed) return t;
  const double adt = std::fabs(dt);
  s.dn_max = std::max(s.dn_max, dn);
  s.dt_max = std::max(s.dt_max, adt);
  const double JI = mode1.area(s.dn_max);
  const double JII = mode2.area(s.dt_max);
  if (JI / mode1.toughness() + JII / mode2.toughness() >= 1.0 || s.dn_max >= mode1.delta_c ||
      s.dt_max >= mode2.delta_c) {
    s.failed = true;
    s.JI = JI;
    s.JII = JII;
    return t;
  }
  t.tn = dn > 0.0 ? mode1.traction(dn, s.dn_max) : 0.0;
  const double tt = mode2.traction(adt, s.dt_max);
  t.tt = dt < 0.0 ? -tt : tt;
  return t;
}

}  // namespace cutbench::mpm
