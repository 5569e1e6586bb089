// Case runners of the EFG solver (verification problems), registered with the framework.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>

#include "cutbench/common/declared.hpp"
#include "cutbench/common/glossary.hpp"
#include "cutbench/common/solver.hpp"
#include "cutbench/efg/register.hpp"
#include "cutbench/efg/cutting.hpp"
#include "cutbench/efg/verification.hpp"

namespace cutbench::efg {

namespace {

ParamSpec p(const std::string& name, Dim dim, const std::string& desc, double def, double lo, double hi) {
  return param(name, dim, desc, def, lo, hi);
}

ParamSpec weight_param() {
  return option_param("weight", "MLS weight function",
                      {{"regularized", "Most-Bucher regularised weight"}, {"cubic_spline", "cubic spline"}}, "regularized");
}

std::vector<ParamSpec> material_params() {
  const double inf = HUGE_VAL;
  return {p("E1", Dim::stress, "fibre-direction modulus (Kahwash Table 2)", 34.28e9, 0, inf),
          p("E2", Dim::stress, "transverse modulus", 11.57e9, 0, inf),
          p("nu12", Dim::dimensionless, "major Poisson ratio", 0.24244, 0, 0.5),
          p("G12", Dim::stress, "in-plane shear modulus", 2.05e9, 0, inf),
          p("rho", Dim::density, "density (Table 2's 1.58 read as g/cm^3)", 1580.0, 0, inf)};
}

// The lamina's elastic constants (Table 2) into the setup's Orthotropic member.
template <class S>
void declare_material(DeclaredParams<S>& d, Orthotropic S::*m) {
  const auto mp = material_params();  // E1, E2, nu12, G12, rho
  d.add(mp[0], [m](S& s, double v) { (s.*m).E1 = v; })
      .add(mp[1], [m](S& s, double v) { (s.*m).E2 = v; })
      .add(mp[2], [m](S& s, double v) { (s.*m).nu12 = v; })
      .add(mp[3], [m](S& s, double v) { (s.*m).G12 = v; })
      .add(mp[4], [m](S& s, double v) { (s.*m).rho = v; });
}

// The MLS weight function into the setup's WeightParams member.
template <class S>
void declare_weight(DeclaredParams<S>& d, WeightParams S::*w) {
  d.add(weight_param(), [w](S& s, double v) { (s.*w).kind = static_cast<WeightKind>(static_cast<int>(v)); });
}

struct CantileverSetup {
  int nodes_x = 0, nodes_y = 0;
  double support_factor = 0, length = 0, height = 0, E = 0, nu = 0, load = 0;
  WeightParams weight;
};

const DeclaredParams<CantileverSetup>& cantilever_declaration() {
  using S = CantileverSetup;
  static const DeclaredParams<S> d = [] {
    const double inf = HUGE_VAL;
    DeclaredParams<S> decl;
    decl.bind(integer_param("nodes_x", "nodes along the beam", 49, 3, 400), &S::nodes_x)
        .bind(integer_param("nodes_y", "nodes through the depth", 13, 3, 200), &S::nodes_y)
        .bind(p("support_factor", Dim::dimensionless, "domain of influence / nodal spacing", 2.5, 1.2, 6), &S::support_factor);
    declare_weight(decl, &S::weight);
    decl.bind(p("length", Dim::length, "beam length", 48.0, 0, inf), &S::length)
        .bind(p("height", Dim::length, "beam depth", 12.0, 0, inf), &S::height)
        .bind(p("E", Dim::stress, "Young's modulus", 3.0e7, 0, inf), &S::E)
        .bind(p("nu", Dim::dimensionless, "Poisson ratio", 0.3, 0, 0.5), &S::nu)
        .bind(p("load", Dim::force_per_width, "end shear resultant per unit thickness", 1000.0, -inf, inf), &S::load);
    return decl;
  }();
  return d;
}

SolverSpec cantilever_spec() {
  SolverSpec cant;
  cant.name = "efg_cantilever";
  cant.description = "EFG static Timoshenko cantilever (plane stress, isotropic): tip deflection and error norms";
  cant.source = "Kahwash et al. 2018 sections 2.2-3.1 (discretisation); Timoshenko & Goodier closed form";
  cant.params = cantilever_declaration().specs();
  cant.scalars = {{"tip_deflection", Dim::length, "EFG u_y(L, 0)"},
                  {"tip_deflection_exact", Dim::length, "closed-form u_y(L, 0)"},
                  {"tip_rel_error", Dim::dimensionless, "relative tip deflection error"},
                  {"l2_rel_error", Dim::dimensionless, "relative L2 displacement error"},
                  {"energy_rel_error", Dim::dimensionless, "relative energy-norm error"}};
  cant.run = [](const Values& v, const ProgressFn& progress) {
    const CantileverSetup s = cantilever_declaration().make(v);
    if (progress) progress(0.0, "assembling");
    const CantileverResult r = timoshenko_cantilever(s.nodes_x, s.nodes_y, s.support_factor, s.weight, s.length,
                                                     s.height, s.E, s.nu, s.load);
    RunOutput out;
    out.scalars = {{"tip_deflection", r.tip},
                   {"tip_deflection_exact", r.tip_exact},
                   {"tip_rel_error", r.tip_rel_error},
                   {"l2_rel_error", r.l2_rel_error},
                   {"energy_rel_error", r.energy_rel_error}};
    out.notes.push_back("EFG cantilever: exact displacements imposed on the nodes at x = 0 (near-interpolating "
                        "weight); 2 x 2 Gauss points per background cell.");
    if (progress) progress(1.0, "done");
    return out;
  };
  return cant;
}

struct WaveSetup {
  Orthotropic material;
  double theta = 0, length = 0, cfl = 0;
  int nodes_x = 0;
  WeightParams weight;
};

const DeclaredParams<WaveSetup>& wave_declaration() {
  using S = WaveSetup;
  static const DeclaredParams<S> d = [] {
    const double inf = HUGE_VAL;
    const double pi = std::acos(-1.0);
    DeclaredParams<S> decl;
    declare_material(decl, &S::material);
    decl.bind(p("theta", Dim::angle, "fibre angle to the bar axis", 0.0, -pi, pi), &S::theta)
        .bind(p("length", Dim::length, "bar length", 0.2, 0, inf), &S::length)
        .bind(integer_param("nodes_x", "nodes along the bar", 201, 11, 4000), &S::nodes_x)
        .bind(p("cfl", Dim::dimensionless, "time step / (min nodal distance / c_max)", 0.5, 0.01, 1.0), &S::cfl);
    declare_weight(decl, &S::weight);
    return decl;
  }();
  return d;
}

SolverSpec wave_spec() {
  SolverSpec wave;
  wave.name = "efg_wave";
  wave.description = "EFG explicit plane wave in a laterally constrained bar: measured vs sqrt(Qbar11/rho)";
  wave.source = "Kahwash et al. 2018 Eqs 47-50, 55-56";
  wave.params = wave_declaration().specs();
  wave.tables = {{"station_velocity",
                  "axial velocity at the quarter and three-quarter stations",
                  {{"t", "s", "time"},
                   {"v_quarter", "m/s", "velocity at x = L/4"},
                   {"v_three_quarter", "m/s", "velocity at x = 3L/4"}}}};
  wave.scalars = {{"wave_speed", Dim::velocity, "measured front speed (half-amplitude arrival)"},
                  {"wave_speed_exact", Dim::velocity, "sqrt(Qbar11/rho)"},
                  {"wave_speed_rel_error", Dim::dimensionless, "measured/exact - 1"},
                  {"steps", Dim::dimensionless, "time steps"}};
  wave.run = [](const Values& v, const ProgressFn& progress) {
    const WaveSetup s = wave_declaration().make(v);
    if (progress) progress(0.0, "running");
    const WaveResult r = bar_wave(s.material, s.theta, s.length, s.nodes_x, 5, s.cfl, Kinematics::small_strain, s.weight);
    RunOutput out;
    Table t;
    t.name = "station_velocity";
    t.add("t", "s", r.t);
    t.add("v_quarter", "m/s", r.v1);
    t.add("v_three_quarter", "m/s", r.v2);
    out.tables.push_back(t);
    out.scalars = {{"wave_speed", r.c_measured},
                   {"wave_speed_exact", r.c_exact},
                   {"wave_speed_rel_error", r.rel_error},
                   {"steps", static_cast<double>(r.steps)}};
    if (progress) progress(1.0, "done");
    return out;
  };
  return wave;
}

struct PatchSetup {
  Orthotropic material;
  double theta = 0, jitter = 0;
  int nodes = 0, gauss = 0;
  WeightParams weight;
};

const DeclaredParams<PatchSetup>& patch_declaration() {
  using S = PatchSetup;
  static const DeclaredParams<S> d = [] {
    const double pi = std::acos(-1.0);
    DeclaredParams<S> decl;
    declare_material(decl, &S::material);
    decl.bind(p("theta", Dim::angle, "fibre angle", pi / 4, -pi, pi), &S::theta)
        .bind(integer_param("nodes", "nodes per side", 11, 3, 200), &S::nodes)
        .bind(p("jitter", Dim::dimensionless, "interior node jitter / spacing", 0.3, 0, 0.45), &S::jitter)
        .bind(integer_param("gauss", "Gauss points per direction per cell", 2, 1, 4), &S::gauss);
    declare_weight(decl, &S::weight);
    return decl;
  }();
  return d;
}

SolverSpec patch_spec() {
  SolverSpec patch;
  patch.name = "efg_patch";
  patch.description = "EFG patch tests: homogeneous finite deformation (TL) and static linear patch";
  patch.source = "Kahwash et al. 2018 sections 2.2-2.3, 3.1";
  patch.params = patch_declaration().specs();
  patch.scalars = {{"max_F_error", Dim::dimensionless, "max |F_G - F| (homogeneous deformation)"},
                   {"max_stress_rel_error", Dim::dimensionless, "max relative PK2 error"},
                   {"static_rel_error", Dim::dimensionless, "static patch: max interior nodal error / (|H| L)"}};
  patch.run = [](const Values& v, const ProgressFn&) {
    const PatchSetup s = patch_declaration().make(v);
    const PatchResult r = patch_test(s.material, s.theta, s.nodes, s.nodes, s.jitter, s.gauss, s.weight);
    RunOutput out;
    out.scalars = {{"max_F_error", r.max_F_error},
                   {"max_stress_rel_error", r.max_stress_rel_error},
                   {"static_rel_error", r.static_rel_error}};
    out.notes.push_back("The static patch test is passed only up to the Gauss quadrature error of the "
                        "background cells (MLS shape functions are rational).");
    return out;
  };
  return patch;
}

// Every parameter of efg_cutting, declared once with its member of the setup.
const DeclaredParams<CuttingSetup>& cutting_declaration() {
  using S = CuttingSetup;
  static const DeclaredParams<S> d = [] {
    const double inf = HUGE_VAL;
    const double pi = std::acos(-1.0);
    DeclaredParams<S> decl;
    declare_material(decl, &S::material);
    decl.bind(p("theta", Dim::angle, "fibre angle: fibres along (cos, sin) with the tool moving +x", pi / 6, 0, pi), &S::theta)
        .bind(analytic::criterion_param("larc02"), &S::criterion)
        .add(p("X_T", Dim::stress, "fibre tensile strength (Table 2)", 697.8e6, 0, inf),
             [](S& s, double v) { s.lamina.X_T = v; })
        .add(p("X_C", Dim::stress, "fibre compressive strength (Table 2)", 443.76e6, 0, inf),
             [](S& s, double v) { s.lamina.X_C = v; })
        .add(p("Y_T", Dim::stress, "transverse tensile strength (Table 2)", 89.7216e6, 0, inf),
             [](S& s, double v) { s.lamina.Y_T = v; })
        .add(p("Y_C", Dim::stress, "transverse compressive strength (Table 2)", 148.33e6, 0, inf),
             [](S& s, double v) { s.lamina.Y_C = v; })
        .add(p("S_L", Dim::stress, "in-plane shear strength (Table 2)", 33.1e6, 0, inf),
             [](S& s, double v) { s.lamina.S_L = v; })
        .add(p("eps1_T", Dim::dimensionless, "fibre tensile failure strain of LaRC02 (Table 2: 2.3 %)", 0.023, 1e-6, 1),
             [](S& s, double v) { s.lamina.eps1_T = v; })
        .bind(p("S_sigma", Dim::stress, "interface normal strength (Table 1; 0: no interface index from it)", 0.0, 0, inf), &S::S_sigma)
        .bind(p("S_tau", Dim::stress, "interface shear strength (Table 1; 0: no interface index from it)", 0.0, 0, inf), &S::S_tau)
        .bind(p(glossary::kDepthOfCut, Dim::length, "depth of cut (Table 3: 0.25 mm)", 0.25e-3, 0, inf), &S::depth)
        .bind(p(glossary::kRakeAngle, Dim::angle, "rake angle (Table 3: 0)", 0.0, -pi / 4, pi / 3), &S::rake)
        .bind(p("work_length", Dim::length, "workpiece length (assumption)", 1.5e-3, 0, inf), &S::work_length)
        .bind(p("work_height", Dim::length, "workpiece height (assumption)", 0.75e-3, 0, inf), &S::work_height)
        .bind(p("notch", Dim::length, "already-cut length: the cut starts inside the workpiece", 0.25e-3, 0, inf), &S::notch)
        .bind(p("spacing", Dim::length, "nodal spacing along x", 0.05e-3, 0, inf), &S::spacing)
        .bind(p("support_factor", Dim::dimensionless, "domain of influence / nodal spacing", 2.0, 1.2, 4), &S::support_factor)
        .bind(p(glossary::kCuttingSpeed, Dim::velocity, "cutting speed (Table 3: 3800 mm/min)", 3800e-3 / 60.0, 0, inf), &S::speed)
        .bind(p("time_scale", Dim::dimensionless, "tool speed multiplier (time scaling)", 50, 1, 1e4), &S::time_scale)
        .bind(p("travel", Dim::length, "maximum tool travel after first contact", 0.3e-3, 0, inf), &S::travel)
        .bind(p("ramp_transits", Dim::dimensionless, "tool speed ramp, in wave transits of the workpiece height", 50, 0, 1e4), &S::ramp_transits)
        .bind(p(glossary::kFriction, Dim::dimensionless, "rake-face friction coefficient (assumption)", 0.3, 0, 2), &S::mu)
        .bind(p(glossary::kClearanceAngle, Dim::angle, "clearance angle (assumption)", 7.0 * pi / 180.0, 0, pi / 4), &S::clearance)
        .bind(p("edge_radius", Dim::length, "cutting-edge radius (assumption, not in the paper; 0: sharp)", 0.0, 0, inf), &S::edge_radius)
        .bind(p("residual", Dim::dimensionless, "residual fraction of failed moduli", 0.01, 0, 1), &S::residual)
        .bind(option_param("degradation", "stiffness degradation of failed material",
                              {{"sudden", "failed moduli x residual"}, {"mode_factors", "mode factors of Camanho-Matthews/Tserpes"}},
                              "mode_factors"), &S::degradation)
        .bind(option_param("damage_growth", "how the failure index degrades the stiffness",
                              {{"at_failure", "a mode's factor applies when its index reaches 1"},
                               {"proportional", "moduli scaled by 1 - d (1 - factor) as the index d grows (the paper's damage status)"}},
                              "proportional"), &S::growth)
        .bind(option_param("erosion", "separation of failed material",
                              {{"none", "no separation"}, {"fibre_and_matrix", "fibre and matrix failed"}, {"either", "fibre or matrix failed"}},
                              "none"), &S::erosion)
        .bind(p("collapse_ratio", Dim::dimensionless,
                   "collapse erosion: failed material whose nodes come closer than this x the initial spacing is eroded (0: off)",
                   0.0, 0, 0.99), &S::collapse_ratio)
        .bind(option_param("kinematics", "kinematic description",
                              {{"small_strain", "linear"}, {"total_lagrangian", "total Lagrangian"},
                               {"updated_lagrangian", "updated Lagrangian (the paper's)"}},
                              "updated_lagrangian"), &S::kinematics)
        .bind(integer_param("update_interval", "updated Lagrangian: steps between reference updates (1: the last configuration, the paper's)", 1, 1, 1e6), &S::update_interval)
        .bind(switch_param("visibility", "visibility criterion across the notch and the cut line", true), &S::visibility)
        .bind(p("drop", Dim::dimensionless, "chip completion: dt below (1 - drop) x its running mean (0: off)", 0.3, 0, 0.99), &S::drop)
        .bind(integer_param("drop_window", "steps of the running mean of dt", 200, 1, 1e6), &S::drop_window)
        .bind(p("min_travel", Dim::length, "no chip-completion detection before this travel", 0.0, 0, inf), &S::min_travel)
        .bind(option_param("completion_guard", "when a drop of the time step counts as chip completion",
                              {{"always", "at the first drop (the paper's Algorithm 3.6)"}, {"damaged_path", "once damaged Gauss points connect the edge and the free surface"},
                               {"eroded_path", "once eroded Gauss points ahead of the edge connect the edge and the free surface"}},
                              "always"), &S::completion_guard)
        .bind(p("cfl", Dim::dimensionless,
                "time step / (min nodal distance / c_max): the reduction factor of Belytschko, Liu & Moran (2000), 0.8-0.98",
                S{}.cfl, 0.01, 1.0), &S::cfl)
        .bind(integer_param("snapshots", "damage snapshots kept (k/n of the run)", 3, 0, 20), &S::snapshots);
    return decl;
  }();
  return d;
}

std::vector<ParamSpec> cutting_params() { return cutting_declaration().specs(); }

std::vector<OutputSpec> cutting_scalars() {
  return {{"F_c", Dim::force_per_width, "mean cutting force from first contact to the end (chip completion)"},
                 {"F_t", Dim::force_per_width, "mean thrust force from first contact to the end"},
                 {"F_c_peak", Dim::force_per_width, "largest window-mean cutting force"},
                 {"t_contact", Dim::time, "first tool contact"},
                 {"t_complete", Dim::time, "chip completion from the Eq 56 step drop (-1: none)"},
                 {"travel_complete", Dim::length, "tool travel at chip completion (-1: none)"},
                 {"chip_complete", Dim::dimensionless, "1 when the time-step drop was detected"},
                 {"travel_path", Dim::length, "travel at which damage first connects the edge to the free surface (-1: never)"},
                 {"travel_first_drop", Dim::length, "travel of the first time-step drop, guard or not (-1: none)"},
                 {"travel_first_failure", Dim::length, "travel at the first Gauss-point failure (any mode; -1: none)"},
                 {"F_c_first_failure", Dim::force_per_width, "window-mean cutting force when the first Gauss point fails (elastic up to there)"},
                 {"travel_separated", Dim::length, "travel at which eroded Gauss points ahead of the edge first connect it to the free surface (-1: never)"},
                 {"dt_drop_ratio", Dim::dimensionless, "dt / running mean at detection (1: none)"},
                 {"dt_mean_at_drop_ratio", Dim::dimensionless,
                  "running mean of dt just before the completion drop / initial dt (1: the step constant until the drop, Fig 10; -1: no completion)"},
                 {"dt_min_ratio", Dim::dimensionless, "smallest / initial time step"},
                 {"fibre_damaged_fraction", Dim::dimensionless, "Gauss points with fibre damage"},
                 {"matrix_damaged_fraction", Dim::dimensionless, "Gauss points with matrix damage"},
                 {"chip_fibre_fraction", Dim::dimensionless, "fibre-damaged fraction of the chip region"},
                 {"chip_matrix_fraction", Dim::dimensionless, "matrix-damaged fraction of the chip region"},
                 {"sub_fibre_fraction", Dim::dimensionless, "fibre-damaged fraction within one depth below the cut"},
                 {"sub_matrix_fraction", Dim::dimensionless, "matrix-damaged fraction within one depth below the cut"},
                 {"eroded", Dim::dimensionless, "separated Gauss points"},
                 {"released", Dim::dimensionless, "released nodes"},
                 {"collapse_eroded", Dim::dimensionless, "Gauss points eroded by the collapse criterion"},
                 {"nodes", Dim::dimensionless, "nodes"},
                 {"gauss_points", Dim::dimensionless, "Gauss points"},
                 {"steps", Dim::dimensionless, "time steps"},
                 {"node_steps_per_s", Dim::dimensionless, "throughput: nodes x steps / wall time (1/s; after a resume, the steps since the resume)"},
                 {"E1_used", Dim::stress, "E1 used"},
                 {"E2_used", Dim::stress, "E2 used"},
                 {"nu12_used", Dim::dimensionless, "nu12 used"},
                 {"nu21_used", Dim::dimensionless, "nu21 used (reciprocity nu12 E2/E1)"},
                 {"G12_used", Dim::stress, "G12 used"},
                 {"rho_used", Dim::density, "density used"},
                 {"X_T_used", Dim::stress, "X_T used"},
                 {"X_C_used", Dim::stress, "X_C used"},
                 {"Y_T_used", Dim::stress, "Y_T used"},
                 {"Y_C_used", Dim::stress, "Y_C used"},
                 {"S_L_used", Dim::stress, "S_L used"},
                 {"depth_used", Dim::length, "depth of cut used"},
                 {"rake_used", Dim::angle, "rake angle used"},
                 {"speed_used", Dim::velocity, "paper cutting speed (before time scaling)"},
                 {"speed_run", Dim::velocity, "speed at which the tool moved (speed x time_scale)"},
                 {"wave_speed", Dim::velocity, "Eq 55 c_max = sqrt(C11/rho)"},
                 {"energy_tool_work", Dim::force_per_width, "energy audit: work of the tool's contact impulses (J/m)"},
                 {"energy_kinetic", Dim::force_per_width, "energy audit: kinetic energy at the end (J/m)"},
                 {"energy_strain", Dim::force_per_width, "energy audit: strain energy at the end, degraded stiffness (J/m)"},
                 {"energy_damage", Dim::force_per_width, "energy audit: strain energy released by stiffness degradation and erosion (J/m)"},
                 {"energy_contact_loss", Dim::force_per_width, "energy audit: tool work the contact's inelastic impulses dissipate (J/m)"},
                 {"energy_internal_work", Dim::force_per_width, "energy audit: work of the internal forces, dx.(f^n + f^{n+1})/2 summed over the steps (J/m)"},
                 {"energy_released", Dim::force_per_width, "energy audit: kinetic energy of released nodes (erosion; J/m)"},
                 {"energy_residual", Dim::force_per_width, "energy audit: tool work - contact loss - released - kinetic - strain - damage (J/m)"},
                 {"energy_residual_fraction", Dim::dimensionless, "energy audit: residual / tool work"}};
}

CuttingSetup cutting_setup_from(const Values& v) {
  CuttingSetup s = cutting_declaration().make(v);
  s.lamina.E1 = s.material.E1;  // LaRC02's fibre strain and kinking use the elastic constants
  s.lamina.G12 = s.material.G12;
  s.lamina.nu12 = s.material.nu12;
  return s;
}

RunOutput cutting_output(const CuttingSetup& s, const CuttingResult& r, double wall) {
  RunOutput out;
  out.notes = drive_notes(r.drive, "efg_cutting");
  if (r.drive.resumed_from_step > 0) out.notes.push_back("efg_cutting: node_steps_per_s counts the steps since the resume");
  Table t;
  t.name = "forces";
  t.add("t", "s", r.t);
  t.add("travel", "m", r.travel);
  t.add("F_c", "N/m", r.Fc);
  t.add("F_t", "N/m", r.Ft);
  t.add("dt", "s", r.dt);
  out.tables.push_back(t);
  Table e;
  e.name = "energy";
  e.add("t", "s", r.t);
  e.add("travel", "m", r.travel);
  e.add("tool_work", "J/m", r.e_tool);
  e.add("kinetic", "J/m", r.e_kinetic);
  e.add("strain", "J/m", r.e_strain);
  e.add("damage", "J/m", r.e_damage);
  e.add("residual", "J/m", r.e_residual);
  out.tables.push_back(e);
  for (const auto& sn : r.snapshots) {
    Snapshot snap;
    snap.time = sn.t;
    snap.x = sn.x;
    snap.y = sn.y;
    snap.add("fibre_damage", "1", sn.fibre);
    snap.add("matrix_damage", "1", sn.matrix);
    out.snapshots.push_back(snap);
  }
  const double ng = static_cast<double>(r.gauss);
  auto frac = [](std::size_t a, std::size_t b) { return b > 0 ? static_cast<double>(a) / b : 0.0; };
  const Orthotropic& m = s.material;
  out.scalars = {{"F_c", r.Fc_mean},
                 {"F_t", r.Ft_mean},
                 {"F_c_peak", r.Fc_peak},
                 {"t_contact", r.t_contact},
                 {"t_complete", r.t_complete},
                 {"travel_complete", r.travel_complete},
                 {"chip_complete", r.t_complete >= 0.0 ? 1.0 : 0.0},
                 {"travel_path", r.travel_path},
                 {"travel_first_drop", r.travel_first_drop},
                 {"travel_separated", r.travel_separated},
                 {"travel_first_failure", r.travel_first_failure},
                 {"F_c_first_failure", r.Fc_first_failure},
                 {"dt_drop_ratio", r.dt_drop_ratio},
                 {"dt_mean_at_drop_ratio", r.dt_mean_at_drop_ratio},
                 {"dt_min_ratio", r.dt_min / r.dt_initial},
                 {"fibre_damaged_fraction", static_cast<double>(r.fibre_damaged) / ng},
                 {"matrix_damaged_fraction", static_cast<double>(r.matrix_damaged) / ng},
                 {"chip_fibre_fraction", frac(r.chip_fibre, r.chip_gauss)},
                 {"chip_matrix_fraction", frac(r.chip_matrix, r.chip_gauss)},
                 {"sub_fibre_fraction", frac(r.sub_fibre, r.sub_gauss)},
                 {"sub_matrix_fraction", frac(r.sub_matrix, r.sub_gauss)},
                 {"eroded", static_cast<double>(r.eroded)},
                 {"released", static_cast<double>(r.released)},
                 {"collapse_eroded", static_cast<double>(r.collapse_eroded)},
                 {"nodes", static_cast<double>(r.nodes)},
                 {"gauss_points", ng},
                 {"steps", static_cast<double>(r.steps)},
                 {"node_steps_per_s", static_cast<double>(r.nodes) * static_cast<double>(r.steps - static_cast<long>(r.drive.resumed_from_step)) / wall},
                 {"E1_used", m.E1},
                 {"E2_used", m.E2},
                 {"nu12_used", m.nu12},
                 {"nu21_used", m.nu12 * m.E2 / m.E1},
                 {"G12_used", m.G12},
                 {"rho_used", m.rho},
                 {"X_T_used", s.lamina.X_T},
                 {"X_C_used", s.lamina.X_C},
                 {"Y_T_used", s.lamina.Y_T},
                 {"Y_C_used", s.lamina.Y_C},
                 {"S_L_used", s.lamina.S_L},
                 {"depth_used", s.depth},
                 {"rake_used", s.rake},
                 {"speed_used", s.speed},
                 {"speed_run", s.speed * s.time_scale},
                 {"wave_speed", m.wave_speed()},
                 {"energy_tool_work", r.energy_tool},
                 {"energy_kinetic", r.energy_kinetic},
                 {"energy_strain", r.energy_strain},
                 {"energy_damage", r.energy_damage},
                 {"energy_contact_loss", r.energy_contact_loss},
                 {"energy_internal_work", r.energy_internal},
                 {"energy_released", r.energy_released},
                 {"energy_residual", r.energy_residual},
                 {"energy_residual_fraction", r.energy_tool > 0.0 ? r.energy_residual / r.energy_tool : nan_value()}};
  out.scalar_units = {{"F_c", "N/m"}, {"F_t", "N/m"}, {"F_c_peak", "N/m"}, {"F_c_first_failure", "N/m"}, {"t_contact", "s"}, {"t_complete", "s"}};
  for (const char* k : {"energy_tool_work", "energy_kinetic", "energy_strain", "energy_damage", "energy_contact_loss",
                        "energy_internal_work", "energy_released", "energy_residual"})
    out.scalar_units[k] = "J/m";
  // the failure model of this run: the declared descriptions of the options it ran with
  const std::vector<ParamSpec> specs = cutting_params();
  auto chosen = [&specs](const char* name, int index) {
    const auto it = std::find_if(specs.begin(), specs.end(), [name](const ParamSpec& p) { return p.name == name; });
    const ParamOption& o = it->options.at(static_cast<std::size_t>(index));
    return it->name + " = " + o.name + ": " + o.description;
  };
  std::ostringstream scale;
  scale << s.time_scale;
  out.notes.push_back("efg_cutting: notched workpiece (cut starts inside it), workpiece size, clearance 7 deg, sharp "
                      "edge, constant friction, fixed bottom and far end and the time scaling (tool at " +
                      scale.str() + " x the given speed) are assumptions; " +
                      chosen("degradation", static_cast<int>(s.degradation)) + "; " +
                      chosen("damage_growth", static_cast<int>(s.growth)) + "; " +
                      chosen("erosion", static_cast<int>(s.erosion)) +
                      "; visibility across the notch and the cut line behind the edge (solvers/efg/README.md).");
  return out;
}

SolverSpec cutting_spec() {
  SolverSpec cut;
  cut.name = "efg_cutting";
  cut.description = "Explicit EFG orthogonal cutting of UD-GFRP (Kahwash 2018): F_c, F_t per unit width to chip completion";
  cut.source = "Kahwash et al. 2018 sections 2-3 and 5, Tables 2-3";
  cut.params = cutting_params();
  cut.tables = {{"forces",
                 "tool force history",
                 {{"t", "s", "time"},
                  {"travel", "m", "tool travel after first contact"},
                  {"F_c", "N/m", "cutting force per unit width"},
                  {"F_t", "N/m", "thrust force per unit width"},
                  {"dt", "s", "critical time step (Eq. 56)"}}},
                {"energy",
                 "energy audit at the end of each force window (solvers/efg/README.md, \"Energy audit\")",
                 {{"t", "s", "time"},
                  {"travel", "m", "tool travel after first contact"},
                  {"tool_work", "J/m", "work of the tool's contact impulses"},
                  {"kinetic", "J/m", "kinetic energy"},
                  {"strain", "J/m", "strain energy (degraded stiffness)"},
                  {"damage", "J/m", "strain energy released by degradation and erosion"},
                  {"residual", "J/m", "residual of the ledger"}}}};
  cut.scalars = cutting_scalars();
  cut.checkpoints = true;
  cut.footprint = [](const Values& v) {
    // the node lattice (hx = spacing, hy about spacing); about 8 kB per node: MLS shape functions
    // and derivatives of about 4 Gauss points per node over (2 support_factor + 1)^2 neighbours
    const double hx = v.at("spacing"), nodes = (v.at("work_length") / hx + 1.0) * (v.at("work_height") / hx + 2.0);
    const double support = 2.0 * v.at("support_factor") + 1.0;
    return Footprint{nodes, nodes * (1024.0 + 4.0 * support * support * 3.0 * 8.0), "nodes"};
  };
  cut.run = [](const Values& v, const ProgressFn& progress) {
    const CuttingSetup s = cutting_setup_from(v);
    const auto t0 = std::chrono::steady_clock::now();
    const CuttingResult r = run_cutting(s, [&](double f) {
      if (progress) progress(f, "simulated " + std::to_string(f * 100.0) + " %");
    });
    return cutting_output(s, r, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  };
  return cut;
}

}  // namespace

void register_solvers(SolverRegistry& registry) {
  if (registry.find("efg_cantilever")) return;  // idempotent
  for (SolverSpec spec : {cantilever_spec(), wave_spec(), patch_spec(), cutting_spec()}) registry.add(std::move(spec));
}

}  // namespace cutbench::efg
