#include "cutbench/common/driver.hpp"
#include "cutbench/common/glossary.hpp"
#include "cutbench/efg/cutting.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "cutbench/common/checkpoint.hpp"
#include "cutbench/common/errors.hpp"

namespace cutbench::efg {

std::vector<Vec2> edge_vertices(const Vec2& E, double rake, double clearance, double radius, int segments) {
  if (!(radius > 0.0)) return {E};
  if (segments < 1) throw InputError("edge_segments", "must be >= 1");
  // Inward normals of the rake face (through E along (-sin rake, cos rake)) and of the clearance
  // face (through E along (-cos clearance, sin clearance)); the edge circle is tangent to both.
  const Vec2 n1(-std::cos(rake), -std::sin(rake)), n2(std::sin(clearance), std::cos(clearance));
  Eigen::Matrix2d A;
  A << n1.x(), n1.y(), n2.x(), n2.y();
  const Vec2 C = E + A.inverse() * Vec2(radius, radius);
  // Arc from the clearance-face tangent point to the rake-face tangent point, counter-clockwise.
  const double a0 = std::atan2(-n2.y(), -n2.x()), a1 = std::atan2(-n1.y(), -n1.x());
  std::vector<Vec2> v;
  for (int k = 0; k <= segments; ++k) {
    const double a = a0 + (a1 - a0) * k / segments;
    v.push_back(C + radius * Vec2(std::cos(a), std::sin(a)));
  }
  return v;
}

EdgeSurfacePath::EdgeSurfacePath(std::vector<Vec2> gauss, double hx, double hy, double y_edge, double top)
    : x_(std::move(gauss)), hx_(hx), hy_(hy), yE_(y_edge), top_(top) {
  const double r = 0.75 * std::max(hx, hy);
  CellList cl;
  cl.build(x_, r);
  std::vector<int> near;
  start_.assign(1, 0);
  for (std::size_t g = 0; g < x_.size(); ++g) {
    cl.query(x_[g], r, near);
    for (int k : near) {
      if (k != static_cast<int>(g) && (x_[k] - x_[g]).norm() < r) adj_.push_back(k);
    }
    start_.push_back(static_cast<int>(adj_.size()));
  }
  seen_.resize(x_.size());
}

bool EdgeSurfacePath::connected(const std::function<bool(std::size_t)>& failed, double cut_tip, bool ahead_only) {
  std::fill(seen_.begin(), seen_.end(), 0);
  queue_.clear();
  const double xmin = cut_tip - hx_;
  for (std::size_t g = 0; g < x_.size(); ++g) {
    const Vec2& X = x_[g];
    if (X.y() > yE_ && X.y() < yE_ + 1.5 * hy_ && X.x() > xmin && X.x() < cut_tip + 1.5 * hx_ && failed(g)) {
      seen_[g] = 1;
      queue_.push_back(static_cast<int>(g));
    }
  }
  for (std::size_t q = 0; q < queue_.size(); ++q) {
    const int g = queue_[q];
    if (x_[g].y() > top_ - 0.5 * hy_) return true;
    for (int e = start_[g]; e < start_[g + 1]; ++e) {
      const int k = adj_[e];
      if (seen_[k] || (ahead_only && (x_[k].x() <= xmin || x_[k].y() <= yE_))) continue;
      if (failed(static_cast<std::size_t>(k))) {
        seen_[k] = 1;
        queue_.push_back(k);
      }
    }
  }
  return false;
}

bool DropDetector::update(double dt, bool collapse_event, bool guard, double travel, bool armed) {
  bool fire = false;
  if (drop_ > 0.0 && armed && (dt < (1.0 - drop_) * mean_ || collapse_event)) {
    if (first_drop_ < 0.0) first_drop_ = travel;
    if (guard) {
      fire = true;
      ratio_ = dt / mean_;
    }
  }
  mean_ += (dt - mean_) / window_;
  return fire;
}

void DropDetector::save(BinaryWriter& w) const {
  for (double d : {mean_, first_drop_, ratio_}) w.f64(d);
}

void DropDetector::load(BinaryReader& r) {
  mean_ = r.f64();
  first_drop_ = r.f64();
  ratio_ = r.f64();
}

namespace {
void write_cutting_snapshot(BinaryWriter& w, const CuttingSnapshot& sn) {
  w.f64(sn.t);
  w.f64(sn.travel);
  for (const auto* v : {&sn.x, &sn.y, &sn.fibre, &sn.matrix}) w.vec(*v);
}
CuttingSnapshot read_cutting_snapshot(BinaryReader& r) {
  CuttingSnapshot sn;
  sn.t = r.f64();
  sn.travel = r.f64();
  for (auto* v : {&sn.x, &sn.y, &sn.fibre, &sn.matrix}) *v = r.vec();
  return sn;
}
}  // namespace

namespace {
// The explicit solver's options of a cutting run: kinematics, time step, failure and erosion.
ExplicitOptions explicit_options(const CuttingSetup& s) {
  ExplicitOptions opt;
  opt.kinematics = s.kinematics;
  opt.update_interval = s.update_interval;
  opt.cfl = s.cfl;
  opt.failure.enabled = true;
  opt.failure.criterion = s.criterion;
  opt.failure.lamina = s.lamina;
  opt.failure.residual = s.residual;
  opt.failure.degradation = s.degradation;
  opt.erosion = s.erosion;
  opt.collapse_ratio = s.collapse_ratio;
  return opt;
}

// The tool: cutting edge at E, rake face at `rake` from the vertical, clearance face rising
// backwards at `clearance`, 4 workpiece heights tall and long; moves along +x at V after a ramp of
// `ramp_transits` wave transits of the workpiece height Ly.
RigidTool cutting_tool(const CuttingSetup& s, const Vec2& E, double V, double Ly) {
  const double T = 4.0 * s.work_height, W = 4.0 * s.work_height;
  RigidTool tool;
  tool.vertices = edge_vertices(E, s.rake, s.clearance, s.edge_radius, s.edge_segments);
  tool.vertices.push_back(E + Vec2(-T * std::tan(s.rake), T));
  tool.vertices.push_back(E + Vec2(-W, T));
  tool.vertices.push_back(E + Vec2(-W, W * std::tan(s.clearance)));
  tool.velocity = Vec2(V, 0.0);
  tool.mu = s.mu;
  tool.ramp_time = s.ramp_transits * Ly / s.material.wave_speed();
  return tool;
}
}  // namespace

namespace {
// Damage at the end of the run: failed Gauss points by mode, eroded ones, and the damaged shares of
// the chip (above the cut line, ahead of the notch, behind the fibre line through the edge) and of
// the layer one depth of cut below the cut line.
void damage_census(const CuttingSetup& s, const Discretisation& d, const ExplicitEFG& solver, double x0, double yE,
                   double tr_end, CuttingResult& r) {
  const double cot = std::abs(std::tan(s.theta)) > 1e-12 ? 1.0 / std::tan(s.theta) : 1e12;
  for (std::size_t g = 0; g < solver.num_gauss(); ++g) {
    const auto dm = solver.damage(g);
    r.fibre_damaged += dm[0] > 0.5;
    r.matrix_damaged += dm[1] > 0.5;
    r.interface_damaged += dm[2] > 0.5;
    r.eroded += solver.eroded(g);
    const Vec2& X = d.gauss[g].x;  // reference position (total Lagrangian)
    if (X.y() > yE && X.x() >= x0 && (cot <= 0.0 || X.x() - (x0 + tr_end) <= (X.y() - yE) * cot)) {
      ++r.chip_gauss;
      r.chip_fibre += dm[0] > 0.5;
      r.chip_matrix += dm[1] > 0.5;
    }
    if (X.y() < yE && X.y() > yE - s.depth && X.x() >= x0 && X.x() <= x0 + tr_end + s.depth) {
      ++r.sub_gauss;
      r.sub_fibre += dm[0] > 0.5;
      r.sub_matrix += dm[1] > 0.5;
    }
  }
  r.released = solver.released_count();
  r.collapse_eroded = solver.collapse_eroded_count();
  r.opaque_segments = solver.opaque_segments().size();
}
}  // namespace

CuttingResult run_cutting(const CuttingSetup& s, const std::function<void(double)>& progress) {
  if (!(s.depth > 0.0)) throw InputError(glossary::kDepthOfCut, "must be > 0");
  if (s.depth >= s.work_height) throw InputError(glossary::kDepthOfCut, "must be smaller than the workpiece height");
  if (!(s.spacing > 0.0) || s.spacing > 0.5 * s.depth) throw InputError("spacing", "must be in (0, depth/2]");
  if (!(s.notch > 0.0) || s.notch >= s.work_length) throw InputError("notch", "must be in (0, work_length)");
  if (s.drop < 0.0 || s.drop >= 1.0) throw InputError("drop", "must be in [0, 1)");
  // Lattice: columns at hx = spacing; rows at hy = depth/(nd + 1/2) so that the cut line
  // y_E = H - depth lies half-way between two rows (no node on the cut line).
  const double hx = s.spacing;
  const int nd = std::max(2, static_cast<int>(std::lround(s.depth / s.spacing)));
  const double hy = s.depth / (nd + 0.5);
  const int nx = static_cast<int>(std::lround(s.work_length / hx)) + 1;
  const int ny = std::max(nd + 3, static_cast<int>(std::lround(s.work_height / hy)) + 1);
  const double Lx = (nx - 1) * hx, Ly = (ny - 1) * hy;
  const double yE = Ly - s.depth;
  const double x0 = std::max(1.0, std::round(s.notch / hx)) * hx;
  const Discretisation d = notched_rectangle(Lx, Ly, nx, ny, s.support_factor, x0, yE);
  // Fibres along (cos theta, sin theta) with the tool moving +x: for 0 < theta < 90 deg they rise
  // ahead of the tool from the edge to the free surface, the path along which the paper's chips
  // separate (sections 5.2 and 6).
  ExplicitEFG solver(d, s.material, s.theta, explicit_options(s));
  const double tol = 1e-9 * Lx;
  std::vector<int> surface_row;  // nodes of the row just below the cut line, by x
  for (std::size_t I = 0; I < d.nodes.size(); ++I) {
    const Vec2& X = d.nodes[I];
    if (X.y() < tol || X.x() > Lx - tol) {  // held on the bottom and the far end
      solver.add_velocity_bc(static_cast<int>(I), 0, [](double) { return 0.0; });
      solver.add_velocity_bc(static_cast<int>(I), 1, [](double) { return 0.0; });
    }
    if (std::abs(X.y() - (yE - 0.5 * hy)) < 1e-6 * hy) surface_row.push_back(static_cast<int>(I));
  }
  std::sort(surface_row.begin(), surface_row.end(),
            [&](int a, int b) { return d.nodes[a].x() < d.nodes[b].x(); });
  // Visibility: the re-entrant corner of the notch (its floor and its face, a quarter spacing
  // inside the void) hides nodes across the void from the chip root.
  const double xf = x0 - 0.25 * hx;
  if (s.visibility) {
    solver.add_opaque_segment({Vec2(-hx, yE), Vec2(xf, yE)});
    solver.add_opaque_segment({Vec2(xf, yE), Vec2(xf, Ly + hx)});
  }
  // Tool: cutting edge at (x_E, y_E), rake face at `rake` from the vertical, clearance face
  // rising backwards at `clearance`; moves along +x. Starts a quarter spacing from the chip.
  const double V = s.speed * s.time_scale;
  const double gap = 0.25 * hx;
  const Vec2 E(x0 - gap, yE);
  const RigidTool tool = cutting_tool(s, E, V, Ly);
  solver.set_tool(tool);

  CuttingResult r;
  r.nodes = static_cast<int>(d.nodes.size());
  r.gauss = solver.num_gauss();
  r.hx = hx;
  r.hy = hy;
  r.y_edge = yE;
  // Contact when the tool has moved by the gap (during or after the ramp).
  r.t_contact_expected = gap < 0.5 * V * tool.ramp_time ? std::sqrt(2.0 * gap * tool.ramp_time / V)
                                                         : gap / V + 0.5 * tool.ramp_time;
  r.dt_initial = solver.critical_time_step() * s.cfl;
  r.dt_min = r.dt_initial;
  auto travel_at = [&](double t) { return std::max(0.0, tool.displacement(t).x() - gap); };
  const double t_end = (s.travel + gap) / V + 0.5 * tool.ramp_time;
  Vec2 acc = Vec2::Zero(), acc_all = Vec2::Zero();
  double tacc = 0.0, tacc_all = 0.0;
  int nacc = 0;
  double cut_tip = xf;  // reference x of the cut line's end
  std::vector<CuttingSnapshot> cand;
  double next_snap = 0.0;
  auto take_snapshot = [&]() {
    CuttingSnapshot sn;
    sn.t = solver.time();
    sn.travel = travel_at(sn.t);
    for (std::size_t g = 0; g < solver.num_gauss(); ++g) {
      const Vec2 x = solver.gauss_position(g);
      const auto dm = solver.damage(g);
      sn.x.push_back(x.x());
      sn.y.push_back(x.y());
      sn.fibre.push_back(dm[0]);
      sn.matrix.push_back(dm[1]);
    }
    cand.push_back(std::move(sn));
  };
  // Edge-to-surface path search in the reference configuration (completion guard, diagnostics).
  std::vector<Vec2> gx(d.gauss.size());
  for (std::size_t g = 0; g < gx.size(); ++g) gx[g] = d.gauss[g].x;
  EdgeSurfacePath paths(std::move(gx), hx, hy, yE, Ly);
  auto damaged = [&](std::size_t g) {
    const auto dm = solver.damage(g);
    return dm[0] > 0.5 || dm[1] > 0.5;
  };
  auto separated = [&](std::size_t g) { return solver.eroded(g); };
  bool path = false, sep = false;
  std::size_t ncoll_prev = 0;
  DropDetector detector(s.drop, s.drop_window, r.dt_initial);
  // The loop through the shared driver (checkpoints of cutbench run --run-cache): the solver state
  // and every accumulator of this loop are the run's state.
  auto loop_state = [&](auto&& f64, auto&& vec) {
    for (double* p : {&acc.x(), &acc.y(), &acc_all.x(), &acc_all.y(), &tacc, &tacc_all, &cut_tip, &next_snap,
                      &r.t_contact, &r.dt_min, &r.Fc_peak, &r.travel_first_failure, &r.Fc_first_failure,
                      &r.travel_path, &r.travel_separated})
      f64(*p);
    for (std::vector<double>* v : {&r.t, &r.travel, &r.Fc, &r.Ft, &r.dt}) vec(*v);
  };
  bool stopped = false;
  CallbackRun loop;
  loop.finished = [&] { return stopped || !(solver.time() < t_end); };
  loop.count = [&] { return static_cast<std::size_t>(solver.steps()); };
  loop.saver = [&](BinaryWriter& w) {
    solver.save_state(w);
    detector.save(w);
    loop_state([&](double& x) { w.f64(x); }, [&](std::vector<double>& v) { w.vec(v); });
    for (std::uint64_t u : {static_cast<std::uint64_t>(nacc), static_cast<std::uint64_t>(path),
                            static_cast<std::uint64_t>(sep), static_cast<std::uint64_t>(ncoll_prev)})
      w.u64(u);
    w.u64(cand.size());
    for (const auto& sn : cand) write_cutting_snapshot(w, sn);
  };
  loop.loader = [&](BinaryReader& rd) {
    solver.load_state(rd);
    detector.load(rd);
    loop_state([&](double& x) { x = rd.f64(); }, [&](std::vector<double>& v) { v = rd.vec(); });
    nacc = static_cast<int>(rd.u64());
    path = rd.u64() != 0;
    sep = rd.u64() != 0;
    ncoll_prev = static_cast<std::size_t>(rd.u64());
    cand.clear();
    for (auto k = rd.u64(); k > 0; --k) cand.push_back(read_cutting_snapshot(rd));
  };
  loop.step = [&] {
    const double dt = solver.step();
    r.dt_min = std::min(r.dt_min, dt);
    if (r.t_contact < 0 && solver.contact_count() > 0) r.t_contact = solver.time();
    const double trav = travel_at(solver.time());
    // Chip completion: sudden drop of the Eq 56 step below its running mean (section 5.4). A
    // collapse-erosion event counts as a drop: it intercepts a step that would have fallen below
    // collapse_ratio x its initial value.
    const std::size_t ncoll = solver.collapse_eroded_count();
    const bool collapse_event = ncoll > ncoll_prev;
    ncoll_prev = ncoll;
    const bool guard = s.completion_guard == CompletionGuard::none ||
                       (s.completion_guard == CompletionGuard::damage_path && path) ||
                       (s.completion_guard == CompletionGuard::separation && sep);
    if (detector.update(dt, collapse_event, guard, trav, trav >= s.min_travel)) {
      r.t_complete = solver.time();
      r.travel_complete = trav;
      r.dt_drop_ratio = detector.ratio();
    }
    const Vec2 f = solver.tool_force();
    acc += f * dt;
    tacc += dt;
    if (r.t_contact >= 0) {
      acc_all += f * dt;
      tacc_all += dt;
    }
    // Cut line: the tool edge separates the chip from the machined surface; the cut reaches the
    // reference position of the surface-row material the edge has passed (interpolated).
    if (s.visibility) {
      const double xe = E.x() + tool.displacement(solver.time()).x();
      const auto& xs = solver.positions();
      double tip = cut_tip;
      for (std::size_t k = 0; k + 1 < surface_row.size(); ++k) {
        const int a = surface_row[k], b = surface_row[k + 1];
        if (xs[a].x() <= xe && xs[b].x() > xe) {
          const double u = (xe - xs[a].x()) / (xs[b].x() - xs[a].x());
          tip = d.nodes[a].x() + u * (d.nodes[b].x() - d.nodes[a].x());
          break;
        }
      }
      if (tip >= cut_tip + 0.5 * hx) {
        solver.add_opaque_segment({Vec2(cut_tip, yE), Vec2(tip, yE)});
        cut_tip = tip;
      }
    }
    if (++nacc == s.record_every || r.t_complete >= 0.0) {
      r.t.push_back(solver.time());
      r.travel.push_back(trav);
      r.Fc.push_back(-acc.x() / tacc);  // resistance of the workpiece to the tool's advance
      r.Ft.push_back(acc.y() / tacc);   // thrust: pushes the tool away from the workpiece (+y)
      r.dt.push_back(dt);
      r.Fc_peak = std::max(r.Fc_peak, r.Fc.back());
      acc.setZero();
      tacc = 0.0;
      nacc = 0;
      if (progress) progress(solver.time() / t_end);
      if (r.travel_first_failure < 0.0 && r.t_contact >= 0.0) {
        for (std::size_t g = 0; g < solver.num_gauss(); ++g) {
          const auto dm = solver.damage(g);
          if (dm[0] + dm[1] + dm[2] > 0.0) {
            r.travel_first_failure = trav;
            r.Fc_first_failure = r.Fc.back();
            break;
          }
        }
      }
      if (!path && r.t_contact >= 0.0 && paths.connected(damaged, cut_tip, false)) {
        path = true;
        r.travel_path = trav;
      }
      if (!sep && r.t_contact >= 0.0 && paths.connected(separated, cut_tip, true)) {
        sep = true;
        r.travel_separated = trav;
      }
      if (s.snapshots > 0 && trav >= next_snap) {
        take_snapshot();
        next_snap = trav + 0.25 * hx;
      }
    }
    if (r.t_complete >= 0.0 || dt < 1e-3 * r.dt_initial) stopped = true;  // completed; collapsed nodes: broken
  };
  const DriveReport drive_report = drive(loop, "efg_cutting");
  r.resumed_from_step = static_cast<long>(drive_report.resumed_from_step);
  r.checkpoints_written = drive_report.checkpoints_written;
  r.checkpoint_error = drive_report.checkpoint_error;
  r.steps = solver.steps();
  r.travel_first_drop = detector.first_drop();
  if (tacc_all > 0.0) {
    r.Fc_mean = -acc_all.x() / tacc_all;
    r.Ft_mean = acc_all.y() / tacc_all;
  }
  // Final state and the snapshots nearest k/n of the run.
  take_snapshot();
  if (s.snapshots > 0) {
    const double tr_end = cand.back().travel;
    for (int k = 1; k <= s.snapshots; ++k) {
      const double target = tr_end * k / s.snapshots;
      std::size_t best = 0;
      for (std::size_t c = 0; c < cand.size(); ++c) {
        if (std::abs(cand[c].travel - target) < std::abs(cand[best].travel - target)) best = c;
      }
      r.snapshots.push_back(cand[best]);
    }
  }
  damage_census(s, d, solver, x0, yE, travel_at(solver.time()), r);
  return r;
}

}  // namespace cutbench::efg
