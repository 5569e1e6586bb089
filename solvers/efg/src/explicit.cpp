#include "cutbench/efg/explicit.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "cutbench/common/errors.hpp"

namespace cutbench::efg {

namespace {
Mat2 voigt_to_tensor(const Eigen::Vector3d& s) {
  Mat2 m;
  m << s(0), s(2), s(2), s(1);
  return m;
}
}  // namespace

ExplicitEFG::ExplicitEFG(const Discretisation& d, const Orthotropic& mat, double theta,
                         const ExplicitOptions& opt)
    : mat_(mat), Qbar_(mat.Qbar(theta)), T_(stress_rotation(theta)), Ti_(stress_rotation(theta).inverse()), opt_(opt), larc_bound_(opt.failure.lamina), support_(d.support), spacing_(d.spacing),
      X0_(d.nodes), xr_(d.nodes), x_(d.nodes) {
  if (opt_.update_interval < 1) throw InputError("update_interval", "must be >= 1");
  const std::size_t n = X0_.size();
  v_.assign(n, Vec2::Zero());
  a_.assign(n, Vec2::Zero());
  fint_.assign(n, Vec2::Zero());
  fext_.assign(n, Vec2::Zero());
  mass_.assign(n, 0.0);
  active_.assign(n, 1);
  xactive_.reserve(n);
  std::vector<Vec2> pts;
  for (const auto& g : d.gauss) pts.push_back(g.x);
  auto sf = shape_functions(pts, X0_, support_, opt_.weight, true);
  Xg0_ = pts;
  gp_.resize(pts.size());
  for (std::size_t g = 0; g < pts.size(); ++g) {
    gp_[g].xr = pts[g];
    gp_[g].Vr = d.gauss[g].weight * opt_.thickness;
    gp_[g].cutting_zone = pts[g].y() > opt_.failure.zone_y_min;
    gp_[g].sd = std::move(sf[g]);
    // Lumped mass: row sums of the consistent mass of Eq 35, M_I = sum_G rho V_G phi_I(x_G).
    for (std::size_t a = 0; a < gp_[g].sd.nodes.size(); ++a) {
      mass_[gp_[g].sd.nodes[a]] += mat_.rho * gp_[g].Vr * gp_[g].sd.phi[a];
    }
  }
  for (std::size_t I = 0; I < n; ++I) {
    if (!(mass_[I] > 0.0)) {
      throw NumericalError("EFG: non-positive lumped mass at node " + std::to_string(I) +
                           " (node outside the integration domain or too small a support)");
    }
  }
  dgp_.assign(gp_.size(), 0.0);
  compute_internal_forces();
  for (std::size_t I = 0; I < n; ++I) a_[I] = (fext_[I] - fint_[I]) / mass_[I];
  dmin0_ = min_active_distance();
  if (opt_.collapse_ratio < 0.0 || opt_.collapse_ratio >= 1.0) {
    throw InputError("collapse_ratio", "must be in [0, 1) (0: off)");
  }
}

void ExplicitEFG::add_velocity_bc(int node, int dof, std::function<double(double)> v) {
  bcs_.push_back({node, dof, std::move(v)});
  v_[node](dof) = bcs_.back().v(t_);
}

void ExplicitEFG::set_displacement(const std::vector<Vec2>& u) {
  for (std::size_t I = 0; I < x_.size(); ++I) x_[I] = X0_[I] + u[I];
  compute_internal_forces();
  if (opt_.kinematics == Kinematics::updated_lagrangian) update_reference();
  for (std::size_t I = 0; I < x_.size(); ++I) a_[I] = (fext_[I] - fint_[I]) / mass_[I];
}

std::vector<Vec2> ExplicitEFG::displacements() const {
  std::vector<Vec2> u(x_.size());
  for (std::size_t I = 0; I < x_.size(); ++I) u[I] = x_[I] - X0_[I];
  return u;
}

void ExplicitEFG::compute_internal_forces() {
  const long ng = static_cast<long>(gp_.size());
  build_node_gp();
  const bool small = opt_.kinematics == Kinematics::small_strain;
  const bool failure = opt_.failure.enabled;
  // Static schedule: a thread's Gauss points and its share of the nodes in the gather below
  // overlap, so fe_ stays in that core's cache (schedule(dynamic, 512) measured 10-15 % slower
  // on the 45-degree bench in spite of the uneven cost per point).
#pragma omp parallel for schedule(static) if (ng > 20000)
  for (long g = 0; g < ng; ++g) {
    GP& q = gp_[g];
    Mat2 P;
    first_piola(q, P, small, failure);
    // Nodal contributions V (P grad phi_I), stored per (Gauss point, node) for the gather below.
    Vec2* fe = fe_.data() + gp_off_[g];
    for (std::size_t a = 0; a < q.sd.nodes.size(); ++a) {
      const Vec2 dphi(q.sd.dphidx[a], q.sd.dphidy[a]);
      fe[a] = q.Vr * (P * dphi);
    }
  }
  if (erosion_changed_) update_release();
  // Assembly as a gather over nodes (parallel, no write conflicts): each node sums its Gauss
  // points' contributions in ascending Gauss-point order, the order of a serial scatter, so the
  // forces are bit for bit those of one thread.
  const long nn = static_cast<long>(x_.size());
#pragma omp parallel for schedule(static) if (ng > 20000)
  for (long I = 0; I < nn; ++I) {
    Vec2 f = Vec2::Zero();
    for (int k = node_gp_start_[I]; k < node_gp_start_[I + 1]; ++k) f += fe_[node_entry_[k]];
    fint_[I] = f;
  }
}

void ExplicitEFG::first_piola(GP& q, Mat2& P, bool small, bool failure) {
  if (q.eroded) {
    P.setZero();
    return;
  }
  // F_inc = I + sum_I (x_I - x_I^r) (grad_r phi_I)^T: the identity is exact, not the sum of
  // large coordinates times derivatives (which loses digits far from the origin).
  Mat2 Finc = Mat2::Identity();
  for (std::size_t a = 0; a < q.sd.nodes.size(); ++a) {
    const int I = q.sd.nodes[a];
    const Vec2 dphi(q.sd.dphidx[a], q.sd.dphidy[a]);
    Finc += (x_[I] - xr_[I]) * dphi.transpose();
  }
  q.F = Finc * q.Fr;
  double& damage_energy = dgp_[static_cast<std::size_t>(&q - gp_.data())];
  // a degradation releases the strain energy the lost stiffness held at this strain
  auto degrade = [&]() {
    const double w_before = q.E.dot(q.S);
    q.S = q.Qd * q.E;
    damage_energy += 0.5 * q.Vr / q.Fr.determinant() * (w_before - q.E.dot(q.S));
  };
  if (small) {
    const Mat2 H = q.F - Mat2::Identity();
    q.E = Eigen::Vector3d(H(0, 0), H(1, 1), H(0, 1) + H(1, 0));
    q.S = (q.degraded ? q.Qd : Qbar_) * q.E;
    if (failure && update_damage(q)) degrade();
    P = voigt_to_tensor(q.S);
  } else {
    const Mat2 C = q.F.transpose() * q.F;
    q.E = Eigen::Vector3d(0.5 * (C(0, 0) - 1.0), 0.5 * (C(1, 1) - 1.0), C(0, 1));  // engineering shear
    q.S = (q.degraded ? q.Qd : Qbar_) * q.E;
    if (failure && update_damage(q)) degrade();
    const Mat2 S = voigt_to_tensor(q.S);
    P = Finc * (q.Fr * S * q.Fr.transpose()) / q.Fr.determinant();
  }
  if (opt_.erosion != Erosion::none) {
    const bool f = q.index[fibre_damage] >= 1.0, m = q.index[matrix_damage] >= 1.0;
    if (opt_.erosion == Erosion::fibre_and_matrix ? (f && m) : (f || m)) {
      q.eroded = true;
      damage_energy += 0.5 * q.Vr / q.Fr.determinant() * q.E.dot(q.S);
      q.S.setZero();
      P.setZero();
#pragma omp atomic write
      erosion_changed_ = true;
    }
  }
}

void ExplicitEFG::build_node_gp() {
  if (!node_gp_dirty_) return;
  gp_off_.assign(gp_.size() + 1, 0);
  node_gp_start_.assign(x_.size() + 1, 0);
  for (std::size_t g = 0; g < gp_.size(); ++g) {
    gp_off_[g + 1] = gp_off_[g] + static_cast<int>(gp_[g].sd.nodes.size());
    for (int I : gp_[g].sd.nodes) ++node_gp_start_[I + 1];
  }
  for (std::size_t I = 0; I < x_.size(); ++I) node_gp_start_[I + 1] += node_gp_start_[I];
  fe_.resize(gp_off_.back());
  node_gp_.assign(node_gp_start_.back(), 0);
  node_entry_.assign(node_gp_start_.back(), 0);
  std::vector<int> fill(node_gp_start_.begin(), node_gp_start_.end() - 1);
  for (std::size_t g = 0; g < gp_.size(); ++g) {
    const auto& nodes = gp_[g].sd.nodes;
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      const int k = fill[nodes[a]]++;
      node_gp_[k] = static_cast<int>(g);
      node_entry_[k] = gp_off_[g] + static_cast<int>(a);
    }
  }
  node_gp_dirty_ = false;
}

Larc02CompressionBound::Larc02CompressionBound(const analytic::Lamina& m)
    : ST_(analytic::transverse_shear_strength(m.Y_C, m.alpha0)), SL_(m.S_L),
      eta_L_(analytic::larc_eta_L(m.S_L, m.Y_C, m.alpha0)) {
  const double eta_T = analytic::larc_eta_T(m.alpha0);
  tT_per_p_ = 0.5 * (std::sqrt(1.0 + eta_T * eta_T) - eta_T);
}

double Larc02CompressionBound::operator()(double s22, double t12) const {
  const double p = std::abs(s22), at = std::abs(t12);
  const double tT = tT_per_p_ * p;
  double tL;
  const double k = eta_L_ * p;  // tau_L = at c - k c^2
  if (k > 0.0) {
    tL = at < 2.0 * k ? at * at / (4.0 * k) : at - k;
  } else {
    tL = at - k;
  }
  return (1.0 + 1e-12) * ((tT / ST_) * (tT / ST_) + (tL / SL_) * (tL / SL_));
}

double larc02_matrix_compression_bound(double s22, double t12, const analytic::Lamina& m) {
  return Larc02CompressionBound(m)(s22, t12);
}

bool ExplicitEFG::update_damage(GP& q) const {
  const FailureOptions& fo = opt_.failure;
  const bool proportional = fo.growth == DamageGrowth::proportional;
  const bool zone = fo.S_sigma > 0.0 && fo.S_tau > 0.0 && q.cutting_zone;  // Table 1 strengths here
  const bool has_interface = fo.criterion == analytic::Criterion::max_stress || zone;
  if (q.index[0] >= 1.0 && q.index[1] >= 1.0 && (!has_interface || q.index[2] >= 1.0)) return false;
  const Eigen::Vector3d s12 = T_ * q.S;  // Eq 52
  // Screen (at_failure): with every material-frame component below 0.2 x the smallest strength,
  // no index of the three criteria can reach 1 (each is at most quadratic in stress/strength with
  // O(1) coefficients; LaRC02 kinking <= 0.4 (1 + eta_L) < 1); skips the costly LaRC02 search.
  // Proportional growth needs every index, so it is not screened.
  const double smin = std::min({fo.lamina.Y_T, fo.lamina.Y_C, fo.lamina.S_L, zone ? fo.S_sigma : HUGE_VAL,
                                zone ? fo.S_tau : HUGE_VAL});
  if (!proportional && s12.cwiseAbs().maxCoeff() < 0.2 * smin) return false;
  analytic::PlaneStress ps;
  ps.s11 = s12(0);
  ps.s22 = s12(1);
  ps.t12 = s12(2);
  analytic::FailureIndices fi;
  if (fo.criterion == analytic::Criterion::larc02) {
    // The matrix-compression search is needed only while the matrix index can still rise: the
    // matrix intact (at_failure) or below its stored index (proportional), and the bound not
    // excluding it (with sigma11 < -Y_C LaRC02 uses misalignment-frame stresses: search).
    const double floor = proportional ? q.index[matrix_damage] : 1.0;
    const bool search = q.index[matrix_damage] < 1.0 &&
                        (ps.s11 < -fo.lamina.Y_C || larc_bound_(ps.s22, ps.t12) >= floor);
    fi = analytic::larc02_failure(ps, fo.lamina, search);
  } else {
    fi = analytic::failure_indices(fo.criterion, ps, fo.lamina);
  }
  // Interface: the criterion's own shear index (maximum stress) and, when the interface strengths
  // are given, (<sigma22>/S_sigma)^2 + (tau12/S_tau)^2; the larger of the two.
  double interface = std::isnan(fi.shear) ? 0.0 : fi.shear;
  if (zone) {
    const double sn = std::max(0.0, ps.s22) / fo.S_sigma, st = ps.t12 / fo.S_tau;
    interface = std::max(interface, sn * sn + st * st);
  }
  const double idx[3] = {fi.fibre, fi.matrix, interface};
  bool failed = false, grown = false;
  for (int k = 0; k < 3; ++k) {
    // the stored running maximum: a failed mode (index 1) stays as it failed; NaN (not
    // evaluated) never replaces it
    if (q.index[k] >= 1.0 || !(idx[k] > q.index[k])) continue;
    const double d = std::min(1.0, idx[k]);
    q.index[k] = d;
    grown = true;
    // the sign of the stress when the index last rose (proportional) or at failure
    if (proportional || d >= 1.0) {
      if (k == fibre_damage) q.compressive[0] = ps.s11 < 0.0;
      if (k == matrix_damage) q.compressive[1] = ps.s22 < 0.0;
    }
    failed = failed || d >= 1.0;
  }
  const bool changed = proportional ? grown : failed;
  if (changed) {
    q.Qd = degraded_stiffness(proportional ? q.index : failed_modes(q), q.compressive);
    q.degraded = true;
  }
  return changed;
}

namespace {
// Modulus multiplier of a mode with damage d and degraded factor f: f when failed (d >= 1; the
// factor itself, bit for bit), 1 - d (1 - f) in between, 1 when undamaged.
double degradation_multiplier(double d, double f) {
  if (d >= 1.0) return f;
  return d > 0.0 ? 1.0 - d * (1.0 - f) : 1.0;
}
}  // namespace

Eigen::Matrix3d ExplicitEFG::degraded_stiffness(const std::array<double, 3>& damage,
                                                const std::array<char, 2>& compressive) const {
  Orthotropic m = mat_;
  const double r = opt_.failure.residual;
  const double df = damage[fibre_damage], dm = damage[matrix_damage], di = damage[interface_damage];
  // scale the selected moduli (E1, E2, G12, nu12) of a mode with damage d and factor f
  auto degrade = [&m](double d, double f, std::array<bool, 4> which) {
    if (!(d > 0.0)) return;
    const double k = degradation_multiplier(d, f);
    if (which[0]) m.E1 *= k;
    if (which[1]) m.E2 *= k;
    if (which[2]) m.G12 *= k;
    if (which[3]) m.nu12 *= k;
  };
  if (opt_.failure.degradation == Degradation::mode_factors) {
    const ModeFactors& f = opt_.failure.factors;
    degrade(df, compressive[0] ? f.fibre_compression : f.fibre_tension, {true, true, true, true});
    degrade(dm, compressive[1] ? f.matrix_compression : f.matrix_tension, {false, true, true, false});
    degrade(di, r, {false, false, true, true});
  } else {
    degrade(df, r, {true, false, true, true});
    degrade(dm, r, {false, true, true, true});
    degrade(di, r, {false, false, true, false});
  }
  return m.Qbar_rotated(Ti_);
}

void ExplicitEFG::set_damage(std::size_t g, const std::array<double, 3>& damage,
                             const std::array<char, 2>& compressive) {
  gp_.at(g).index = damage;
  gp_[g].compressive = compressive;
  gp_[g].Qd = degraded_stiffness(damage, compressive);
  gp_[g].degraded = damage[0] + damage[1] + damage[2] > 0.0;
}

void ExplicitEFG::apply_contact(double dt, std::vector<Vec2>& vhalf) {
  tool_force_.setZero();
  ncontact_ = nstick_ = 0;
  impulses_.clear();
  if (!has_tool_) return;
  const std::size_t nv = tool_.vertices.size();
  const Vec2 shift = tool_.displacement(t_ + dt);  // tool at t^{n+1}
  const Vec2 vtool = (shift - tool_.displacement(t_)) / dt;
  std::vector<Vec2> v(nv);
  Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
  for (std::size_t k = 0; k < nv; ++k) {
    v[k] = tool_.vertices[k] + shift;
    lo = lo.cwiseMin(v[k]);
    hi = hi.cwiseMax(v[k]);
  }
  for (std::size_t I = 0; I < x_.size(); ++I) {
    if (!active_[I]) continue;
    const Vec2 xp = x_[I] + dt * vhalf[I];  // predicted x^{n+1} (Eq 49)
    if ((xp.array() < lo.array()).any() || (xp.array() > hi.array()).any()) continue;
    double gmin = 1e300;
    std::size_t face = 0;
    bool inside = true;
    for (std::size_t k = 0; k < nv && inside; ++k) {
      const Vec2 e = (v[(k + 1) % nv] - v[k]).normalized();
      const Vec2 r = xp - v[k];
      const double depth = e.x() * r.y() - e.y() * r.x();  // > 0: left of the CCW edge (inside)
      if (depth <= 0.0) inside = false;
      if (depth < gmin) {
        gmin = depth;
        face = k;
      }
    }
    if (!inside) continue;
    const Vec2 t = (v[(face + 1) % nv] - v[face]).normalized();
    const Vec2 n(t.y(), -t.x());  // outward normal of the face
    const double M = mass_[I];
    const double fn = 2.0 * M * gmin / (dt * dt);                       // Eq 39
    const double gt = (dt * vhalf[I] - dt * vtool).dot(t);  // tangential slip in the step
    // Eq 40 with the factor 2 of Eq 39: both trial forces act through the half step of Eq 48,
    // so this stick force removes the step's tangential slip exactly, and the stick/slip
    // comparison compares like with like (README: contact).
    const double ft_stick = -2.0 * M * gt / (dt * dt);
    const double ft_slip = tool_.mu * fn;                              // Eq 41
    double ft;
    if (std::abs(ft_stick) <= ft_slip) {
      ft = ft_stick;
      ++nstick_;
    } else {
      ft = gt > 0.0 ? -ft_slip : ft_slip;
    }
    const Vec2 fc = fn * n + ft * t;  // Eqs 42-43
    // Contact force in a^n of Eq 48: v^{n+1/2} += dt/2 f/M (so x^{n+1} moves by dt^2/2 f/M = g n).
    vhalf[I] += 0.5 * dt * fc / M;
    ledger_.tool_work += 0.5 * dt * fc.dot(vtool);
    impulses_.emplace_back(static_cast<int>(I), Vec2(0.5 * dt * fc));
    // Momentum given to the node in the step: dt/2 fc, i.e. a mean force fc/2 over dt. The tool
    // force is reported from that impulse (in steady contact it equals the pressing force, while
    // the Eq 39 value is twice it).
    tool_force_ -= 0.5 * fc;
    ++ncontact_;
  }
}

void ExplicitEFG::update_release() {
  erosion_changed_ = false;
  std::vector<char> carried(x_.size(), 0);
  neroded_ = 0;
  for (const auto& q : gp_) {
    if (q.eroded) {
      ++neroded_;
      continue;
    }
    for (int I : q.sd.nodes) carried[I] = 1;
  }
  nreleased_ = 0;
  for (std::size_t I = 0; I < x_.size(); ++I) {
    if (!carried[I]) active_[I] = 0;  // irreversible
    if (!active_[I]) {
      ++nreleased_;
      ledger_.release_kinetic -= 0.5 * mass_[I] * v_[I].squaredNorm();
      v_[I].setZero();
      a_[I].setZero();
    }
  }
}

void ExplicitEFG::add_opaque_segment(const Segment& s) {
  opaque_.push_back(s);
  const double dmax = *std::max_element(support_.begin(), support_.end());
  std::vector<std::size_t> ids;
  const Vec2 ab = s.b - s.a;
  const double L2 = ab.squaredNorm();
  // the segment is material (initial configuration): the Gauss points near it there; with the
  // updated Lagrangian form a point's support may have grown since (dmax is the initial largest
  // support radius; points whose current supports reach further are rare and keep their functions
  // until the next reference update)
  for (std::size_t g = 0; g < gp_.size(); ++g) {
    const Vec2& x = Xg0_[g];
    const double u = L2 > 0.0 ? std::clamp((x - s.a).dot(ab) / L2, 0.0, 1.0) : 0.0;
    if ((x - (s.a + u * ab)).norm() < dmax) ids.push_back(g);
  }
  if (ids.empty()) return;
  auto sf = gauss_shapes(ids);
  for (std::size_t k = 0; k < ids.size(); ++k) gp_[ids[k]].sd = std::move(sf[k]);
  node_gp_dirty_ = true;
  update_release();
}

void ExplicitEFG::update_reference() {
  for (auto& q : gp_) {
    Vec2 xg = Vec2::Zero();
    for (std::size_t a = 0; a < q.sd.nodes.size(); ++a) xg += q.sd.phi[a] * x_[q.sd.nodes[a]];
    const Mat2 Finc = q.F * q.Fr.inverse();
    q.Vr *= Finc.determinant();
    q.Fr = q.F;
    q.xr = xg;
  }
  xr_ = x_;
  // every Gauss point's functions rebuilt into the spare set, then swapped in: the spare keeps the
  // previous functions' storage for the next update, so the rebuild allocates nothing
  gauss_pts_.resize(gp_.size());
  for (std::size_t g = 0; g < gp_.size(); ++g) gauss_pts_[g] = gp_[g].xr;
  shape_functions_into(gauss_pts_, xr_, support_, opt_.weight, true, opaque_, VisibilityFrame{&Xg0_, &X0_},
                       spare_sd_);
  for (std::size_t g = 0; g < gp_.size(); ++g) std::swap(gp_[g].sd, spare_sd_[g]);
  node_gp_dirty_ = true;
}

std::vector<ShapeData> ExplicitEFG::gauss_shapes(const std::vector<std::size_t>& ids) const {
  std::vector<Vec2> pts(ids.size()), mat(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    pts[k] = gp_[ids[k]].xr;
    mat[k] = Xg0_[ids[k]];
  }
  return shape_functions(pts, xr_, support_, opt_.weight, true, opaque_, VisibilityFrame{&mat, &X0_});
}

void ExplicitEFG::apply_bcs(double t) {
  for (const auto& b : bcs_) v_[b.node](b.dof) = b.v(t);
}

double ExplicitEFG::critical_time_step() const { return min_active_distance() / mat_.wave_speed(); }

double ExplicitEFG::min_active_distance() const {
  CellList cl;
  const std::vector<Vec2>* pts = &x_;
  if (nreleased_ > 0) {
    xactive_.clear();
    for (std::size_t I = 0; I < x_.size(); ++I) {
      if (active_[I]) xactive_.push_back(x_[I]);
    }
    pts = &xactive_;
  }
  cl.build(*pts, spacing_);
  const double dmin = cl.min_pair_distance();
  return std::isfinite(dmin) ? dmin : spacing_;
}

bool ExplicitEFG::erode_collapsed() {
  const double r = opt_.collapse_ratio * dmin0_;
  std::vector<int> ids;
  std::vector<Vec2> pts;
  for (std::size_t I = 0; I < x_.size(); ++I) {
    if (active_[I]) {
      ids.push_back(static_cast<int>(I));
      pts.push_back(x_[I]);
    }
  }
  CellList cl;
  cl.build(pts, std::max(spacing_, r));
  pairs_.clear();
  cl.pairs_within(r, pairs_);
  if (pairs_.empty()) return false;
  build_node_gp();
  auto failed = [&](int g) {
    const GP& q = gp_[g];
    return q.eroded || q.index[0] >= 1.0 || q.index[1] >= 1.0 || q.index[2] >= 1.0;
  };
  bool any = false;
  for (const auto& pr : pairs_) {
    for (int I : {ids[pr.first], ids[pr.second]}) {
      if (!active_[I]) continue;
      bool all = true;
      for (int k = node_gp_start_[I]; k < node_gp_start_[I + 1] && all; ++k) all = failed(node_gp_[k]);
      if (!all) continue;
      for (int k = node_gp_start_[I]; k < node_gp_start_[I + 1]; ++k) {
        GP& q = gp_[node_gp_[k]];
        if (!q.eroded) {
          q.eroded = true;
          dgp_[static_cast<std::size_t>(node_gp_[k])] += 0.5 * q.Vr / q.Fr.determinant() * q.E.dot(q.S);
          q.S.setZero();
          ++ncollapse_;
        }
      }
      active_[I] = 0;  // all its support is eroded: released (update_release confirms)
      any = true;
    }
  }
  if (any) {
    update_release();
    compute_internal_forces();
    for (std::size_t I = 0; I < x_.size(); ++I) {
      a_[I] = active_[I] ? Vec2((fext_[I] - fint_[I]) / mass_[I]) : Vec2::Zero();
    }
  }
  return any;
}

double ExplicitEFG::step() {
  double dt = opt_.cfl * critical_time_step();
  if (opt_.collapse_ratio > 0.0 && dt < opt_.collapse_ratio * opt_.cfl * dmin0_ / mat_.wave_speed() &&
      erode_collapsed()) {
    dt = opt_.cfl * critical_time_step();
  }
  step(dt);
  return dt;
}

void ExplicitEFG::step(double dt) {
  const std::size_t n = x_.size();
  for (std::size_t I = 0; I < n; ++I) v_[I] += 0.5 * dt * a_[I];  // Eq 48
  apply_contact(dt, v_);
  apply_bcs(t_ + 0.5 * dt);
  for (std::size_t I = 0; I < n; ++I) x_[I] += dt * v_[I];  // Eq 49
  t_ += dt;
  ++nstep_;
  // energy ledger: the impulses and the internal forces at both ends of the step do work over
  // the step's displacement dt v^{n+1/2}
  for (const auto& [I, J] : impulses_) ledger_.contact_work += J.dot(v_[I]);
  double w_int = 0.0;
  for (std::size_t I = 0; I < n; ++I) w_int += v_[I].dot(fint_[I]);
  compute_internal_forces();
  for (std::size_t I = 0; I < n; ++I) w_int += v_[I].dot(fint_[I]);
  ledger_.internal_work += 0.5 * dt * w_int;
  if (opt_.kinematics == Kinematics::updated_lagrangian && nstep_ % opt_.update_interval == 0) {
    update_reference();
  }
  for (std::size_t I = 0; I < n; ++I) {
    if (!active_[I]) {
      v_[I].setZero();
      a_[I].setZero();
      continue;
    }
    a_[I] = (fext_[I] - fint_[I]) / mass_[I];  // Eq 46
    v_[I] += 0.5 * dt * a_[I];                  // Eq 50
  }
  apply_bcs(t_);
}

Eigen::Vector3d ExplicitEFG::cauchy(std::size_t g) const {
  const GP& q = gp_[g];
  if (opt_.kinematics == Kinematics::small_strain) return q.S;
  const Mat2 s = q.F * voigt_to_tensor(q.S) * q.F.transpose() / q.F.determinant();
  return Eigen::Vector3d(s(0, 0), s(1, 1), s(0, 1));
}

Vec2 ExplicitEFG::gauss_position(std::size_t g) const {
  const GP& q = gp_[g];
  Vec2 xg = Vec2::Zero();
  for (std::size_t a = 0; a < q.sd.nodes.size(); ++a) xg += q.sd.phi[a] * x_[q.sd.nodes[a]];
  return xg;
}

namespace {
// Gauss-point state in a checkpoint (bytewise record).
struct GPState {
  Mat2 Fr, F;
  Eigen::Vector3d E, S;
  Eigen::Matrix3d Qd;
  Vec2 xr;
  double Vr;
  double index[3];
  char compressive[2];
  char eroded;
  char degraded;
};
constexpr std::uint64_t kStateVersion = 4;
}  // namespace

void ExplicitEFG::save_state(BinaryWriter& w) const {
  w.u64(kStateVersion);
  w.u64(x_.size());
  w.u64(gp_.size());
  w.pods(x_);
  w.pods(v_);
  w.pods(a_);
  w.pods(fint_);
  w.pods(xr_);
  w.pods(active_);
  std::vector<GPState> gs(gp_.size());
  for (std::size_t g = 0; g < gp_.size(); ++g) {
    const GP& q = gp_[g];
    GPState& o = gs[g];
    o = GPState{q.Fr,
                q.F,
                q.E,
                q.S,
                q.Qd,
                q.xr,
                q.Vr,
                {q.index[0], q.index[1], q.index[2]},
                {q.compressive[0], q.compressive[1]},
                static_cast<char>(q.eroded),
                static_cast<char>(q.degraded)};
  }
  w.pods(gs);
  w.pods(opaque_);
  for (std::uint64_t u : {static_cast<std::uint64_t>(nreleased_), static_cast<std::uint64_t>(neroded_),
                          static_cast<std::uint64_t>(ncollapse_), static_cast<std::uint64_t>(nstep_),
                          static_cast<std::uint64_t>(ncontact_), static_cast<std::uint64_t>(nstick_),
                          static_cast<std::uint64_t>(erosion_changed_)})
    w.u64(u);
  for (double d : {t_, tool_force_.x(), tool_force_.y(), ledger_.tool_work, ledger_.contact_work,
                   ledger_.internal_work, ledger_.release_kinetic})
    w.f64(d);
  w.pods(dgp_);
}

void ExplicitEFG::load_state(BinaryReader& r) {
  if (r.u64() != kStateVersion) throw NumericalError("efg checkpoint: unknown state version");
  const std::size_t n = x_.size(), ng = gp_.size();
  if (r.u64() != n || r.u64() != ng) throw NumericalError("efg checkpoint: node or Gauss point count differs from the setup");
  auto sized = [](auto v, std::size_t m) {
    if (v.size() != m) throw NumericalError("efg checkpoint: array size differs from the setup");
    return v;
  };
  x_ = sized(r.pods<Vec2>(), n);
  v_ = sized(r.pods<Vec2>(), n);
  a_ = sized(r.pods<Vec2>(), n);
  fint_ = sized(r.pods<Vec2>(), n);
  xr_ = sized(r.pods<Vec2>(), n);
  active_ = sized(r.pods<char>(), n);
  const std::vector<GPState> gs = sized(r.pods<GPState>(), ng);
  for (std::size_t g = 0; g < ng; ++g) {
    GP& q = gp_[g];
    const GPState& o = gs[g];
    q.Fr = o.Fr;
    q.F = o.F;
    q.E = o.E;
    q.S = o.S;
    q.Qd = o.Qd;
    q.xr = o.xr;
    q.Vr = o.Vr;
    q.index = {o.index[0], o.index[1], o.index[2]};
    q.compressive = {o.compressive[0], o.compressive[1]};
    q.eroded = o.eroded != 0;
    q.degraded = o.degraded != 0;
  }
  opaque_ = r.pods<Segment>();
  nreleased_ = static_cast<std::size_t>(r.u64());
  neroded_ = static_cast<std::size_t>(r.u64());
  ncollapse_ = static_cast<std::size_t>(r.u64());
  nstep_ = static_cast<long>(r.u64());
  ncontact_ = static_cast<int>(r.u64());
  nstick_ = static_cast<int>(r.u64());
  erosion_changed_ = r.u64() != 0;
  t_ = r.f64();
  tool_force_.x() = r.f64();
  tool_force_.y() = r.f64();
  ledger_.tool_work = r.f64();
  ledger_.contact_work = r.f64();
  ledger_.internal_work = r.f64();
  ledger_.release_kinetic = r.f64();
  dgp_ = sized(r.pods<double>(), ng);
  std::vector<std::size_t> ids(ng);
  for (std::size_t g = 0; g < ng; ++g) ids[g] = g;
  auto sf = gauss_shapes(ids);
  for (std::size_t g = 0; g < ng; ++g) gp_[g].sd = std::move(sf[g]);
  node_gp_dirty_ = true;
}

double ExplicitEFG::kinetic_energy() const {
  double k = 0.0;
  for (std::size_t I = 0; I < x_.size(); ++I) k += 0.5 * mass_[I] * v_[I].squaredNorm();
  return k;
}

double ExplicitEFG::strain_energy() const {
  double e = 0.0;
  for (const auto& q : gp_) e += 0.5 * q.Vr / q.Fr.determinant() * q.E.dot(q.S);
  return e;
}

double ExplicitEFG::damage_dissipation() const {
  double e = 0.0;
  for (double d : dgp_) e += d;
  return e;
}

}  // namespace cutbench::efg
