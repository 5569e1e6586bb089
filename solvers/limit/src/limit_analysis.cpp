#include "cutbench/limit/limit_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <set>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "cutbench/common/errors.hpp"

namespace cutbench::limit {

using Eigen::Vector2d;
using Eigen::VectorXd;
using Trip = Eigen::Triplet<double>;

double LimitModel::add_traction(const std::function<bool(const Vector2d&)>& on, const Vector2d& t, bool dead) {
  VectorXd& f = dead ? dead_load : load;
  if (f.size() == 0) f = VectorXd::Zero(2 * mesh.num_nodes());
  double length = 0.0;
  for (const auto& e : boundary_edges(mesh)) {
    if (!on(mesh.nodes[static_cast<std::size_t>(e.m)])) continue;
    const double L = (mesh.nodes[static_cast<std::size_t>(e.b)] - mesh.nodes[static_cast<std::size_t>(e.a)]).norm();
    length += L;
    const double w[3] = {L / 6.0, 4.0 * L / 6.0, L / 6.0};
    const int nd[3] = {e.a, e.m, e.b};
    for (int i = 0; i < 3; ++i) {
      f[2 * nd[i]] += w[i] * t.x();
      f[2 * nd[i] + 1] += w[i] * t.y();
    }
  }
  return length;
}

void LimitModel::add_contact(const std::vector<int>& nodes, double mu) {
  // normal at a node: average over the boundary edges lying entirely in the contact set
  const std::set<int> in(nodes.begin(), nodes.end());
  std::map<int, Vector2d> normal;
  for (const auto& e : boundary_edges(mesh)) {
    if (!in.count(e.a) || !in.count(e.m) || !in.count(e.b)) continue;
    const Vector2d n = boundary_normal(mesh, e);
    for (int nd : {e.a, e.m, e.b}) {
      auto it = normal.find(nd);
      if (it == normal.end()) normal.emplace(nd, n);
      else it->second += n;
    }
  }
  for (int nd : nodes) {
    auto it = normal.find(nd);
    if (it == normal.end()) throw InputError("contact", "node " + std::to_string(nd) + " is not on a boundary edge of the contact set");
    contacts.push_back({nd, it->second.normalized(), mu});
  }
}

void LimitModel::add_contact(const std::vector<int>& nodes, double mu, const Vector2d& normal) {
  for (int nd : nodes) contacts.push_back({nd, normal.normalized(), mu});
}

namespace {

// Bᵀ: rows = velocity dofs (2·nodes), columns = stress unknowns (9 per element: (p,q,τ) at
// the 3 vertices). (Bᵀσ)_d = ∫ σ : ε(φ_d) with the exact 3-point rule.
SpMat assemble_bt(const Mesh& mesh) {
  std::vector<Trip> t;
  t.reserve(static_cast<std::size_t>(mesh.num_elements()) * 6 * 2 * 3 * 3 * 3);
  const double gp[3][3] = {{2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto& el = mesh.elements[static_cast<std::size_t>(e)];
    const Vector2d& x1 = mesh.nodes[static_cast<std::size_t>(el[0])];
    const Vector2d& x2 = mesh.nodes[static_cast<std::size_t>(el[1])];
    const Vector2d& x3 = mesh.nodes[static_cast<std::size_t>(el[2])];
    const double A2 = (x2 - x1).x() * (x3 - x1).y() - (x2 - x1).y() * (x3 - x1).x();
    if (A2 <= 0.0) throw InputError("mesh", "element " + std::to_string(e) + " is not counter-clockwise");
    Vector2d gL[3];
    gL[0] = Vector2d(x2.y() - x3.y(), x3.x() - x2.x()) / A2;
    gL[1] = Vector2d(x3.y() - x1.y(), x1.x() - x3.x()) / A2;
    gL[2] = Vector2d(x1.y() - x2.y(), x2.x() - x1.x()) / A2;
    const double w = 0.5 * A2 / 3.0;
    for (const auto& L : gp) {
      Vector2d dN[6];
      for (int i = 0; i < 3; ++i) dN[i] = (4.0 * L[i] - 1.0) * gL[i];
      for (int k = 0; k < 3; ++k) {
        const int i = k, j = (k + 1) % 3;
        dN[3 + k] = 4.0 * (L[i] * gL[j] + L[j] * gL[i]);
      }
      for (int sp = 0; sp < 3; ++sp) {
        const double ws = w * L[sp];
        const int col = 9 * e + 3 * sp;
        for (int a = 0; a < 6; ++a) {
          const int dx = 2 * el[static_cast<std::size_t>(a)], dy = dx + 1;
          const double nx = dN[a].x(), ny = dN[a].y();
          // ε:σ = p (vx,x + vy,y) + q (vx,x − vy,y) + τ (vx,y + vy,x)
          t.emplace_back(dx, col, ws * nx);
          t.emplace_back(dx, col + 1, ws * nx);
          t.emplace_back(dx, col + 2, ws * ny);
          t.emplace_back(dy, col, ws * ny);
          t.emplace_back(dy, col + 1, -ws * ny);
          t.emplace_back(dy, col + 2, ws * nx);
        }
      }
    }
  }
  SpMat bt(2 * mesh.num_nodes(), 9 * mesh.num_elements());
  bt.setFromTriplets(t.begin(), t.end());
  bt.prune(0.0);
  return bt;
}

}  // namespace

LimitSolution solve_limit(const LimitModel& model, const SocpSettings& settings) {
  const Mesh& mesh = model.mesh;
  const int nn = mesh.num_nodes(), ne = mesh.num_elements();
  const int ndof = 2 * nn;
  const VectorXd F = model.load.size() ? model.load : VectorXd::Zero(ndof);
  const VectorXd F0 = model.dead_load.size() ? model.dead_load : VectorXd::Zero(ndof);
  if (F.size() != ndof || F0.size() != ndof) throw InputError("load", "load vectors must have 2 entries per node");
  if (!(model.k > 0.0)) throw InputError("k", "shear yield stress must be positive");

  bool imposed_motion = false;
  for (const auto& [d, v] : model.fixed) {
    if (d < 0 || d >= ndof) throw InputError("fixed", "dof out of range");
    if (v != 0.0) imposed_motion = true;
  }
  const bool load_mode = F.norm() > 0.0;
  if (load_mode == imposed_motion)
    throw InputError("model", load_mode ? "give either a reference load or imposed velocities, not both"
                                        : "no reference load and no imposed velocity: nothing drives collapse");

  std::vector<int> contact_of(static_cast<std::size_t>(nn), -1);
  for (std::size_t c = 0; c < model.contacts.size(); ++c) {
    const int nd = model.contacts[c].node;
    if (model.fixed.count(2 * nd) || model.fixed.count(2 * nd + 1))
      throw InputError("contact", "contact node " + std::to_string(nd) + " also has a fixed velocity");
    if (contact_of[static_cast<std::size_t>(nd)] >= 0) throw InputError("contact", "node in contact twice");
    contact_of[static_cast<std::size_t>(nd)] = static_cast<int>(c);
  }
  std::vector<int> slider_of(static_cast<std::size_t>(nn), -1);
  for (std::size_t c = 0; c < model.sliders.size(); ++c) {
    const int nd = model.sliders[c].first;
    if (nd < 0 || nd >= nn) throw InputError("sliders", "node out of range");
    if (model.fixed.count(2 * nd) || model.fixed.count(2 * nd + 1) || contact_of[static_cast<std::size_t>(nd)] >= 0 ||
        slider_of[static_cast<std::size_t>(nd)] >= 0)
      throw InputError("sliders", "slider node " + std::to_string(nd) + " is also fixed, in contact or repeated");
    if (!(model.sliders[c].second.norm() > 0.0)) throw InputError("sliders", "normal must be non-zero");
    slider_of[static_cast<std::size_t>(nd)] = static_cast<int>(c);
  }

  const SpMat bt = assemble_bt(mesh);
  const SpMat btr = SpMat(bt.transpose());  // columns = dofs
  const int nsig = 9 * ne;
  const int nc = static_cast<int>(model.contacts.size());
  const int ilam = nsig + nc;
  const int n = nsig + nc + (load_mode ? 1 : 0);

  auto add_row = [&](std::vector<Trip>& t, int row, int dof, double scale) {
    for (SpMat::InnerIterator it(btr, dof); it; ++it) t.emplace_back(row, it.row(), scale * it.value());
  };

  // equality rows
  std::vector<Trip> ta;
  std::vector<double> bvec;
  std::vector<int> row_of_dof(static_cast<std::size_t>(ndof), -1);
  int p = 0;
  for (int d = 0; d < ndof; ++d) {
    if (model.fixed.count(d) || contact_of[static_cast<std::size_t>(d / 2)] >= 0 ||
        slider_of[static_cast<std::size_t>(d / 2)] >= 0)
      continue;
    add_row(ta, p, d, 1.0);
    if (load_mode && F[d] != 0.0) ta.emplace_back(p, ilam, -F[d]);
    bvec.push_back(F0[d]);
    row_of_dof[static_cast<std::size_t>(d)] = p++;
  }
  std::vector<int> row_of_contact(static_cast<std::size_t>(nc));
  for (int c = 0; c < nc; ++c) {
    const auto& cn = model.contacts[static_cast<std::size_t>(c)];
    const Vector2d tt(-cn.normal.y(), cn.normal.x());
    const int dx = 2 * cn.node, dy = dx + 1;
    add_row(ta, p, dx, tt.x());
    add_row(ta, p, dy, tt.y());
    ta.emplace_back(p, nsig + c, -1.0);
    const double Ft = tt.x() * F[dx] + tt.y() * F[dy];
    if (load_mode && Ft != 0.0) ta.emplace_back(p, ilam, -Ft);
    bvec.push_back(tt.x() * F0[dx] + tt.y() * F0[dy]);
    row_of_contact[static_cast<std::size_t>(c)] = p++;
  }
  const int ns = static_cast<int>(model.sliders.size());
  std::vector<int> row_of_slider(static_cast<std::size_t>(ns));
  for (int c = 0; c < ns; ++c) {  // tangential equilibrium only, no tangential reaction
    const Vector2d nrm = model.sliders[static_cast<std::size_t>(c)].second.normalized();
    const Vector2d tt(-nrm.y(), nrm.x());
    const int nd = model.sliders[static_cast<std::size_t>(c)].first, dx = 2 * nd, dy = dx + 1;
    add_row(ta, p, dx, tt.x());
    add_row(ta, p, dy, tt.y());
    const double Ft = tt.x() * F[dx] + tt.y() * F[dy];
    if (load_mode && Ft != 0.0) ta.emplace_back(p, ilam, -Ft);
    bvec.push_back(tt.x() * F0[dx] + tt.y() * F0[dy]);
    row_of_slider[static_cast<std::size_t>(c)] = p++;
  }

  // cone rows: 2 per contact (orthant), then one Q3 per stress point
  std::vector<Trip> tg;
  std::vector<double> hvec;
  int m = 0;
  std::vector<int> rn_row(static_cast<std::size_t>(nc), -1), cone_row(static_cast<std::size_t>(nc), -1);
  for (int c = 0; c < nc; ++c) {
    const auto& cn = model.contacts[static_cast<std::size_t>(c)];
    if (!std::isfinite(cn.normal_velocity) || (cn.normal_velocity != 0.0 && (std::isfinite(cn.tresca_bound) || !(cn.mu > 0.0))))
      throw InputError("contact", "an imposed normal velocity needs the coupled cone with mu > 0 (node " + std::to_string(cn.node) + ")");
    const int dx = 2 * cn.node, dy = dx + 1;
    const double Fn = cn.normal.x() * F[dx] + cn.normal.y() * F[dy];
    const double F0n = cn.normal.x() * F0[dx] + cn.normal.y() * F0[dy];
    if (std::isfinite(cn.tresca_bound)) {  // |r_t| ≤ g (fixed bound, from the previous pressure)
      for (double sgn : {1.0, -1.0}) {
        tg.emplace_back(m, nsig + c, sgn);
        hvec.push_back(std::max(cn.tresca_bound, 0.0));
        ++m;
      }
      // r_n ≤ 0: the contact transmits compression only (Eq. 5); its multiplier z ≥ 0 is the
      // separation velocity (v·n = −z, away from the rigid body)
      rn_row[static_cast<std::size_t>(c)] = m;
      add_row(tg, m, dx, cn.normal.x());
      add_row(tg, m, dy, cn.normal.y());
      if (load_mode && Fn != 0.0) tg.emplace_back(m, ilam, -Fn);
      hvec.push_back(F0n);
      ++m;
      continue;
    }
    cone_row[static_cast<std::size_t>(c)] = m;
    for (double sgn : {1.0, -1.0}) {
      add_row(tg, m, dx, cn.mu * cn.normal.x());
      add_row(tg, m, dy, cn.mu * cn.normal.y());
      tg.emplace_back(m, nsig + c, sgn);
      if (load_mode && Fn != 0.0) tg.emplace_back(m, ilam, -cn.mu * Fn);
      hvec.push_back(cn.mu * F0n);
      ++m;
    }
  }
  const int lp_rows = m;
  for (int sp = 0; sp < 3 * ne; ++sp) {
    hvec.push_back(model.k);
    hvec.push_back(0.0);
    hvec.push_back(0.0);
    tg.emplace_back(m + 1, 3 * sp + 1, -1.0);
    tg.emplace_back(m + 2, 3 * sp + 2, -1.0);
    m += 3;
  }

  SocpProblem prob;
  prob.c = VectorXd::Zero(n);
  // the power of a velocity v imposed on dof d, v (B^T sigma)_d, enters the objective as -v B_d
  auto impose_velocity = [&](int d, double v) {
    for (SpMat::InnerIterator it(btr, d); it; ++it) prob.c[it.row()] -= v * it.value();
  };
  double offset = 0.0;
  if (load_mode) {
    prob.c[ilam] = -1.0;
  } else {
    for (const auto& [d, v] : model.fixed) {
      if (v == 0.0) continue;
      impose_velocity(d, v);
      offset -= v * F0[d];
    }
  }
  // imposed normal velocities g at coupled contacts: the objective gains the power −g (r_n + F0_n)
  // (as for an imposed velocity on a free normal dof), taken out of the collapse value below
  for (int c = 0; c < nc; ++c) {
    const auto& cn = model.contacts[static_cast<std::size_t>(c)];
    if (cn.normal_velocity == 0.0) continue;
    const int dx = 2 * cn.node, dy = dx + 1;
    impose_velocity(dx, cn.normal_velocity * cn.normal.x());
    impose_velocity(dy, cn.normal_velocity * cn.normal.y());
    if (load_mode) prob.c[ilam] += cn.normal_velocity * (cn.normal.x() * F[dx] + cn.normal.y() * F[dy]);
  }
  prob.A.resize(p, n);
  prob.A.setFromTriplets(ta.begin(), ta.end());
  prob.b = Eigen::Map<VectorXd>(bvec.data(), static_cast<Eigen::Index>(bvec.size()));
  prob.G.resize(m, n);
  prob.G.setFromTriplets(tg.begin(), tg.end());
  prob.h = Eigen::Map<VectorXd>(hvec.data(), static_cast<Eigen::Index>(hvec.size()));
  prob.cones.nonneg = lp_rows;
  prob.cones.soc.assign(static_cast<std::size_t>(3 * ne), 3);

  LimitSolution sol;
  sol.load_mode = load_mode;
  sol.socp = solve_socp(prob, settings);
  const auto& r = sol.socp;
  if (r.status != SocpStatus::optimal && r.status != SocpStatus::optimal_inaccurate) {
    if (r.status == SocpStatus::dual_infeasible)
      throw NumericalError("limit analysis: the stress problem is unbounded (no collapse: the structure is "
                           "over-constrained or the load is carried by the supports)");
    if (r.status == SocpStatus::primal_infeasible)
      throw NumericalError("limit analysis: no admissible stress field (dead loads exceed the capacity)");
    throw NumericalError("limit analysis: SOCP failed: " + to_string(r.status) + (r.message.empty() ? "" : ": " + r.message));
  }
  sol.collapse = -r.pcost + offset;

  // velocities: v = −y on the free dofs, w_t = −y on the tangential contact rows
  sol.velocity = VectorXd::Zero(ndof);
  for (const auto& [d, v] : model.fixed) sol.velocity[d] = v;
  for (int d = 0; d < ndof; ++d) {
    if (row_of_dof[static_cast<std::size_t>(d)] >= 0) sol.velocity[d] = -r.y[row_of_dof[static_cast<std::size_t>(d)]];
  }
  sol.contact_rn = VectorXd::Zero(nc);
  sol.contact_rt = VectorXd::Zero(nc);
  sol.contact_wt = VectorXd::Zero(nc);
  sol.contact_wn = VectorXd::Zero(nc);
  const VectorXd sig = r.x.head(nsig);
  const double lam = load_mode ? r.x[ilam] : 0.0;
  const VectorXd fint = bt * sig - lam * F - F0;
  for (int c = 0; c < nc; ++c) {
    const auto& cn = model.contacts[static_cast<std::size_t>(c)];
    const Vector2d tt(-cn.normal.y(), cn.normal.x());
    const double wt = -r.y[row_of_contact[static_cast<std::size_t>(c)]];
    const int cr = cone_row[static_cast<std::size_t>(c)];
    const double wn = rn_row[static_cast<std::size_t>(c)] >= 0 ? -r.z[rn_row[static_cast<std::size_t>(c)]]
                                                             : cn.normal_velocity - cn.mu * (r.z[cr] + r.z[cr + 1]);
    sol.velocity[2 * cn.node] = wt * tt.x() + wn * cn.normal.x();
    sol.velocity[2 * cn.node + 1] = wt * tt.y() + wn * cn.normal.y();
    sol.contact_wt[c] = wt;
    sol.contact_rt[c] = r.x[nsig + c];
    sol.contact_wn[c] = wn;
    sol.contact_rn[c] = cn.normal.x() * fint[2 * cn.node] + cn.normal.y() * fint[2 * cn.node + 1];
    if (cn.normal_velocity != 0.0)
      sol.collapse -= cn.normal_velocity * (sol.contact_rn[c] + cn.normal.x() * F0[2 * cn.node] + cn.normal.y() * F0[2 * cn.node + 1]);
    sol.friction_dissipation += std::abs(sol.contact_rt[c] * wt);
  }
  sol.slider_rn = VectorXd::Zero(ns);
  for (int c = 0; c < ns; ++c) {
    const int nd = model.sliders[static_cast<std::size_t>(c)].first;
    const Vector2d nrm = model.sliders[static_cast<std::size_t>(c)].second.normalized();
    const Vector2d tt(-nrm.y(), nrm.x());
    const double w = -r.y[row_of_slider[static_cast<std::size_t>(c)]];
    sol.velocity[2 * nd] = w * tt.x();
    sol.velocity[2 * nd + 1] = w * tt.y();
    sol.slider_rn[c] = nrm.x() * fint[2 * nd] + nrm.y() * fint[2 * nd + 1];
  }

  sol.stress.resize(3 * ne, 3);
  sol.point_dissipation.resize(3 * ne);
  sol.element_dissipation_density = VectorXd::Zero(ne);
  for (int sp = 0; sp < 3 * ne; ++sp) {
    const double pm = sig[3 * sp], q = sig[3 * sp + 1], tau = sig[3 * sp + 2];
    sol.stress(sp, 0) = pm + q;
    sol.stress(sp, 1) = pm - q;
    sol.stress(sp, 2) = tau;
    const double d = model.k * r.z[lp_rows + 3 * sp];
    sol.point_dissipation[sp] = d;
    sol.plastic_dissipation += d;
    sol.element_dissipation_density[sp / 3] += d;
  }
  for (int e = 0; e < ne; ++e) sol.element_dissipation_density[e] /= mesh.area(e);
  return sol;
}

LimitSolution solve_limit_coulomb(LimitModel model, const SocpSettings& settings, const CoulombOptions& opt,
                                  CoulombReport* report) {
  if (opt.anderson_depth < 0) throw InputError("anderson_depth", "must be >= 0");
  if (!(opt.relaxation > 0.0 && opt.relaxation <= 1.0)) throw InputError("relaxation", "must be in (0, 1]");
  const bool on_slip = opt.variable == CoulombVariable::slip;
  if (on_slip)
    for (const auto& c : model.contacts)
      if (!(c.mu > 0.0)) throw InputError("coulomb_variable", "the fixed point on the slip needs mu > 0 at every contact node");
  CoulombReport rep;
  auto solve = [&]() {
    LimitSolution s = solve_limit(model, settings);
    rep.ipm_iterations.push_back(s.socp.iterations);
    return s;
  };
  // the iterate x (pressure p or imposed normal velocity g) and its image G(x) from a solution
  auto image = [&](const LimitSolution& s) -> VectorXd {
    if (!on_slip) return (-s.contact_rn).cwiseMax(0.0);
    VectorXd g(s.contact_wt.size());
    for (Eigen::Index c = 0; c < g.size(); ++c) g[c] = model.contacts[static_cast<std::size_t>(c)].mu * std::abs(s.contact_wt[c]);
    return g;
  };
  auto apply = [&](const VectorXd& x) {
    for (std::size_t c = 0; c < model.contacts.size(); ++c) {
      auto& cn = model.contacts[c];
      const double xc = x[static_cast<Eigen::Index>(c)];
      if (on_slip)
        cn.normal_velocity = xc;
      else
        cn.tresca_bound = cn.mu * xc;
    }
  };
  if (opt.start.size() > 0 && (opt.start.size() != static_cast<Eigen::Index>(model.contacts.size()) ||
                               !opt.start.allFinite() || opt.start.minCoeff() < 0.0))
    throw InputError("start", "one finite value >= 0 per contact node");
  if (opt.start.size() > 0 && opt.max_iter < 1) throw InputError("max_iter", "must be >= 1 with a start");
  // start: the given iterate, or the associated (coupled) formulation's pressure and slip
  for (auto& c : model.contacts) {
    c.tresca_bound = std::numeric_limits<double>::quiet_NaN();
    c.normal_velocity = 0.0;
  }
  LimitSolution sol;
  VectorXd p;
  if (opt.start.size() > 0) {
    p = opt.start;
  } else {
    sol = solve();
    p = image(sol);
    rep.collapse_history.push_back(sol.collapse);
    rep.iterate = p;
  }
  std::deque<VectorXd> dp, df;  // Anderson history: differences of iterates and residuals
  VectorXd p_prev, f_prev;
  for (int it = 1; it <= opt.max_iter; ++it) {
    apply(p);
    sol = solve();
    const VectorXd g = image(sol);
    const VectorXd f = g - p;
    const double change = f.cwiseAbs().maxCoeff() / std::max(1e-12, g.cwiseAbs().maxCoeff());
    rep.iterations = it;
    rep.change = change;
    rep.change_history.push_back(change);
    rep.collapse_history.push_back(sol.collapse);
    rep.iterate = g;
    if (change < opt.tol) {
      rep.converged = true;
      break;
    }
    VectorXd next = p + opt.relaxation * f;
    if (opt.anderson_depth > 0) {
      if (f_prev.size() == f.size()) {
        if (f.norm() > opt.anderson_restart * f_prev.norm()) {
          dp.clear();
          df.clear();
        } else {
          dp.push_back(p - p_prev);
          df.push_back(f - f_prev);
          if (static_cast<int>(df.size()) > opt.anderson_depth) {
            dp.pop_front();
            df.pop_front();
          }
        }
      }
      p_prev = p;
      f_prev = f;
      if (!df.empty()) {
        Eigen::MatrixXd F(f.size(), static_cast<Eigen::Index>(df.size())), P(f.size(), static_cast<Eigen::Index>(df.size()));
        for (std::size_t j = 0; j < df.size(); ++j) {
          F.col(static_cast<Eigen::Index>(j)) = df[j];
          P.col(static_cast<Eigen::Index>(j)) = dp[j];
        }
        const VectorXd gamma = F.colPivHouseholderQr().solve(f);
        if (gamma.allFinite()) next -= (P + opt.relaxation * F) * gamma;
      }
    }
    p = next.cwiseMax(0.0);
  }
  if (report) *report = rep;
  return sol;
}

// ------------------------------------------------------------------------------------------
// Verification models
// ------------------------------------------------------------------------------------------
LimitModel strip_tension_model(double length, double width, int nx, int ny, Pattern pattern) {
  LimitModel m;
  m.mesh = structured_quad({0, 0}, {length, 0}, {length, width}, {0, width}, uniform_grid(nx), uniform_grid(ny), pattern);
  const double tol = 1e-9 * length;
  for (int i = 0; i < m.mesh.num_nodes(); ++i) {
    const Vector2d& x = m.mesh.nodes[static_cast<std::size_t>(i)];
    if (std::abs(x.x()) < tol) {
      m.fix(i, 0);
      if (std::abs(x.y()) < tol) m.fix(i, 1);
    }
  }
  m.add_traction([&](const Vector2d& x) { return std::abs(x.x() - length) < tol; }, {1.0, 0.0}, false);
  return m;
}

LimitModel prandtl_punch_model(double B, int n, double grading, Pattern pattern) {
  // half model x ∈ [0, 5B], y ∈ [−3B, 0]; punch on 0 ≤ x ≤ B; refined toward the punch corner
  const double L = 5.0 * B, D = 3.0 * B;
  const int n1 = std::max(2, n), n2 = std::max(2, 2 * n), ny = std::max(2, 2 * n);
  const auto xi = piecewise_grid({0.0, B / L, 1.0}, {graded_grid(n1, grading, 1.0), graded_grid(n2, grading, 0.0)});
  const auto eta = graded_grid(ny, grading, 1.0);
  return prandtl_punch_on_mesh(structured_quad({0, -D}, {L, -D}, {L, 0}, {0, 0}, xi, eta, pattern), B);
}

LimitModel prandtl_punch_on_mesh(Mesh mesh, double B) {
  const double L = 5.0 * B, D = 3.0 * B;
  LimitModel m;
  m.mesh = std::move(mesh);
  const double tol = 1e-9 * B;
  for (int i = 0; i < m.mesh.num_nodes(); ++i) {
    const Vector2d& x = m.mesh.nodes[static_cast<std::size_t>(i)];
    const bool top = std::abs(x.y()) < tol;
    if (std::abs(x.x()) < tol) m.fix(i, 0);                          // symmetry
    if (std::abs(x.y() + D) < tol || std::abs(x.x() - L) < tol) {    // far boundary: fixed
      m.fix(i, 0);
      m.fix(i, 1);
    }
    if (top && x.x() <= B + tol) m.fix(i, 1, -1.0);                  // smooth rigid punch
  }
  return m;
}

std::vector<int> dorfler_mark(const LimitSolution& sol, int num_elements, double fraction) {
  std::vector<std::pair<double, int>> d(static_cast<std::size_t>(num_elements));
  double total = 0.0;
  for (int e = 0; e < num_elements; ++e) {
    const double de = sol.point_dissipation.segment(3 * e, 3).sum();
    d[static_cast<std::size_t>(e)] = {de, e};
    total += de;
  }
  std::sort(d.begin(), d.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<int> marked;
  double acc = 0.0;
  for (const auto& [de, e] : d) {
    if (acc >= fraction * total) break;
    marked.push_back(e);
    acc += de;
  }
  return marked;
}

Mesh adapt_mesh(const Mesh& mesh, const LimitSolution& sol, const AdaptOptions& opt) {
  if (!(opt.fraction > 0.0 && opt.fraction <= 1.0)) throw InputError("fraction", "must be in (0, 1]");
  const std::vector<int> marked = dorfler_mark(sol, mesh.num_elements(), opt.fraction);
  if (!opt.anisotropic) return refine(mesh, marked);
  if (!(opt.max_aspect >= 1.0)) throw InputError("max_aspect", "must be >= 1");
  const Metrics hess = recovered_hessian(mesh, sol.element_dissipation_density);
  Metrics metric(hess.size());
  for (std::size_t e = 0; e < hess.size(); ++e) metric[e] = shape_metric(hess[e], opt.max_aspect);
  return refine_anisotropic(mesh, marked, metric, opt.theta, opt.swap_passes);
}

std::vector<AdaptStep> adapt_limit(const Mesh& initial, const std::function<LimitModel(Mesh)>& build,
                                   const AdaptOptions& opt, const SocpSettings& settings, LimitSolution* final_solution,
                                   Mesh* final_mesh) {
  std::vector<AdaptStep> steps;
  Mesh mesh = initial;
  LimitSolution sol;
  for (int step = 0;; ++step) {
    const LimitModel model = build(mesh);
    sol = solve_limit(model, settings);
    steps.push_back({model.mesh.num_elements(), sol.collapse, sol.socp.seconds, sol.socp.iterations});
    if (step == opt.steps) break;
    mesh = adapt_mesh(model.mesh, sol, opt);
  }
  if (final_solution) *final_solution = std::move(sol);
  if (final_mesh) *final_mesh = std::move(mesh);
  return steps;
}

LimitModel frictional_block_model(double W, double H, double q, double mu, int nx, int ny) {
  LimitModel m;
  m.mesh = structured_quad({0, 0}, {W, 0}, {W, H}, {0, H}, uniform_grid(nx), uniform_grid(ny), Pattern::union_jack);
  const double tol = 1e-9 * std::max(W, H);
  m.add_traction([&](const Vector2d& x) { return std::abs(x.y() - H) < tol; }, {0.0, -q}, true);
  m.add_traction([&](const Vector2d& x) { return std::abs(x.x()) < tol; }, {1.0, 0.0}, false);
  m.add_contact(boundary_nodes(m.mesh, [&](const Vector2d& x) { return std::abs(x.y()) < tol; }), mu);
  return m;
}

}  // namespace cutbench::limit
