#pragma once
// Case runners of the SPH solver, registered with the framework as SolverSpecs.
#include <cstdint>
#include <string>
#include <vector>

#include "cutbench/common/driver.hpp"
#include "cutbench/common/solver.hpp"
#include "cutbench/sph/register.hpp"
#include "cutbench/sph/solid.hpp"

namespace cutbench::sph {


// Fig. 3: Laplacian of f = x^2 + y^2 on an n x n lattice over [-1, 1]^2, V_j = dx^2, h = h/dx * dx.
struct LaplacianReconstruction {
  std::vector<double> x, y, exact, brookshaw, fmfs;
  double brookshaw_interior_mean = 0.0;     // over particles with |x|,|y| <= 0.8
  double brookshaw_interior_max_abs_error = 0.0;
  double brookshaw_corner = 0.0;            // mean of the four corner particles
  double brookshaw_max_abs_error = 0.0;
  double fmfs_max_abs_error = 0.0;
  double fmfs_irregular = 0.0;              // particles where FMFS fell back (expected 0)
};
LaplacianReconstruction laplacian_reconstruction(std::size_t n, double h_over_dx, double jitter_fraction,
                                                 std::uint64_t seed = 1);

// Orthogonal cutting (paper Sec. 5.2, Table 1). SI units.
struct CuttingSetup {
  int particles_over_height = 41;
  double length = 3e-3, height = 0.3e-3, uncut_thickness = 0.1e-3, cut_distance = 2e-3;
  double speed = 318.5 / 60.0;  // m/s
  double friction = 0.35;
  double rake = 0.0, clearance = 7.0 * 3.14159265358979323846 / 180.0, edge_radius = 2.8e-6;
  bool enhanced_thermal = true;
  bool brookshaw_band = true;     // enhanced model: Brookshaw on a 2h surface band (README decision); false: paper
  int fixed_layers = 3;
  bool tool_conduction = true;   // tool particles conduct heat (k 88, c_p 292 from Table 1)
  double tool_density = 15000.0;  // kg/m^3, NOT in the paper (WC-Co assumed)
  double tool_depth = 0.2e-3;     // tool band discretised around the edge
  double steady_from = 0.3;      // forces averaged over the cut after this fraction
  double history_window = 1e-6;  // s, force-history averaging window
  int snapshots = 1;              // equally spaced in time, the last at the end of the cut
  bool penalty_contact = true;    // true: penalty + stick-slip friction (default); false: velocity level
  double contact_offset = 0.5;    // contact surface offset in units of dx
  double tool_conductivity = 88.0;     // W/mK, Table 1
  double tool_specific_heat = 292.0;   // J/kgK, Table 1
  double tool_heat_share = -1.0;  // friction heat to the tool; < 0: effusivity partition (ContactOptions)
  bool shear_cap = false;         // Zorev cap of the friction stress (ContactOptions::shear_cap)
  double contact_stiffness = 0.1; // penalty alpha (ContactOptions::alpha), a choice (not in the paper)
  // stabilisers (SolidOptions; the paper does not list them): Monaghan viscosity, Gray artificial
  // stress, XSPH
  double alpha_visc = 1.0, beta_visc = 1.0, artificial_stress = 0.3, xsph = 0.5;
  int flow_law = 0;  // 0: Johnson-Cook with the Table 1 constants; 1: Sima & Oezel (2010) softening law
  // run-to-run scatter: the free particles of the initial lattice displaced by up to
  // lattice_jitter dx in x and y (uniform, seeded); 0 = the regular lattice
  double lattice_jitter = 0.0;
  double lattice_seed = 1.0;  // a whole number up to 2^32 - 1
};

// The material, thermal and contact inputs run_cutting() builds from a setup (one place, so that
// the Table 1 case can check what the runner really uses).
struct CuttingInputs {
  SolidMaterial material;
  SolidOptions options;
  ThermalOptions thermal;
  ContactOptions contact;
  HeatMaterial tool_heat;
  double h_over_dx = 1.5;
};
CuttingInputs cutting_inputs(const CuttingSetup& setup);

struct CuttingResult {
  std::vector<double> t, cut, fc, ft;  // windowed means of the force on the tool, N/m
  // First-law audit at the end of each window (J/m, from the start): the tool's work on the
  // workpiece, kinetic and elastic energy, plastic, friction and artificial-viscosity dissipation,
  // work of the artificial-stress forces, energy in the contact springs, and the two halves of the
  // stress power (pair forces on the particles; constitutive sum V sigma:D), see SolidSph::EnergyLedger.
  std::vector<double> e_tool, e_kinetic, e_elastic, e_plastic, e_friction, e_viscous, e_art, e_spring, e_stress, e_internal, e_xsph;
  double fc_mean = 0.0, ft_mean = 0.0;
  double rake_temperature = 0.0, T_max = 0.0, chip_height = 0.0;
  double rake_temperature_avg = 0.0;  // rake-face sample averaged over the steady part's windows
  double tool_rake_temperature = 0.0, tool_T_max = 0.0;  // tool particles on the rake face / all
  double friction_heat = 0.0, plastic_heat = 0.0;  // J/m
  // heat audit (J/m): generated = plastic + friction; stored in workpiece and tool, lost to the air,
  // sunk into the fixed-temperature particles; imbalance = (generated - stored - lost - sunk) / generated
  double stored_workpiece = 0.0, stored_tool = 0.0, heat_lost = 0.0, heat_sunk = 0.0, heat_imbalance = 0.0;
  double friction_heat_tool = 0.0, tool_share = 0.0;  // friction heat put into the tool, J/m; beta
  // where the heat is (J/m): plastic heat put into, and heat content at the end of, the particles
  // that started in the uncut layer (above the cut line) and those that started below it, and the
  // heat content of the chip (the columns counted as chip below)
  double plastic_heat_layer = 0.0, plastic_heat_below = 0.0;
  double stored_layer = 0.0, stored_below = 0.0, stored_chip = 0.0;
  Vec2 T_max_at = Vec2::Zero();  // position of T_max relative to the lowest tool edge point
  // Chip: columns of the initial lattice in the uncut layer that the tool has passed by more than
  // t_u / 2 and most of whose particles are above the original surface; only those lifted particles
  // count (area, temperature, eps_p, centroid). In cutting order: position u along the uncut layer
  // (from the first column the tool met), mean eps_p and centroid of each column. Thickness = chip
  // area / length of the centroid line (smoothed over 3 columns); curl = turning angle of that line
  // (first third to last third); serration: the eps_p profile against u after the entry transient
  // (u >= 2 t_u), smoothed over 3 columns, peaks found with hysteresis 0.2 x mean (segments), their
  // mean spacing in u (pitch, along the uncut layer), std/mean of the profile (cv).
  std::vector<double> chip_x0, chip_u, chip_eps, chip_cx, chip_cy, chip_s;
  // thickness of each chip column across the chip and the saw-tooth of the free surface measured on
  // it after the entry transient (teeth, their pitch along the uncut layer and half their height)
  std::vector<double> chip_t;
  double tooth_segments = 0.0, tooth_pitch = 0.0, tooth_amplitude = 0.0;
  double chip_thickness = 0.0, chip_length = 0.0, chip_curl = 0.0, chip_T_mean = 0.0;
  double chip_segments = 0.0, serration_pitch = 0.0, serration_cv = 0.0;
  // Surface detection on the uncut surface at the end (paper Fig. 2): over the lattice columns
  // more than 3 t_u ahead of the tool, the share whose top particle is a surface particle and the
  // share whose second particle from the top is one too (NaN without surface detection)
  double surface_top_fraction = 0.0, surface_second_fraction = 0.0;
  // Steady-part mean force on the tool split by the tool face of each contact normal (rake face,
  // rounded edge, clearance face), N/m; on the rake face: sum |f_t| / sum |f_n| (the friction
  // ratio the chip actually uses) and the share of contacts at the Coulomb limit (sliding).
  Vec2 force_rake = Vec2::Zero(), force_edge = Vec2::Zero(), force_flank = Vec2::Zero();
  double rake_friction_ratio = 0.0, rake_slip_fraction = 0.0;
  double dx = 0.0;
  std::size_t particles = 0, steps = 0;
  Snapshot snapshot;               // final state: T, eps_p, surface flag
  std::vector<Snapshot> snapshots;  // `snapshots` states, the last one equal to `snapshot`
  Snapshot tool_snapshot;          // final tool particles (world frame) with T
  DriveReport drive;  // resume and checkpoints of the run (common/driver.hpp)
};

// Peaks of a profile f(s) by hysteresis: a peak counts when f rose by more than rel_threshold x
// |mean f| from the last minimum and then fell by as much; returns the abscissae of the peaks.
std::vector<double> serration_peaks(const std::vector<double>& s, const std::vector<double>& f, double rel_threshold);

CuttingResult run_cutting(const CuttingSetup& setup, const ProgressFn& progress = nullptr);

}  // namespace cutbench::sph
