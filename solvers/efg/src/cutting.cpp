#include "cutbench/common/driver.hpp"
#include "cutbench/common/glossary.hpp"
#include "cutbench/efg/cutting.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <optional>
#include <cmath>
#include <cstdio>

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
ExplicitOptions explicit_options(const CuttingSetup& s, double y_cut) {
  ExplicitOptions opt;
  opt.kinematics = s.kinematics;
  opt.update_interval = s.update_interval;
  opt.cfl = s.cfl;
  opt.failure.enabled = true;
  opt.failure.criterion = s.criterion;
  opt.failure.lamina = s.lamina;
  opt.failure.residual = s.residual;
  opt.failure.degradation = s.degradation;
  opt.failure.growth = s.growth;
  opt.failure.S_sigma = s.S_sigma;
  opt.failure.S_tau = s.S_tau;
  opt.failure.zone_y_min = y_cut;  // the cutting zone: the layer the tool removes (above the cut line)
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

namespace {
// The node lattice of a cutting run: columns at hx = spacing; rows at hy = depth/(nd + 1/2) so that
// the cut line y_E = H - depth lies half-way between two rows (no node on the cut line); the notch
// (already cut) ends at x0.
struct Lattice {
  double hx = 0.0, hy = 0.0, Lx = 0.0, Ly = 0.0, yE = 0.0, x0 = 0.0;
  int nx = 0, ny = 0;
};

Lattice cutting_lattice(const CuttingSetup& s) {
  if (!(s.depth > 0.0)) throw InputError(glossary::kDepthOfCut, "must be > 0");
  if (s.depth >= s.work_height) throw InputError(glossary::kDepthOfCut, "must be smaller than the workpiece height");
  if (!(s.spacing > 0.0) || s.spacing > 0.5 * s.depth) throw InputError("spacing", "must be in (0, depth/2]");
  if (!(s.notch > 0.0) || s.notch >= s.work_length) throw InputError("notch", "must be in (0, work_length)");
  if (s.drop < 0.0 || s.drop >= 1.0) throw InputError("drop", "must be in [0, 1)");
  Lattice l;
  l.hx = s.spacing;
  const int nd = std::max(2, static_cast<int>(std::lround(s.depth / s.spacing)));
  l.hy = s.depth / (nd + 0.5);
  l.nx = static_cast<int>(std::lround(s.work_length / l.hx)) + 1;
  l.ny = std::max(nd + 3, static_cast<int>(std::lround(s.work_height / l.hy)) + 1);
  l.Lx = (l.nx - 1) * l.hx;
  l.Ly = (l.ny - 1) * l.hy;
  l.yE = l.Ly - s.depth;
  l.x0 = std::max(1.0, std::round(s.notch / l.hx)) * l.hx;
  return l;
}

// One cutting run as the shared driver sees it: the explicit EFG solver with the tool, the
// visibility cut line, the force windows, chip completion (time-step drop with its guard), the
// edge-to-surface damage paths and the snapshot candidates; the whole state saved for checkpoints.
class CuttingRun final : public SteppedRun {
public:
  CuttingRun(const CuttingSetup& s, const std::function<void(double)>& progress)
      : s_(s), progress_(progress), l_(cutting_lattice(s)),
        d_(notched_rectangle(l_.Lx, l_.Ly, l_.nx, l_.ny, s.support_factor, l_.x0, l_.yE)),
        // Fibres along (cos theta, sin theta) with the tool moving +x: for 0 < theta < 90 deg they
        // rise ahead of the tool from the edge to the free surface, the path along which the
        // paper's chips separate (sections 5.2 and 6).
        solver_(d_, s.material, s.theta, explicit_options(s, l_.yE)),
        xf_(l_.x0 - 0.25 * l_.hx), V_(s.speed * s.time_scale), gap_(0.25 * l_.hx), E_(l_.x0 - gap_, l_.yE),
        tool_(cutting_tool(s, E_, V_, l_.Ly)), paths_(reference_gauss(d_), l_.hx, l_.hy, l_.yE, l_.Ly),
        cut_tip_(xf_) {
    hold_and_find_surface_row();
    // Visibility: the re-entrant corner of the notch (its floor and its face, a quarter spacing
    // inside the void) hides nodes across the void from the chip root.
    if (s.visibility) {
      solver_.add_opaque_segment({Vec2(-l_.hx, l_.yE), Vec2(xf_, l_.yE)});
      solver_.add_opaque_segment({Vec2(xf_, l_.yE), Vec2(xf_, l_.Ly + l_.hx)});
    }
    // Tool: starts a quarter spacing from the chip.
    solver_.set_tool(tool_);
    r_.nodes = static_cast<int>(d_.nodes.size());
    r_.gauss = solver_.num_gauss();
    r_.hx = l_.hx;
    r_.hy = l_.hy;
    r_.y_edge = l_.yE;
    // Contact when the tool has moved by the gap (during or after the ramp).
    r_.t_contact_expected = gap_ < 0.5 * V_ * tool_.ramp_time ? std::sqrt(2.0 * gap_ * tool_.ramp_time / V_)
                                                                : gap_ / V_ + 0.5 * tool_.ramp_time;
    r_.dt_initial = solver_.critical_time_step() * s.cfl;
    r_.dt_min = r_.dt_initial;
    t_end_ = (s.travel + gap_) / V_ + 0.5 * tool_.ramp_time;
    detector_.emplace(s.drop, s.drop_window, r_.dt_initial);
  }

  bool done() const override { return stopped_ || !(solver_.time() < t_end_); }
  std::size_t steps() const override { return static_cast<std::size_t>(solver_.steps()); }

  void advance() override {
    const double dt = solver_.step();
    r_.dt_min = std::min(r_.dt_min, dt);
    if (r_.t_contact < 0 && solver_.contact_count() > 0) r_.t_contact = solver_.time();
    const double trav = travel_at(solver_.time());
    // Chip completion: sudden drop of the Eq 56 step below its running mean (section 5.4). A
    // collapse-erosion event counts as a drop: it intercepts a step that would have fallen below
    // collapse_ratio x its initial value.
    const std::size_t ncoll = solver_.collapse_eroded_count();
    const bool collapse_event = ncoll > ncoll_prev_;
    ncoll_prev_ = ncoll;
    const bool guard = s_.completion_guard == CompletionGuard::none ||
                       (s_.completion_guard == CompletionGuard::damage_path && path_) ||
                       (s_.completion_guard == CompletionGuard::separation && sep_);
    if (detector_->update(dt, collapse_event, guard, trav, trav >= s_.min_travel)) {
      r_.t_complete = solver_.time();
      r_.travel_complete = trav;
      r_.dt_drop_ratio = detector_->ratio();
      r_.dt_mean_at_drop_ratio = dt / detector_->ratio() / r_.dt_initial;
    }
    const Vec2 f = solver_.tool_force();
    acc_ += f * dt;
    tacc_ += dt;
    if (r_.t_contact >= 0) {
      acc_all_ += f * dt;
      tacc_all_ += dt;
    }
    if (s_.visibility) extend_cut_line();
    if (++nacc_ == s_.record_every || r_.t_complete >= 0.0) record_window(dt, trav);
    if (r_.t_complete >= 0.0) {
      stopped_ = true;
    } else if (dt < 1e-3 * r_.dt_initial) {
      // Nodes have collapsed onto each other (a degraded Gauss point squeezed flat): the run cannot
      // go on at any useful cost and its state is no longer the model's, so it is a fault (as an
      // explicit code stops below its minimum step), not a run that ended.
      char msg[256];
      std::snprintf(msg, sizeof msg,
                    "EFG cutting: the Eq. 56 time step fell below 1e-3 of its initial value after %zu steps "
                    "and %.4g um of tool travel, before a chip completion was detected (collapsed nodes)",
                    steps(), 1e6 * trav);
      throw NumericalError(msg);
    }
  }

  // The solver state and every accumulator of the loop.
  void save(BinaryWriter& w) const override {
    solver_.save_state(w);
    detector_->save(w);
    loop_state(*this, [&](double x) { w.f64(x); }, [&](const std::vector<double>& v) { w.vec(v); });
    for (std::uint64_t u : {static_cast<std::uint64_t>(nacc_), static_cast<std::uint64_t>(path_),
                            static_cast<std::uint64_t>(sep_), static_cast<std::uint64_t>(ncoll_prev_)})
      w.u64(u);
    w.u64(cand_.size());
    for (const auto& sn : cand_) write_cutting_snapshot(w, sn);
  }
  void load(BinaryReader& rd) override {
    solver_.load_state(rd);
    detector_->load(rd);
    loop_state(*this, [&](double& x) { x = rd.f64(); }, [&](std::vector<double>& v) { v = rd.vec(); });
    nacc_ = static_cast<int>(rd.u64());
    path_ = rd.u64() != 0;
    sep_ = rd.u64() != 0;
    ncoll_prev_ = static_cast<std::size_t>(rd.u64());
    cand_.clear();
    for (auto k = rd.u64(); k > 0; --k) cand_.push_back(read_cutting_snapshot(rd));
  }

  // The result once the driver is done: mean forces, the snapshots nearest k/n of the run and the
  // final damage census.
  CuttingResult finish(const DriveReport& report) {
    r_.drive = report;
    r_.steps = solver_.steps();
    r_.travel_first_drop = detector_->first_drop();
    if (tacc_all_ > 0.0) {
      r_.Fc_mean = -acc_all_.x() / tacc_all_;
      r_.Ft_mean = acc_all_.y() / tacc_all_;
    }
    take_snapshot();  // the final state
    audit();
    if (s_.snapshots > 0) {
      const double tr_end = cand_.back().travel;
      for (int k = 1; k <= s_.snapshots; ++k) {
        const double target = tr_end * k / s_.snapshots;
        std::size_t best = 0;
        for (std::size_t c = 0; c < cand_.size(); ++c) {
          if (std::abs(cand_[c].travel - target) < std::abs(cand_[best].travel - target)) best = c;
        }
        r_.snapshots.push_back(cand_[best]);
      }
    }
    damage_census(s_, d_, solver_, l_.x0, l_.yE, travel_at(solver_.time()), r_);
    return std::move(r_);
  }

private:
  static std::vector<Vec2> reference_gauss(const Discretisation& d) {
    std::vector<Vec2> gx(d.gauss.size());
    for (std::size_t g = 0; g < gx.size(); ++g) gx[g] = d.gauss[g].x;
    return gx;
  }

  // Nodes on the bottom and the far end held; the row just below the cut line, sorted by x.
  void hold_and_find_surface_row() {
    const double tol = 1e-9 * l_.Lx;
    for (std::size_t I = 0; I < d_.nodes.size(); ++I) {
      const Vec2& X = d_.nodes[I];
      if (X.y() < tol || X.x() > l_.Lx - tol) {
        solver_.add_velocity_bc(static_cast<int>(I), 0, [](double) { return 0.0; });
        solver_.add_velocity_bc(static_cast<int>(I), 1, [](double) { return 0.0; });
      }
      if (std::abs(X.y() - (l_.yE - 0.5 * l_.hy)) < 1e-6 * l_.hy) surface_row_.push_back(static_cast<int>(I));
    }
    std::sort(surface_row_.begin(), surface_row_.end(),
              [&](int a, int b) { return d_.nodes[a].x() < d_.nodes[b].x(); });
  }

  double travel_at(double t) const { return std::max(0.0, tool_.displacement(t).x() - gap_); }

  // Cut line: the tool edge separates the chip from the machined surface; the cut reaches the
  // reference position of the surface-row material the edge has passed (interpolated).
  void extend_cut_line() {
    const double xe = E_.x() + tool_.displacement(solver_.time()).x();
    const auto& xs = solver_.positions();
    double tip = cut_tip_;
    for (std::size_t k = 0; k + 1 < surface_row_.size(); ++k) {
      const int a = surface_row_[k], b = surface_row_[k + 1];
      if (xs[a].x() <= xe && xs[b].x() > xe) {
        const double u = (xe - xs[a].x()) / (xs[b].x() - xs[a].x());
        tip = d_.nodes[a].x() + u * (d_.nodes[b].x() - d_.nodes[a].x());
        break;
      }
    }
    if (tip >= cut_tip_ + 0.5 * l_.hx) {
      solver_.add_opaque_segment({Vec2(cut_tip_, l_.yE), Vec2(tip, l_.yE)});
      cut_tip_ = tip;
    }
  }

  // One force window: its means, the first failure, the damage and separation paths, a snapshot.
  void record_window(double dt, double trav) {
    r_.t.push_back(solver_.time());
    r_.travel.push_back(trav);
    r_.Fc.push_back(-acc_.x() / tacc_);  // resistance of the workpiece to the tool's advance
    r_.Ft.push_back(acc_.y() / tacc_);   // thrust: pushes the tool away from the workpiece (+y)
    r_.dt.push_back(dt);
    audit();
    r_.e_tool.push_back(r_.energy_tool);
    r_.e_kinetic.push_back(r_.energy_kinetic);
    r_.e_strain.push_back(r_.energy_strain);
    r_.e_damage.push_back(r_.energy_damage);
    r_.e_residual.push_back(r_.energy_residual);
    r_.Fc_peak = std::max(r_.Fc_peak, r_.Fc.back());
    acc_.setZero();
    tacc_ = 0.0;
    nacc_ = 0;
    if (progress_) progress_(solver_.time() / t_end_);
    if (r_.travel_first_failure < 0.0 && r_.t_contact >= 0.0) {
      for (std::size_t g = 0; g < solver_.num_gauss(); ++g) {
        const auto dm = solver_.damage(g);
        if (dm[0] + dm[1] + dm[2] > 0.0) {
          r_.travel_first_failure = trav;
          r_.Fc_first_failure = r_.Fc.back();
          break;
        }
      }
    }
    auto damaged = [&](std::size_t g) {
      const auto dm = solver_.damage(g);
      return dm[0] > 0.5 || dm[1] > 0.5;
    };
    auto separated = [&](std::size_t g) { return solver_.eroded(g); };
    if (!path_ && r_.t_contact >= 0.0 && paths_.connected(damaged, cut_tip_, false)) {
      path_ = true;
      r_.travel_path = trav;
    }
    if (!sep_ && r_.t_contact >= 0.0 && paths_.connected(separated, cut_tip_, true)) {
      sep_ = true;
      r_.travel_separated = trav;
    }
    if (s_.snapshots > 0 && trav >= next_snap_) {
      take_snapshot();
      next_snap_ = trav + 0.25 * l_.hx;
    }
  }

  // The energy ledger now (J/m: the model is 1 m thick, as the forces are per unit width): what
  // the contact impulses gave the nodes against kinetic, strain and damage energy.
  void audit() {
    const auto& lg = solver_.energy_ledger();
    r_.energy_tool = lg.tool_work;
    r_.energy_kinetic = solver_.kinetic_energy();
    r_.energy_strain = solver_.strain_energy();
    r_.energy_damage = solver_.damage_dissipation();
    r_.energy_contact_loss = lg.tool_work - lg.contact_work;
    r_.energy_released = -lg.release_kinetic;
    r_.energy_internal = lg.internal_work;
    r_.energy_residual = lg.contact_work + lg.release_kinetic - r_.energy_kinetic - r_.energy_strain - r_.energy_damage;
  }

  void take_snapshot() {
    CuttingSnapshot sn;
    sn.t = solver_.time();
    sn.travel = travel_at(sn.t);
    for (std::size_t g = 0; g < solver_.num_gauss(); ++g) {
      const Vec2 x = solver_.gauss_position(g);
      const auto dm = solver_.damage(g);
      sn.x.push_back(x.x());
      sn.y.push_back(x.y());
      sn.fibre.push_back(dm[0]);
      sn.matrix.push_back(dm[1]);
    }
    cand_.push_back(std::move(sn));
  }

  // Every accumulator of the loop, in checkpoint order (Self: const to save, mutable to load).
  template <class Self, class F64, class Vec>
  static void loop_state(Self& self, F64&& f64, Vec&& vec) {
    for (auto* p : {&self.acc_.x(), &self.acc_.y(), &self.acc_all_.x(), &self.acc_all_.y(), &self.tacc_,
                    &self.tacc_all_, &self.cut_tip_, &self.next_snap_, &self.r_.t_contact, &self.r_.dt_min,
                    &self.r_.Fc_peak, &self.r_.travel_first_failure, &self.r_.Fc_first_failure, &self.r_.travel_path,
                    &self.r_.travel_separated})
      f64(*p);
    for (auto* v : {&self.r_.t, &self.r_.travel, &self.r_.Fc, &self.r_.Ft, &self.r_.dt, &self.r_.e_tool,
                    &self.r_.e_kinetic, &self.r_.e_strain, &self.r_.e_damage, &self.r_.e_residual})
      vec(*v);
  }

  const CuttingSetup& s_;
  const std::function<void(double)>& progress_;
  const Lattice l_;
  const Discretisation d_;
  ExplicitEFG solver_;
  const double xf_, V_, gap_;
  const Vec2 E_;
  const RigidTool tool_;
  EdgeSurfacePath paths_;
  std::vector<int> surface_row_;  // nodes of the row just below the cut line, by x
  CuttingResult r_;
  double t_end_ = 0.0;
  Vec2 acc_ = Vec2::Zero(), acc_all_ = Vec2::Zero();
  double tacc_ = 0.0, tacc_all_ = 0.0;
  int nacc_ = 0;
  double cut_tip_;  // reference x of the cut line's end
  std::vector<CuttingSnapshot> cand_;
  double next_snap_ = 0.0;
  bool path_ = false, sep_ = false, stopped_ = false;
  std::size_t ncoll_prev_ = 0;
  std::optional<DropDetector> detector_;
};
}  // namespace

CuttingResult run_cutting(const CuttingSetup& s, const std::function<void(double)>& progress) {
  CuttingRun run(s, progress);
  const DriveReport report = drive(run, "efg_cutting");
  return run.finish(report);
}

}  // namespace cutbench::efg
