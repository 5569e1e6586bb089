// The eval adapters: every registered model evaluates with defaults + required parameters,
// declares what it returns, and rejects out-of-range input naming the field.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "cutbench/analytic/models.hpp"
#include "cutbench/common/errors.hpp"

using namespace cutbench;
namespace tt = boost::test_tools;

namespace {
constexpr double kPi = 3.14159265358979323846;
double deg(double d) { return d * kPi / 180.0; }

const ModelRegistry& registry() {
  static ModelRegistry reg;
  analytic::register_models(reg);
  analytic::register_models(reg);  // idempotent
  return reg;
}

// Representative value of every required parameter name.
const std::map<std::string, double>& samples() {
  static const std::map<std::string, double> s = {
      {"mu", 0.5}, {"k", 600e6}, {"t1", 0.2e-3}, {"w", 3.5e-3}, {"F_c", 1447.1}, {"F_f", 793.6},
      {"F_t", 400.0}, {"phi", deg(33.8)}, {"phi_star", deg(28)}, {"G_c", 2000.0}, {"sigma_y", 25e6},
      {"h", 2e-3}, {"sigma_y0", 25e6}, {"E_prime", 1122e6}, {"kappa0", 2.0}, {"E", 3e9}, {"d", 1e-3},
      {"K_IC", 1.5e6}, {"tau_ys", 40e6}, {"X_T", 697.8e6}, {"X_C", 443.76e6}, {"Y_T", 89.7216e6},
      {"Y_C", 148.33e6}, {"S_L", 33.1e6}, {"E1", 34.28e9}, {"G12", 2.05e9}, {"nu12", 0.24244},
      {"criterion", 2.0}, {"plane", 1.0}};
  return s;
}

// Models that need one of several optional inputs.
const std::map<std::string, Values>& extras() {
  static const std::map<std::string, Values> e = {
      {"chip_geometry", {{"r", 0.6}}},
      {"williams_bending", {{"E_p", 111e6}}},  // hardening: a bending root exists at any depth
      {"failure_envelope", {{"E1", 34.28e9}, {"G12", 2.05e9}, {"nu12", 0.24244}}}};
  return e;
}

Values minimal_inputs(const ModelSpec& m) {
  Values v;
  for (const auto& p : m.params) {
    if (!p.default_value) {
      auto it = samples().find(p.name);
      BOOST_TEST_REQUIRE((it != samples().end()), "no sample value for required parameter " << p.name
                                                                                            << " of " << m.name);
      v[p.name] = it->second;
    }
  }
  if (auto it = extras().find(m.name); it != extras().end()) {
    for (const auto& [k, x] : it->second) v[k] = x;
  }
  return v;
}

Values eval(const std::string& name, const Values& v) {
  const auto r = evaluate_model(registry().get(name), v);
  BOOST_TEST_REQUIRE(r.applicable, name << ": " << r.note);
  return r.outputs;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(models)

BOOST_AUTO_TEST_CASE(registry_has_the_proposed_names) {
  for (const char* name : {"merchant", "chip_geometry", "devries", "molinari_moufki", "zorev_contact",
                           "kahwash_strengths", "nairn_friction", "atkins_touching", "williams_bending",
                           "moment_curvature", "dcb_energy_release", "aghababaei_transition",
                           "failure_max_stress", "failure_hashin", "failure_larc02", "failure_envelope"}) {
    BOOST_TEST(registry().find(name) != nullptr, name);
  }
}

BOOST_AUTO_TEST_CASE(every_model_evaluates_with_defaults_and_declares_outputs) {
  for (const auto& m : registry().all()) {
    BOOST_TEST_CONTEXT("model " << m.name) {
      BOOST_TEST(!m.description.empty());
      BOOST_TEST(!m.source.empty());
      for (const auto& p : m.params) BOOST_TEST(!p.description.empty(), p.name);
      for (const auto& o : m.outputs) BOOST_TEST(!o.description.empty(), o.name);
      const auto r = evaluate_model(m, minimal_inputs(m));
      BOOST_TEST(r.applicable, r.note);
      std::set<std::string> declared;
      for (const auto& o : m.outputs) {
        declared.insert(o.name);
        BOOST_TEST(r.outputs.count(o.name) == 1u, "missing output " << o.name);
      }
      for (const auto& [k, x] : r.outputs) BOOST_TEST(declared.count(k) == 1u, "undeclared output " << k);
    }
  }
}

BOOST_AUTO_TEST_CASE(out_of_range_input_names_the_field) {
  for (const auto& m : registry().all()) {
    const Values base = minimal_inputs(m);
    for (const auto& p : m.params) {
      std::vector<double> bad;
      if (std::isfinite(p.min)) bad.push_back(p.min_inclusive ? p.min - 1.0 : p.min);
      if (std::isfinite(p.max)) bad.push_back(p.max_inclusive ? p.max + 1.0 : p.max);
      bad.push_back(std::nan(""));
      for (double x : bad) {
        Values v = base;
        v[p.name] = x;
        BOOST_TEST_CONTEXT("model " << m.name << " param " << p.name << " = " << x) {
          try {
            evaluate_model(m, v);
            BOOST_ERROR("expected InputError");
          } catch (const InputError& e) {
            BOOST_TEST(e.field() == p.name);
          }
        }
      }
    }
    Values v = base;
    v["no_such_parameter"] = 1.0;
    BOOST_CHECK_THROW(evaluate_model(m, v), InputError);
  }
}

BOOST_AUTO_TEST_CASE(rake_angle_is_open_interval) {
  const auto& m = registry().get("merchant");
  Values v = minimal_inputs(m);
  v["rake"] = deg(90);
  BOOST_CHECK_THROW(evaluate_model(m, v), InputError);
  v["rake"] = deg(-90);
  BOOST_CHECK_THROW(evaluate_model(m, v), InputError);
  v["rake"] = deg(89);
  BOOST_CHECK_NO_THROW(evaluate_model(m, v));
}

BOOST_AUTO_TEST_CASE(merchant_and_chip_geometry_values) {
  const auto o = eval("merchant", {{"rake", deg(6)}, {"mu", 0.6797}, {"k", 634.6e6}, {"t1", 0.2e-3}, {"w", 3.5e-3}});
  BOOST_TEST(o.at("phi_deg") == 30.898, tt::tolerance(1e-4));
  BOOST_TEST(o.at("F_c") == o.at("F_c_bar") * 634.6e6 * 0.2e-3 * 3.5e-3, tt::tolerance(1e-13));
  const auto g = eval("chip_geometry", {{"rake", deg(6)}, {"phi", o.at("phi")}});
  BOOST_TEST(g.at("chip_ratio") == o.at("chip_ratio"), tt::tolerance(1e-13));
  const auto g2 = eval("chip_geometry", {{"rake", deg(6)}, {"r", g.at("cutting_ratio")}});
  BOOST_TEST(g2.at("phi") == o.at("phi"), tt::tolerance(1e-13));
  try {
    evaluate_model(registry().get("chip_geometry"), {{"phi", 0.5}, {"r", 0.5}});
    BOOST_ERROR("expected InputError");
  } catch (const InputError& e) {
    BOOST_TEST(e.field() == "r");
  }
  BOOST_CHECK_THROW(evaluate_model(registry().get("chip_geometry"), {}), InputError);
}

BOOST_AUTO_TEST_CASE(devries_model_table1_row2) {
  const auto o = eval("devries", {{"F_c", 3222.0}, {"F_f", 1160.8}, {"phi", deg(32.9)}, {"t1", 0.5e-3},
                                  {"w", 3.5e-3}, {"rake", deg(6)}});
  BOOST_TEST(o.at("k") == 643.97e6, tt::tolerance(1e-4));
  BOOST_TEST(o.at("F_c_bar") == 2.859, tt::tolerance(1e-3));
}

BOOST_AUTO_TEST_CASE(nairn_friction_both_directions) {
  const auto& m = registry().get("nairn_friction");
  const auto a = eval("nairn_friction", {{"mu", 0.3}, {"rake", deg(30)}, {"F_c", 5000.0}, {"F_nb", 600.0}});
  const auto b = eval("nairn_friction", {{"mu", 0.3}, {"rake", deg(30)}, {"F_c", 5000.0}, {"F_t", a.at("F_t")}});
  BOOST_TEST(b.at("F_nb") == 600.0, tt::tolerance(1e-12));
  BOOST_TEST(std::isnan(eval("nairn_friction", {{"mu", 0.3}}).at("F_t")));
  BOOST_CHECK_THROW(evaluate_model(m, {{"mu", 0.3}, {"F_c", 1.0}, {"F_t", 1.0}, {"F_nb", 1.0}}), InputError);
  BOOST_CHECK_THROW(evaluate_model(m, {{"mu", 0.3}, {"F_t", 1.0}}), InputError);
}

BOOST_AUTO_TEST_CASE(williams_model_not_applicable_cases) {
  const auto& m = registry().get("williams_bending");
  Values v = {{"G_c", 2000.0}, {"sigma_y0", 25e6}, {"E_prime", 1122.25e6}, {"t1", 5e-3}, {"rake", deg(30)}, {"mu", 0.6}};
  auto r = evaluate_model(m, v);
  BOOST_TEST(!r.applicable);
  BOOST_TEST(r.note == "no bending solution: Z > 0 (mu > tan(rake))");
  BOOST_TEST(std::isnan(r.outputs.at("F_c")));
  BOOST_TEST(std::isfinite(r.outputs.at("h_star")));
  v = {{"G_c", 2000.0}, {"sigma_y0", 25e6}, {"E_prime", 1122.25e6}, {"t1", 5e-3}};  // h* = 0.696 EPP
  r = evaluate_model(m, v);
  BOOST_TEST(!r.applicable);
  BOOST_TEST(r.note.find("no root") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(atkins_model_matches_eq15) {
  const auto o = eval("atkins_touching", {{"G_c", 2000.0}, {"sigma_y", 25e6}, {"t1", 2e-3}, {"rake", deg(30)},
                                          {"E_prime", 1122.25e6}});
  const double eq15 = 2000.0 + 2 * 25e6 * 2e-3 / std::sqrt(3.0) * (1 / std::cos(deg(30)) - std::tan(deg(30)));
  BOOST_TEST(o.at("F_c") == eq15, tt::tolerance(1e-13));
  BOOST_TEST(o.at("h_star") == 0.2784, tt::tolerance(1e-3));  // Nairn: 2.0 mm <-> 0.278
}

BOOST_AUTO_TEST_CASE(failure_and_envelope_models) {
  const Values lam = {{"X_T", 697.8e6}, {"X_C", 443.76e6}, {"Y_T", 89.7216e6}, {"Y_C", 148.33e6}, {"S_L", 33.1e6}};
  Values v = lam;
  v["sigma22"] = -148.33e6;
  v["E1"] = 34.28e9;
  v["G12"] = 2.05e9;
  v["nu12"] = 0.24244;
  const auto o = eval("failure_larc02", v);
  BOOST_TEST(o.at("index") == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(o.at("mode") == 4.0);
  BOOST_TEST(o.at("fracture_angle") == deg(53), tt::tolerance(1e-9));
  Values e = lam;
  e["criterion"] = 1;
  e["plane"] = 1;
  e["theta"] = kPi / 2;
  BOOST_TEST(eval("failure_envelope", e).at("radius") == 33.1e6, tt::tolerance(1e-9));
  e["criterion"] = 2;
  try {
    evaluate_model(registry().get("failure_envelope"), e);
    BOOST_ERROR("expected InputError");
  } catch (const InputError& err) {
    BOOST_TEST(err.field() == "E1");
  }
  e["criterion"] = 0.5;
  BOOST_CHECK_THROW(evaluate_model(registry().get("failure_envelope"), e), InputError);
}

BOOST_AUTO_TEST_CASE(aghababaei_model_regimes) {
  // The d_c of PMMA (0.14 mm) with K_IC/tau implied by it; observed regimes of the text.
  // K_IC/tau_ys = 0.0427329 sqrt(m) (1.351 sqrt(mm)).
  Values v = {{"K_IC", 1.0}, {"tau_ys", 1.0 / 0.0427329}, {"w", 4e-3}, {"t1", 0.5e-3}};
  auto o = eval("aghababaei_transition", v);
  BOOST_TEST(o.at("d_c") == 0.14e-3, tt::tolerance(1e-3));
  BOOST_TEST(o.at("regime") == 1.0);  // PMMA at 0.5 mm: fracture (observed)
  v["t1"] = 0.1e-3;
  BOOST_TEST(eval("aghababaei_transition", v).at("regime") == -1.0);  // 0.1 mm: plastic (observed)
}

BOOST_AUTO_TEST_CASE(kahwash_table1_from_tables4_and_5) {
  // Kahwash Table 1 (interfacial strengths, 15..75 deg) recomputed with Eqs. 57-59 from the
  // experimental mean forces of Tables 4 (F_c) and 5 (F_t), N/mm, depth 0.25 mm, rake 0, r = 1.
  // theta = 0 and 90 deg: forces not given in the text (NOT RUN).
  struct Row { double theta, Fc, Ft, S_sigma, S_z; };
  const Row rows[] = {{15, 32.6, 19.2, 103.5, 26.8}, {30, 34.5, 16.9, 102.9, 35.2}, {45, 42.3, 17.3, 119.2, 50.2},
                      {60, 53.5, 18.0, 143.0, 71.0}, {75, 61.0, 18.5, 158.9, 85.1}};
  for (const auto& row : rows) {
    const auto o = eval("kahwash_strengths", {{"F_c", row.Fc}, {"F_t", row.Ft}, {"t1", 0.25e-3}, {"w", 1e-3}});
    BOOST_TEST_MESSAGE("theta " << row.theta << ": S_sigma " << o.at("normal_strength") / 1e6 << " (paper "
                                << row.S_sigma << "), S_z " << o.at("shear_strength") / 1e6 << " (paper " << row.S_z << ")");
    BOOST_TEST(o.at("phi_deg") == 45.0, tt::tolerance(1e-12));
    BOOST_TEST(std::abs(o.at("normal_strength") / 1e6 - row.S_sigma) < 0.25);
    BOOST_TEST(std::abs(o.at("shear_strength") / 1e6 - row.S_z) < 0.25);
  }
}

BOOST_AUTO_TEST_SUITE_END()
