#pragma once
// MpmProblem: a 2D plane-strain material point method problem on a regular grid with uGIMP shape
// functions (deal.II-like: configure -> add particles -> setup() -> step()... -> observe).
//
// Physics: explicit USL (or MUSL) update with a CFL time step; neo-Hookean J2 material (material.hpp);
// PIC-damped velocity update and 0th/1st/2nd-order position updates (Nairn 2015, Eqs. 8-10);
// one rigid body made of particles moving at a prescribed (ramped) velocity, in Coulomb-friction
// contact with the deformable material through prescribed normals; one straight explicit crack
// (CRAMP-like: two velocity fields at nodes the crack separates) with cohesive segments; fixed
// nodes; grid-kinetic-energy feedback damping.
//
// Threading: OpenMP over particles (per-thread node buffers reduced in thread order) and over
// nodes. For a fixed thread count, results are bitwise reproducible. No allocation in step().
#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cutbench/common/binary_io.hpp"
#include "cutbench/mpm/cohesive.hpp"
#include "cutbench/mpm/material.hpp"
#include "cutbench/mpm/shape.hpp"

namespace cutbench::mpm {

struct GridSpec {
  double x0 = 0.0, y0 = 0.0;  // position of node (0, 0), m
  double dx = 1e-3;           // square cell size, m
  int nx = 10, ny = 10;       // number of cells
};

struct Numerics {
  double pic_fraction = 1.0;  // PIC damping fraction: 1 = pure PIC (default), 0 = pure FLIP
  int position_order = 2;     // 0: x += dt v_g(n+1); 1: adds the PIC term; 2: full Eq. 10
  // When the particle strains (and so the stresses) are updated from the grid velocities:
  //   usl:   after the grid update, from the updated grid velocities (update stress last);
  //   musl:  after the particle update, from the updated particle momenta re-extrapolated to the
  //          grid with the step's shape functions, contact and boundary conditions re-applied;
  //   usavg: NairnMPM's default scheme (USAVG): half the step's strain increment first, from the
  //          momenta extrapolated to the grid (tool and crack contact and boundary conditions
  //          applied to them) before the grid forces are found, and half last, from the updated
  //          particle momenta re-extrapolated at the particles' new positions (contact and
  //          boundary conditions applied). The two halves are NairnMPM's UpdateStrainsFirst and
  //          UpdateStrainsLastContact tasks with dt/2 each.
  // usl and musl apply no contact to the extrapolated momenta before the grid update. With MUSL
  // and USAVG the crack surfaces move with the strain-last field (see move_crack_surfaces).
  // Default USL; NairnMPM's default is USAVG (benchmarks/nairn2015/FINDINGS.md F14).
  enum class StrainUpdate { usl = 0, musl = 1, usavg = 2 };
  StrainUpdate strain_update = StrainUpdate::usl;
  // Diagnostic (musl): false skips the contact re-applied to the re-extrapolated momenta
  // (boundary conditions are still applied), to separate MUSL's two ingredients.
  bool musl_recontact = true;
  double cfl = 0.5;           // dt = cfl * dx / (c_p + tool speed); 0.5: NairnMPM's default FractCellTime
  int sort_interval = 50;     // steps between particle sorts by cell (0 = never)
  double min_mass_fraction = 1e-8;  // nodes lighter than this times a particle mass are empty
  int threads = 0;                  // OpenMP threads (0: omp_get_max_threads())
  int min_particles_per_thread = 3000;  // fewer threads for small problems (barriers dominate)
  // A particle that leaves the grid is returned into its last cell and counted once (NairnMPM's
  // ResetElementsTask::ReturnToElement); the run stops as a fault when more than this fraction of
  // the deformable particles have left (NairnMPM's LeaveLimit, default 1 % of the points). 0: the
  // first particle that leaves stops the run.
  double leave_limit = 0.01;
};

struct ContactSpec {
  double mu = 0.0;  // Coulomb friction coefficient between material and rigid body
  // Prescribed unit normals from the cut material into the rigid body, chosen by which side of
  // the crack line the material came from (without a crack all material is "above").
  Eigen::Vector2d n_above{0.0, -1.0};
  Eigen::Vector2d n_below{0.0, 1.0};
  // Contact detection besides the approach test (v - V).n > 0:
  //   0: none (velocity test only);
  //   1: the nodal centres of mass of the two materials are closer than gap_factor * dx along n;
  //   2: the particle domains touch: max over the material's particles at the node of the
  //      domain's far edge along n  >=  min over the rigid particles of their near edge
  //      - gap_factor * dx (gap_factor is then a tolerance; 0 = exact touching).
  int detection = 1;
  // Order of the two contacts at a node: false applies the crack-face contact first and the tool's
  // impulses on the result; true the tool's first, NairnMPM's order (UpdateMomentaTask::
  // ContactAndMomentaBCs: material contact, then crack contact), which here multiplies the rubbing
  // force at coarse resolution (FINDINGS F04, nairn2015).
  bool tool_contact_first = false;
  double gap_factor = 1.0;
};

struct CrackSpec {
  bool enabled = false;
  double y = 0.0;           // straight horizontal crack line (fixed in space), m
  double x_end = 0.0;       // the explicit crack runs from -infinity to x_end, m
  double x_begin = 0.0;     // first crack-surface segment starts here, m
  double x_free_end = 0.0;  // segments with centre below this are traction-free, m
  double seg_len = 0.0;     // segment length (0: dx/2), m
  TractionLaw mode1, mode2;
  bool cohesive = true;     // false: a traction-free crack everywhere
};

struct RigidMotion {
  Eigen::Vector2d velocity{0.0, 0.0};  // full speed, m/s
  double t_ramp = 0.0;                 // linear ramp 0 -> velocity over [0, t_ramp], s
  Eigen::Vector2d at(double t) const {
    return t_ramp > 0.0 && t < t_ramp ? Eigen::Vector2d(velocity * (t / t_ramp)) : velocity;
  }
};

struct FeedbackDamping {
  // d(alpha)/dt = gain * KE_grid / (M v_ref^2 / 2), alpha >= 0, applied as -alpha*p on the grid
  // until t_off, then alpha = 0. gain in 1/s^2; gain = 0 disables it.
  double gain = 0.0;
  double t_off = 0.0;
  double v_ref = 1.0;
};

struct MpmConfig {
  GridSpec grid;
  HyperelasticJ2 material;
  Numerics numerics;
  ContactSpec contact;
  CrackSpec crack;
  RigidMotion tool;
  FeedbackDamping damping;
  Eigen::Vector2d gravity{0.0, 0.0};
  // Fixed-displacement nodes: bit 0 fixes x, bit 1 fixes y (empty function: none fixed).
  std::function<int(double x, double y)> fixed_mask;
  double dt = 0.0;  // 0: from the CFL condition
};

// Forces of the rigid body on the material, averaged over the last step (N per m of width).
struct ContactForces {
  Eigen::Vector2d total{0.0, 0.0};
  Eigen::Vector2d below{0.0, 0.0};  // part acting on material below the crack line
  double normal_below = 0.0;        // compressive normal force on that part (along -n_below)
};

// The energy audit of a run, J per m of width, accumulated over the steps (save_state carries
// them). Nodal terms are over the nodes the grid update keeps (m > mmin), with v_mid = (v_old +
// v_new)/2 the mean of a node's velocity before and after the step's momentum update:
//   tool_work          sum of dp . V_tool over every contact impulse of the tool on the material;
//   pic_damping        kinetic energy the PIC part of the particle update removes: per particle
//                      m/2 (|v_FLIP|^2 - |v_new|^2), v_FLIP = v_p + dv_p, v_new = v_FLIP - beta (v_p - v_g);
//   feedback_loss      work of the feedback damping force alpha p at the extrapolated velocity;
//   increment_loss     kinetic energy lost mapping the grid's velocity increments to the particles:
//                      sum_I m_I/2 |dv_I|^2 - sum_p m_p/2 |dv_p|^2, dv_p = sum_I S_Ip dv_I (>= 0);
//   tool_contact_loss  sum of dp . (V_tool - v_mid) over the tool's contact impulses: the part of
//                      tool_work the nodal contact does not pass to the material (inelastic nodal
//                      impacts when > 0; the contact gives more than dp . V_tool when < 0);
//   crack_contact_loss -sum of dp . v_mid over the crack-face contact impulses (momentum-neutral);
//   internal_work      -dt sum_I f_int,I . v_mid,I: what the stresses' nodal forces take from the grid;
//   cohesive_work      -dt sum_I f_coh,I . v_mid,I: what the cohesive forces take from the grid.
// Why these: the momentum update changes the grid kinetic energy by exactly sum_I dp_I . v_mid,I
// over every impulse (forces, damping, contacts), and the particle kinetic energy after the update
// is exactly KE_p(n+1) = KE_p(n) + [KE_g(n+1) - KE_g(n)] - increment_loss - pic_damping (the cross
// terms sum_p m v_p . dv_p and sum_I m_I v_I . dv_I are equal, and the loss of extrapolating v_p to
// the grid cancels against the FLIP increment). Two further terms of EnergyBalance compare what the
// grid's forces deliver with what the models book: stress_lag (internal_work less the stress power
// the stress updates book; the explicit scheme's lag between the forces' work and the strain
// increment it uses) and cohesive_lag (cohesive_work less the cohesive energy the traction law
// books). What is left, the residual, is the stress updates' booked stress power less the elastic
// and plastic energy they store (second order in the step), plus, for MUSL and USAVG, what their
// extra passes over the grid do that no term measures.
struct EnergyAudit {
  double tool_work = 0.0, pic_damping = 0.0, feedback_loss = 0.0, increment_loss = 0.0;
  double tool_contact_loss = 0.0, crack_contact_loss = 0.0, internal_work = 0.0, cohesive_work = 0.0;
};

struct EnergyBalance {
  EnergyAudit audit;
  double kinetic = 0.0;   // deformable particles
  double strain = 0.0;    // stored elastic energy
  double plastic = 0.0;   // plastic work (dissipated, hardening included)
  double cohesive = 0.0;  // work of the cohesive tractions (failed segments: J_I + J_II; intact: to the present opening)
  double stress_power = 0.0;  // booked by the stress updates: sum over updates of V0 (tau_n + tau_n+1)/2 : l (l = L h)
  double stress_lag = 0.0;    // audit.internal_work - stress_power
  double cohesive_lag = 0.0;  // audit.cohesive_work - cohesive
  // the scheme's numerical terms, signed: PIC and feedback damping, increment loss, tool and crack
  // contact losses, stress and cohesive lags
  double numerical = 0.0;
  // initial energy + tool_work minus every other term (kinetic, strain, plastic, cohesive, the
  // audit's losses, stress_lag, cohesive_lag): the stress updates' booked stress power less the
  // elastic and plastic energies they store, plus what the scheme's extra passes (MUSL's re-mapped
  // momenta, USAVG's extrapolations) do that no term measures
  double residual = 0.0;
};

struct CrackSurface {
  std::vector<double> xc;           // segment centre (reference), m
  std::vector<Eigen::Vector2d> top, bot;  // tracked surface points
  std::vector<CohesiveState> state;
  std::vector<std::uint8_t> free;   // traction-free from the start
};

class MpmProblem {
public:
  explicit MpmProblem(MpmConfig cfg);

  // Particles are added before setup(). Rigid particles move with the prescribed tool velocity.
  void add_particle(double x, double y, double volume, bool rigid, double vx = 0.0, double vy = 0.0);
  void setup();
  void step();

  // --- observers (const; never change state) ---
  const MpmConfig& config() const { return cfg_; }
  double time() const { return time_; }
  double dt() const { return dt_; }
  long steps() const { return steps_; }
  std::size_t size() const { return x_.size(); }
  std::size_t num_deformable() const { return n_deformable_; }
  long frozen() const { return frozen_count_; }  // particles that left the grid (each counted once)
  int threads() const { return nthreads_; }
  const ContactForces& contact_forces() const { return forces_; }
  double kinetic_energy() const;   // deformable particles
  double strain_energy() const;    // deformable particles, sum of V0 W
  Eigen::Vector2d momentum() const;       // deformable particles
  Eigen::Vector2d grid_momentum() const;  // deformable fields on the grid after the last step (USAVG: its strain-last extrapolation)
  Eigen::Vector2d rigid_displacement() const { return rigid_disp_; }
  double feedback_alpha() const { return alpha_fb_; }
  const CrackSurface& crack() const { return crack_; }
  // centre of the first intact cohesive segment at or beyond x_from (x_end if none)
  double crack_tip_x(double x_from = -std::numeric_limits<double>::infinity()) const;
  std::size_t intact_segments_behind(double x) const;  // intact cohesive segments with centre below x
  double released_energy() const;   // J/m, sum over failed segments of (J_I + J_II) * length
  double mode1_fraction() const;    // sum J_I len / sum (J_I + J_II) len over failed segments
  double cohesive_energy() const;   // J/m, work done on the cohesive segments so far (EnergyBalance)
  double plastic_work() const;      // J/m, deformable particles
  double stress_power() const;      // J/m, booked by the stress updates (EnergyBalance)
  EnergyBalance energy_balance() const;
  // Empty while the state is sound; else what went wrong, naming the particle: a non-finite
  // position, velocity or stress, or a particle that left the grid (a blow-up).
  std::string fault() const;

  // The whole state that carries from one step to the next (particles in their current order,
  // crack surfaces and cohesive states, tool displacement, feedback damping, time, step count),
  // for checkpoints: a problem built and set up from the same configuration and particles, then
  // given load_state(), continues exactly as the saved one would have (bit for bit).
  void save_state(BinaryWriter& w) const;
  void load_state(BinaryReader& r);

  // Particle access (index order changes when particles are sorted; id() is the insertion index).
  std::size_t id(std::size_t p) const { return id_[p]; }
  bool rigid(std::size_t p) const { return rigid_[p] != 0; }
  Eigen::Vector2d position(std::size_t p) const { return {x_[p], y_[p]}; }
  Eigen::Vector2d reference_position(std::size_t p) const { return {X0_[p], Y0_[p]}; }
  bool above_crack(std::size_t p) const { return side_[p] != 0; }  // side label (no crack: true)
  Eigen::Vector2d velocity(std::size_t p) const { return {vx_[p], vy_[p]}; }
  double mass(std::size_t p) const { return mass_[p]; }
  double volume0(std::size_t p) const { return vol0_[p]; }
  Eigen::Matrix2d deformation_gradient(std::size_t p) const;
  Eigen::Matrix3d cauchy_stress(std::size_t p) const;
  double plastic_strain(std::size_t p) const { return alpha_[p]; }
  double jacobian(std::size_t p) const { return J_[p]; }

  // A point whose 3 x 3 stencil of nodes lies inside the grid (where a particle may be).
  bool valid_position(double x, double y) const;
  // Test hook (fault injection): set a particle's velocity (by current index) between steps.
  void set_velocity(std::size_t p, double vx, double vy) {
    vx_[p] = vx;
    vy_[p] = vy;
    extrapolated_ = false;
  }


private:
  struct NodeData {
    double m, px, py, fx, fy, mx, my;
    double e0, e1;  // domain extents along the contact normals (detection 2), see ContactSpec
  };
  int field_of(double xp, double yp, int side_p, double xi, double yi) const;
  // false: a particle with a non-finite position or none to return it to (frozen, a fault); a
  // particle off the grid is returned into it and, the first time, added to newly_left
  bool compute_shape(std::size_t p, long& newly_left);
  bool return_to_grid(std::size_t p);
  // Mass, momentum and the rigid body's data (and, with_forces, the grid forces) from the particles.
  void particles_to_grid(bool with_forces);
  // USAVG: contact (the tool at its velocity at time t) and boundary conditions on the
  // extrapolated momenta (in place), the strain velocities vstrain_ and each particle's velocity
  // gradient (L*_); `count` adds the contact to the energy audit (false where the same
  // extrapolation is being redone); `fresh_openings` recomputes the crack openings crack contact
  // uses (false in a redo: the openings the extrapolation saw, before the crack surfaces moved).
  void constrain_extrapolated(bool count, double t, bool fresh_openings);
  // USAVG: the strain half-step from the cached velocity gradients and, first = true, the grid
  // forces from the stresses after it.
  void usavg_half(bool first);
  Eigen::Matrix2d stored_L(std::size_t p) const {  // USAVG: the velocity gradient kept by the extrapolation
    Eigen::Matrix2d L;
    L << Lxx_[p], Lxy_[p], Lyx_[p], Lyy_[p];
    return L;
  }
  void update_crack_openings();  // per node column, for crack contact
  void cohesive_forces();
  void grid_update();
  void grid_to_particles();
  void remap_momenta();  // MUSL: particle momenta -> grid -> contact/BCs -> vstrain_
  // Sums the per-thread node buffers tbuf_ over the first nfield node slots in fixed thread order
  // (deterministic for a given thread count): add(i, acc, other) accumulates, store(i, acc) writes node
  // i. An orphaned worksharing loop: called by every thread of an enclosing parallel region.
  template <class Add, class Store>
  void reduce_node_buffers(std::size_t nfield, Add&& add, Store&& store);
  // Node n's strain velocities vstrain_ from its momenta with tool and crack contact (when
  // `contact`) and the fixed components applied to a copy: the constrained momenta and the tool's
  // impulse out.
  void constrained_velocities(std::size_t n, const Eigen::Vector2d& V, bool contact, Eigen::Vector2d pm[2],
                              Eigen::Vector2d& imp, Eigen::Vector2d& impb);
  void update_strain(std::size_t p, const Eigen::Matrix2d& L, double h);  // over a time h
  void resolve_contacts(std::size_t n, Eigen::Vector2d p[2], const bool has[2], const Eigen::Vector2d& V,
                        Eigen::Vector2d& imp, Eigen::Vector2d& impb, Eigen::Vector2d dp_crack[2]) const;
  // Moves the crack surfaces with the field that strains the material: the updated grid velocities
  // (USL), the re-extrapolated, constrained ones (MUSL, USAVG: vstrain_, after the strain-last
  // pass, as NairnMPM moves its cracks after that pass). A surface moved with another field than
  // the material's strain sees no opening where the material opens (FINDINGS F14).
  void move_crack_surfaces();
  void sort_particles();
  Eigen::Vector2d field_velocity(const Eigen::Vector2d& pt, int side, const std::vector<Eigen::Vector2d>& vel) const;
  template <class F>
  void for_point_nodes(const Eigen::Vector2d& pt, int side, F&& fn) const;

  MpmConfig cfg_;
  int nnx_ = 0, nny_ = 0, nn_ = 0;  // nodes per row/column, total
  double lp_ = 0.0;
  UgimpGrid ugx_, ugy_;  // shape-function constants of the two axes
  double dt_ = 0.0, time_ = 0.0;
  long steps_ = 0;
  int nthreads_ = 1;
  double mmin_ = 0.0;
  std::size_t n_deformable_ = 0;
  long frozen_count_ = 0;
  bool setup_done_ = false;

  // particles (structure of arrays)
  std::vector<double> x_, y_, X0_, Y0_, vx_, vy_, mass_, vol0_, J_, alpha_;
  std::vector<double> Fxx_, Fxy_, Fyx_, Fyy_;
  std::vector<double> bxx_, bxy_, byy_, bzz_;  // isochoric elastic left Cauchy-Green
  std::vector<double> txx_, txy_, tyy_, tzz_;  // Kirchhoff stress
  std::vector<double> wp_;                     // plastic work per particle, J/m
  std::vector<double> sp_;                     // stress power booked per particle, J/m
  std::vector<double> Lxx_, Lxy_, Lyx_, Lyy_;  // USAVG: the velocity gradient of the extrapolation
  std::vector<std::uint8_t> rigid_, side_, frozen_, left_;
  std::vector<std::size_t> id_;
  // shape cache: base nodes, 1D weights and derivatives, field of each of the 9 nodes
  std::vector<int> i0_, j0_;
  std::vector<double> wx_, wy_, dwx_, dwy_;  // 3 per particle
  std::vector<std::uint8_t> fid_;            // 9 per particle
  // sorting scratch
  std::vector<std::size_t> perm_, count_;
  std::vector<double> dscratch_;
  std::vector<std::uint8_t> bscratch_;
  std::vector<std::size_t> sscratch_;
  std::vector<int> iscratch_;

  // grid: 3 fields (0: node's own side, 1: across the crack, 2: rigid body), nn_ nodes each
  std::vector<NodeData> nodes_;
  std::vector<std::vector<NodeData>> tbuf_;
  std::vector<Eigen::Vector2d> vnew_, acc_, vstrain_;
  std::vector<int> fixed_;
  // per-thread sums of the grid update over the nodes: the tool's impulse (all, below the crack),
  // grid kinetic energy, and the audit's tool work, feedback damping work, grid side of the
  // increment loss, tool contact loss, crack contact loss, work of the grid forces (internal,
  // cohesive, gravity) at v_mid
  struct GridSums {
    Eigen::Vector2d imp = Eigen::Vector2d::Zero(), impb = Eigen::Vector2d::Zero();
    double ke = 0.0;
    std::array<double, 6> au{};
  };
  std::vector<GridSums> grid_sums_;
  std::vector<std::pair<std::size_t, Eigen::Vector2d>> coh_impulses_;  // this step's cohesive forces: (node field, force)
  std::vector<Eigen::Vector2d> thread_sum_;  // per-thread partial sums (deterministic order): PIC damping, particle side of the increment loss
  std::vector<double> cohesive_opening_;  // per node column: normal opening of nearest segment

  CrackSurface crack_;
  ContactForces forces_;
  Eigen::Vector2d rigid_disp_{0.0, 0.0};
  double alpha_fb_ = 0.0;
  double mass_deformable_ = 0.0;
  EnergyAudit audit_;
  double initial_energy_ = 0.0;  // kinetic + strain energy at setup (the balance starts from it)       // grid kinetic energy after the last grid update
  bool extrapolated_ = false;  // USAVG: nodes_, vstrain_ and L*_ hold the extrapolation of the current particles
};

}  // namespace cutbench::mpm
