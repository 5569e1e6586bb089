#pragma once
// Transient heat conduction on a fixed particle configuration (Afrasiabi et al. 2021, Eqs. 4, 7,
// 8, 12, 13):
//
//   rho c_p dT_i/dt = k lap(T)_i + Q_i,
//   lap: FMFS at interior particles, Brookshaw at detected free-surface particles and wherever
//        the FMFS system is singular (scheme fmfs), or Brookshaw everywhere (scheme brookshaw);
//   Dirichlet particles (clamped layers) hold a prescribed T(x, t);
//   free-surface particles that are not Dirichlet lose q_i = h_c (T_i - T_inf)
//        + eps sigma (T_i^4 - T_inf^4) [W/m^2] through a surface length l_i = sqrt(V_i) (per unit
//        depth), i.e. a volumetric sink Q_i = -q_i l_i / V_i.
//
// Time integration: explicit Euler, dt = cfl * h^2 rho c_p / k (cfl = 0.1 by default; the
// Brookshaw Gershgorin bound is about 0.175). Energy bookkeeping: thermal_energy() over the
// non-Dirichlet particles and the accumulated boundary_heat_loss() (J per metre of depth).
#include <functional>
#include <vector>

#include "cutbench/sph/operators.hpp"
#include "cutbench/sph/surface.hpp"

namespace cutbench::sph {

constexpr double kStefanBoltzmann = 5.670374419e-8;  // W / (m^2 K^4)

struct HeatMaterial {
  double conductivity = 1.0;   // W / (m K)
  double density = 1.0;        // kg / m^3
  double specific_heat = 1.0;  // J / (kg K)
  double diffusivity() const { return conductivity / (density * specific_heat); }
};

struct HeatBoundary {
  double h_conv = 0.0;      // W / (m^2 K)
  double emissivity = 0.0;  // radiation to the ambient
  double T_ambient = 300.0;
};

enum class HeatScheme { brookshaw, fmfs };

struct HeatOptions {
  HeatScheme scheme = HeatScheme::fmfs;
  SurfaceOptions surface;
  double cfl = 0.1;
  // false (paper): Brookshaw only on detected surface particles. true: also on every particle with
  // a surface particle among its neighbours (a band of width 2h), FMFS only deeper inside.
  bool brookshaw_band = false;
};

// dT/dt from conduction (FMFS where use_fmfs[i] and the particle is regular, else Brookshaw; pass
// fmfs = nullptr for Brookshaw everywhere) and surface losses at particles with loss[i]; zero at
// fixed (Dirichlet) particles. Returns sum_i q_i l_i (W per metre of depth).
double heat_rates(const ParticleView& p, const std::vector<double>& T, const FmfsLaplacian* fmfs,
                  const std::vector<char>& use_fmfs, const std::vector<char>& fixed,
                  const std::vector<char>& loss, const HeatMaterial& mat, const HeatBoundary& bc,
                  std::vector<double>& rate, std::vector<char>* fmfs_used = nullptr,
                  double* fixed_inflow = nullptr);
// fixed_inflow (if given) receives sum over fixed particles of k lap(T)_i V_i (W/m): the heat that
// conduction would carry into the Dirichlet particles (their temperature is held).

// Which particles use FMFS and which lose heat (surface and not fixed). FMFS needs an interior
// particle in the paper's sense, lambda_i > lambda_interior (Afrasiabi et al. 2021, Sec. 4.2: Fatehi's
// Laplacian "is computed for interior particles (lambda > 0.75)", and "by doing so, the singularity
// of correction matrices in FMFS can be avoided"), not on the detected surface; with `band`, also not next to a
// surface particle. Particles with lambda <= lambda_interior that the scan test keeps off the
// surface (small voids, sheared gaps) conduct with Brookshaw and lose no heat.
void heat_masks(const NeighbourList& nl, const SurfaceDetection& surface, const std::vector<char>& fixed,
                bool band, double lambda_interior, std::vector<char>& use_fmfs, std::vector<char>& loss);

double surface_flux(const HeatBoundary& bc, double T);

// Conduction between two bodies a and b (e.g. workpiece and tool) by pairwise Brookshaw terms with
// the harmonic-mean conductivity k_ab = 2 k_a k_b / (k_a + k_b) (Cleary & Monaghan 1999):
//   rho_a c_a dT_i/dt += sum_{j in b} 2 k_ab (T_i - T_j) / r_ij  dW/dr(r_ij) V_j
// and the mirror term for b. Adds dT/dt into rate_a and rate_b (pairwise: energy-conserving).
// `cross` holds the neighbours in b of every particle of a.
void cross_body_conduction(const std::vector<Vec2>& xa, const std::vector<double>& Va,
                           const std::vector<double>& Ta, const HeatMaterial& ma, const std::vector<Vec2>& xb,
                           const std::vector<double>& Vb, const std::vector<double>& Tb, const HeatMaterial& mb,
                           const NeighbourList& cross, const CubicSpline2D& kernel, std::vector<double>& rate_a,
                           std::vector<double>& rate_b);

class HeatConduction {
public:
  using Field = std::function<double(const Vec2&, double)>;

  HeatConduction(std::vector<Vec2> x, std::vector<double> volume, double h, HeatMaterial material,
                 HeatBoundary boundary, HeatOptions options = {});

  // Particles with fixed[i] != 0 hold value(x_i, t) at every time.
  void set_dirichlet(std::vector<char> fixed, Field value);
  void set_temperature(std::vector<double> T);
  void set_temperature(const Field& initial);

  // Neighbour list, FMFS geometry and surface detection for the (fixed) configuration.
  void setup();

  double stable_time_step() const;
  void step(double dt);
  void advance_to(double t_end);  // stable steps, the last one shortened

  double time() const { return time_; }
  std::size_t steps() const { return steps_; }
  const std::vector<Vec2>& positions() const { return x_; }
  const std::vector<double>& temperature() const { return T_; }
  const std::vector<char>& dirichlet() const { return fixed_; }
  const SurfaceDetection& surface() const { return surface_; }
  // 1 where the last rate evaluation used FMFS.
  const std::vector<char>& fmfs_used() const { return fmfs_used_; }
  // Particles losing heat by convection / radiation (surface and not Dirichlet).
  const std::vector<char>& heat_loss_particles() const { return loss_; }

  double thermal_energy() const;       // sum rho c_p V_i T_i over non-Dirichlet particles, J/m
  double boundary_heat_loss() const { return lost_; }  // integral of sum q_i l_i dt, J/m
  double surface_flux(double T) const;  // q(T), W/m^2

  // dT/dt at every particle (zero at Dirichlet ones); also returns sum q_i l_i in W/m.
  std::vector<double> rate(double& heat_loss_rate);

private:
  std::vector<Vec2> x_;
  std::vector<double> V_;
  CubicSpline2D kernel_;
  HeatMaterial mat_;
  HeatBoundary bc_;
  HeatOptions opt_;
  NeighbourList nl_;
  FmfsLaplacian fmfs_;
  SurfaceDetection surface_;
  std::vector<char> fixed_, loss_, use_fmfs_, fmfs_used_;
  Field dirichlet_value_;
  std::vector<double> T_;
  double time_ = 0.0, lost_ = 0.0;
  std::size_t steps_ = 0;
  bool ready_ = false;

  void apply_dirichlet();
};

}  // namespace cutbench::sph
