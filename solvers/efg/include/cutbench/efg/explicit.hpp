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
#include <functional>
#include <vector>

#include "cutbench/efg/discretisation.hpp"
#include "cutbench/efg/material.hpp"

namespace cutbench::efg {

using Mat2 = Eigen::Matrix2d;

enum class Kinematics { small_strain, total_lagrangian, updated_lagrangian };

struct ExplicitOptions {
  Kinematics kinematics = Kinematics::total_lagrangian;
  int update_interval = 1;  // updated Lagrangian: steps between reference updates
  double cfl = 0.5;         // dt = cfl * min(dist)/c_max (Eq 56 requires cfl < 1)
  WeightParams weight;
  double thickness = 1.0;   // out-of-plane thickness (m); forces are per this thickness
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

  double critical_time_step() const;  // Eqs 55-56 on the current configuration
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
  double kinetic_energy() const;
  double strain_energy() const;
  const Orthotropic& material() const { return mat_; }

private:
  struct GP {
    Vec2 xr = Vec2::Zero();          // reference position
    double Vr = 0.0;                 // reference volume (area x thickness)
    Mat2 Fr = Mat2::Identity();      // total F at the reference
    Mat2 F = Mat2::Identity();       // current total F
    Eigen::Vector3d E = Eigen::Vector3d::Zero(), S = Eigen::Vector3d::Zero();
    ShapeData sd;                    // shape functions on the reference configuration
  };
  void compute_internal_forces();
  void update_reference();
  void apply_bcs(double t);

  Orthotropic mat_;
  Eigen::Matrix3d Qbar_;
  ExplicitOptions opt_;
  std::vector<double> support_;
  double spacing_ = 0.0;
  std::vector<Vec2> X0_, xr_, x_, v_, a_, fint_, fext_;
  std::vector<double> mass_;
  std::vector<GP> gp_;
  std::vector<VelocityBC> bcs_;
  double t_ = 0.0;
  long nstep_ = 0;
};

}  // namespace cutbench::efg
