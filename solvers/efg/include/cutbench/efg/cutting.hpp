#pragma once
// PROTOTYPE orthogonal-cutting set-up of Kahwash et al. (2018) section 3.4 on the explicit EFG
// solver: rectangular UD workpiece, rigid tool (rake 0 deg, clearance and edge radius recorded
// as assumptions: 7 deg, sharp), per-Gauss-point failure, Eq 39-43 contact, F_c and F_t per
// unit width. Not validated against Tables 4-6: see solvers/efg/README.md.
#include <string>
#include <vector>

#include "cutbench/efg/explicit.hpp"

namespace cutbench::efg {

struct CuttingSetup {
  Orthotropic material;
  analytic::Lamina lamina;
  analytic::Criterion criterion = analytic::Criterion::larc02;
  double theta = 0.0;            // fibre angle, measured clockwise from the cutting direction (+x)
  double work_length = 1.5e-3;   // m
  double work_height = 0.75e-3;  // m
  double depth = 0.25e-3;        // depth of cut (Table 3)
  double spacing = 0.05e-3;      // nodal spacing
  double support_factor = 2.0;
  double rake = 0.0;             // rad (Table 3: 0)
  double clearance = 7.0 * 3.14159265358979323846 / 180.0;  // assumption (not in the paper)
  double speed = 3800e-3 / 60.0;  // m/s (Table 3)
  double time_scale = 1.0;       // tool speed multiplier (time scaling); 1 = paper speed
  double travel = 0.5e-3;        // tool travel after first contact
  double mu = 0.3;               // rake-face friction (paper: function of theta, [63])
  double residual = 0.01;
  double cfl = 0.5;
  Kinematics kinematics = Kinematics::total_lagrangian;
  int update_interval = 20;
  int record_every = 20;         // steps per force record (forces averaged over the window)
};

struct CuttingResult {
  std::vector<double> t, Fc, Ft, dt;    // per-width forces (N/m) averaged over each window
  double t_contact = -1.0;              // first contact
  double t_contact_expected = 0.0;      // initial gap / speed
  double Fc_mean = 0.0, Ft_mean = 0.0;  // over the second half of the travel
  double dt_initial = 0.0, dt_min = 0.0;
  double t_dt_drop = -1.0;              // first time dt < 0.5 dt_initial (Fig 10 idea), -1: none
  long steps = 0;
  int nodes = 0;
  std::size_t fibre_damaged = 0, matrix_damaged = 0, interface_damaged = 0, gauss = 0;
  std::vector<double> gx, gy, dfibre, dmatrix;  // final Gauss point positions and damage
};

CuttingResult run_cutting(const CuttingSetup& s, const std::function<void(double)>& progress = nullptr);

}  // namespace cutbench::efg
