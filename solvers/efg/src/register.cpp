// Case runners of the EFG solver (verification problems), registered with the framework.
#include <chrono>
#include <cmath>
#include <string>

#include "cutbench/common/solver.hpp"
#include "cutbench/efg/cutting.hpp"
#include "cutbench/efg/verification.hpp"

namespace cutbench::efg {

namespace {

ParamSpec p(const std::string& name, Dim dim, const std::string& desc, double def, double lo, double hi) {
  return param(name, dim, desc, def, lo, hi);
}

WeightParams weight_of(const Values& v) {
  WeightParams w;
  w.kind = v.at("weight") > 0.5 ? WeightKind::cubic_spline : WeightKind::regularized;
  return w;
}

Orthotropic gfrp_of(const Values& v) {
  Orthotropic m;
  m.E1 = v.at("E1");
  m.E2 = v.at("E2");
  m.nu12 = v.at("nu12");
  m.G12 = v.at("G12");
  m.rho = v.at("rho");
  return m;
}

std::vector<ParamSpec> material_params() {
  const double inf = HUGE_VAL;
  return {p("E1", Dim::stress, "fibre-direction modulus (Kahwash Table 2)", 34.28e9, 0, inf),
          p("E2", Dim::stress, "transverse modulus", 11.57e9, 0, inf),
          p("nu12", Dim::dimensionless, "major Poisson ratio", 0.24244, 0, 0.5),
          p("G12", Dim::stress, "in-plane shear modulus", 2.05e9, 0, inf),
          p("rho", Dim::density, "density (Table 2's 1.58 read as g/cm^3)", 1580.0, 0, inf)};
}

}  // namespace

void register_solvers(SolverRegistry& registry) {
  if (registry.find("efg_cantilever")) return;  // idempotent
  const double inf = HUGE_VAL;
  const double pi = std::acos(-1.0);

  SolverSpec cant;
  cant.name = "efg_cantilever";
  cant.description = "EFG static Timoshenko cantilever (plane stress, isotropic): tip deflection and error norms";
  cant.source = "Kahwash et al. 2018 sections 2.2-3.1 (discretisation); Timoshenko & Goodier closed form";
  cant.params = {p("nodes_x", Dim::dimensionless, "nodes along the beam", 49, 3, 400),
                 p("nodes_y", Dim::dimensionless, "nodes through the depth", 13, 3, 200),
                 p("support_factor", Dim::dimensionless, "domain of influence / nodal spacing", 2.5, 1.2, 6),
                 p("weight", Dim::dimensionless, "0: Most-Bucher regularised, 1: cubic spline", 0, 0, 1),
                 p("length", Dim::length, "beam length", 48.0, 0, inf),
                 p("height", Dim::length, "beam depth", 12.0, 0, inf),
                 p("E", Dim::stress, "Young's modulus", 3.0e7, 0, inf),
                 p("nu", Dim::dimensionless, "Poisson ratio", 0.3, 0, 0.5),
                 p("load", Dim::force_per_width, "end shear resultant per unit thickness", 1000.0, -inf, inf)};
  cant.scalars = {{"tip_deflection", Dim::length, "EFG u_y(L, 0)"},
                  {"tip_deflection_exact", Dim::length, "closed-form u_y(L, 0)"},
                  {"tip_rel_error", Dim::dimensionless, "relative tip deflection error"},
                  {"l2_rel_error", Dim::dimensionless, "relative L2 displacement error"},
                  {"energy_rel_error", Dim::dimensionless, "relative energy-norm error"}};
  cant.run = [](const Values& v, const ProgressFn& progress) {
    if (progress) progress(0.0, "assembling");
    const CantileverResult r =
        timoshenko_cantilever(static_cast<int>(v.at("nodes_x")), static_cast<int>(v.at("nodes_y")),
                              v.at("support_factor"), weight_of(v), v.at("length"), v.at("height"), v.at("E"),
                              v.at("nu"), v.at("load"));
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
  registry.add(cant);

  SolverSpec wave;
  wave.name = "efg_wave";
  wave.description = "EFG explicit plane wave in a laterally constrained bar: measured vs sqrt(Qbar11/rho)";
  wave.source = "Kahwash et al. 2018 Eqs 47-50, 55-56";
  wave.params = material_params();
  for (auto q : {p("theta", Dim::angle, "fibre angle to the bar axis", 0.0, -pi, pi),
                 p("length", Dim::length, "bar length", 0.2, 0, inf),
                 p("nodes_x", Dim::dimensionless, "nodes along the bar", 201, 11, 4000),
                 p("cfl", Dim::dimensionless, "time step / (min nodal distance / c_max)", 0.5, 0.01, 1.0)}) {
    wave.params.push_back(q);
  }
  wave.params.push_back(p("weight", Dim::dimensionless, "0: Most-Bucher regularised, 1: cubic spline", 0, 0, 1));
  wave.scalars = {{"wave_speed", Dim::velocity, "measured front speed (half-amplitude arrival)"},
                  {"wave_speed_exact", Dim::velocity, "sqrt(Qbar11/rho)"},
                  {"wave_speed_rel_error", Dim::dimensionless, "measured/exact - 1"},
                  {"steps", Dim::dimensionless, "time steps"}};
  wave.run = [](const Values& v, const ProgressFn& progress) {
    if (progress) progress(0.0, "running");
    const WaveResult r = bar_wave(gfrp_of(v), v.at("theta"), v.at("length"), static_cast<int>(v.at("nodes_x")), 5,
                                  v.at("cfl"), Kinematics::small_strain, weight_of(v));
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
  registry.add(wave);

  SolverSpec patch;
  patch.name = "efg_patch";
  patch.description = "EFG patch tests: homogeneous finite deformation (TL) and static linear patch";
  patch.source = "Kahwash et al. 2018 sections 2.2-2.3, 3.1";
  patch.params = material_params();
  for (auto q : {p("theta", Dim::angle, "fibre angle", pi / 4, -pi, pi),
                 p("nodes", Dim::dimensionless, "nodes per side", 11, 3, 200),
                 p("jitter", Dim::dimensionless, "interior node jitter / spacing", 0.3, 0, 0.45),
                 p("gauss", Dim::dimensionless, "Gauss points per direction per cell", 2, 1, 4),
                 p("weight", Dim::dimensionless, "0: Most-Bucher regularised, 1: cubic spline", 0, 0, 1)}) {
    patch.params.push_back(q);
  }
  patch.scalars = {{"max_F_error", Dim::dimensionless, "max |F_G - F| (homogeneous deformation)"},
                   {"max_stress_rel_error", Dim::dimensionless, "max relative PK2 error"},
                   {"static_rel_error", Dim::dimensionless, "static patch: max interior nodal error / (|H| L)"}};
  patch.run = [](const Values& v, const ProgressFn&) {
    const int n = static_cast<int>(v.at("nodes"));
    const PatchResult r = patch_test(gfrp_of(v), v.at("theta"), n, n, v.at("jitter"),
                                     static_cast<int>(v.at("gauss")), weight_of(v));
    RunOutput out;
    out.scalars = {{"max_F_error", r.max_F_error},
                   {"max_stress_rel_error", r.max_stress_rel_error},
                   {"static_rel_error", r.static_rel_error}};
    out.notes.push_back("The static patch test is passed only up to the Gauss quadrature error of the "
                        "background cells (MLS shape functions are rational).");
    return out;
  };
  registry.add(patch);

  SolverSpec cut;
  cut.name = "efg_cutting";
  cut.description = "PROTOTYPE explicit EFG orthogonal cutting of UD-GFRP: F_c, F_t per unit width (not validated)";
  cut.source = "Kahwash et al. 2018 sections 2-3, Tables 2-3";
  cut.params = material_params();
  for (auto q : {p("theta", Dim::angle, "fibre angle, clockwise from the cutting direction", pi / 6, 0, pi),
                 p("criterion", Dim::dimensionless, "0 max stress, 1 Hashin, 2 LaRC02", 2, 0, 2),
                 p("X_T", Dim::stress, "fibre tensile strength", 697.8e6, 0, inf),
                 p("X_C", Dim::stress, "fibre compressive strength", 443.76e6, 0, inf),
                 p("Y_T", Dim::stress, "transverse tensile strength", 89.7216e6, 0, inf),
                 p("Y_C", Dim::stress, "transverse compressive strength", 148.33e6, 0, inf),
                 p("S_L", Dim::stress, "in-plane shear strength", 33.1e6, 0, inf),
                 p("depth", Dim::length, "depth of cut", 0.25e-3, 0, inf),
                 p("work_length", Dim::length, "workpiece length", 1.5e-3, 0, inf),
                 p("work_height", Dim::length, "workpiece height", 0.75e-3, 0, inf),
                 p("spacing", Dim::length, "nodal spacing", 0.05e-3, 0, inf),
                 p("speed", Dim::velocity, "cutting speed (Table 3: 3800 mm/min)", 3800e-3 / 60.0, 0, inf),
                 p("time_scale", Dim::dimensionless, "tool speed multiplier (time scaling)", 50, 1, 1e4),
                 p("travel", Dim::length, "tool travel after first contact", 0.05e-3, 0, inf),
                 p("mu", Dim::dimensionless, "rake-face friction coefficient", 0.3, 0, 2),
                 p("clearance", Dim::angle, "clearance angle (assumption)", 7.0 * pi / 180.0, 0, pi / 4),
                 p("residual", Dim::dimensionless, "residual fraction of failed moduli", 0.01, 0, 1)}) {
    cut.params.push_back(q);
  }
  cut.scalars = {{"F_c", Dim::force_per_width, "mean cutting force over the second half of the travel"},
                 {"F_t", Dim::force_per_width, "mean thrust force over the second half of the travel"},
                 {"t_contact", Dim::time, "first tool contact"},
                 {"t_dt_drop", Dim::time, "first time the Eq 56 step fell below half its initial value (-1: none)"},
                 {"dt_min_ratio", Dim::dimensionless, "smallest / initial time step"},
                 {"fibre_damaged_fraction", Dim::dimensionless, "Gauss points with fibre damage"},
                 {"matrix_damaged_fraction", Dim::dimensionless, "Gauss points with matrix damage"},
                 {"nodes", Dim::dimensionless, "nodes"},
                 {"steps", Dim::dimensionless, "time steps"},
                 {"node_steps_per_s", Dim::dimensionless, "throughput: nodes x steps / wall time (1/s)"}};
  cut.run = [](const Values& v, const ProgressFn& progress) {
    CuttingSetup s;
    s.material = gfrp_of(v);
    s.lamina.X_T = v.at("X_T");
    s.lamina.X_C = v.at("X_C");
    s.lamina.Y_T = v.at("Y_T");
    s.lamina.Y_C = v.at("Y_C");
    s.lamina.S_L = v.at("S_L");
    s.lamina.E1 = s.material.E1;
    s.lamina.G12 = s.material.G12;
    s.lamina.nu12 = s.material.nu12;
    s.criterion = static_cast<analytic::Criterion>(static_cast<int>(std::lround(v.at("criterion"))));
    s.theta = v.at("theta");
    s.depth = v.at("depth");
    s.work_length = v.at("work_length");
    s.work_height = v.at("work_height");
    s.spacing = v.at("spacing");
    s.speed = v.at("speed");
    s.time_scale = v.at("time_scale");
    s.travel = v.at("travel");
    s.mu = v.at("mu");
    s.clearance = v.at("clearance");
    s.residual = v.at("residual");
    const auto t0 = std::chrono::steady_clock::now();
    const CuttingResult r = run_cutting(s, [&](double f) {
      if (progress) progress(f, "simulated " + std::to_string(f * 100.0) + " %");
    });
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    RunOutput out;
    Table t;
    t.name = "forces";
    t.add("t", "s", r.t);
    t.add("F_c", "N/m", r.Fc);
    t.add("F_t", "N/m", r.Ft);
    t.add("dt", "s", r.dt);
    out.tables.push_back(t);
    Snapshot snap;
    snap.time = r.t.empty() ? 0.0 : r.t.back();
    snap.x = r.gx;
    snap.y = r.gy;
    snap.add("fibre_damage", "1", r.dfibre);
    snap.add("matrix_damage", "1", r.dmatrix);
    out.snapshots.push_back(snap);
    const double ng = static_cast<double>(r.gauss);
    out.scalars = {{"F_c", r.Fc_mean},
                   {"F_t", r.Ft_mean},
                   {"t_contact", r.t_contact},
                   {"t_dt_drop", r.t_dt_drop},
                   {"dt_min_ratio", r.dt_min / r.dt_initial},
                   {"fibre_damaged_fraction", static_cast<double>(r.fibre_damaged) / ng},
                   {"matrix_damaged_fraction", static_cast<double>(r.matrix_damaged) / ng},
                   {"nodes", static_cast<double>(r.nodes)},
                   {"steps", static_cast<double>(r.steps)},
                   {"node_steps_per_s", static_cast<double>(r.nodes) * static_cast<double>(r.steps) / wall}};
    out.scalar_units = {{"F_c", "N/m"}, {"F_t", "N/m"}, {"t_contact", "s"}, {"t_dt_drop", "s"}};
    out.notes.push_back("efg_cutting is a PROTOTYPE: not validated against Kahwash Tables 4-6; workpiece size, "
                        "clearance angle (7 deg), sharp edge, friction 0.3, fixed bottom and far end, and the "
                        "time scaling are assumptions; no visibility criterion; damaged points keep 1 % stiffness "
                        "(no separation).");
    return out;
  };
  registry.add(cut);
}

}  // namespace cutbench::efg
