#include "cutbench/common/glossary.hpp"
#include "cutbench/analytic/models.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "cutbench/analytic/chip_transition.hpp"
#include "cutbench/analytic/composite_failure.hpp"
#include "cutbench/analytic/cutting.hpp"
#include "cutbench/analytic/fracture_cutting.hpp"
#include "cutbench/common/errors.hpp"

namespace cutbench::analytic {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();
double deg(double d) { return d * kPi / 180.0; }
double todeg(double r) { return r * 180.0 / kPi; }

// ---- parameter builders --------------------------------------------------------------------

ParamSpec ranged(std::string name, Dim dim, std::string desc, double lo, bool lo_inc, double hi,
                 bool hi_inc, std::optional<double> def = std::nullopt) {
  return param(std::move(name), dim, std::move(desc), def, lo, hi, lo_inc, hi_inc);
}
// > 0
ParamSpec pos(std::string name, Dim dim, std::string desc, std::optional<double> def = std::nullopt) {
  return ranged(std::move(name), dim, std::move(desc), 0.0, false, kInf, true, def);
}
// >= 0
ParamSpec nonneg(std::string name, Dim dim, std::string desc, std::optional<double> def = std::nullopt) {
  return ranged(std::move(name), dim, std::move(desc), 0.0, true, kInf, true, def);
}
// any finite value
ParamSpec any(std::string name, Dim dim, std::string desc, std::optional<double> def = std::nullopt) {
  return ranged(std::move(name), dim, std::move(desc), -kInf, true, kInf, true, def);
}
ParamSpec rake_param(std::optional<double> def = 0.0, std::string name = glossary::kRakeAngle) {
  return ranged(std::move(name), Dim::angle, "tool rake angle", -kPi / 2, false, kPi / 2, false, def);
}
ParamSpec mu_param(std::optional<double> def = std::nullopt) {
  return nonneg(glossary::kFriction, Dim::dimensionless, "Coulomb friction coefficient on the rake face (mu = tan beta)", def);
}
// Shear-plane angle in (0, 90 deg).
ParamSpec shear_angle_param(std::string name, std::string desc, std::optional<double> def = std::nullopt) {
  return ranged(std::move(name), Dim::angle, std::move(desc), 0.0, false, kPi / 2, false, def);
}

OutputSpec out(std::string name, Dim dim, std::string desc) {
  return OutputSpec{std::move(name), dim, std::move(desc)};
}

bool given(const Values& v, const std::string& name) { return !std::isnan(v.at(name)); }

ModelResult not_applicable(std::string note) {
  ModelResult r;
  r.applicable = false;
  r.note = std::move(note);
  return r;
}

// ---- cutting mechanics ---------------------------------------------------------------------

ModelSpec merchant_model() {
  ModelSpec m;
  m.name = "merchant";
  m.description =
      "Merchant/Ernst single-shear-plane model: shear angle (minimum energy unless phi is given), "
      "cutting and thrust forces, chip thickness ratio and shear strain";
  m.source = "da Costa Figueiredo et al. 2024 LAJSS Eqs. 1-3 (Eq. 3 with beta -> beta - alpha); EQUATIONS.md C1";
  m.params = {rake_param(0.0), mu_param(),
              pos("k", Dim::stress, "shear flow stress of the work material"),
              pos("t1", Dim::length, "uncut chip thickness (depth of cut)"),
              pos("w", Dim::length, "width of cut"),
              shear_angle_param("phi", "shear-plane angle; unset: Merchant's phi_M = pi/4 - (beta - alpha)/2", kNaN)};
  m.outputs = {out("phi", Dim::angle, "shear-plane angle used"),
               out("phi_deg", Dim::dimensionless, "shear-plane angle in degrees"),
               out("beta", Dim::angle, "friction angle atan(mu)"),
               out("F_c", Dim::force, "cutting force k t1 w cos(beta-alpha)/(sin phi cos(phi+beta-alpha))"),
               out("F_t", Dim::force, "thrust (feed) force F_c tan(beta - alpha)"),
               out("F_c_bar", Dim::dimensionless, "F_c/(k t1 w)"),
               out("chip_ratio", Dim::dimensionless, "t2/t1 = cos(phi - alpha)/sin(phi)"),
               out("shear_strain", Dim::dimensionless, "gamma = cot(phi) + tan(phi - alpha)")};
  m.evaluate = [](const Values& v) {
    const double a = v.at("rake"), beta = friction_angle(v.at("mu"));
    const double phi = given(v, "phi") ? v.at("phi") : merchant_shear_angle(a, beta);
    if (!(phi > 0.0)) return not_applicable("no Merchant shear angle: beta - rake >= 90 deg");
    if (!(std::cos(phi + beta - a) > 0.0)) {
      if (given(v, "phi")) throw InputError("phi", "phi + beta - rake must be below 90 deg");
      return not_applicable("no Merchant solution: phi + beta - rake >= 90 deg");
    }
    const auto f = merchant_forces(v.at("k"), v.at("t1"), v.at("w"), a, beta, phi);
    ModelResult r;
    r.outputs = {{"phi", phi}, {"phi_deg", todeg(phi)}, {"beta", beta}, {"F_c", f.F_c}, {"F_t", f.F_t},
                 {"F_c_bar", f.F_c_bar}, {"chip_ratio", chip_thickness_ratio(phi, a)},
                 {"shear_strain", shear_strain(phi, a)}};
    return r;
  };
  return m;
}

ModelSpec chip_geometry_model() {
  ModelSpec m;
  m.name = "chip_geometry";
  m.description = "Ernst-Merchant chip geometry from the shear angle or from the cutting ratio r = t1/t2";
  m.source = "Kahwash et al. 2018 Eq. 59; da Costa Figueiredo et al. 2024 Eq. 2; EQUATIONS.md C1";
  m.params = {rake_param(0.0),
              shear_angle_param("phi", "shear-plane angle (give phi or r)", kNaN),
              pos("r", Dim::dimensionless,
                  "cutting ratio t1/t2 (give phi or r); Eq. 59: phi = atan(r cos a/(1 - r sin a))", kNaN)};
  m.outputs = {out("phi", Dim::angle, "shear-plane angle"),
               out("phi_deg", Dim::dimensionless, "shear-plane angle in degrees"),
               out("chip_ratio", Dim::dimensionless, "t2/t1 = cos(phi - alpha)/sin(phi)"),
               out("cutting_ratio", Dim::dimensionless, "r = t1/t2"),
               out("shear_strain", Dim::dimensionless, "gamma = cot(phi) + tan(phi - alpha)")};
  m.evaluate = [](const Values& v) {
    const bool has_phi = given(v, "phi"), has_r = given(v, "r");
    if (has_phi == has_r) throw InputError(has_phi ? "r" : "phi", "give exactly one of phi and r");
    const double a = v.at("rake");
    const double phi = has_phi ? v.at("phi") : shear_angle_from_cutting_ratio(v.at("r"), a);
    if (!(phi - a < kPi / 2)) throw InputError(has_phi ? "phi" : "r", "phi - rake must be below 90 deg");
    const double cr = chip_thickness_ratio(phi, a);
    ModelResult r;
    r.outputs = {{"phi", phi}, {"phi_deg", todeg(phi)}, {"chip_ratio", cr}, {"cutting_ratio", 1.0 / cr},
                 {"shear_strain", shear_strain(phi, a)}};
    return r;
  };
  return m;
}

ModelSpec devries_model() {
  ModelSpec m;
  m.name = "devries";
  m.description = "Shear flow stress k (DeVries), shear-plane normal stress and rake-face friction from measured forces";
  m.source = "da Costa Figueiredo et al. 2024 Eq. 14 (DeVries 1992), Eq. 1 for phi_M; EQUATIONS.md C3";
  m.params = {pos("F_c", Dim::force, "measured cutting force"),
              any("F_f", Dim::force, "measured feed (thrust) force"),
              shear_angle_param("phi", "measured shear-plane angle"),
              pos("t1", Dim::length, "uncut chip thickness"), pos("w", Dim::length, "width of cut"),
              rake_param(0.0)};
  m.outputs = {out("k", Dim::stress, "shear flow stress (F_c sin phi cos phi - F_f sin^2 phi)/(t1 w)"),
               out("sigma_n", Dim::stress, "normal stress on the shear plane (F_c sin^2 phi + F_f sin phi cos phi)/(t1 w)"),
               out("mu", Dim::dimensionless, "friction coefficient (F_f + F_c tan a)/(F_c - F_f tan a)"),
               out("beta", Dim::angle, "friction angle atan(mu)"),
               out("F_c_bar", Dim::dimensionless, "F_c/(t1 w k)"),
               out("phi_merchant", Dim::angle, "Merchant angle from that mu"),
               out("phi_merchant_deg", Dim::dimensionless, "Merchant angle in degrees")};
  m.evaluate = [](const Values& v) {
    const double a = v.at("rake");
    const auto d = devries(v.at("F_c"), v.at("F_f"), v.at("phi"), v.at("t1"), v.at("w"), a);
    ModelResult r;
    const double pm = merchant_shear_angle(a, d.beta);
    r.outputs = {{"k", d.k}, {"sigma_n", d.sigma_n}, {"mu", d.mu}, {"beta", d.beta}, {"F_c_bar", d.F_c_bar},
                 {"phi_merchant", pm}, {"phi_merchant_deg", todeg(pm)}};
    if (!(d.k > 0.0)) {
      r.applicable = false;
      r.note = "forces give a non-positive shear flow stress (F_f tan(phi) >= F_c)";
    }
    return r;
  };
  return m;
}

ModelSpec molinari_moufki_model() {
  ModelSpec m;
  m.name = "molinari_moufki";
  m.description = "Molinari-Moufki cutting force for phi <= phi* (Merchant) and phi >= phi* (chip-formation branch)";
  m.source =
      "da Costa Figueiredo et al. 2024 Eqs. 3-4 (Molinari & Moufki 2008) with beta -> beta - alpha for a "
      "non-zero rake; Eq. 4 form confidence M/L (EQUATIONS.md C2)";
  m.params = {pos("k", Dim::stress, "shear flow stress"), pos("t1", Dim::length, "uncut chip thickness"),
              pos("w", Dim::length, "width of cut"), mu_param(), rake_param(0.0),
              shear_angle_param("phi", "shear-plane angle"),
              shear_angle_param("phi_star", "optimal (stability) shear angle phi*")};
  m.outputs = {out("F_c", Dim::force, "cutting force"), out("F_c_bar", Dim::dimensionless, "F_c/(k t1 w)"),
               out("branch", Dim::dimensionless, "3 (phi <= phi*, Eq. 3) or 4 (phi > phi*, Eq. 4)"),
               out("phi_merchant", Dim::angle, "Merchant angle phi_M")};
  m.evaluate = [](const Values& v) {
    const double a = v.at("rake"), beta = friction_angle(v.at("mu"));
    const double phi = v.at("phi"), ps = v.at("phi_star");
    if (!(std::cos(phi + beta - a) > 0.0)) throw InputError("phi", "phi + beta - rake must be below 90 deg");
    const double fb = molinari_moufki_force_bar(a, beta, phi, ps);
    ModelResult r;
    r.outputs = {{"F_c", fb * v.at("k") * v.at("t1") * v.at("w")}, {"F_c_bar", fb},
                 {"branch", phi <= ps ? 3.0 : 4.0}, {"phi_merchant", merchant_shear_angle(a, beta)}};
    return r;
  };
  return m;
}

ModelSpec zorev_model() {
  ModelSpec m;
  m.name = "zorev_contact";
  m.description = "Zorev tool-chip contact length l = m t2 (tan beta + tan(phi - alpha)) (Hahn and Rubenstein forms: not sourced)";
  m.source = "da Costa Figueiredo et al. 2024 Eq. 15 (after Fatima & Mativenga 2013); equals EQUATIONS.md C4(b)";
  m.params = {pos("t1", Dim::length, "uncut chip thickness"), rake_param(0.0), mu_param(),
              shear_angle_param("phi", "shear-plane angle; unset: Merchant's phi_M", kNaN),
              pos("m", Dim::dimensionless, "material factor m (Figueiredo fit: about 1.10)", 1.0)};
  m.outputs = {out("l", Dim::length, "contact length"), out("l_over_t1", Dim::dimensionless, "l/t1"),
               out("t2", Dim::length, "chip thickness t1 cos(phi - alpha)/sin(phi)"),
               out("phi", Dim::angle, "shear-plane angle used")};
  m.evaluate = [](const Values& v) {
    const double a = v.at("rake"), t1 = v.at("t1");
    const double phi = given(v, "phi") ? v.at("phi") : merchant_shear_angle(a, friction_angle(v.at("mu")));
    if (!(phi - a < kPi / 2)) throw InputError("phi", "phi - rake must be below 90 deg");
    const double l = zorev_contact_length(t1, a, friction_angle(v.at("mu")), phi, v.at("m"));
    ModelResult r;
    r.outputs = {{"l", l}, {"l_over_t1", l / t1}, {"t2", t1 * chip_thickness_ratio(phi, a)}, {"phi", phi}};
    return r;
  };
  return m;
}

ModelSpec kahwash_strengths_model() {
  ModelSpec m;
  m.name = "kahwash_strengths";
  m.description = "Shear and normal strengths on the Merchant shear plane from measured forces and the cutting ratio";
  m.source = "Kahwash et al. 2018 Eqs. 57-59 (Table 1)";
  m.params = {any("F_c", Dim::force, "measured cutting force"), any("F_t", Dim::force, "measured thrust force"),
              pos("r", Dim::dimensionless, "cutting ratio t1/t2 (Kahwash: about 1 for brittle composites)", 1.0),
              rake_param(0.0), pos("t1", Dim::length, "depth of cut"), pos("w", Dim::length, "width of cut")};
  m.outputs = {out("phi", Dim::angle, "shear-plane angle (Eq. 59)"),
               out("phi_deg", Dim::dimensionless, "shear-plane angle in degrees"),
               out("F_s", Dim::force, "shear force on the shear plane F_c cos phi - F_t sin phi (Eq. 57)"),
               out("F_ns", Dim::force, "normal force on the shear plane F_c sin phi + F_t cos phi (Eq. 58)"),
               out("shear_strength", Dim::stress, "F_s sin(phi)/(t1 w)"),
               out("normal_strength", Dim::stress, "F_ns sin(phi)/(t1 w)")};
  m.evaluate = [](const Values& v) {
    const double phi = shear_angle_from_cutting_ratio(v.at("r"), v.at("rake"));
    const auto f = shear_plane_forces(v.at("F_c"), v.at("F_t"), phi);
    const double area = v.at("t1") * v.at("w") / std::sin(phi);
    ModelResult r;
    r.outputs = {{"phi", phi}, {"phi_deg", todeg(phi)}, {"F_s", f.F_s}, {"F_ns", f.F_ns},
                 {"shear_strength", f.F_s / area}, {"normal_strength", f.F_ns / area}};
    return r;
  };
  return m;
}

// ---- Nairn ---------------------------------------------------------------------------------

ModelSpec nairn_friction_model() {
  ModelSpec m;
  m.name = "nairn_friction";
  m.description =
      "Rake-face friction with a rubbing force: Z = (mu - tan a)/(1 + mu tan a), F_t = Z F_c + (1 - mu Z) F_nb; "
      "give F_c with F_nb (-> F_t) or with F_t (-> F_nb)";
  m.source = "Nairn 2015 EFM Eqs. 11-12; EQUATIONS.md A5";
  m.params = {mu_param(), rake_param(0.0),
              any("F_c", Dim::force_per_width, "cutting force per width", kNaN),
              any("F_nb", Dim::force_per_width, "rubbing normal force per width", kNaN),
              any("F_t", Dim::force_per_width, "thrust force per width", kNaN)};
  m.outputs = {out("Z", Dim::dimensionless, "friction factor tan(beta - alpha)"),
               out("F_t", Dim::force_per_width, "thrust force per width (Eq. 12)"),
               out("F_nb", Dim::force_per_width, "rubbing force per width (Eq. 12 inverted)")};
  m.evaluate = [](const Values& v) {
    const double mu = v.at("mu"), a = v.at("rake");
    const bool c = given(v, "F_c"), n = given(v, "F_nb"), t = given(v, "F_t");
    if (c && n && t) throw InputError("F_t", "give at most two of F_c, F_nb, F_t");
    if (!c && (n || t)) throw InputError("F_c", "F_c is needed with F_nb or F_t");
    ModelResult r;
    r.outputs["Z"] = nairn_friction_factor(mu, a);
    r.outputs["F_t"] = t ? v.at("F_t") : (c && n ? nairn_thrust_force(v.at("F_c"), v.at("F_nb"), mu, a) : kNaN);
    r.outputs["F_nb"] = n ? v.at("F_nb") : (c && t ? nairn_rubbing_force(v.at("F_c"), v.at("F_t"), mu, a) : kNaN);
    return r;
  };
  return m;
}

ModelSpec atkins_model() {
  ModelSpec m;
  m.name = "atkins_touching";
  m.description =
      "Crack-tip-touching (Atkins) model with rubbing force and friction, minimised over the shear angle; "
      "reduces to Eq. 15 at mu = 0 and to Merchant at G_c = 0";
  m.source = "Nairn 2015 EFM Eqs. 13-15 (Eq. 14 as printed); shear angle EQUATIONS.md A6";
  m.params = {nonneg("G_c", Dim::energy_per_area, "toughness (fracture energy)"),
              pos("sigma_y", Dim::stress, "tensile yield stress"), pos(glossary::kDepthOfCut, Dim::length, "depth of cut h"),
              rake_param(0.0), mu_param(0.0),
              nonneg("F_nb", Dim::force_per_width, "rubbing normal force per width", 0.0),
              pos("Y", Dim::dimensionless, "tau_y = sigma_y/Y: sqrt(3) von Mises (Eq. 2), 2 Tresca", std::sqrt(3.0)),
              pos("E_prime", Dim::stress, "plane-strain modulus, only for h* (optional)", kNaN)};
  m.outputs = {out("F_c", Dim::force_per_width, "cutting force per width (Eq. 14)"),
               out("F_c_dimless", Dim::dimensionless, "F_c/(b G_c)"),
               out("phi", Dim::angle, "force-minimising shear angle"),
               out("phi_deg", Dim::dimensionless, "shear angle in degrees"),
               out("F_t", Dim::force_per_width, "thrust force per width (Eq. 12)"),
               out("h_star", Dim::dimensionless, "sigma_y^2 h/(2 E' G_c) (NaN without E_prime)")};
  m.evaluate = [](const Values& v) {
    AtkinsInput in;
    in.G_c = v.at("G_c");
    in.sigma_y = v.at("sigma_y");
    in.h = v.at(glossary::kDepthOfCut);
    in.rake = v.at("rake");
    in.mu = v.at("mu");
    in.F_nb = v.at("F_nb");
    in.Y = v.at("Y");
    if (!(1.0 + in.mu * std::tan(in.rake) > 0.0)) {
      return not_applicable("1 + mu tan(rake) <= 0: friction law of Eq. 12 undefined");
    }
    const auto a = atkins_cutting(in);
    ModelResult r;
    r.outputs = {{"F_c", a.F_c}, {"F_c_dimless", in.G_c > 0.0 ? a.F_c / in.G_c : kNaN}, {"phi", a.phi},
                 {"phi_deg", todeg(a.phi)}, {"F_t", a.F_t},
                 {"h_star", given(v, "E_prime") && in.G_c > 0.0
                                ? dimensionless_depth(in.sigma_y, in.h, v.at("E_prime"), in.G_c)
                                : kNaN}};
    return r;
  };
  return m;
}

ModelSpec williams_model() {
  ModelSpec m;
  m.name = "williams_bending";
  m.description =
      "Williams et al. plastic-bending (tool off the crack tip) model with rubbing force and linear hardening: "
      "Eq. 19 solved for k0 (GSL Brent), Eq. 18 for F_c, Eq. 12 for F_t; no solution when Z > 0";
  m.source = "Nairn 2015 EFM Eqs. 16-20; EQUATIONS.md A7";
  m.params = {pos("G_c", Dim::energy_per_area, "toughness"),
              pos("sigma_y0", Dim::stress, "initial yield stress"),
              pos("E_prime", Dim::stress, "plane-strain modulus E/(1 - nu^2)"),
              nonneg("E_p", Dim::stress, "plastic (hardening) modulus, E_p = E E_T/(E - E_T); 0 = perfectly plastic", 0.0),
              pos(glossary::kDepthOfCut, Dim::length, "depth of cut h (chip thickness)"), rake_param(0.0), mu_param(0.0),
              nonneg("F_nb", Dim::force_per_width, "rubbing normal force per width", 0.0),
              pos("lambda", Dim::dimensionless, "crack-root rotation correction", 0.64)};
  m.outputs = {out("k0", Dim::dimensionless, "root curvature / yield curvature 2 sigma_y0/(h E')"),
               out("F_c", Dim::force_per_width, "cutting force per width (Eq. 18)"),
               out("F_c_dimless", Dim::dimensionless, "F_c/(b G_c)"),
               out("F_t", Dim::force_per_width, "thrust force per width (Eq. 12)"),
               out("A1_dimless", Dim::dimensionless, "A1/(b G_c)"),
               out("A2_dimless", Dim::dimensionless, "A2/(b G_c)"),
               out("h_star", Dim::dimensionless, "sigma_y0^2 h/(2 E' G_c)")};
  m.evaluate = [](const Values& v) {
    WilliamsInput in;
    in.G_c = v.at("G_c");
    in.sigma_y0 = v.at("sigma_y0");
    in.E_prime = v.at("E_prime");
    in.E_p = v.at("E_p");
    in.h = v.at(glossary::kDepthOfCut);
    in.rake = v.at("rake");
    in.mu = v.at("mu");
    in.F_nb = v.at("F_nb");
    in.lambda = v.at("lambda");
    if (!(1.0 + in.mu * std::tan(in.rake) > 0.0)) {
      return not_applicable("1 + mu tan(rake) <= 0: friction law of Eq. 12 undefined");
    }
    const auto w = williams_bending(in);
    ModelResult r;
    r.applicable = w.applicable;
    r.note = w.note;
    r.outputs["h_star"] = w.h_star;
    if (w.applicable) {
      r.outputs["k0"] = w.kappa0;
      r.outputs["F_c"] = w.F_c;
      r.outputs["F_c_dimless"] = w.F_c_dimless;
      r.outputs["F_t"] = w.F_t;
      r.outputs["A1_dimless"] = w.a1;
      r.outputs["A2_dimless"] = w.a2;
    }
    return r;
  };
  return m;
}

ModelSpec moment_curvature_model() {
  ModelSpec m;
  m.name = "moment_curvature";
  m.description = "Beam moment-curvature law with linear hardening and the areas A1, A2 of Fig. 7 (per unit width)";
  m.source = "Nairn 2015 EFM Eq. 20 and Fig. 7; EQUATIONS.md A7 (areas derived from Eq. 20)";
  m.params = {pos("sigma_y0", Dim::stress, "initial yield stress"),
              pos("E_prime", Dim::stress, "plane-strain modulus"),
              nonneg("E_p", Dim::stress, "plastic modulus (0 = perfectly plastic)", 0.0),
              pos("h", Dim::length, "beam (chip) thickness"),
              pos("kappa0", Dim::dimensionless, "curvature / yield curvature k_y = 2 sigma_y0/(h E')")};
  m.outputs = {out("M", Dim::moment_per_width, "bending moment per width"),
               out("M_dimless", Dim::dimensionless, "M/M_y, M_y = sigma_y0 h^2/6 per width"),
               out("k", Dim::inverse_length, "curvature kappa0 k_y"),
               out("k_y", Dim::inverse_length, "yield curvature 2 sigma_y0/(h E')"),
               out("A1", Dim::energy_per_area, "complementary area A1/b (Fig. 7)"),
               out("A2", Dim::energy_per_area, "loading-unloading loop area A2/b (Fig. 7)"),
               out("A1_hat", Dim::dimensionless, "A1/(M_y k_y)"),
               out("A2_hat", Dim::dimensionless, "A2/(M_y k_y)")};
  m.evaluate = [](const Values& v) {
    const double sy = v.at("sigma_y0"), Ep = v.at("E_prime"), h = v.at("h"), k0 = v.at("kappa0");
    const double bh = v.at("E_p") / Ep;
    const double My = sy * h * h / 6.0, ky = 2.0 * sy / (h * Ep), myky = my_ky_per_width(sy, h, Ep);
    ModelResult r;
    r.outputs = {{"M", My * moment_hat(k0, bh)}, {"M_dimless", moment_hat(k0, bh)}, {"k", k0 * ky}, {"k_y", ky},
                 {"A1", myky * area_A1_hat(k0, bh)}, {"A2", myky * area_A2_hat(k0, bh)},
                 {"A1_hat", area_A1_hat(k0, bh)}, {"A2_hat", area_A2_hat(k0, bh)}};
    return r;
  };
  return m;
}

// ---- Aghababaei ----------------------------------------------------------------------------

ModelSpec dcb_model() {
  ModelSpec m;
  m.name = "dcb_energy_release";
  m.description = "DCB energy release rate G = (N^2 + S^2 + 12 M^2/d^2)/(E w^2 d), with forces and moment per unit width";
  m.source = "Aghababaei et al. 2021 PRL Eq. 1 (N/w, S/w, M/w given per width)";
  m.params = {pos("E", Dim::stress, "elastic modulus"), pos("d", Dim::length, "chip thickness"),
              any("N", Dim::force_per_width, "normal force per width at the crack tip", 0.0),
              any("S", Dim::force_per_width, "shear force per width at the crack tip", 0.0),
              any("M", Dim::moment_per_width, "bending moment per width at the crack tip", 0.0)};
  m.outputs = {out("G", Dim::energy_per_area, "energy release rate")};
  m.evaluate = [](const Values& v) {
    ModelResult r;
    r.outputs = {{"G", dcb_energy_release_rate_per_width(v.at("E"), v.at("d"), v.at("N"), v.at("S"), v.at("M"))}};
    return r;
  };
  return m;
}

ModelSpec aghababaei_model() {
  ModelSpec m;
  m.name = "aghababaei_transition";
  m.description =
      "Fracture force, plastic shearing force, critical depth d_c and regime (+1 fracture-induced chip "
      "breakage for d > d_c, -1 plastic shearing)";
  m.source = "Aghababaei et al. 2021 PRL Eqs. 2-4 (Merchant shear angle)";
  m.params = {pos("K_IC", Dim::stress_intensity, "fracture toughness"),
              pos("tau_ys", Dim::stress, "shear strength"), rake_param(deg(45.0)), mu_param(0.3),
              pos("alpha_c", Dim::dimensionless, "contact length / chip thickness ratio", 1.2),
              pos("w", Dim::length, "width of cut"), pos(glossary::kDepthOfCut, Dim::length, "depth of cut d")};
  m.outputs = {out("phi", Dim::angle, "Merchant shear angle pi/4 + lambda/2 - beta/2"),
               out("phi_deg", Dim::dimensionless, "shear angle in degrees"),
               out("F_fr", Dim::force, "fracture force (Eq. 2)"), out("F_pl", Dim::force, "plastic shearing force (Eq. 3)"),
               out("shape_factor", Dim::dimensionless, "(tan phi cos lambda)^2/(12 alpha^2 + 1)"),
               out("d_c", Dim::length, "critical depth of cut (Eq. 4)"),
               out("regime", Dim::dimensionless, "+1 fracture (d > d_c), -1 plastic shearing (d < d_c), 0 at d_c"),
               out("F_ratio", Dim::dimensionless, "F_fr/F_pl")};
  m.evaluate = [](const Values& v) {
    const double lam = v.at("rake"), mu = v.at("mu"), a = v.at("alpha_c"), w = v.at("w"), d = v.at(glossary::kDepthOfCut);
    const double phi = aghababaei_shear_angle(lam, mu);
    if (!(phi > 0.0 && phi < kPi / 2)) return not_applicable("Merchant shear angle outside (0, 90 deg)");
    if (!(std::cos(lam) > 0.0)) return not_applicable("rake angle must be below 90 deg");
    const double Ffr = fracture_force(v.at("K_IC"), w, d, lam, a);
    const double Fpl = plastic_shearing_force(v.at("tau_ys"), w, d, phi);
    const double dc = critical_depth(v.at("K_IC"), v.at("tau_ys"), lam, mu, a);
    ModelResult r;
    r.outputs = {{"phi", phi}, {"phi_deg", todeg(phi)}, {"F_fr", Ffr}, {"F_pl", Fpl},
                 {"shape_factor", critical_depth_shape_factor(lam, mu, a)}, {"d_c", dc},
                 {"regime", static_cast<double>(chip_regime(d, dc))}, {"F_ratio", Ffr / Fpl}};
    return r;
  };
  return m;
}

// ---- composite failure ---------------------------------------------------------------------

std::vector<ParamSpec> strength_params(bool with_S_T) {
  std::vector<ParamSpec> p = {
      pos("X_T", Dim::stress, "longitudinal tensile strength"),
      pos("X_C", Dim::stress, "longitudinal compressive strength (positive)"),
      pos("Y_T", Dim::stress, "transverse tensile strength"),
      pos("Y_C", Dim::stress, "transverse compressive strength (positive)"),
      pos("S_L", Dim::stress, "in-plane (longitudinal) shear strength")};
  if (with_S_T) {
    p.push_back(pos("S_T", Dim::stress,
                    "transverse shear strength (Hashin); unset: Y_C cos a0 (sin a0 + cos a0/tan 2a0), a0 = 53 deg",
                    kNaN));
  }
  return p;
}

std::vector<ParamSpec> larc_params(std::optional<double> def) {
  return {pos("E1", Dim::stress, "longitudinal modulus (LaRC02)", def),
          pos("G12", Dim::stress, "in-plane shear modulus (LaRC02 kinking)", def),
          ranged("nu12", Dim::dimensionless, "major Poisson ratio (LaRC02 fibre strain)", 0.0, true, 5.0, true, def),
          pos("eps1_T", Dim::dimensionless, "fibre tensile failure strain; unset: X_T/E1", kNaN),
          ranged("alpha0", Dim::angle, "fracture angle in pure transverse compression", kPi / 4, false, kPi / 2,
                 false, deg(53.0)),
          nonneg("g", Dim::dimensionless, "G_Ic/G_IIc in the matrix-tension form; 1 = Kahwash's printed quadratic form", 1.0)};
}

Lamina lamina_from(const Values& v) {
  Lamina m;
  m.X_T = v.at("X_T");
  m.X_C = v.at("X_C");
  m.Y_T = v.at("Y_T");
  m.Y_C = v.at("Y_C");
  m.S_L = v.at("S_L");
  m.S_T = v.count("S_T") && given(v, "S_T") ? v.at("S_T") : 0.0;
  if (v.count("E1")) {
    m.E1 = v.at("E1");
    m.G12 = v.at("G12");
    m.nu12 = v.at("nu12");
    m.eps1_T = given(v, "eps1_T") ? v.at("eps1_T") : 0.0;
    m.alpha0 = v.at("alpha0");
    m.g = v.at("g");
  }
  return m;
}

std::vector<ParamSpec> stress_params() {
  return {any("sigma11", Dim::stress, "fibre-direction normal stress", 0.0),
          any("sigma22", Dim::stress, "transverse normal stress", 0.0),
          any("tau12", Dim::stress, "in-plane shear stress", 0.0)};
}

ModelSpec failure_model(Criterion c) {
  ModelSpec m;
  const char* names[] = {"failure_max_stress", "failure_hashin", "failure_larc02"};
  m.name = names[static_cast<int>(c)];
  m.params = stress_params();
  std::vector<ParamSpec> s = strength_params(c == Criterion::hashin);
  m.params.insert(m.params.end(), s.begin(), s.end());
  m.outputs = {out("fibre", Dim::dimensionless, "fibre failure index (tension or compression)"),
               out("matrix", Dim::dimensionless, "matrix failure index (tension or compression)")};
  switch (c) {
    case Criterion::max_stress:
      m.description = "Maximum-stress criterion in Kahwash's squared form ((s/strength)^2 per mode)";
      m.source = "Kahwash et al. 2018 Appendix A.1";
      m.outputs.push_back(out("shear", Dim::dimensionless, "in-plane shear index (tau12/S_L)^2"));
      break;
    case Criterion::hashin:
      m.description = "Hashin (1980) plane-stress criterion: fibre and matrix modes";
      m.source = "Kahwash et al. 2018 Appendix A.2; EQUATIONS.md E2";
      break;
    case Criterion::larc02: {
      m.description =
          "LaRC02: strain-based fibre tension, fibre kinking in the misalignment frame, matrix tension, matrix "
          "compression with a fracture-plane search over [0, alpha0]; UD bulk: no in-situ strengths";
      m.source = "Kahwash et al. 2018 Appendix A.3 (Davila et al. LaRC02); EQUATIONS.md E1";
      auto l = larc_params(std::nullopt);
      m.params.insert(m.params.end(), l.begin(), l.end());
      m.outputs.push_back(out("fracture_angle", Dim::angle, "fracture-plane angle (matrix compression; NaN otherwise)"));
      m.outputs.push_back(out("misalignment", Dim::angle, "kink misalignment angle psi (s11 < 0; NaN otherwise)"));
      break;
    }
  }
  m.outputs.push_back(out("index", Dim::dimensionless, "largest failure index (failure at 1)"));
  m.outputs.push_back(out("mode", Dim::dimensionless,
                          "governing mode: 1 fibre tension, 2 fibre compression, 3 matrix tension, "
                          "4 matrix compression, 5 shear"));
  m.evaluate = [c](const Values& v) {
    const Lamina lam = lamina_from(v);
    const auto f = failure_indices(c, {v.at("sigma11"), v.at("sigma22"), v.at("tau12")}, lam);
    ModelResult r;
    r.outputs = {{"fibre", f.fibre}, {"matrix", f.matrix}, {"index", f.index},
                 {"mode", static_cast<double>(static_cast<int>(f.mode))}};
    if (c == Criterion::max_stress) r.outputs["shear"] = f.shear;
    if (c == Criterion::larc02) {
      r.outputs["fracture_angle"] = f.fracture_angle;
      r.outputs["misalignment"] = f.misalignment;
    }
    return r;
  };
  return m;
}

ModelSpec envelope_model() {
  ModelSpec m;
  m.name = "failure_envelope";
  m.description =
      "Failure envelope point: distance along a ray in the s11-s22 (plane s11_s22, tau12 fixed) or s22-tau12 "
      "(plane s22_tau12, s11 fixed) plane to the first point with index 1 (bracket scan + GSL Brent)";
  m.source = "Kahwash et al. 2018 Fig. 3 and Appendix A";
  ParamSpec criterion = criterion_param("max_stress");
  criterion.default_value.reset();  // required
  ParamSpec plane_spec = option_param("plane", "the stress plane of the envelope",
                                 {{"s11_s22", "sigma11-sigma22 plane, tau12 fixed"},
                                  {"s22_tau12", "sigma22-tau12 plane, sigma11 fixed"}},
                                 "s11_s22");
  plane_spec.default_value.reset();  // required
  m.params = {criterion, plane_spec,
              any("theta", Dim::angle, "direction of the ray from the s1 axis", 0.0),
              any("fixed", Dim::stress, "the third stress: tau12 (plane s11_s22) or sigma11 (plane s22_tau12)", 0.0)};
  auto s = strength_params(true);
  m.params.insert(m.params.end(), s.begin(), s.end());
  auto l = larc_params(kNaN);
  m.params.insert(m.params.end(), l.begin(), l.end());
  m.outputs = {out("radius", Dim::stress, "distance to the failure surface along the ray"),
               out("s1", Dim::stress, "sigma11 (plane s11_s22) or sigma22 (plane s22_tau12) at failure"),
               out("s2", Dim::stress, "sigma22 (plane s11_s22) or tau12 (plane s22_tau12) at failure"),
               out("mode", Dim::dimensionless, "governing mode at the envelope point (codes as failure_*)")};
  m.evaluate = [](const Values& v) {
    const double cv = v.at("criterion"), pv = v.at("plane");  // validated option indices
    const auto c = static_cast<Criterion>(static_cast<int>(cv));
    const auto plane = static_cast<EnvelopePlane>(static_cast<int>(pv));
    if (c == Criterion::larc02) {
      for (const char* name : {"E1", "G12", "nu12"}) {
        if (!given(v, name)) throw InputError(name, "required for criterion \"larc02\"");
      }
    }
    Lamina lam = lamina_from(v);
    if (c != Criterion::larc02) {
      lam.E1 = 1.0;  // unused outside LaRC02
    }
    const auto p = failure_envelope_point(c, plane, v.at("theta"), v.at("fixed"), lam);
    const PlaneStress st = plane == EnvelopePlane::s11_s22 ? PlaneStress{p.s1, p.s2, v.at("fixed")}
                                                           : PlaneStress{v.at("fixed"), p.s1, p.s2};
    ModelResult r;
    r.outputs = {{"radius", p.radius}, {"s1", p.s1}, {"s2", p.s2},
                 {"mode", static_cast<double>(static_cast<int>(failure_indices(c, st, lam).mode))}};
    return r;
  };
  return m;
}

}  // namespace

void register_models(ModelRegistry& registry) {
  if (registry.find("merchant")) return;
  registry.add(merchant_model());
  registry.add(chip_geometry_model());
  registry.add(devries_model());
  registry.add(molinari_moufki_model());
  registry.add(zorev_model());
  registry.add(kahwash_strengths_model());
  registry.add(nairn_friction_model());
  registry.add(atkins_model());
  registry.add(williams_model());
  registry.add(moment_curvature_model());
  registry.add(dcb_model());
  registry.add(aghababaei_model());
  registry.add(failure_model(Criterion::max_stress));
  registry.add(failure_model(Criterion::hashin));
  registry.add(failure_model(Criterion::larc02));
  registry.add(envelope_model());
}

}  // namespace cutbench::analytic
