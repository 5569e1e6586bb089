#include "cutbench/mpm/cutting.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cutbench/common/declared.hpp"
#include "cutbench/common/driver.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/common/glossary.hpp"
#include "cutbench/mpm/coverage.hpp"
#include "cutbench/mpm/register.hpp"

namespace cutbench::mpm {

MpmProblem build_cutting_problem(const CuttingSetup& s, double* tool_tip_x0) {
  if (s.particles_through_chip < 2.0) throw InputError("particles_through_chip", "must be >= 2");
  const int nchip = static_cast<int>(std::lround(s.particles_through_chip));
  const double ps = s.h / nchip;  // particle size (4 particles per cell)
  const double dx = 2.0 * ps;
  const int nw = static_cast<int>(std::lround(s.width_factor * s.h / ps));
  const int nbase = std::max(1, static_cast<int>(std::lround(s.base_factor * s.h / ps)));
  const double W = nw * ps, base = nbase * ps;
  const double tool_len = s.tool_length_factor * s.h, tool_hgt = s.tool_height_factor * s.h;

  MpmConfig cfg;
  cfg.material = s.material;
  cfg.numerics = s.numerics;
  GridSpec& g = cfg.grid;
  g.dx = dx;
  const int left_cells = static_cast<int>(std::ceil((tool_len + 2.0 * dx) / dx)) + 1;
  const int below_cells = static_cast<int>(std::ceil(base / dx)) + 2;
  const int above_cells = static_cast<int>(std::ceil(s.chip_room_factor * s.h / dx)) + 2;
  const int right_cells = static_cast<int>(std::ceil(W / dx)) + 3;
  g.x0 = -left_cells * dx;
  g.y0 = -below_cells * dx;
  g.nx = left_cells + right_cells;
  g.ny = below_cells + above_cells;
  // bottom of the specimen fixed in x and y (all nodes at or below it)
  const double ybot = -base;
  cfg.fixed_mask = [ybot, dx](double, double y) { return y <= ybot + 1e-9 * dx ? 3 : 0; };

  // crack just below the node row y = 0 at the tool-tip height
  CrackSpec& c = cfg.crack;
  c.enabled = true;
  c.y = -s.crack_offset * dx;
  c.x_begin = 0.0;
  c.x_end = std::min(W, s.precrack_factor * s.h);
  c.x_free_end = s.free_crack_factor * s.h;
  c.seg_len = ps;
  c.mode1 = TractionLaw::from_toughness(s.law, s.G_c, s.sigma_c);
  c.mode2 = c.mode1;

  ContactSpec& ct = cfg.contact;
  ct.mu = s.mu;
  ct.n_above = Eigen::Vector2d(-std::cos(s.rake), -std::sin(s.rake));  // rake face
  ct.n_below = Eigen::Vector2d(0.0, 1.0);                              // bottom (clearance) face
  ct.gap_factor = s.contact_gap_factor;
  ct.detection = s.contact_detection;
  ct.tool_contact_first = s.contact_order == 1;

  cfg.tool.velocity = Eigen::Vector2d(s.speed, 0.0);
  cfg.tool.t_ramp = s.ramp_fraction * s.total_time;
  if (s.feedback_gain > 0.0 && cfg.tool.t_ramp > 0.0) {
    cfg.damping.gain = s.feedback_gain / (cfg.tool.t_ramp * cfg.tool.t_ramp);
    cfg.damping.t_off = cfg.tool.t_ramp;
    cfg.damping.v_ref = s.speed;
  }

  MpmProblem pb(cfg);
  const double vol = ps * ps;
  // specimen: x in [0, W], y in [-base, h]
  const int nh = nchip;
  for (int j = -nbase; j < nh; ++j) {
    for (int i = 0; i < nw; ++i) pb.add_particle((i + 0.5) * ps, (j + 0.5) * ps, vol, false);
  }
  // tool: wedge behind the tip (xt, 0), bounded by the rake face x = xt - y tan(rake), the
  // clearance face, its height and length. Particle rows at the specimen's row heights, each
  // row's centres aligned with the rake face (the paper: "particle centers were aligned to
  // conform to the tool's rake and clearance angles"): the first centre of a row half a particle
  // size behind the face, so the face is straight at every rake angle.
  const double xt = -0.5 * dx;
  const double ta = std::tan(s.rake), tc = std::tan(s.clearance);
  const int ni = static_cast<int>(std::ceil(tool_len / ps)), nj = static_cast<int>(std::ceil(tool_hgt / ps));
  for (int j = 0; j < nj; ++j) {
    for (int i = 0; i < ni + nj; ++i) {
      const double x = xt - (i + 0.5) * ps - (j + 0.5) * ps * ta;  // rows follow the rake face
      const double y = (j + 0.5) * ps;
      if (y < (xt - x) * tc - 1e-12 * ps) continue;    // below the clearance face
      if (x < xt - tool_len) continue;
      pb.add_particle(x, y, vol, true);
    }
  }
  if (tool_tip_x0) *tool_tip_x0 = xt;
  return pb;
}

BenchResult bench_cutting(const CuttingSetup& s, long warmup, long steps) {
  MpmProblem pb = build_cutting_problem(s);
  pb.setup();
  for (long k = 0; k < warmup; ++k) pb.step();
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) pb.step();
  BenchResult r;
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.particles = pb.size();
  r.steps = steps;
  r.threads = pb.threads();
  r.particle_steps_per_s = r.wall > 0.0 ? static_cast<double>(r.particles) * static_cast<double>(steps) / r.wall : 0.0;
  return r;
}

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDeg = M_PI / 180.0;
}  // namespace

// Every parameter of mpm_cutting, declared once with where it goes in the setup (or read by the
// runner from Values: output interval, steady window, snapshots).
const DeclaredParams<CuttingSetup>& cutting_declaration() {
  using S = CuttingSetup;
  static const DeclaredParams<S> d = [] {
    DeclaredParams<S> p;
    p.bind(param(glossary::kDepthOfCut, Dim::length, "depth of cut h", 0.9e-3, 0.0, kInf, false), &S::h)
        .bind(param(glossary::kRakeAngle, Dim::angle, "tool rake angle alpha", 10.0 * kDeg, -30.0 * kDeg, 60.0 * kDeg), &S::rake)
        .bind(param(glossary::kClearanceAngle, Dim::angle, "tool clearance angle", 5.0 * kDeg, 1.0 * kDeg, 30.0 * kDeg), &S::clearance)
        .add(param("K", Dim::stress, "bulk modulus", 980e6, 0.0, kInf, false), [](S& s, double v) { s.material.K = v; })
        .add(param("G", Dim::stress, "shear modulus", 376e6, 0.0, kInf, false), [](S& s, double v) { s.material.G = v; })
        .add(param("rho", Dim::density, "density", 1000.0, 0.0, kInf, false), [](S& s, double v) { s.material.rho = v; })
        .add(param("sigma_y0", Dim::stress, "initial yield stress", 25e6, 0.0, kInf, false),
             [](S& s, double v) { s.material.sigma_y0 = v; })
        .add(param("E_T", Dim::stress, "tangent modulus of the tensile curve (E_p = E E_T/(E - E_T))", 100e6, 0.0, kInf),
             [](S& s, double v) {  // after K and G (declared before it)
               const double E = s.material.youngs();
               if (v >= E) throw InputError("E_T", "must be below the Young's modulus E = 9KG/(3K+G)");
               s.material.Ep = HyperelasticJ2::plastic_modulus(E, v);
             })
        .bind(param("G_c", Dim::energy_per_area, "cohesive toughness (modes I and II)", 2000.0, 0.0, kInf, false), &S::G_c)
        .bind(param("sigma_c", Dim::stress, "cohesive strength (modes I and II)", 40e6, 0.0, kInf, false), &S::sigma_c)
        .add(option_param("traction_law", "shape of the cohesive traction law",
                          {{"cubic", "the cubic law of Eq. 3"}, {"triangular", "linear softening"}}, "cubic"),
             [](S& s, double v) { s.law = v == 0.0 ? TractionLawType::cubic : TractionLawType::triangular; })
        .bind(param(glossary::kFriction, Dim::dimensionless, "Coulomb friction, tool/material", 0.0, 0.0, 5.0), &S::mu)
        .add(param("pic_fraction", Dim::dimensionless, "PIC damping fraction (paper's 1 - beta): 1 = pure PIC", 1.0, 0.0, 1.0),
             [](S& s, double v) { s.numerics.pic_fraction = v; })
        .add(integer_param("position_order", "order of the particle position update (Eq. 10)", 2.0, 0.0, 2.0),
             [](S& s, double v) { s.numerics.position_order = static_cast<int>(v); })
        .add(option_param("strain_update", "when the particle strain is updated (Numerics::StrainUpdate)",
                          {{"usl", "update stress last: from the updated grid velocities"},
                           {"musl", "modified USL: from the updated particle momenta re-extrapolated to the grid"},
                           {"usavg", "NairnMPM's default (USAVG): half first, from the extrapolated momenta with contact, half last, "
                                     "from the updated particles re-extrapolated at their new positions"}},
                          "usavg"),
             [](S& s, double v) { s.numerics.strain_update = static_cast<Numerics::StrainUpdate>(static_cast<int>(v)); })
        .add(switch_param("musl_recontact",
                          "MUSL only: re-apply tool/crack contact to the re-extrapolated momenta (false: skip it, diagnostic)",
                          true),
             [](S& s, double v) { s.numerics.musl_recontact = v == 1.0; })
        .bind(integer_param("particles_through_chip", "particles through the depth of cut", 15.0, 2.0, 200.0),
              &S::particles_through_chip)
        .bind(param("width_factor", Dim::dimensionless, "specimen width / h", 30.0, 4.0, 200.0), &S::width_factor)
        .bind(param("precrack_factor", Dim::dimensionless,
                    "explicit crack (cohesive) length / h (the paper's a = 18; 26 so that the crack tip stays clear of the crack's end, FINDINGS F03)",
                    26.0, 2.0, 200.0),
              &S::precrack_factor)
        .bind(param("free_crack_factor", Dim::dimensionless, "traction-free start of the crack / h", 2.0, 0.0, 200.0),
              &S::free_crack_factor)
        .bind(param("base_factor", Dim::dimensionless, "depth below the cut plane / h", 3.0, 0.25, 50.0), &S::base_factor)
        .bind(param("tool_height_factor", Dim::dimensionless, "tool height above the cut plane / h", 4.0, 1.0, 50.0),
              &S::tool_height_factor)
        .bind(param("tool_length_factor", Dim::dimensionless, "tool length behind the tip / h", 4.0, 1.0, 50.0),
              &S::tool_length_factor)
        .bind(param("chip_room_factor", Dim::dimensionless, "grid height above the cut plane / h", 12.0, 2.0, 100.0),
              &S::chip_room_factor)
        .bind(param(glossary::kCuttingSpeed, Dim::velocity, "cutting speed V", 2.0, 0.0, 1000.0, false), &S::speed)
        .bind(param("ramp_fraction", Dim::dimensionless, "fraction of the run over which the speed ramps 0 -> V", 0.3, 0.0, 1.0),
              &S::ramp_fraction)
        .bind(param("total_time", Dim::time, "simulated time", 8e-3, 0.0, kInf, false), &S::total_time)
        .declare(param("output_interval", Dim::time, "force-history interval (0: total_time/400)", 0.0, 0.0, kInf))
        .declare(param("steady_start_fraction", Dim::dimensionless, "steady window starts at this fraction of the run", 0.5,
                       0.0, 1.0))
        .declare(param("steady_end_fraction", Dim::dimensionless, "steady window ends at this fraction of the run", 1.0,
                       0.0, 1.0))
        .bind(param("feedback_gain", Dim::dimensionless, "grid-KE feedback damping gain during the ramp (0 = off)", 100.0,
                    0.0, 1e9),
              &S::feedback_gain)
        // at most NairnMPM's default time-step factor (0.5 of the cell crossing time): the explicit
        // update with GIMP shape functions, contact and large strains diverges well before the
        // linear limit 1 (cfl = 0.99 sends particles off the grid)
        .add(param("cfl", Dim::dimensionless, "time step / (dx / c_p)", 0.5, 0.0, 0.5, false),
             [](S& s, double v) { s.numerics.cfl = v; })
        // NairnMPM's LeaveLimit (default: 1 % of the material points): a particle that leaves the
        // grid is returned into it and counted once; more than this fraction stops the run
        .add(param("leave_limit", Dim::dimensionless,
                   "fraction of the deformable particles that may leave the grid (each returned into it; 0: none)", 0.01,
                   0.0, 1.0),
             [](S& s, double v) { s.numerics.leave_limit = v; })
        .add(option_param("contact_detection", "when a tool/material node pair is in contact",
                          {{"velocity", "the approach-velocity test only"},
                           {"nodal_gap", "nodal centres of mass closer than contact_gap_factor*dx"},
                           {"domains", "particle domains touch (within contact_gap_factor*dx)"}},
                          "nodal_gap"),
             [](S& s, double v) { s.contact_detection = static_cast<int>(v); })
        .add(option_param("contact_order", "order of the tool's contact and the crack-face contact at a node",
                          {{"crack_first", "the crack-face contact, then the tool's contact"},
                           {"tool_first", "the tool's contact, then the crack-face contact (NairnMPM's order; "
                                          "multiplies the rubbing force at coarse resolution, FINDINGS F04)"}},
                          "crack_first"),
             [](S& s, double v) { s.contact_order = static_cast<int>(v); })
        .bind(param("contact_gap_factor", Dim::dimensionless, "contact distance / tolerance in cells (see contact_detection)",
                    1.0, 0.0, 10.0),
              &S::contact_gap_factor)
        .declare(integer_param("snapshots", "number of particle snapshots (evenly spaced, last at the end)", 4.0, 0.0, 1000.0))
        .add(integer_param("threads", "OpenMP threads (0 = OMP_NUM_THREADS)", 0.0, 0.0, 1024.0),
             [](S& s, double v) { s.numerics.threads = static_cast<int>(v); });
    return p;
  }();
  return d;
}

std::vector<ParamSpec> cutting_params() { return cutting_declaration().specs(); }

CuttingSetup cutting_setup_from(const Values& v) {
  const CuttingSetup s = cutting_declaration().make(v);
  if (s.free_crack_factor > s.precrack_factor) throw InputError("free_crack_factor", "must not exceed precrack_factor");
  if (s.precrack_factor > s.width_factor) throw InputError("precrack_factor", "must not exceed width_factor");
  return s;
}

namespace {
Snapshot take_snapshot(const MpmProblem& pb) {
  Snapshot s;
  s.time = pb.time();
  const std::size_t n = pb.size();
  s.x.resize(n);
  s.y.resize(n);
  std::vector<double> seq(n), ep(n), fxx(n), fxy(n), fyx(n), fyy(n), rig(n);
  // keep a stable particle order (insertion id) across snapshots
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t q = pb.id(p);
    const Eigen::Vector2d x = pb.position(p);
    s.x[q] = x.x();
    s.y[q] = x.y();
    seq[q] = pb.rigid(p) ? 0.0 : von_mises(pb.cauchy_stress(p));
    ep[q] = pb.plastic_strain(p);
    const Eigen::Matrix2d F = pb.deformation_gradient(p);
    fxx[q] = F(0, 0);
    fxy[q] = F(0, 1);
    fyx[q] = F(1, 0);
    fyy[q] = F(1, 1);
    rig[q] = pb.rigid(p) ? 1.0 : 0.0;
  }
  s.add("sigma_eq", "Pa", std::move(seq));
  s.add("plastic_strain", "1", std::move(ep));
  s.add("F_xx", "1", std::move(fxx));
  s.add("F_xy", "1", std::move(fxy));
  s.add("F_yx", "1", std::move(fyx));
  s.add("F_yy", "1", std::move(fyy));
  s.add("rigid", "1", std::move(rig));
  return s;
}

void mean_std(const std::vector<double>& v, double& mean, double& sd) {
  mean = sd = std::nan("");
  if (v.empty()) return;
  double s = 0.0;
  for (double x : v) s += x;
  mean = s / static_cast<double>(v.size());
  double q = 0.0;
  for (double x : v) q += (x - mean) * (x - mean);
  sd = std::sqrt(q / static_cast<double>(v.size()));
}
}  // namespace

// Step-count bound of one run: far beyond any paper-resolution case (about 2e5 steps), small enough
// that a mistyped total_time is refused instead of overflowing the step count or running for weeks.
constexpr double kMaxSteps = 1e8;

namespace {
// The time loop of one cutting run as the shared driver sees it (common/driver.hpp): one MPM
// step plus its observers (blow-up guard, force-history windows, steady-window energy mark,
// snapshot schedule, progress), with the whole state saved for checkpoints.
class CuttingRun : public SteppedRun {
public:
  CuttingRun(MpmProblem& pb, double T, double out_dt, int nsnap, double t_window, long max_steps,
             const ProgressFn& progress, double xt0)
      : pb_(pb), T_(T), out_dt_(out_dt), nsnap_(nsnap), t_window_(t_window), max_steps_(max_steps),
        progress_(progress), xt0_(xt0), next_out_(out_dt), t0_(std::chrono::steady_clock::now()) {}

  bool done() const override { return pb_.steps() >= max_steps_ || !(pb_.time() < T_ - 0.5 * pb_.dt()); }
  std::size_t steps() const override { return static_cast<std::size_t>(pb_.steps()); }

  void advance() override {
    pb_.step();
    // blow-up guard: a non-finite state or a particle off the grid stops the run (every 16 steps
    // and at the last, so that the scan costs a fraction of a step)
    if (pb_.steps() % 16 == 0 || pb_.steps() == max_steps_ || !std::isfinite(pb_.contact_forces().total.x())) {
      const std::string f = pb_.fault();
      if (!f.empty()) throw std::runtime_error("MPM run stopped: " + f);
    }
    if (!window_open_ && pb_.time() >= t_window_ - 0.5 * pb_.dt()) {
      window_open_ = true;
      e_at_window_ = pb_.released_energy();
      eI_at_window_ = e_at_window_ > 0.0 ? pb_.mode1_fraction() * e_at_window_ : 0.0;
    }
    const ContactForces& f = pb_.contact_forces();
    acc_c_ += f.total.x();
    acc_t_ += -f.total.y();
    acc_nb_ += f.normal_below;
    ++acc_n_;
    if (pb_.time() >= next_out_ - 0.5 * pb_.dt()) {
      const double n = static_cast<double>(acc_n_);
      tt.push_back(pb_.time());
      fc.push_back(acc_c_ / n);
      ft.push_back(acc_t_ / n);
      fnb.push_back(acc_nb_ / n);
      const double xtool = xt0_ + pb_.rigid_displacement().x();
      gap.push_back(pb_.crack_tip_x(xtool - pb_.config().crack.seg_len) - 0.5 * pb_.config().crack.seg_len - xtool);
      alph.push_back(pb_.feedback_alpha());
      const EnergyBalance eb = pb_.energy_balance();
      for (auto [v, x] : {std::pair{&e_tool, eb.audit.tool_work}, {&e_kin, eb.kinetic}, {&e_strain, eb.strain},
                          {&e_plastic, eb.plastic}, {&e_coh, eb.cohesive}, {&e_pic, eb.audit.pic_damping},
                          {&e_fb, eb.audit.feedback_loss}, {&e_inc, eb.audit.increment_loss},
                          {&e_tcl, eb.audit.tool_contact_loss}, {&e_ccl, eb.audit.crack_contact_loss},
                          {&e_slag, eb.stress_lag}, {&e_clag, eb.cohesive_lag}, {&e_res, eb.residual}}) {
        v->push_back(x);
      }
      acc_c_ = acc_t_ = acc_nb_ = 0.0;
      acc_n_ = 0;
      next_out_ += out_dt_;
    }
    if (nsnap_ > 0 && pb_.time() >= T_ * (snap_done_ + 1) / nsnap_ - 0.5 * pb_.dt()) {
      snapshots.push_back(take_snapshot(pb_));
      ++snap_done_;
    }
    const double frac = pb_.time() / T_;
    if (progress_ && frac >= next_progress_) {
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
      std::ostringstream msg;
      msg.precision(3);
      msg << "t = " << pb_.time() * 1e3 << " ms, ETA " << (frac > 0 ? el * (1.0 - frac) / frac : 0.0) << " s";
      progress_(frac, msg.str());
      next_progress_ += 0.01;
    }
  }

  void save(BinaryWriter& w) const override {
    pb_.save_state(w);
    for (const auto* v : {&tt, &fc, &ft, &fnb, &gap, &alph, &e_tool, &e_kin, &e_strain, &e_plastic, &e_coh, &e_pic,
                          &e_fb, &e_inc, &e_tcl, &e_ccl, &e_slag, &e_clag, &e_res}) {
      w.vec(*v);
    }
    for (double d : {acc_c_, acc_t_, acc_nb_, next_out_, e_at_window_, eI_at_window_}) w.f64(d);
    w.u64(static_cast<std::uint64_t>(acc_n_));
    w.u64(static_cast<std::uint64_t>(snap_done_));
    w.u64(window_open_ ? 1 : 0);
    w.u64(snapshots.size());
    for (const auto& sn : snapshots) write_snapshot(w, sn);
  }

  void load(BinaryReader& r) override {
    pb_.load_state(r);
    for (auto* v : {&tt, &fc, &ft, &fnb, &gap, &alph, &e_tool, &e_kin, &e_strain, &e_plastic, &e_coh, &e_pic, &e_fb,
                    &e_inc, &e_tcl, &e_ccl, &e_slag, &e_clag, &e_res}) {
      *v = r.vec();
    }
    for (double* d : {&acc_c_, &acc_t_, &acc_nb_, &next_out_, &e_at_window_, &eI_at_window_}) *d = r.f64();
    acc_n_ = static_cast<long>(r.u64());
    snap_done_ = static_cast<int>(r.u64());
    window_open_ = r.u64() != 0;
    snapshots.clear();
    for (auto n = r.u64(); n > 0; --n) snapshots.push_back(read_snapshot(r));
    next_progress_ = std::floor(pb_.time() / T_ * 100.0) / 100.0;
  }

  double e_at_window() const { return e_at_window_; }
  double eI_at_window() const { return eI_at_window_; }
  double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }

  std::vector<double> tt, fc, ft, fnb, gap, alph;  // force history (output-interval means)
  // energy audit at the output times (MpmProblem::energy_balance)
  std::vector<double> e_tool, e_kin, e_strain, e_plastic, e_coh, e_pic, e_fb, e_inc, e_tcl, e_ccl, e_slag, e_clag, e_res;
  std::vector<Snapshot> snapshots;

private:
  MpmProblem& pb_;
  const double T_, out_dt_;
  const int nsnap_;
  const double t_window_;
  const long max_steps_;
  const ProgressFn& progress_;
  const double xt0_;
  double acc_c_ = 0.0, acc_t_ = 0.0, acc_nb_ = 0.0;
  long acc_n_ = 0;
  double next_out_;
  int snap_done_ = 0;
  // released energy (total and mode I) when the steady window opens, for the steady-state mode mix
  bool window_open_ = false;
  double e_at_window_ = 0.0, eI_at_window_ = 0.0;
  double next_progress_ = 0.0;
  std::chrono::steady_clock::time_point t0_;
};

// The chip's Fig 2 metric (domain gaps and overlaps of the cut chip: material from above the crack,
// originally behind the crack tip) and its curl (Fig 17).
void add_chip_metrics(RunOutput& out, const MpmProblem& pb, const CuttingSetup& s) {
  auto put = [&](const std::string& name, double value, const std::string& unit) { out.set_scalar(name, value, unit); };
  const std::size_t n = pb.size();
  std::vector<double> px(n), py(n), fxx(n), fxy(n), fyx(n), fyy(n);
  std::vector<bool> use(n);
  const double tip = pb.crack_tip_x();
  for (std::size_t p = 0; p < n; ++p) {
    const Eigen::Vector2d x = pb.position(p);
    const Eigen::Matrix2d F = pb.deformation_gradient(p);
    px[p] = x.x();
    py[p] = x.y();
    fxx[p] = F(0, 0);
    fxy[p] = F(0, 1);
    fyx[p] = F(1, 0);
    fyy[p] = F(1, 1);
    use[p] = !pb.rigid(p) && pb.above_crack(p) && pb.reference_position(p).x() < tip;
  }
  const DomainCoverage cov = domain_coverage(px, py, fxx, fxy, fyx, fyy, use, s.h / std::lround(s.particles_through_chip));
  put("chip_domain_gap_fraction", cov.gap_fraction, "1");
  put("chip_domain_overlap_fraction", cov.overlap_fraction, "1");
  // chip curling (Fig 17): direction of the deformed image F e_x of the originally horizontal
  // material fibres (the chip's layers). Per reference column of the material above the crack
  // (width one particle), the circular mean of the unit vectors F e_x / |F e_x|; the angles are
  // unwrapped from uncut material (2h ahead of the crack tip, angle ~0) back along the chip to its
  // leading end, so turns beyond 180 deg are counted. Reported: minus the mean unwrapped angle of
  // the columns that started within h of the left edge (curling turns the layers clockwise).
  const double psz = s.h / std::lround(s.particles_through_chip);
  const double xlast = std::min(tip + 2.0 * s.h, s.width_factor * s.h);
  const int ncol = std::max(1, static_cast<int>(std::ceil(xlast / psz)));
  std::vector<double> cs(static_cast<std::size_t>(ncol), 0.0), sn(static_cast<std::size_t>(ncol), 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    if (pb.rigid(p) || !pb.above_crack(p)) continue;
    const int c = static_cast<int>(std::floor(pb.reference_position(p).x() / psz));
    const double len = std::hypot(fxx[p], fyx[p]);
    if (c < 0 || c >= ncol || len <= 0.0) continue;
    cs[static_cast<std::size_t>(c)] += fxx[p] / len;
    sn[static_cast<std::size_t>(c)] += fyx[p] / len;
  }
  double prev = 0.0, end_sum = 0.0;
  int end_n = 0;
  for (int c = ncol - 1; c >= 0; --c) {
    const auto k = static_cast<std::size_t>(c);
    if (cs[k] == 0.0 && sn[k] == 0.0) continue;
    double a = std::atan2(sn[k], cs[k]);
    a += 2.0 * M_PI * std::round((prev - a) / (2.0 * M_PI));  // nearest branch to the previous column
    prev = a;
    if ((c + 0.5) * psz <= s.h) {
      end_sum += a;
      ++end_n;
    }
  }
  put("chip_end_rotation", end_n > 0 ? -end_sum / end_n : std::nan(""), "rad");
}

}  // namespace

namespace {
// The run's histories: forces and the energy audit at the output times.
void add_histories(RunOutput& out, const CuttingRun& loop) {
  Table forces;
  forces.name = "forces";
  forces.add("t", "s", loop.tt);
  forces.add("F_c", "N/m", loop.fc);
  forces.add("F_t", "N/m", loop.ft);
  forces.add("F_nb", "N/m", loop.fnb);
  forces.add("tip_gap", "m", loop.gap);
  forces.add("feedback_alpha", "1/s", loop.alph);
  out.tables.push_back(std::move(forces));
  Table energy;
  energy.name = "energy";
  energy.add("t", "s", loop.tt);
  energy.add("tool_work", "J/m", loop.e_tool);
  energy.add("kinetic", "J/m", loop.e_kin);
  energy.add("strain", "J/m", loop.e_strain);
  energy.add("plastic", "J/m", loop.e_plastic);
  energy.add("cohesive", "J/m", loop.e_coh);
  energy.add("pic_damping", "J/m", loop.e_pic);
  energy.add("feedback_loss", "J/m", loop.e_fb);
  energy.add("increment_loss", "J/m", loop.e_inc);
  energy.add("tool_contact_loss", "J/m", loop.e_tcl);
  energy.add("crack_contact_loss", "J/m", loop.e_ccl);
  energy.add("stress_lag", "J/m", loop.e_slag);
  energy.add("cohesive_lag", "J/m", loop.e_clag);
  energy.add("residual", "J/m", loop.e_res);
  out.tables.push_back(std::move(energy));
}

// Steady-window means of the output-interval forces and gaps over [t0, t1], touching, and
// the scaled quantities of the paper's figures.
void add_steady_window(RunOutput& out, const CuttingRun& loop, const CuttingSetup& s, double t0, double t1,
                       double out_dt, double dx) {
  std::vector<double> wc, wt, wn, wg;
  for (std::size_t i = 0; i < loop.tt.size(); ++i) {
    if (loop.tt[i] >= t0 && loop.tt[i] <= t1 + 0.5 * out_dt) {
      wc.push_back(loop.fc[i]);
      wt.push_back(loop.ft[i]);
      wn.push_back(loop.fnb[i]);
      wg.push_back(loop.gap[i]);
    }
  }
  double m, sd;
  auto put = [&](const std::string& name, double value, const std::string& unit) { out.set_scalar(name, value, unit); };
  mean_std(wc, m, sd);
  put("F_c", m, "N/m");
  put("F_c_std", sd, "N/m");
  put("F_c_noise", sd / std::fabs(m), "1");
  put("F_c_over_bGc", m / s.G_c, "1");
  mean_std(wt, m, sd);
  put("F_t", m, "N/m");
  put("F_t_std", sd, "N/m");
  mean_std(wn, m, sd);
  put("F_nb", m, "N/m");
  put("F_nb_std", sd, "N/m");
  mean_std(wn, m, sd);
  put("F_nb_over_bGc", m / s.G_c, "1");
  mean_std(wg, m, sd);
  put("tip_gap", m, "m");
  put("touching", m < dx ? 1.0 : 0.0, "1");
  std::size_t nt = 0;
  for (double g : wg) nt += g < dx ? 1 : 0;
  put("touching_fraction", wg.empty() ? std::nan("") : static_cast<double>(nt) / static_cast<double>(wg.size()), "1");
  // Williams' scaling and the friction parameter of Eq. 12
  const double E = s.material.youngs(), nu = s.material.poisson();
  const double Eprime = E / (1.0 - nu * nu);
  put("h_star", s.material.sigma_y0 * s.material.sigma_y0 * s.h / (2.0 * Eprime * s.G_c), "1");
  const double ta = std::tan(s.rake);
  put("Z", (s.mu - ta) / (1.0 + s.mu * ta), "1");
  out.notes.push_back("F_c, F_t: force of the tool on the material per unit width (F_t positive pushing the "
                      "material down, the paper's sign); averages over " +
                      std::to_string(t0) + " s <= t <= " + std::to_string(t1) + " s of output-interval means.");
  out.notes.push_back("touching = mean gap in the steady window below one cell (" + std::to_string(dx) +
                      " m), the gap from the tool tip to the first intact cohesive segment ahead of it (intact "
                      "segments left behind the tip, stranded_segments, do not count).");
}

// The crack's mode mix and the energy audit at the end of the run.
void add_crack_and_energy(RunOutput& out, const MpmProblem& pb, const CuttingRun& loop, double xt0) {
  auto put = [&](const std::string& name, double value, const std::string& unit) { out.set_scalar(name, value, unit); };
  put("mode1_fraction", pb.mode1_fraction(), "1");
  const double e = pb.released_energy();
  put("released_energy", e, "J/m");
  const double eI = e > 0.0 ? pb.mode1_fraction() * e : 0.0;
  put("mode1_fraction_steady",
      e - loop.e_at_window() > 0.0 ? (eI - loop.eI_at_window()) / (e - loop.e_at_window()) : std::nan(""), "1");
  const double xtool = xt0 + pb.rigid_displacement().x();
  put("stranded_segments", static_cast<double>(pb.intact_segments_behind(xtool - pb.config().crack.seg_len)), "1");
  const EnergyBalance eb = pb.energy_balance();
  put("energy_tool_work", eb.audit.tool_work, "J/m");
  put("energy_kinetic", eb.kinetic, "J/m");
  put("energy_strain", eb.strain, "J/m");
  put("energy_plastic", eb.plastic, "J/m");
  put("energy_cohesive", eb.cohesive, "J/m");
  put("energy_pic_damping", eb.audit.pic_damping, "J/m");
  put("energy_feedback_loss", eb.audit.feedback_loss, "J/m");
  put("energy_increment_loss", eb.audit.increment_loss, "J/m");
  put("energy_tool_contact_loss", eb.audit.tool_contact_loss, "J/m");
  put("energy_crack_contact_loss", eb.audit.crack_contact_loss, "J/m");
  put("energy_stress_lag", eb.stress_lag, "J/m");
  put("energy_cohesive_lag", eb.cohesive_lag, "J/m");
  put("energy_residual", eb.residual, "J/m");
  put("energy_residual_fraction", eb.audit.tool_work > 0.0 ? std::fabs(eb.residual) / eb.audit.tool_work : std::nan(""), "1");
  put("energy_numerical_fraction", eb.audit.tool_work > 0.0 ? eb.numerical / eb.audit.tool_work : std::nan(""), "1");
}
}  // namespace

RunOutput run_cutting(const Values& given, const ProgressFn& progress) {
  ModelSpec spec;
  spec.name = "mpm_cutting";
  spec.params = cutting_params();
  const Values v = validate_params(spec, given);
  if (v.at("steady_end_fraction") <= v.at("steady_start_fraction")) {
    throw InputError("steady_end_fraction", "must exceed steady_start_fraction");
  }
  const CuttingSetup s = cutting_setup_from(v);
  double xt0 = 0.0;
  MpmProblem pb = build_cutting_problem(s, &xt0);
  pb.setup();
  const double T = s.total_time;
  const double out_dt = v.at("output_interval") > 0.0 ? v.at("output_interval") : T / 400.0;
  const int nsnap = static_cast<int>(std::lround(v.at("snapshots")));
  const double steps_needed = std::ceil(T / pb.dt());
  if (!(steps_needed <= kMaxSteps)) {
    std::ostringstream os;
    os << "total_time " << T << " s needs " << steps_needed << " steps of " << pb.dt() << " s (at most "
       << kMaxSteps << ")";
    throw std::runtime_error(os.str());
  }
  CuttingRun loop(pb, T, out_dt, nsnap, v.at("steady_start_fraction") * T, static_cast<long>(steps_needed) + 1,
                  progress, xt0);
  const DriveReport drive_report = drive(loop, "mpm_cutting");
  if (const std::string f = pb.fault(); !f.empty()) throw std::runtime_error("MPM run stopped: " + f);
  const double wall = loop.wall();

  RunOutput out;
  out.snapshots = std::move(loop.snapshots);
  out.notes = drive_notes(drive_report, "mpm_cutting");
  add_histories(out, loop);
  add_steady_window(out, loop, s, v.at("steady_start_fraction") * T, v.at("steady_end_fraction") * T, out_dt,
                    pb.config().grid.dx);
  add_crack_and_energy(out, pb, loop, xt0);
  auto put = [&](const std::string& name, double value, const std::string& unit) { out.set_scalar(name, value, unit); };
  put("particles", static_cast<double>(pb.size()), "1");
  put("steps", static_cast<double>(pb.steps()), "1");
  put("dt", pb.dt(), "s");
  put("wall_time", wall, "s");
  put("particle_steps_per_s",
      static_cast<double>(pb.size()) * static_cast<double>(pb.steps() - static_cast<long>(drive_report.resumed_from_step)) / wall,
      "1/s");
  put("threads", pb.threads(), "1");
  put("frozen_particles", static_cast<double>(pb.frozen()), "1");
  add_chip_metrics(out, pb, s);
  if (pb.frozen() > 0) {
    out.notes.push_back(std::to_string(pb.frozen()) +
                        " particles left the grid and were returned into it (NairnMPM's rule, each counted once).");
  }
  return out;
}

SolverSpec cutting_solver_spec() {
  SolverSpec spec;
  spec.name = "mpm_cutting";
  spec.description = "2D plane-strain MPM orthogonal cutting: rigid tool, cohesive crack along the cut plane, "
                     "neo-Hookean J2 material, PIC damping";
  spec.source = "Nairn (2015) Eng. Fract. Mech. 149:262-275, sections 2-2.2; EQUATIONS.md A1-A4";
  spec.params = cutting_params();
  spec.scalars = {
      {"F_c", Dim::force_per_width, "steady cutting force per unit width"},
      {"F_c_std", Dim::force_per_width, "std of F_c over the steady window"},
      {"F_c_noise", Dim::dimensionless, "std/mean of F_c in the steady window"},
      {"F_c_over_bGc", Dim::dimensionless, "F_c / (b G_c)"},
      {"F_t", Dim::force_per_width, "steady transverse force per unit width"},
      {"F_t_std", Dim::force_per_width, "std of F_t"},
      {"F_nb", Dim::force_per_width, "steady bottom-face (rubbing) normal force"},
      {"F_nb_std", Dim::force_per_width, "std of F_nb"},
      {"F_nb_over_bGc", Dim::dimensionless, "F_nb / (b G_c), the rubbing force of Fig. 10"},
      {"tip_gap", Dim::length, "mean gap in the steady window from the tool tip to the crack tip (the first intact cohesive segment ahead of the tool tip)"},
      {"touching", Dim::dimensionless, "1 when the tool touches the crack tip (mean gap below one cell)"},
      {"touching_fraction", Dim::dimensionless, "fraction of steady-window outputs with the gap below one cell"},
      {"h_star", Dim::dimensionless, "Williams' dimensionless depth sigma_y0^2 h / (2 E' G_c), E' = E/(1 - nu^2)"},
      {"Z", Dim::dimensionless, "(mu - tan alpha) / (1 + mu tan alpha), the abscissa of Fig. 16"},
      {"chip_end_rotation", Dim::angle, "clockwise turn of the chip layers (F e_x, unwrapped along the chip from uncut material) at the chip's leading end: 0 uncut, 90 deg - alpha for a straight chip on the rake face, 360 deg for a full curl"},
      {"mode1_fraction", Dim::dimensionless, "fraction of released energy in mode I (all segments failed in the run)"},
      {"mode1_fraction_steady", Dim::dimensionless,
       "fraction of released energy in mode I, segments failed in the steady window (t >= steady_start_fraction T)"},
      {"released_energy", Dim::force_per_width, "cohesive energy released per unit width (J/m)"},
      {"stranded_segments", Dim::dimensionless, "intact cohesive segments more than one segment behind the tool tip at the end"},
      {"energy_tool_work", Dim::force_per_width, "energy audit: work of the tool's contact impulses on the material (J/m)"},
      {"energy_kinetic", Dim::force_per_width, "energy audit: kinetic energy of the material at the end (J/m)"},
      {"energy_strain", Dim::force_per_width, "energy audit: stored elastic energy at the end (J/m)"},
      {"energy_plastic", Dim::force_per_width, "energy audit: plastic work (J/m)"},
      {"energy_cohesive", Dim::force_per_width, "energy audit: work of the cohesive tractions (J/m)"},
      {"energy_pic_damping", Dim::force_per_width, "energy audit: kinetic energy removed by the PIC damping of the particle update (J/m)"},
      {"energy_feedback_loss", Dim::force_per_width, "energy audit: removed by the feedback damping (J/m)"},
      {"energy_increment_loss", Dim::force_per_width, "energy audit: kinetic energy lost mapping the grid's velocity increments to the particles (J/m)"},
      {"energy_tool_contact_loss", Dim::force_per_width, "energy audit: tool work the nodal contact does not pass to the material, sum dp . (V_tool - v_mid) (J/m; < 0: the contact gives more)"},
      {"energy_crack_contact_loss", Dim::force_per_width, "energy audit: removed by the crack-face contact, -sum dp . v_mid (J/m; < 0: created)"},
      {"energy_stress_lag", Dim::force_per_width, "energy audit: work the stresses' nodal forces take from the grid at mid-step velocities less the stress power the stress updates book (J/m)"},
      {"energy_cohesive_lag", Dim::force_per_width, "energy audit: work the cohesive forces take from the grid at mid-step velocities less the cohesive energy booked (J/m)"},
      {"energy_residual", Dim::force_per_width, "energy audit: tool work minus every measured term: the stress updates' booked stress power less the elastic and plastic energy they store, and what the scheme's extra passes do (MUSL, USAVG) (J/m)"},
      {"energy_residual_fraction", Dim::dimensionless, "|energy_residual| / energy_tool_work"},
      {"energy_numerical_fraction", Dim::dimensionless, "share of the tool work taken by the numerical terms (PIC and feedback damping, increment loss, contact losses, stress and cohesive lags; signed)"},
      {"particles", Dim::dimensionless, "number of particles"},
      {"steps", Dim::dimensionless, "time steps"},
      {"dt", Dim::time, "time step"},
      {"wall_time", Dim::time, "wall-clock time of the time loop"},
      {"particle_steps_per_s", Dim::strain_rate, "throughput, particle-steps per second (after a resume: the steps since the resume)"},
      {"threads", Dim::dimensionless, "OpenMP threads used"},
      {"frozen_particles", Dim::dimensionless, "particles that left the grid (returned into it, each counted once)"},
      {"chip_domain_gap_fraction", Dim::dimensionless, "Fig 2 metric: enclosed uncovered area / covered area"},
      {"chip_domain_overlap_fraction", Dim::dimensionless, "Fig 2 metric: multiply covered area / covered area"},
  };
  spec.tables = {{"forces",
                  "force history: means over each output interval",
                  {{"t", "s", "time at the end of the interval"},
                   {"F_c", "N/m", "cutting force of the tool on the material per unit width"},
                   {"F_t", "N/m", "transverse force (positive pushing the material down)"},
                   {"F_nb", "N/m", "normal force on the tool's bottom (clearance) face"},
                   {"tip_gap", "m", "gap from the tool tip to the first intact cohesive segment ahead of it"},
                   {"feedback_alpha", "1/s", "grid kinetic-energy feedback damping coefficient"}}},
                 {"energy",
                  "energy audit at the output times (J/m): tool_work = kinetic + strain + plastic + cohesive + pic_damping + feedback_loss + increment_loss + tool_contact_loss + crack_contact_loss + stress_lag + cohesive_lag + residual",
                  {{"t", "s", "time"},
                   {"tool_work", "J/m", "work of the tool's contact impulses"},
                   {"kinetic", "J/m", "kinetic energy of the material"},
                   {"strain", "J/m", "stored elastic energy"},
                   {"plastic", "J/m", "plastic work"},
                   {"cohesive", "J/m", "work of the cohesive tractions"},
                   {"pic_damping", "J/m", "removed by the PIC damping of the particle update"},
                   {"feedback_loss", "J/m", "removed by the feedback damping"},
                   {"increment_loss", "J/m", "lost mapping the grid's velocity increments to the particles"},
                   {"tool_contact_loss", "J/m", "tool work the nodal contact does not pass to the material"},
                   {"crack_contact_loss", "J/m", "removed by the crack-face contact (< 0: created)"},
                   {"stress_lag", "J/m", "internal forces' work at mid-step velocities less the booked stress power"},
                   {"cohesive_lag", "J/m", "cohesive forces' work at mid-step velocities less the booked cohesive energy"},
                   {"residual", "J/m", "the balance's remainder: booked stress power less stored elastic and plastic energy"}}}};
  spec.run = run_cutting;
  spec.checkpoints = true;
  spec.footprint = [](const Values& v) {
    // specimen (width_factor + tool) x (base_factor + 1 + chip room) in particles of size h / N,
    // 4 particles per cell; about 0.6 kB per particle (fields, shape functions, scratch) and 0.3 kB
    // per grid node (nodal fields, per-thread buffers)
    const double n = v.at("particles_through_chip");
    const double w = v.at("width_factor") + v.at("tool_length_factor");
    const double particles = n * n * (v.at("width_factor") * (v.at("base_factor") + 1.0) +
                                      v.at("tool_length_factor") * v.at("tool_height_factor"));
    const double nodes = 0.25 * n * n * (w + 4.0) * (v.at("base_factor") + v.at("chip_room_factor") + 4.0);
    return Footprint{particles, 600.0 * particles + 300.0 * nodes, "particles"};
  };
  return spec;
}

void register_solvers(SolverRegistry& registry) {
  if (registry.find("mpm_cutting")) return;
  registry.add(cutting_solver_spec());
}

}  // namespace cutbench::mpm
