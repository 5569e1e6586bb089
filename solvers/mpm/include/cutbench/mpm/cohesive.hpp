#pragma once
// Cohesive traction laws (EQUATIONS A3) and the decoupled mixed-mode failure criterion
// J_I/J_Ic + J_II/J_IIc = 1 (Nairn 2015, Eq. 4). Pure functions plus a small per-segment state.
namespace cutbench::mpm {

enum class TractionLawType { cubic = 0, triangular = 1 };

struct TractionLaw {
  TractionLawType type = TractionLawType::cubic;
  double sigma_c = 40e6;  // peak traction, Pa
  double delta_c = 0.0889e-3;  // critical opening, m
  // Triangular law only: opening at the peak as a fraction of delta_c (1/3 = cubic law's peak).
  double peak_fraction = 1.0 / 3.0;

  // Toughness (area under the law): 9 sigma_c delta_c / 16 (cubic), sigma_c delta_c / 2 (triangle).
  double toughness() const;
  // Law built from toughness and peak stress.
  static TractionLaw from_toughness(TractionLawType type, double G_c, double sigma_c);
  // Traction on the monotonic envelope at opening d >= 0 (0 beyond delta_c).
  double envelope(double d) const;
  // Area under the envelope from 0 to d (saturates at toughness()).
  double area(double d) const;
  // Traction at opening d >= 0 with unloading/reloading along the secant to the origin from dmax.
  double traction(double d, double dmax) const;
};

// State of one cohesive segment (mode I and II openings are tracked separately).
struct CohesiveState {
  double dn_max = 0.0;  // largest normal opening reached, m
  double dt_max = 0.0;  // largest |tangential| opening reached, m
  bool failed = false;
  double JI = 0.0, JII = 0.0;  // areas J_I(dn_max), J_II(dt_max) at the time of failure, J/m^2
};

struct CohesiveTraction {
  double tn = 0.0;  // normal traction (>= 0: resists opening), Pa
  double tt = 0.0;  // tangential traction, sign opposes dt, Pa
};

// Evaluate tractions at openings (dn, dt) and update the state (maximum openings, failure by the
// decoupled criterion). Mode I acts only for dn > 0; compression is left to crack contact.
CohesiveTraction cohesive_update(const TractionLaw& mode1, const TractionLaw& mode2, double dn, double dt,
                                 CohesiveState& state);

}  // namespace cutbench::mpm
