#pragma once
// Explicit dynamic EFG solver (Kahwash 2018, sections 2.3, 2.5, 3.1-3.2): lumped mass (row sums
// of Eq 35), central-difference integration (Eqs 47-50), critical time step from sqrt(C11/rho)
// and the smallest current nodal distance (Eqs 55-56), recomputed every step.
//
// Kinematics:
//  - small_strain: eps = sym(grad u), sigma = Qbar eps (linear reference);
//  - total_lagrangian: Green-Lagrange strain E = (F^T F - I)/2 and PK2 S = Qbar E (Eq 51), shape
//    functions on the initial configuration, f_I = sum_G V_G (F S) grad0 phi_I;
//  - updated_lagrangian: as total, but the reference configuration (node and Gauss point
//    positions, Gauss volumes, shape functions) is moved to the current one every
//    `update_interval` steps; the total deformation gradient is carried multiplicatively,
//    F = F_inc F_r, and the first Piola stress relative to the last reference is
//    P_r = F_inc (F_r S F_r^T)/J_r. With an infinite interval this is the total form.
// Dirichlet conditions are imposed on nodal values, which the near-interpolating regularised
// weight makes acceptable (the paper's choice); the residual error is tested.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "cutbench/analytic/composite_failure.hpp"
#include "cutbench/common/binary_io.hpp"

#include "cutbench/efg/discretisation.hpp"
#include "cutbench/efg/material.hpp"

namespace cutbench::efg {

using Mat2 = Eigen::Matrix2d;

enum class Kinematics { small_strain, total_lagrangian, updated_lagrangian };

// Progressive failure per Gauss point (Kahwash 2018 section 2.6.2): the trial PK2 stress is
// rotated to the material frame (Eq 52-53) and checked with the analytic library's criterion;
// three damage flags are stored per Gauss point (fibre, matrix, interface), each 0 or 1, and the
// stiffness is degraded suddenly and irreversibly (see solvers/efg/README.md):
//   fibre     -> E1, G12, nu12 times `residual`;
//   matrix    -> E2, G12, nu12 times `residual`;
//   interface -> G12 times `residual`.
// Interface index: the criterion's own in-plane shear index where it has one (maximum stress);
// otherwise (sigma22+/S_sigma)^2 + (tau12/S_tau)^2 with the interface strengths of Table 1 when
// given (> 0), else none. When the stress of a Gauss point gains damage it is recomputed with the
// degraded stiffness in the same step (the paper's "trial stress", section 3.6).
//
// Degradation schemes (solvers/efg/README.md, "Progressive failure"):
//  - sudden: the table above, every failed modulus times `residual`;
//  - mode_factors: mode- and sign-dependent factors of Camanho & Matthews (1999) as tabulated by
//    Tserpes et al. (2002), the selective sudden degradation used in FE models of FRP cutting:
//      fibre tension (sigma11 >= 0 at failure)    -> E1, E2, G12, nu12 x 0.07
//      fibre compression                          -> E1, E2, G12, nu12 x 0.14
//      matrix tension (sigma22 >= 0 at failure)   -> E2, G12 x 0.2
//      matrix compression                         -> E2, G12 x 0.4
//      interface (fibre-matrix shear)             -> G12, nu12 x `residual` (0 in the source)
//    rules of several failed modes are applied in sequence (factors multiply).
enum class Degradation { sudden = 0, mode_factors = 1 };
// How the failure index d (Appendix A: 0 no failure, 1 total failure; stored per Gauss point and
// mode as its running maximum, capped at 1, the paper's damage matrix D) degrades the stiffness:
//  - at_failure: a mode's moduli take the factor of the degradation scheme when its d reaches 1
//    (sudden, irreversible: Camanho & Matthews' selective degradation);
//  - proportional: every modulus of a mode is scaled by 1 - d (1 - factor) as d grows, reaching
//    the scheme's factor at d = 1 (continuous, irreversible).
enum class DamageGrowth { at_failure = 0, proportional = 1 };
struct ModeFactors {
  double fibre_tension = 0.07, fibre_compression = 0.14;
  double matrix_tension = 0.2, matrix_compression = 0.4;
};
struct FailureOptions {
  bool enabled = false;
  analytic::Criterion criterion = analytic::Criterion::larc02;
  analytic::Lamina lamina;
  double residual = 0.01;  // degraded fraction of a failed modulus
  Degradation degradation = Degradation::sudden;
  DamageGrowth growth = DamageGrowth::at_failure;
  ModeFactors factors;     // mode_factors scheme
  double S_sigma = 0.0;    // interface normal strength (Table 1), 0: unused
  double S_tau = 0.0;      // interface shear strength (Table 1), 0: unused
  // The cutting zone where S_sigma, S_tau apply: Gauss points whose initial y exceeds this (the
  // cutting model: the cut line, i.e. the layer the tool removes); -inf: everywhere.
  double zone_y_min = -HUGE_VAL;
};
// Separation of failed material (solvers/efg/README.md, "Separation"): with `erosion` on, a Gauss
// point whose fibre and matrix modes have both failed (every modulus degraded) carries no stress
// from then on ("eroded"); a node none of whose supporting Gauss points carries stress any more
// is released: it leaves the model (no internal force, no contact, excluded from the Eq 56 time
// step, velocity frozen), as the debris of an element-free crack.
enum class Erosion { none, fibre_and_matrix, fibre_or_matrix };

// Upper bound of the LaRC02 matrix-compression index (sigma22 < 0, fracture plane searched over
// [0, alpha0]) from |sigma22| = p and |tau12| alone: with c = cos a, s = sin a,
//   tau_T = <p c (s - eta_T c)> = <(p/2) (sin 2a - eta_T cos 2a - eta_T)> <= (p/2) (sqrt(1 + eta_T^2) - eta_T),
//   tau_L = <c (|t12| - eta_L p c)> <= max over c in [0, 1] of |t12| c - eta_L p c^2
//         (|t12|^2 / (4 eta_L p) at the vertex c = |t12| / (2 eta_L p) <= 1, else |t12| - eta_L p;
//          |t12| + |eta_L| p for eta_L < 0),
// so the index is at most (tau_T,max/S_T)^2 + (tau_L,max/S_L)^2, raised by 1e-12 against round-off
// (for t12 = 0 the bound is attained at a = alpha0). Below the stored index the costly search
// cannot raise it and is skipped without changing any failure decision (used by ExplicitEFG;
// tested against the search). The lamina constants are computed once.
class Larc02CompressionBound {
public:
  explicit Larc02CompressionBound(const analytic::Lamina& m);
  double operator()(double s22, double t12) const;

private:
  double ST_ = 0.0, SL_ = 0.0, eta_L_ = 0.0, tT_per_p_ = 0.0;
};
double larc02_matrix_compression_bound(double s22, double t12, const analytic::Lamina& m);
enum DamageMode : int { fibre_damage = 0, matrix_damage = 1, interface_damage = 2 };

// Rigid tool: a convex polygon (counter-clockwise vertices at t = 0) translating at `velocity`,
// in contact with every workpiece node through the central-difference contact forces of
// Eqs 39-43, applied in the half-step velocity of Eq 48 (predictor-corrector): normal
// f_n = 2 M g / dt^2 (Eq 39, moves the node back by exactly g), stick trial
// f_t = 2 M g_t / dt^2 (Eq 40 with the same factor, removes the step's slip), slip trial mu f_n
// (Eq 41), stick when the stick trial is the smaller (Eqs 42-43); no penalty parameter. The
// reported tool force is the momentum exchanged per step over dt (half the Eq 39 value).
// The velocity may be ramped linearly from zero over `ramp_time` (a quasi-static start: a tool
// hitting the workpiece at full speed launches a stress wave of rho c |v|).
struct RigidTool {
  std::vector<Vec2> vertices;
  Vec2 velocity = Vec2::Zero();
  double mu = 0.0;
  double ramp_time = 0.0;
  Vec2 velocity_at(double t) const {
    return ramp_time > 0.0 && t < ramp_time ? Vec2(velocity * (t / ramp_time)) : velocity;
  }
  Vec2 displacement(double t) const {
    if (ramp_time > 0.0 && t < ramp_time) return velocity * (0.5 * t * t / ramp_time);
    return velocity * (t - 0.5 * ramp_time);
  }
};

struct ExplicitOptions {
  Kinematics kinematics = Kinematics::total_lagrangian;
  int update_interval = 1;  // updated Lagrangian: steps between reference updates
  double cfl = 0.5;         // dt = cfl * min(dist)/c_max (Eq 56 requires cfl < 1)
  WeightParams weight;
  double thickness = 1.0;   // out-of-plane thickness (m); forces are per this thickness
  FailureOptions failure;
  Erosion erosion = Erosion::none;
  // Erosion of collapsed failed material (solvers/efg/README.md, "Collapse erosion"): when two
  // active nodes come closer than `collapse_ratio` x the initial smallest nodal distance (the
  // Eq 56 step would fall below that fraction of its initial value), each node of the pair whose
  // supporting Gauss points have all failed (any mode) or are eroded has those Gauss points
  // eroded, so it is released and leaves the time-step estimate. Intact material is never
  // eroded: a pair with an intact supporting Gauss point on both nodes keeps the small step.
  // 0: off.
  double collapse_ratio = 0.0;
};

// A prescribed nodal velocity component v(t) (displacement follows by integration).
struct VelocityBC {
  int node = 0;
  int dof = 0;  // 0 = x, 1 = y
  std::function<double(double)> v;
};

class ExplicitEFG {
public:
  ExplicitEFG(const Discretisation& d, const Orthotropic& mat, double theta, const ExplicitOptions& opt);

  void add_velocity_bc(int node, int dof, std::function<double(double)> v);
  void set_external_force(std::vector<Vec2> f) { fext_ = std::move(f); }  // constant nodal forces
  void set_initial_velocity(const std::vector<Vec2>& v) { v_ = v; }
  // Moves the nodes to X0 + u and recomputes stresses, forces and accelerations (updated
  // Lagrangian: then moves the reference configuration there).
  void set_displacement(const std::vector<Vec2>& u);

  void set_tool(const RigidTool& tool) { tool_ = tool; has_tool_ = true; }
  // Force exerted by the workpiece on the tool during the last step (per thickness of the model),
  // the number of nodes in contact and how many of them stuck.
  Vec2 tool_force() const { return tool_force_; }
  int contact_count() const { return ncontact_; }
  int stick_count() const { return nstick_; }

  // Visibility criterion: opaque segments (crack faces, cut line, re-entrant boundaries) given in
  // the reference configuration. Adding one recomputes the shape functions of the Gauss points
  // within the largest support radius of it, without the nodes it hides (lumped masses are kept).
  void add_opaque_segment(const Segment& s);
  const std::vector<Segment>& opaque_segments() const { return opaque_; }
  // Shape data (reference configuration) of Gauss point g.
  const ShapeData& shape(std::size_t g) const { return gp_[g].sd; }
  bool eroded(std::size_t g) const { return gp_[g].eroded; }
  bool released(std::size_t I) const { return !active_[I]; }
  std::size_t released_count() const { return nreleased_; }
  std::size_t eroded_count() const { return neroded_; }
  std::size_t collapse_eroded_count() const { return ncollapse_; }  // Gauss points eroded by collapse

  double critical_time_step() const;  // Eqs 55-56 on the current configuration (active nodes)
  double step();                      // one step at cfl * critical; returns dt
  void step(double dt);

  double time() const { return t_; }
  long steps() const { return nstep_; }
  const std::vector<Vec2>& positions() const { return x_; }
  std::vector<Vec2> displacements() const;
  const std::vector<Vec2>& velocities() const { return v_; }
  const std::vector<double>& masses() const { return mass_; }
  const std::vector<Vec2>& internal_forces() const { return fint_; }
  std::size_t num_gauss() const { return gp_.size(); }
  // Per Gauss point: PK2 (or small-strain) stress and Cauchy stress, Voigt (xx, yy, xy), current
  // position and deformation gradient.
  Eigen::Vector3d pk2(std::size_t g) const { return gp_[g].S; }
  Eigen::Vector3d cauchy(std::size_t g) const;
  Eigen::Vector3d green_lagrange(std::size_t g) const { return gp_[g].E; }
  Mat2 deformation_gradient(std::size_t g) const { return gp_[g].F; }
  Vec2 gauss_position(std::size_t g) const;
  // Failed flags of Gauss point g (fibre, matrix, interface): 1 where the failure index reached 1.
  std::array<double, 3> damage(std::size_t g) const { return failed_modes(gp_[g]); }
  // The failure indices of Gauss point g (fibre, matrix, interface): running maximum, capped at 1
  // (the paper's damage matrix D). With at_failure growth, indices of stress states screened out
  // as far below every strength (each material-frame component under 0.2 x the smallest
  // strength, index below about 0.04-0.16) are not evaluated and leave the stored value as it was.
  std::array<double, 3> failure_index(std::size_t g) const { return gp_[g].index; }
  // Imposes failure indices on Gauss point g (1: failed; pre-failed material, tests); the stiffness is degraded
  // as for failure in the run, and erosion applies at the next force evaluation. `compressive`:
  // fibre / matrix failed in compression (mode_factors scheme).
  void set_damage(std::size_t g, const std::array<double, 3>& damage,
                  const std::array<char, 2>& compressive = {0, 0});
  // Fibre / matrix of Gauss point g failed in compression (sign of sigma11 / sigma22 at failure).
  std::array<char, 2> compressive(std::size_t g) const { return gp_[g].compressive; }
  // Degraded x-y stiffness for the given damage state (the undamaged Qbar when none): a mode with
  // damage 1 takes its factor, one with damage d in (0, 1) the proportional 1 - d (1 - factor).
  Eigen::Matrix3d degraded_stiffness(const std::array<double, 3>& damage,
                                     const std::array<char, 2>& compressive = {0, 0}) const;
  // Recomputes stresses and internal forces at the current positions (no time advance).
  void refresh() { compute_internal_forces(); }
  double kinetic_energy() const;
  double strain_energy() const;  // sum of V0 E.S/2 over the Gauss points (degraded stiffness)
  // Energy ledger (solvers/efg/README.md, "Energy audit"), accumulated over the steps:
  //  - tool_work: the tool's contact impulses J times the tool's velocity (what the tool spends);
  //  - contact_work: the same impulses times the velocity the node then moves with, J . v^{n+1/2}
  //    (what the nodes receive; tool_work - contact_work is the contact's friction and impact loss);
  //  - internal_work: the work of the internal forces over each step, dx . (f^n + f^{n+1}) / 2;
  //  - release_kinetic: kinetic energy of nodes released by erosion (set to zero; <= 0).
  // The central-difference scheme then closes contact_work + release_kinetic = kinetic +
  // internal_work up to O(dt^2), and internal_work = strain + damage_dissipation up to the time
  // integration and the changes of the shape functions (reference updates, the visibility cut).
  // Not booked: constant external forces and non-zero prescribed velocities (the cutting model has
  // neither: its held nodes do not move and do no work).
  struct EnergyLedger {
    double tool_work = 0.0, contact_work = 0.0, internal_work = 0.0, release_kinetic = 0.0;
  };
  const EnergyLedger& energy_ledger() const { return ledger_; }
  double damage_dissipation() const;
  const Orthotropic& material() const { return mat_; }
  // Checkpoints of long runs: the state between two steps (nodes, Gauss points, released nodes,
  // counters, opaque segments, last contact force). load_state expects an object built with the
  // same discretisation, material, options, tool and boundary conditions; the run then continues
  // bit for bit as if it had not been interrupted. The shape functions are rebuilt from the stored
  // opaque segments: a Gauss point's functions depend only on the segments that cross its support,
  // so one rebuild with all of them equals the incremental updates of add_opaque_segment.
  void save_state(BinaryWriter& w) const;
  void load_state(BinaryReader& r);

private:
  struct GP {
    Vec2 xr = Vec2::Zero();          // reference position
    double Vr = 0.0;                 // reference volume (area x thickness)
    Mat2 Fr = Mat2::Identity();      // total F at the reference
    Mat2 F = Mat2::Identity();       // current total F
    Eigen::Vector3d E = Eigen::Vector3d::Zero(), S = Eigen::Vector3d::Zero();
    ShapeData sd;                    // shape functions on the reference configuration
    std::array<double, 3> index = {0.0, 0.0, 0.0};   // failure indices (fibre, matrix, interface), running max capped at 1
    std::array<char, 2> compressive = {0, 0};         // fibre, matrix failed in compression
    Eigen::Matrix3d Qd = Eigen::Matrix3d::Zero();    // degraded x-y stiffness (when `degraded`)
    bool degraded = false;                           // Qd, not the undamaged Qbar, applies
    bool cutting_zone = true;                        // the interface strengths apply here
    bool eroded = false;                             // separated: carries no stress
  };
  // 1 for each mode whose failure index reached 1, else 0
  static std::array<double, 3> failed_modes(const GP& q) {
    return {q.index[0] >= 1.0 ? 1.0 : 0.0, q.index[1] >= 1.0 ? 1.0 : 0.0, q.index[2] >= 1.0 ? 1.0 : 0.0};
  }
  void update_release();
  bool erode_collapsed();           // collapse erosion; true when something was eroded
  double min_active_distance() const;  // smallest distance between active nodes (Eq 56)
  bool update_damage(GP& q) const;  // true when the stiffness of q changed
  void apply_contact(double dt, std::vector<Vec2>& vhalf);
  void compute_internal_forces();
  void first_piola(GP& q, Mat2& P, bool small, bool failure);  // stress update of one Gauss point
  void update_reference();
  // Shape functions of the given Gauss points on the reference configuration, with the visibility
  // decided in the initial (material) configuration, where the opaque segments are given.
  std::vector<ShapeData> gauss_shapes(const std::vector<std::size_t>& ids) const;
  std::vector<Vec2> gauss_pts_;        // reference positions of every Gauss point (update_reference)
  std::vector<ShapeData> spare_sd_;    // storage swapped with the Gauss points' functions on a rebuild
  void build_node_gp();
  void apply_bcs(double t);

  Orthotropic mat_;
  Eigen::Matrix3d Qbar_;
  Eigen::Matrix3d T_;  // stress rotation x-y -> 1-2 (Eq 52) for theta
  Eigen::Matrix3d Ti_;  // its inverse, for the degraded stiffnesses (a sincos and an inverse each otherwise)
  RigidTool tool_;
  bool has_tool_ = false;
  Vec2 tool_force_ = Vec2::Zero();
  int ncontact_ = 0, nstick_ = 0;
  ExplicitOptions opt_;
  Larc02CompressionBound larc_bound_;  // of opt_.failure.lamina
  std::vector<double> support_;
  double spacing_ = 0.0;
  std::vector<Vec2> X0_, xr_, x_, v_, a_, fint_, fext_;
  std::vector<Vec2> Xg0_;  // initial Gauss-point positions (material frame of the visibility)
  std::vector<double> mass_;
  std::vector<GP> gp_;
  std::vector<VelocityBC> bcs_;
  std::vector<Segment> opaque_;
  std::vector<char> active_;
  std::size_t nreleased_ = 0, neroded_ = 0, ncollapse_ = 0;
  double dmin0_ = 0.0;                        // initial smallest nodal distance
  // node -> supporting Gauss points (CSR, ascending) and the index of each one's contribution in
  // fe_; fe_ holds the (Gauss point, node) force contributions, Gauss point g's from gp_off_[g].
  // Rebuilt on demand after the shape functions change.
  std::vector<int> node_gp_start_, node_gp_, node_entry_, gp_off_;
  std::vector<Vec2> fe_;
  bool node_gp_dirty_ = true;
  std::vector<std::pair<int, int>> pairs_;    // scratch
  bool erosion_changed_ = false;
  mutable std::vector<Vec2> xactive_;  // scratch for the time step (capacity kept)
  double t_ = 0.0;
  long nstep_ = 0;
  EnergyLedger ledger_;
  std::vector<double> dgp_;  // per Gauss point: strain energy released by degradation and erosion
  std::vector<std::pair<int, Vec2>> impulses_;  // contact impulses of the present step (node, J)
};

}  // namespace cutbench::efg
