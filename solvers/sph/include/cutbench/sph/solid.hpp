#pragma once
// Updated-Lagrangian solid SPH in 2D plane strain (Afrasiabi et al. 2021, Eqs. 1-3, 10, 11).
//
//   drho_i/dt = -rho_i sum_j (v_j - v_i) . gradW_ij V_j                                  (10)
//   dv_i/dt   = sum_j m_j (sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I + f_ij^4 (R_i + R_j)) gradW_ij
//   (grad v)_i = sum_j V_j (v_j - v_i) (x) gradW_ij        [optionally times L_i^{-1}]
//   dS/dt = 2G (D - tr(D)/3 I) + Omega S - S Omega (Jaumann), p = K (rho/rho0 - 1), sigma = -p I + S
//   J2 plasticity by radial return on S with Johnson-Cook flow stress (optional).
//
// Pi_ij: Monaghan artificial viscosity (alpha, beta, eta = 0.1 h). R_i: Monaghan/Gray artificial
// stress, R = -eps sigma'_+ / rho^2 in the principal frame, f_ij = W(r_ij)/W(dx). XSPH position
// smoothing: dx_i/dt = v_i + eps_x sum_j m_j/rhobar_ij (v_j - v_i) W_ij.
//
// Time integration, kick-drift-kick (second order): v^{n+1/2} = v^n + dt/2 a^n; rates of rho and S
// from v^{n+1/2} on x^n; x^{n+1} = x^n + dt (v^{n+1/2} + XSPH); a^{n+1}; v^{n+1} = v^{n+1/2} + dt/2 a^{n+1}.
// dt = cfl h / (c + max |v|), c = sqrt((K + 4G/3) / rho0).
#include <cmath>
#include <cstdint>
#include <vector>

#include "cutbench/common/binary_io.hpp"
#include "cutbench/sph/heat.hpp"
#include "cutbench/sph/johnson_cook.hpp"
#include "cutbench/sph/tool.hpp"
#include "cutbench/sph/tool_contact.hpp"
#include "cutbench/sph/tool_heat.hpp"
#include "cutbench/sph/workpiece_heat.hpp"
#include "cutbench/sph/neighbours.hpp"

namespace cutbench::sph {

struct SolidMaterial {
  double density = 4430.0;   // kg/m^3
  double young = 113.8e9;    // Pa
  double poisson = 0.35;
  bool plastic = false;
  JohnsonCook jc;

  double shear() const { return young / (2.0 * (1.0 + poisson)); }
  double bulk() const { return young / (3.0 * (1.0 - 2.0 * poisson)); }
  double p_wave_speed() const { return std::sqrt((bulk() + 4.0 / 3.0 * shear()) / density); }
  double bulk_speed() const { return std::sqrt(bulk() / density); }
};

struct SolidOptions {
  double alpha_visc = 1.0, beta_visc = 1.0;  // Monaghan artificial viscosity
  double artificial_stress = 0.3;            // eps of Gray et al. (0 = off)
  double xsph = 0.5;                         // XSPH eps (0 = off)
  double cfl = 0.3;
  bool correct_velocity_gradient = false;    // multiply grad v by L_i^{-1} (renormalisation)
  Vec2 body_force = Vec2::Zero();            // b / rho, m/s^2
  // Verlet skin in units of h: neighbours are listed up to 2h + skin and the list is rebuilt
  // when a particle has moved more than skin/2 since the last build (0 = rebuild every step).
  double neighbour_skin = 0.3;
};

class SolidSph {
public:
  // dx: initial particle spacing (volume dx^2, mass rho0 dx^2 unless set_masses), h = h_over_dx dx.
  SolidSph(std::vector<Vec2> x, double dx, SolidMaterial material, SolidOptions options = {},
           double h_over_dx = 1.5);

  std::vector<Vec2>& velocity() { return v_; }
  const std::vector<Vec2>& velocity() const { return v_; }
  const std::vector<Vec2>& positions() const { return x_; }
  const std::vector<double>& density() const { return rho_; }
  const std::vector<double>& mass() const { return m_; }
  const std::vector<double>& plastic_strain() const { return eps_p_; }
  std::vector<double>& temperature() { return T_; }
  const std::vector<double>& temperature() const { return T_; }
  const std::vector<Stress3>& deviator() const { return S_; }
  std::vector<Stress3>& deviator() { return S_; }  // e.g. to impose an initial stress
  std::vector<double> pressure() const;

  // Particles with prescribed (constant) velocity: their acceleration is discarded.
  void set_fixed(std::vector<char> fixed);
  // Switch on the heat equation; particles with fixed_temperature[i] keep their temperature.
  void enable_thermal(ThermalOptions options, std::vector<char> fixed_temperature);
  const SurfaceDetection& surface() const { return heat_.surface; }

  // Rigid tool translating at constant velocity; contact applied at the end of every step.
  void set_tool(std::shared_ptr<const ToolGeometry> tool, const Vec2& position, const Vec2& velocity,
                ContactOptions contact);
  const Vec2& tool_position() const { return contact_.position; }
  const Vec2& tool_force() const { return contact_.force; }  // on the tool, N per metre of depth, last step
  // Contacts of the last step (diagnostics: force split by tool face, friction use). Forces act on
  // the particle (N/m); `limit` is the Coulomb bound mu |f_n| in force (the velocity model's
  // impulses are divided by dt).
  using ContactRecord = sph::ContactRecord;
  const std::vector<ContactRecord>& contacts() const { return contact_.contacts(); }
  double friction_heat() const { return heat_.friction_heat; }  // J per metre of depth, accumulated
  // friction heat put into the tool (share beta, see ContactOptions::tool_heat_share), J/m
  double friction_heat_to_tool() const { return heat_.friction_heat_tool; }
  double tool_heat_share() const { return heat_.tool_share; }  // beta in use (0 without tool conduction)

  // Discretise the tool for heat conduction (requires set_tool and enable_thermal): particles of
  // spacing dx inside the tool within `depth` of its lowest edge point; those beyond depth - 3 dx
  // are held at the ambient temperature (heat sink). Tool and workpiece are separate bodies for
  // surface detection; they exchange heat through cross_body_conduction(); surface particles in
  // contact (a particle of the other body within 1.5 dx) lose no heat to the air.
  void set_tool_thermal(HeatMaterial tool_heat, double depth);
  const std::vector<Vec2>& tool_particles() const { return tool_body_.x; }  // tool frame
  const std::vector<double>& tool_temperature() const { return tool_body_.T; }

  // Checkpoints: the dynamic state (positions, velocities, accelerations, densities, stresses,
  // plastic strains and their last increments, temperatures of workpiece and tool, contact and
  // neighbour-list history, heat counters, tool position and force, time and step count).
  // load_state expects an object built with the same setup (particles, options, tool); the run
  // then continues bit for bit as if it had not been interrupted (same thread count).
  void save_state(BinaryWriter& w) const;
  void load_state(BinaryReader& r);
  double tool_heat_content() const;  // sum rho c V (T - T_ambient) over the tool, J/m
  // sum rho0 c V_i (T_i - T_ambient) over the free (not fixed-temperature) workpiece particles, J/m
  double workpiece_heat_content() const;
  // heat conducted into the fixed-temperature particles (workpiece and tool sinks), J/m
  double heat_sunk() const { return heat_.heat_sunk; }
  double plastic_heat() const { return heat_.plastic_heat; }  // J per metre of depth, accumulated
  // plastic heat put into each workpiece particle so far, J per metre of depth (empty before the
  // first thermal step); sums to plastic_heat()
  const std::vector<double>& plastic_heat_by_particle() const { return heat_.plastic_at; }
  double boundary_heat_loss() const { return heat_.heat_lost; }

  double stable_time_step() const;
  void step(double dt);
  double time() const { return time_; }
  std::size_t steps() const { return steps_; }
  std::size_t neighbour_builds() const { return builds_; }

  Vec2 momentum() const;
  double kinetic_energy() const;
  double strain_energy() const;  // elastic: sum V (p^2/(2K) + S:S/(4G))
  // Mechanical energy ledger, J per metre of depth, accumulated over the steps (first-law audit).
  // The pair powers are evaluated with the forces of the end of each step (positions x^{n+1},
  // velocities v^{n+1/2}) times dt; the constitutive ones in the stress update of the step.
  // Particles with a prescribed velocity are taken at rest (their share of a pair's power is zero).
  struct EnergyLedger {
    double tool_work = 0.0;          // work of the tool on the workpiece, -F_tool . v_tool dt
    double stress_work = 0.0;        // work of the stress pair forces (sigma_i/rho_i^2 + sigma_j/rho_j^2) on the particles
    double internal_work = 0.0;      // constitutive power sum V sigma:D of the stress update
    double plastic = 0.0;            // plastic dissipation sum V sigma_y d(eps_p)
    double viscous = 0.0;            // dissipated by the artificial viscosity (>= 0)
    double artificial_stress = 0.0;  // work of the artificial-stress pair forces on the particles
    double friction = 0.0;           // slip dissipation at the tool (friction heat / heat_fraction)
    // work of the contact forces along the XSPH part of the particles' drift, sum f_i . xsph_i dt:
    // the penalty gap follows the drifted positions while the forces work on v only, so this is
    // energy the contact springs gain (< 0: given to the particles) without work of the tool
    double xsph_contact = 0.0;
  };
  const EnergyLedger& energy() const { return energy_; }
  // energy stored in the penalty contact's normal and stick springs at the last step (0 otherwise)
  double contact_spring_energy() const;

private:
  std::vector<Vec2> x_, v_, a_;
  std::vector<double> m_, rho_, eps_p_, T_;
  std::vector<double> eps_pn_;  // eps_p^n per particle (radial_return's, kept for its next call; not checkpointed)
  std::vector<Stress3> S_;
  std::vector<char> fixed_;
  SolidMaterial mat_;
  SolidOptions opt_;
  CubicSpline2D kernel_;
  double dx_, w_dx_;
  NeighbourList nl_;
  std::vector<Vec2> x_listed_;  // positions at the last neighbour build
  // Half list: the pairs (i, j > i) of nl_ (rows of nl_ are sorted, so these are the row tails),
  // compressed. Both mechanical passes run over it once per pair with symmetric updates.
  std::vector<std::size_t> half_offset_;
  std::vector<std::uint32_t> half_index_;
  // The half pairs inside the kernel support at the current positions, compacted per row (row i
  // holds pair_count_[i] of them from half_offset_[i] on, in list order), one array per component
  // (SIMD loops): j, grad_i W_ij and W_ij / rhobar_ij (0 without XSPH). Filled by accelerations(),
  // reused by the rate pass of the next step (same positions and densities).
  std::vector<double> pair_gx_, pair_gy_, pair_wr_;
  std::vector<std::uint32_t> pair_j_, pair_count_;
  // per-particle data of the pair loops, packed for locality: position, velocity, density, mass,
  // volume, sigma/rho^2 and artificial stress R, in-plane (xx, xy, yy)
  struct ParticleData {
    double x, y, vx, vy, rho, m, vol, sxx, sxy, syy, axx, axy, ayy;
  };
  std::vector<ParticleData> pdata_;
  // per-step work buffers (kept to avoid allocation in the time loop); per-thread accumulators
  // for the symmetric pair passes (summed in thread order)
  struct RateAcc {
    double g00, g01, g10, g11, sx, sy;  // velocity gradient and XSPH sums
    RateAcc& operator+=(const RateAcc& o) {
      g00 += o.g00;
      g01 += o.g01;
      g10 += o.g10;
      g11 += o.g11;
      sx += o.sx;
      sy += o.sy;
      return *this;
    }
  };
  std::vector<Stress3> s_new_;
  std::vector<Vec2> acc_, xsph_;
  std::vector<RateAcc> racc_;
  std::vector<Mat2> lren_;
  std::vector<double> rho_new_, plastic_dT_;
  // per particle, for the energy ledger: powers of its half row's pairs (stress, viscosity,
  // artificial stress) from accelerations(); constitutive and plastic work of the step
  std::vector<double> pow_stress_, pow_visc_, pow_art_, work_int_, work_plastic_;
  EnergyLedger energy_;
  std::vector<double> last_dep_;  // plastic strain increment of each particle's last plastic step
  std::vector<std::vector<Vec2>> acc_part_;
  std::vector<std::vector<RateAcc>> racc_part_;
  std::vector<std::vector<Mat2>> lren_part_;
  std::size_t builds_ = 0;
  double time_ = 0.0;
  std::size_t steps_ = 0;
  bool have_accel_ = false;
  double last_dt_ = 0.0;
  // The components: heat in the workpiece (enable_thermal), the tool contact (set_tool), tool
  // conduction (set_tool_thermal).
  WorkpieceHeat heat_;
  ToolContact contact_;
  ToolHeatBody tool_body_;

  void deposit_friction_heat(std::size_t i, double heat);
  double shear_cap(std::size_t i) const;  // Zorev cap of |f_t| for particle i (N/m), infinity when off
  void accelerations();
  void update_neighbours();
  void rebuild_neighbours(const std::vector<Vec2>& at);
  double yield_floor(double T) const;  // a lower bound of the J-C flow stress at temperature T
};

}  // namespace cutbench::sph
