#pragma once
// Orthogonal cutting of a UD composite with the explicit EFG solver (Kahwash et al. 2018,
// sections 3.4-3.6, 5.1-5.4): notched rectangular workpiece (the cut starts inside the workpiece,
// section 5.1), rigid tool (rake from Table 3; clearance and edge radius are assumptions: 7 deg,
// sharp), per-Gauss-point progressive failure, separation of failed material, visibility
// criterion across the cut line behind the tool edge and the re-entrant notch corner, Eq 39-43
// contact, F_c and F_t per unit width, termination at chip completion detected from the drop of
// the Eq 56 time step (section 5.4, Fig 10). Choices are stated in solvers/efg/README.md.
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "cutbench/common/driver.hpp"
#include "cutbench/efg/explicit.hpp"

namespace cutbench::efg {

enum class CompletionGuard { none = 0, damage_path = 1, separation = 2 };

struct CuttingSetup {
  Orthotropic material;
  analytic::Lamina lamina;
  analytic::Criterion criterion = analytic::Criterion::larc02;
  double theta = 0.0;            // fibre angle: fibres along (cos theta, sin theta), tool moving +x
  double work_length = 1.5e-3;   // m (assumption: not stated in the paper)
  double work_height = 0.75e-3;  // m (assumption)
  double notch = 0.25e-3;        // already-cut length at the start (tool starts inside the workpiece)
  double depth = 0.25e-3;        // depth of cut (Table 3)
  double spacing = 0.05e-3;      // nodal spacing along x; rows: depth/(round(depth/spacing) + 0.5)
  double support_factor = 2.0;
  double rake = 0.0;             // rad (Table 3: 0)
  double clearance = 7.0 * 3.14159265358979323846 / 180.0;  // assumption (not in the paper)
  // Cutting-edge radius (not in the paper; 0 = sharp): the edge is an arc tangent to the rake and
  // clearance faces, drawn with `edge_segments` straight faces (the tool stays convex).
  double edge_radius = 0.0;
  int edge_segments = 8;
  double speed = 3800e-3 / 60.0;  // m/s (Table 3)
  double time_scale = 1.0;       // tool speed multiplier (time scaling); 1 = paper speed
  double travel = 0.5e-3;        // maximum tool travel after first contact
  // Tool speed ramped from zero over this many wave transits of the workpiece height (H/c_max):
  // keeps the start quasi-static at scaled speeds (at full speed the impact stress rho c V is
  // 94 MPa at 200 x 3800 mm/min, above S_L and Y_T). 0: full speed from the start.
  double ramp_transits = 50.0;
  double mu = 0.3;               // rake-face friction (paper: function of theta after [63], not given)
  double residual = 0.01;
  Degradation degradation = Degradation::mode_factors;  // see FailureOptions
  DamageGrowth growth = DamageGrowth::proportional;     // see FailureOptions
  // Interface strengths of Table 1 (0: unused): the interface index (<sigma22>/S_sigma)^2 +
  // (tau12/S_tau)^2 everywhere in the workpiece (see FailureOptions).
  double S_sigma = 0.0, S_tau = 0.0;
  // Paper's model by default: failed material keeps its degraded stiffness (no erosion, no
  // collapse erosion); both stay selectable for comparison.
  double collapse_ratio = 0.0;  // collapse erosion (ExplicitOptions::collapse_ratio), 0: off
  // Time step Delta t = cfl x Eq 56's min(dist)/c_max. The paper adopts the central-difference
  // procedure of Belytschko, Liu & Moran (2000, its ref. [56]), whose step is a reduction factor of
  // 0.8-0.98 times the critical one; 0.9 is the explicit codes' usual default (Radioss, OptiStruct).
  double cfl = 0.9;
  Erosion erosion = Erosion::none;
  bool visibility = true;
  // Chip completion (section 5.4): the Eq 56 step falls below (1 - drop) times its running mean
  // over the last `drop_window` steps, or a collapse-erosion event intercepts a step below
  // collapse_ratio x its initial value; 0 disables the detector (run to `travel`).
  double drop = 0.3;
  int drop_window = 200;
  double min_travel = 0.0;       // no detection before this travel (start-up transient)
  // Guard (checked every record window): which drop counts as chip completion.
  //  - none: the first drop, as the paper's Algorithm 3.6 terminates ("when the sudden drop is
  //    detected, the code terminates", section 5.4, a criterion devised "without resorting to
  //    burdensome geometrical calculations"); the default;
  //  - damage_path: only once damaged Gauss points (fibre or matrix) connect the tool edge to the
  //    free surface (the paper's verbal "damage propagating from the cutting point to the free
  //    surface", section 5.4), an option for comparison;
  //  - separation: only once Gauss points that carry no stress (eroded: fibre and matrix failed)
  //    connect the edge to the free surface through material ahead of the edge (with erosion on).
  CompletionGuard completion_guard = CompletionGuard::none;
  Kinematics kinematics = Kinematics::updated_lagrangian;
  int update_interval = 1;
  int record_every = 20;         // steps per force record (forces averaged over the window)
  int snapshots = 3;             // damage snapshots kept (at k/snapshots of the run)
};

struct CuttingSnapshot {
  double t = 0.0, travel = 0.0;
  std::vector<double> x, y, fibre, matrix;  // Gauss points: current position and damage
};

struct CuttingResult {
  std::vector<double> t, travel, Fc, Ft, dt;  // per-width forces (N/m) averaged over each window
  // Energy audit per window end (J/m): the tool's work, kinetic, strain and damage energy, and the
  // residual of the ledger (ExplicitEFG::EnergyLedger); the final values below.
  std::vector<double> e_tool, e_kinetic, e_strain, e_damage, e_residual;
  double energy_tool = 0.0, energy_kinetic = 0.0, energy_strain = 0.0, energy_damage = 0.0;
  double energy_contact_loss = 0.0, energy_released = 0.0, energy_internal = 0.0, energy_residual = 0.0;
  double t_contact = -1.0;              // first contact
  double t_contact_expected = 0.0;      // initial gap / speed
  double Fc_mean = 0.0, Ft_mean = 0.0;  // mean from first contact to the end of the run
  double Fc_peak = 0.0;
  double dt_initial = 0.0, dt_min = 0.0;
  double t_complete = -1.0;             // chip completion (time-step drop), -1: not detected
  double travel_complete = -1.0;        // tool travel at chip completion
  double dt_drop_ratio = 1.0;           // dt / running mean at detection
  double dt_mean_at_drop_ratio = -1.0;  // running mean of dt before the drop / initial dt (-1: none)
  double travel_path = -1.0;            // first travel at which damage connects edge and surface
  double travel_first_drop = -1.0;      // first time-step drop (guard or not), -1: none
  double travel_separated = -1.0;       // first travel at which eroded points connect edge and surface
  // First failure of any Gauss point (any mode): travel and the window-mean F_c of that record
  // window (N/m). Before it the response is elastic, independent of the degradation scheme.
  double travel_first_failure = -1.0, Fc_first_failure = 0.0;
  long steps = 0;
  int nodes = 0;
  double hx = 0.0, hy = 0.0, y_edge = 0.0;
  std::size_t fibre_damaged = 0, matrix_damaged = 0, interface_damaged = 0, gauss = 0;
  std::size_t eroded = 0, released = 0, collapse_eroded = 0;
  std::size_t opaque_segments = 0;     // visibility segments at the end (notch corner + cut line)
  // Damage in the chip: Gauss points above the cut line between the rake face at the start and
  // the fibre line through the tool edge at the end of the run (reference configuration).
  std::size_t chip_gauss = 0, chip_fibre = 0, chip_matrix = 0;
  // Damage below the cut line (machined surface), within one depth of cut.
  std::size_t sub_gauss = 0, sub_fibre = 0, sub_matrix = 0;
  std::vector<CuttingSnapshot> snapshots;
  // Checkpoints (cutbench run --run-cache): the step a resumed run started from (0: from the
  // beginning), how many were written, and why one could not be written (the run goes on).
  DriveReport drive;  // resume and checkpoints of the run (common/driver.hpp)
};

// Edge-to-surface path search over Gauss points in the reference configuration (the chip-completion
// guard). Gauss points closer than 0.75 max(hx, hy) are neighbours (the 2 x 2 points of a cell and
// those of the adjacent cells). A path starts at a failed point just above the cut line y_E
// (y_E < y < y_E + 1.5 hy) near the reference position of the edge (cut_tip - hx < x < cut_tip +
// 1.5 hx) and must reach a failed point within hy/2 of the free surface y = top. With ahead_only,
// only points with x > cut_tip - hx (material ahead of the edge: the chip's root) may be used.
class EdgeSurfacePath {
public:
  EdgeSurfacePath(std::vector<Vec2> gauss, double hx, double hy, double y_edge, double top);
  bool connected(const std::function<bool(std::size_t)>& failed, double cut_tip, bool ahead_only);
  std::size_t size() const { return x_.size(); }

private:
  std::vector<Vec2> x_;
  double hx_, hy_, yE_, top_;
  std::vector<int> start_, adj_;  // CSR neighbours
  std::vector<char> seen_;
  std::vector<int> queue_;
};

// Time-step drop detector of section 5.4: fires when dt < (1 - drop) x its running mean over
// `window` steps (exponential mean), or on a collapse-erosion event, provided the guard holds.
// first_drop() is the travel of the first drop with or without the guard.
class DropDetector {
public:
  DropDetector(double drop, int window, double dt0) : drop_(drop), window_(std::max(1, window)), mean_(dt0) {}
  // Returns true when completion is detected at this step (ratio() = dt / running mean then);
  // drops are looked for only when `armed` (the running mean is always updated).
  bool update(double dt, bool collapse_event, bool guard, double travel, bool armed = true);
  double first_drop() const { return first_drop_; }
  double ratio() const { return ratio_; }
  void save(BinaryWriter& w) const;
  void load(BinaryReader& r);

private:
  double drop_;
  int window_;
  double mean_;
  double first_drop_ = -1.0, ratio_ = 1.0;
};

// Tool-edge vertices replacing the sharp edge E (counter-clockwise, from the clearance face to
// the rake face): {E} when radius = 0, else segments + 1 points on the tangent arc.
std::vector<Vec2> edge_vertices(const Vec2& E, double rake, double clearance, double radius, int segments);

CuttingResult run_cutting(const CuttingSetup& s, const std::function<void(double)>& progress = nullptr);

}  // namespace cutbench::efg
