// sph_cutting: orthogonal cutting of Ti6Al4V (Afrasiabi et al. 2021, Sec. 5.2, Fig. 4, Table 1).
//
// Workpiece [0, L] x [0, H] on a square lattice (n particles over the height), clamped (velocity
// zero, T = T_inf) on `fixed_layers` layers at the bottom and at x = 0. The rigid tool starts just
// right of x = L with its lowest edge point at y = H - t_u and moves at -v_c (the mirror image of
// the paper's Fig. 4, which clamps the right side). Forces on the tool per unit width; F_c along the
// cut (positive against the tool motion), F_t normal to the machined surface (positive pushing the
// tool up). Tool particles (a band of tool_depth around the edge) conduct heat; the far ones are a
// heat sink at T_inf.
#include <algorithm>
#include <cmath>

#include "cutbench/common/errors.hpp"
#include "cutbench/sph/lattice.hpp"
#include "cutbench/sph/runners.hpp"
#include "specs.hpp"
#include "cutbench/sph/solid.hpp"

namespace cutbench::sph {

CuttingResult run_cutting(const CuttingSetup& c, const ProgressFn& progress) {
  if (c.particles_over_height < 4) throw InputError("particles_over_height", "needs at least 4");
  if (!(c.uncut_thickness > 0.0 && c.uncut_thickness < c.height)) throw InputError("uncut_thickness", "must be in (0, height)");
  if (!(c.cut_distance > 0.0 && c.cut_distance < c.length)) throw InputError("cut_distance", "must be in (0, length)");
  const double dx = c.height / static_cast<double>(c.particles_over_height - 1);
  const auto nx = static_cast<std::size_t>(std::lround(c.length / dx)) + 1;
  const auto ny = static_cast<std::size_t>(c.particles_over_height);
  const auto x = rectangle_lattice(nx, ny, 0.0, dx * static_cast<double>(nx - 1), 0.0, c.height);
  std::vector<char> fixed(x.size(), 0);
  const double lim = (static_cast<double>(c.fixed_layers) - 0.5) * dx;
  for (std::size_t i = 0; i < x.size(); ++i) fixed[i] = x[i].y() < lim || x[i].x() < lim;

  SolidMaterial mat;
  mat.plastic = true;
  SolidOptions opt;
  SolidSph s(x, dx, mat, opt);
  s.set_fixed(fixed);
  ThermalOptions th;
  if (c.enhanced_thermal) {
    th.scheme = HeatScheme::fmfs;
  } else {  // reference model: Brookshaw everywhere, no convection or radiation
    th.scheme = HeatScheme::brookshaw;
    th.boundary.h_conv = 0.0;
    th.boundary.emissivity = 0.0;
  }
  th.brookshaw_band = c.brookshaw_band;
  s.enable_thermal(th, fixed);
  ContactOptions contact;
  contact.friction = c.friction;
  contact.model = c.penalty_contact ? ContactModel::penalty : ContactModel::velocity;
  contact.offset_fraction = c.contact_offset;
  const double x_tool = dx * static_cast<double>(nx - 1) + 0.5 * dx + c.edge_radius + 0.5 * dx;
  const double y_low = c.height - c.uncut_thickness;
  s.set_tool(cutting_tool(c.rake, c.clearance, c.edge_radius, Vec2::Zero(), 10.0 * c.height),
             Vec2(x_tool, y_low), Vec2(-c.speed, 0.0), contact);
  if (c.tool_conduction)
    s.set_tool_thermal(HeatMaterial{88.0, c.tool_density, 292.0}, std::max(c.tool_depth, 8.0 * dx));

  CuttingResult r;
  r.dx = dx;
  r.particles = x.size();
  const double t_end = c.cut_distance / c.speed;
  const double window = std::max(c.history_window, 1e-12);
  double acc_fc = 0.0, acc_ft = 0.0, acc_t = 0.0, t_next = window;
  double steady_fc = 0.0, steady_ft = 0.0, steady_t = 0.0;
  const double t_steady = c.steady_from * t_end;
  auto take_snapshot = [&]() {
    Snapshot snap;
    snap.time = s.time();
    for (std::size_t i = 0; i < x.size(); ++i) {
      snap.x.push_back(s.positions()[i].x());
      snap.y.push_back(s.positions()[i].y());
    }
    snap.add("T", "K", s.temperature());
    snap.add("eps_p", "1", s.plastic_strain());
    std::vector<double> surf(x.size(), 0.0);
    for (std::size_t i = 0; i < x.size() && i < s.surface().surface.size(); ++i) surf[i] = s.surface().surface[i];
    snap.add("surface", "1", surf);
    return snap;
  };
  const int n_snap = std::max(1, c.snapshots);
  int snap_taken = 0;
  while (s.time() < t_end) {
    const double dt = std::min(s.stable_time_step(), t_end - s.time());
    if (!(dt > 0.0)) break;
    s.step(dt);
    const double fc = s.tool_force().x(), ft = s.tool_force().y();  // force on the tool
    // tool moves in -x: the cutting force resists it (+x on the tool); thrust pushes it up (+y)
    acc_fc += fc * dt;
    acc_ft += ft * dt;
    acc_t += dt;
    if (s.time() >= t_steady) {
      steady_fc += fc * dt;
      steady_ft += ft * dt;
      steady_t += dt;
    }
    if (snap_taken < n_snap - 1 && s.time() >= t_end * static_cast<double>(snap_taken + 1) / n_snap) {
      r.snapshots.push_back(take_snapshot());
      ++snap_taken;
    }
    if (s.time() >= t_next || s.time() >= t_end) {
      r.t.push_back(s.time());
      r.cut.push_back(s.time() * c.speed);
      r.fc.push_back(acc_fc / acc_t);
      r.ft.push_back(acc_ft / acc_t);
      acc_fc = acc_ft = acc_t = 0.0;
      t_next += window;
      if (progress)
        progress(s.time() / t_end, "cut " + std::to_string(s.time() * c.speed * 1e3) + " mm, step " +
                                       std::to_string(s.steps()));
    }
  }
  r.steps = s.steps();
  r.fc_mean = steady_t > 0.0 ? steady_fc / steady_t : nan_value();
  r.ft_mean = steady_t > 0.0 ? steady_ft / steady_t : nan_value();
  // Rake-face temperature: free particles within 1.5 dx of the tool whose contact normal points
  // against the cut (the rake face), above the edge.
  double tsum = 0.0;
  std::size_t tn = 0;
  r.T_max = 0.0;
  double chip_top = 0.0;
  const auto tool = cutting_tool(c.rake, c.clearance, c.edge_radius, Vec2::Zero(), 10.0 * c.height);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec2& p = s.positions()[i];
    r.T_max = std::max(r.T_max, s.temperature()[i]);
    chip_top = std::max(chip_top, p.y());
    if (fixed[i]) continue;
    const auto sd = tool->at(p - s.tool_position());
    if (sd.distance < 1.5 * dx && sd.normal.x() < -0.7 && p.y() > s.tool_position().y() + c.edge_radius) {
      tsum += s.temperature()[i];
      ++tn;
    }
  }
  r.rake_temperature = tn ? tsum / static_cast<double>(tn) : nan_value();
  tsum = 0.0;
  tn = 0;
  r.tool_T_max = nan_value();
  if (c.tool_conduction) {
    r.tool_T_max = 0.0;
    for (std::size_t k = 0; k < s.tool_particles().size(); ++k) {
      const Vec2& p = s.tool_particles()[k];
      const double tk = s.tool_temperature()[k];
      r.tool_T_max = std::max(r.tool_T_max, tk);
      const auto sd = tool->at(p);
      if (sd.distance > -1.5 * dx && sd.normal.x() < -0.7 && p.y() > c.edge_radius && p.y() < 2.0 * c.uncut_thickness) {
        tsum += tk;
        ++tn;
      }
    }
  }
  r.tool_rake_temperature = tn ? tsum / static_cast<double>(tn) : nan_value();
  r.chip_height = chip_top - c.height;
  r.snapshot = take_snapshot();
  r.snapshots.push_back(r.snapshot);
  r.tool_snapshot.time = s.time();
  for (std::size_t k = 0; k < s.tool_particles().size(); ++k) {
    r.tool_snapshot.x.push_back(s.tool_particles()[k].x() + s.tool_position().x());
    r.tool_snapshot.y.push_back(s.tool_particles()[k].y() + s.tool_position().y());
  }
  r.tool_snapshot.add("T", "K", s.tool_temperature());
  r.friction_heat = s.friction_heat();
  r.plastic_heat = s.plastic_heat();
  r.stored_workpiece = s.workpiece_heat_content();
  r.stored_tool = s.tool_heat_content();
  r.heat_lost = s.boundary_heat_loss();
  r.heat_sunk = s.heat_sunk();
  const double generated = r.plastic_heat + r.friction_heat;
  r.heat_imbalance =
      generated > 0.0 ? (generated - r.stored_workpiece - r.stored_tool - r.heat_lost - r.heat_sunk) / generated
                      : 0.0;
  return r;
}

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}

SolverSpec detail::cutting_spec() {
  SolverSpec s;
  s.name = "sph_cutting";
  s.description = "Thermo-mechanical SPH orthogonal cutting of Ti6Al4V (rigid tool, Coulomb friction); "
                  "reference (Brookshaw, adiabatic) or enhanced (FMFS + convection/radiation) thermal model";
  s.source = "Afrasiabi et al. (2021) Appl. Sci. 11:1020, Sec. 5.2, Fig. 4, Table 1";
  const CuttingSetup def;
  s.params = {
      param("particles_over_height", Dim::dimensionless, "particles over the workpiece height", def.particles_over_height, 4, 400),
      param("length", Dim::length, "workpiece length", def.length, 1e-6, 1.0),
      param("height", Dim::length, "workpiece height", def.height, 1e-6, 1.0),
      param("uncut_thickness", Dim::length, "uncut chip thickness t_u", def.uncut_thickness, 1e-7, 1.0),
      param("cut_distance", Dim::length, "cut distance", def.cut_distance, 1e-7, 1.0),
      param("speed", Dim::velocity, "cutting speed v_c", def.speed, 1e-3, 1e3),
      param("friction", Dim::dimensionless, "Coulomb friction coefficient", def.friction, 0.0, 2.0),
      param("rake", Dim::angle, "rake angle", def.rake, -60 * kDeg, 60 * kDeg),
      param("clearance", Dim::angle, "clearance angle", def.clearance, 0.5 * kDeg, 45 * kDeg),
      param("edge_radius", Dim::length, "cutting-edge radius", def.edge_radius, 0.0, 1e-3),
      param("enhanced_thermal", Dim::dimensionless, "1: FMFS + convection/radiation (paper); 0: reference", 1.0, 0.0, 1.0),
      param("brookshaw_band", Dim::dimensionless, "1: Brookshaw on a 2h band at surfaces (energy-conserving variant)", 0.0, 0.0, 1.0),
      param("fixed_layers", Dim::dimensionless, "clamped particle layers at the bottom and the far end", def.fixed_layers, 1, 20),
      param("tool_conduction", Dim::dimensionless, "1: tool particles conduct heat", 1.0, 0.0, 1.0),
      param("tool_density", Dim::density, "tool density (not in the paper; WC-Co assumed)", def.tool_density, 1.0, 1e5),
      param("tool_depth", Dim::length, "size of the discretised tool band around the edge", def.tool_depth, 1e-6, 1.0),
      param("penalty_contact", Dim::dimensionless, "1: penalty + stick-slip friction (default); 0: velocity-level contact", 1.0, 0.0, 1.0),
      param("contact_offset", Dim::dimensionless, "contact surface offset in particle spacings", def.contact_offset, 0.0, 1.0),
      param("snapshots", Dim::dimensionless, "number of workpiece snapshots (equally spaced, last at the end)", 1.0, 1.0, 1000.0),
      param("steady_from", Dim::dimensionless, "fraction of the cut after which forces are averaged", def.steady_from, 0.0, 0.99),
  };
  s.scalars = {{"F_c", Dim::force_per_width, "mean cutting force per unit width (steady part)"},
               {"F_t", Dim::force_per_width, "mean thrust force per unit width (steady part)"},
               {"rake_temperature", Dim::temperature, "mean temperature of particles on the rake face at the end"},
               {"T_max", Dim::temperature, "maximum temperature at the end"},
               {"tool_rake_temperature", Dim::temperature, "mean temperature of tool particles on the rake face (up to 2 t_u)"},
               {"tool_T_max", Dim::temperature, "maximum tool temperature"},
               {"chip_height", Dim::length, "highest particle above the original surface"},
               {"steps", Dim::dimensionless, "time steps"},
               {"heat_generated", Dim::force_per_width, "plastic + friction heat, J per metre of depth"},
               {"heat_imbalance", Dim::dimensionless, "(generated - stored - lost - sunk) / generated"}};
  s.run = [](const Values& v, const ProgressFn& progress) {
    CuttingSetup c;
    const double n = v.at("particles_over_height");
    if (n != std::floor(n)) throw InputError("particles_over_height", "must be an integer");
    c.particles_over_height = static_cast<int>(n);
    c.length = v.at("length");
    c.height = v.at("height");
    c.uncut_thickness = v.at("uncut_thickness");
    c.cut_distance = v.at("cut_distance");
    c.speed = v.at("speed");
    c.friction = v.at("friction");
    c.rake = v.at("rake");
    c.clearance = v.at("clearance");
    c.edge_radius = v.at("edge_radius");
    c.enhanced_thermal = v.at("enhanced_thermal") != 0.0;
    c.brookshaw_band = v.at("brookshaw_band") != 0.0;
    c.fixed_layers = static_cast<int>(v.at("fixed_layers"));
    c.steady_from = v.at("steady_from");
    c.tool_conduction = v.at("tool_conduction") != 0.0;
    c.snapshots = static_cast<int>(v.at("snapshots"));
    c.penalty_contact = v.at("penalty_contact") != 0.0;
    c.contact_offset = v.at("contact_offset");
    c.tool_density = v.at("tool_density");
    c.tool_depth = v.at("tool_depth");
    c.history_window = c.cut_distance / c.speed / 200.0;
    const auto r = run_cutting(c, progress);
    RunOutput out;
    Table t;
    t.name = "forces";
    t.add("t", "s", r.t);
    t.add("cut_distance", "m", r.cut);
    t.add("F_c", "N/m", r.fc);
    t.add("F_t", "N/m", r.ft);
    out.tables.push_back(std::move(t));
    out.snapshots = r.snapshots;
    if (!r.tool_snapshot.x.empty()) out.snapshots.push_back(r.tool_snapshot);
    out.scalars = {{"F_c", r.fc_mean}, {"F_t", r.ft_mean}, {"rake_temperature", r.rake_temperature},
                   {"T_max", r.T_max}, {"chip_height", r.chip_height}, {"steps", static_cast<double>(r.steps)},
                   {"tool_rake_temperature", r.tool_rake_temperature}, {"tool_T_max", r.tool_T_max},
                   {"heat_generated", r.plastic_heat + r.friction_heat}, {"heat_imbalance", r.heat_imbalance}};
    out.scalar_units = {{"F_c", "N/m"}, {"F_t", "N/m"}, {"rake_temperature", "K"}, {"T_max", "K"},
                        {"chip_height", "m"}, {"steps", "1"}, {"tool_rake_temperature", "K"}, {"tool_T_max", "K"},
                        {"heat_generated", "J/m"}, {"heat_imbalance", "1"}};
    out.notes.push_back("Snapshots: the workpiece states in time order, then (if the tool conducts) the "
                        "final tool particles with their temperature.");
    out.notes.push_back("Tool is rigid; its particles conduct heat (k 88 W/mK, c_p 292 J/kgK, density "
                        "assumed) and exchange heat with the workpiece by harmonic-mean Brookshaw pairs; "
                        "all friction heat goes to the workpiece particle (eta = 1). Stabiliser "
                        "parameters (artificial viscosity 1/1, artificial stress 0.3, XSPH 0.5) are "
                        "assumed, the paper does not list them.");
    return out;
  };
  return s;
}

}  // namespace cutbench::sph
