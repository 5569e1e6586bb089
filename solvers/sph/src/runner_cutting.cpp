// sph_cutting: orthogonal cutting of Ti6Al4V (Afrasiabi et al. 2021, Sec. 5.2, Fig. 4, Table 1).
//
// Workpiece [0, L] x [0, H] on a square lattice (n particles over the height), clamped (velocity
// zero, T = T_inf) on `fixed_layers` layers at the bottom and at x = 0. The rigid tool starts just
// right of x = L with its lowest edge point at y = H - t_u and moves at -v_c (the mirror image of
// the paper's Fig. 4, which clamps the right side). Forces on the tool per unit width; F_c along the
// cut (positive against the tool motion), F_t normal to the machined surface (positive pushing the
// tool up). Tool particles (a band of tool_depth around the edge) conduct heat; the far ones are a
// heat sink at T_inf.
#include <algorithm>
#include <limits>
#include <cmath>
#include <map>

#include "cutbench/common/declared.hpp"
#include "cutbench/common/driver.hpp"
#include "cutbench/common/glossary.hpp"
#include "cutbench/common/checkpoint.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/sph/lattice.hpp"
#include "cutbench/sph/runners.hpp"
#include "specs.hpp"
#include "cutbench/sph/solid.hpp"

namespace cutbench::sph {

CuttingInputs cutting_inputs(const CuttingSetup& c) {
  CuttingInputs in;
  in.material.plastic = true;
  if (c.flow_law == 1) in.material.jc = sima_ozel_ti6al4v();
  if (c.enhanced_thermal) {
    in.thermal.scheme = HeatScheme::fmfs;
  } else {  // reference model: Brookshaw everywhere, no convection or radiation
    in.thermal.scheme = HeatScheme::brookshaw;
    in.thermal.boundary.h_conv = 0.0;
    in.thermal.boundary.emissivity = 0.0;
  }
  in.thermal.brookshaw_band = c.brookshaw_band;
  in.contact.friction = c.friction;
  in.contact.model = c.penalty_contact ? ContactModel::penalty : ContactModel::velocity;
  in.contact.offset_fraction = c.contact_offset;
  in.contact.tool_heat_share = c.tool_heat_share;
  in.contact.shear_cap = c.shear_cap;
  in.contact.alpha = c.contact_stiffness;
  in.options.alpha_visc = c.alpha_visc;
  in.options.beta_visc = c.beta_visc;
  in.options.artificial_stress = c.artificial_stress;
  in.options.xsph = c.xsph;
  in.tool_heat = HeatMaterial{c.tool_conductivity, c.tool_density, c.tool_specific_heat};
  return in;
}

std::vector<double> serration_peaks(const std::vector<double>& s, const std::vector<double>& f, double rel_threshold) {
  std::vector<double> peaks;
  const std::size_t n = std::min(s.size(), f.size());
  if (n == 0) return peaks;
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += f[k];
  mean /= static_cast<double>(n);
  const double thr = rel_threshold * std::abs(mean);
  double lo = f[0], hi = f[0], s_hi = s[0];
  bool rising = true;
  for (std::size_t k = 1; k < n; ++k) {
    const double e = f[k];
    if (rising) {
      if (e < lo) {  // still descending: restart the rise from here
        lo = hi = e;
        s_hi = s[k];
      }
      if (e > hi) {
        hi = e;
        s_hi = s[k];
      }
      if (hi - lo > thr && hi - e > thr) {  // a peak that rose and fell by more than thr
        peaks.push_back(s_hi);
        rising = false;
        lo = e;
      }
    } else {
      if (e < lo) lo = e;
      if (e - lo > thr) {
        rising = true;
        hi = e;
        s_hi = s[k];
      }
    }
  }
  return peaks;
}

namespace {

// Heat content of workpiece particle i above the ambient temperature, J per metre of depth.
double particle_heat(const SolidSph& s, std::size_t i, double rho_c, double T_ambient) {
  return rho_c * s.mass()[i] / s.density()[i] * (s.temperature()[i] - T_ambient);
}

// Centred moving average over 2 half + 1 points (shorter at the ends).
std::vector<double> moving_average(const std::vector<double>& f, std::size_t half) {
  const std::size_t n = f.size();
  std::vector<double> g(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k >= half ? k - half : 0, b = std::min(n - 1, k + half);
    double sum = 0.0;
    for (std::size_t q = a; q <= b; ++q) sum += f[q];
    g[k] = sum / static_cast<double>(b - a + 1);
  }
  return g;
}

// Chip metrics (see CuttingResult). x0: initial positions.
// rho_c, T_ambient: rho c of the workpiece and the ambient temperature, for the chip's heat content.
void chip_metrics(const CuttingSetup& c, const std::vector<Vec2>& x0, const SolidSph& s, double rho_c,
                  double T_ambient, CuttingResult& r) {
  const double dx = r.dx;
  const double x_done = s.tool_position().x() + 0.5 * c.uncut_thickness;  // columns the tool has passed
  const double y_cut = c.height - c.uncut_thickness;
  // columns of the initial lattice, in cutting order (decreasing x0)
  std::vector<std::pair<double, std::size_t>> members;
  double x_first = -std::numeric_limits<double>::infinity();  // the first column the tool met
  for (std::size_t i = 0; i < x0.size(); ++i)
    if (x0[i].y() > y_cut + 0.25 * dx) {
      x_first = std::max(x_first, x0[i].x());
      if (x0[i].x() > x_done) members.emplace_back(-x0[i].x(), i);
    }
  std::sort(members.begin(), members.end());
  std::vector<std::vector<std::size_t>> columns;  // the lifted particles of each chip column
  double area = 0.0, t_sum = 0.0;
  std::size_t t_n = 0;
  for (std::size_t a = 0; a < members.size();) {
    std::size_t b = a;
    while (b < members.size() && std::abs(members[b].first - members[a].first) < 0.25 * dx) ++b;
    // the chip part of the column: its particles above the original surface (a few particles of a
    // column can stay on the machined surface; counting them pulled the centroid out of the chip)
    double eps = 0.0, col_area = 0.0, col_T = 0.0, col_heat = 0.0;
    Vec2 cen = Vec2::Zero();
    std::size_t lifted = 0;
    std::vector<std::size_t> col_particles;
    for (std::size_t k = a; k < b; ++k) {
      const std::size_t i = members[k].second;
      if (s.positions()[i].y() <= c.height) continue;
      col_particles.push_back(i);
      eps += s.plastic_strain()[i];
      cen += s.positions()[i];
      ++lifted;
      col_area += s.mass()[i] / s.density()[i];
      col_T += s.temperature()[i];
      col_heat += particle_heat(s, i, rho_c, T_ambient);
    }
    if (2 * lifted > b - a) {  // most of the column went into the chip
      const double cnt = static_cast<double>(lifted);
      r.chip_x0.push_back(-members[a].first);
      r.chip_u.push_back(x_first + members[a].first);
      r.chip_eps.push_back(eps / cnt);
      r.chip_cx.push_back(cen.x() / cnt);
      r.chip_cy.push_back(cen.y() / cnt);
      columns.push_back(std::move(col_particles));
      area += col_area;
      t_sum += col_T;
      r.stored_chip += col_heat;
      t_n += lifted;
    }
    a = b;
  }
  const std::size_t nc = r.chip_x0.size();
  // centroid line, smoothed over 3 columns (particle disorder across the chip makes the raw line
  // zig-zag and too long)
  const auto sx = moving_average(r.chip_cx, 1), sy = moving_average(r.chip_cy, 1);
  r.chip_s.assign(nc, 0.0);
  for (std::size_t k = 1; k < nc; ++k) r.chip_s[k] = r.chip_s[k - 1] + std::hypot(sx[k] - sx[k - 1], sy[k] - sy[k - 1]);
  r.chip_length = nc ? r.chip_s.back() : 0.0;
  r.chip_thickness = r.chip_length > 0.0 ? area / r.chip_length : nan_value();
  r.chip_T_mean = t_n ? t_sum / static_cast<double>(t_n) : nan_value();
  r.chip_curl = nan_value();
  r.chip_segments = r.serration_pitch = r.serration_cv = nan_value();
  r.tooth_segments = r.tooth_pitch = r.tooth_amplitude = nan_value();
  // thickness of each column across the chip: the span of its lifted particles along the normal of
  // the smoothed centroid line, plus one particle spacing (the free-surface profile: teeth of a
  // serrated chip are thick columns between thin ones)
  r.chip_t.assign(nc, 0.0);
  for (std::size_t k = 0; k < nc; ++k) {
    const std::size_t k0 = k > 0 ? k - 1 : k, k1 = k + 1 < nc ? k + 1 : k;
    Vec2 tan(sx[k1] - sx[k0], sy[k1] - sy[k0]);
    if (!(tan.norm() > 0.0)) tan = Vec2(1.0, 0.0);
    const Vec2 nrm(-tan.y() / tan.norm(), tan.x() / tan.norm());
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i : columns[k]) {
      const double d = (s.positions()[i] - Vec2(r.chip_cx[k], r.chip_cy[k])).dot(nrm);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    r.chip_t[k] = hi - lo + dx;
  }
  if (nc < 6) return;
  // curl: direction of the (smoothed) centroid line over the first third versus the last third
  const std::size_t third = nc / 3;
  const Vec2 d0(sx[third] - sx[0], sy[third] - sy[0]);
  const Vec2 d1(sx[nc - 1] - sx[nc - 1 - third], sy[nc - 1] - sy[nc - 1 - third]);
  r.chip_curl = std::abs(std::atan2(d0.x() * d1.y() - d0.y() * d1.x(), d0.dot(d1))) * 180.0 / 3.14159265358979323846;
  // serration: the column-mean eps_p against the position u along the uncut layer, after the entry
  // transient (the first 2 t_u of cut), smoothed over 3 columns
  std::vector<double> u, f;
  for (std::size_t k = 0; k < nc; ++k)
    if (r.chip_u[k] >= 2.0 * c.uncut_thickness) {
      u.push_back(r.chip_u[k]);
      f.push_back(r.chip_eps[k]);
    }
  if (u.size() < 6) return;
  f = moving_average(f, 1);
  double mean = 0.0, var = 0.0;
  for (double e : f) mean += e;
  mean /= static_cast<double>(f.size());
  for (double e : f) var += (e - mean) * (e - mean);
  r.serration_cv = mean > 0.0 ? std::sqrt(var / static_cast<double>(f.size())) / mean : 0.0;
  const auto peaks = serration_peaks(u, f, 0.2);
  r.chip_segments = static_cast<double>(peaks.size());
  r.serration_pitch = peaks.size() >= 2 ? (peaks.back() - peaks.front()) / static_cast<double>(peaks.size() - 1)
                                        : nan_value();
  // saw-tooth of the free surface: the column thickness against u after the entry transient,
  // smoothed over 3 columns; teeth = peaks with a hysteresis of 0.1 x the mean thickness; pitch =
  // their mean spacing along the uncut layer; amplitude = half the mean height of a tooth over the
  // lowest point before the next one
  std::vector<double> tu, th;
  for (std::size_t k = 0; k < nc; ++k)
    if (r.chip_u[k] >= 2.0 * c.uncut_thickness) {
      tu.push_back(r.chip_u[k]);
      th.push_back(r.chip_t[k]);
    }
  if (tu.size() < 6) return;
  th = moving_average(th, 1);
  const auto teeth = serration_peaks(tu, th, 0.1);
  r.tooth_segments = static_cast<double>(teeth.size());
  if (teeth.size() < 2) return;
  r.tooth_pitch = (teeth.back() - teeth.front()) / static_cast<double>(teeth.size() - 1);
  double height = 0.0;
  for (std::size_t p = 0; p + 1 < teeth.size(); ++p) {
    double top = -std::numeric_limits<double>::infinity(), low = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < tu.size(); ++k) {
      if (tu[k] == teeth[p]) top = th[k];
      if (tu[k] > teeth[p] && tu[k] < teeth[p + 1]) low = std::min(low, th[k]);
    }
    height += top - low;
  }
  r.tooth_amplitude = 0.5 * height / static_cast<double>(teeth.size() - 1);
}

}  // namespace

namespace {
// The workpiece particles with temperature, plastic strain and the surface flag.
// The workpiece state; `surface` is the detection flag, `surface_group` the paper's Fig. 2 groups
// for the thermal boundary conditions: 0 interior, 1 surface particle losing heat to the air
// (convection and radiation), 2 surface particle within 1.5 dx of the tool (no air loss).
Snapshot workpiece_snapshot(const SolidSph& s, std::size_t n, const RoundedPolygon& tool, double dx) {
  Snapshot snap;
  snap.time = s.time();
  for (std::size_t i = 0; i < n; ++i) {
    snap.x.push_back(s.positions()[i].x());
    snap.y.push_back(s.positions()[i].y());
  }
  snap.add("T", "K", s.temperature());
  snap.add("eps_p", "1", s.plastic_strain());
  std::vector<double> surf(n, 0.0), group(n, 0.0);
  for (std::size_t i = 0; i < n && i < s.surface().surface.size(); ++i) {
    surf[i] = s.surface().surface[i];
    if (surf[i] != 0.0) group[i] = tool.at(s.positions()[i] - s.tool_position()).distance < 1.5 * dx ? 2.0 : 1.0;
  }
  snap.add("surface", "1", surf);
  snap.add("surface_group", "1", group);
  return snap;
}

// Surface detection on the uncut surface (see CuttingResult::surface_top_fraction).
void surface_metrics(const CuttingSetup& c, const std::vector<Vec2>& x0, const std::vector<char>& fixed, const SolidSph& s,
                     CuttingResult& r) {
  const auto& flag = s.surface().surface;
  if (flag.size() < x0.size()) {
    r.surface_top_fraction = r.surface_second_fraction = nan_value();
    return;
  }
  const double x_max = s.tool_position().x() - 3.0 * c.uncut_thickness;
  // the lattice columns the tool has not reached, chosen by their initial x: a choice by the
  // current x would add the columns of the chip that curls forward over the uncut surface
  std::map<long, std::vector<std::pair<double, char>>> columns;  // initial column -> (y, flag)
  for (std::size_t i = 0; i < x0.size(); ++i) {
    if (fixed[i] || x0[i].x() > x_max) continue;
    columns[std::lround(x0[i].x() / r.dx)].emplace_back(s.positions()[i].y(), flag[i]);
  }
  double n = 0.0, top = 0.0, second = 0.0;
  for (auto& [k, col] : columns) {
    if (col.size() < 2) continue;
    std::sort(col.begin(), col.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    n += 1.0;
    top += col[0].second ? 1.0 : 0.0;
    second += col[1].second ? 1.0 : 0.0;
  }
  r.surface_top_fraction = n > 0.0 ? top / n : nan_value();
  r.surface_second_fraction = n > 0.0 ? second / n : nan_value();
}

// Rake-face temperature: the mean over the free particles within 1.5 dx of the tool whose contact
// normal points against the cut (the rake face), above the edge; NaN when there are none.
double rake_face_mean_temperature(const SolidSph& s, const std::vector<char>& fixed, const RoundedPolygon& tool,
                                  double dx, double edge_radius) {
  double tsum = 0.0;
  std::size_t tn = 0;
  for (std::size_t i = 0; i < fixed.size(); ++i) {
    if (fixed[i]) continue;
    const Vec2& p = s.positions()[i];
    const auto sd = tool.at(p - s.tool_position());
    if (sd.distance < 1.5 * dx && sd.normal.x() < -0.7 && p.y() > s.tool_position().y() + edge_radius) {
      tsum += s.temperature()[i];
      ++tn;
    }
  }
  return tn ? tsum / static_cast<double>(tn) : nan_value();
}

// Tool temperatures at the end: the hottest tool particle and the mean over the tool particles on
// the rake face (within 1.5 dx of it, above the edge, below 2 t_u; NaN without tool conduction).
void tool_temperatures(const CuttingSetup& c, const SolidSph& s, const RoundedPolygon& tool, double dx,
                       CuttingResult& r) {
  double tsum = 0.0;
  std::size_t tn = 0;
  r.tool_T_max = nan_value();
  if (c.tool_conduction) {
    r.tool_T_max = 0.0;
    for (std::size_t k = 0; k < s.tool_particles().size(); ++k) {
      const Vec2& p = s.tool_particles()[k];
      const double tk = s.tool_temperature()[k];
      r.tool_T_max = std::max(r.tool_T_max, tk);
      const auto sd = tool.at(p);
      if (sd.distance > -1.5 * dx && sd.normal.x() < -0.7 && p.y() > c.edge_radius && p.y() < 2.0 * c.uncut_thickness) {
        tsum += tk;
        ++tn;
      }
    }
  }
  r.tool_rake_temperature = tn ? tsum / static_cast<double>(tn) : nan_value();
}

// The tool particles (world frame) with their temperature.
Snapshot tool_snapshot(const SolidSph& s) {
  Snapshot snap;
  snap.time = s.time();
  for (std::size_t k = 0; k < s.tool_particles().size(); ++k) {
    snap.x.push_back(s.tool_particles()[k].x() + s.tool_position().x());
    snap.y.push_back(s.tool_particles()[k].y() + s.tool_position().y());
  }
  snap.add("T", "K", s.tool_temperature());
  return snap;
}

// Heat audit: plastic heat generated in, and heat content at the end of, the particles that started
// in the uncut layer (above y_low) and below it; stored, lost and sunk heat; the imbalance
// (generated - stored - lost - sunk) / generated.
void heat_audit(const std::vector<Vec2>& x, const std::vector<char>& fixed, const SolidSph& s, double y_low,
                double rho_c, double T_ambient, CuttingResult& r) {
  r.plastic_heat = s.plastic_heat();
  const auto& q = s.plastic_heat_by_particle();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const bool layer = x[i].y() > y_low;
    if (i < q.size()) (layer ? r.plastic_heat_layer : r.plastic_heat_below) += q[i];
    if (!fixed[i]) (layer ? r.stored_layer : r.stored_below) += particle_heat(s, i, rho_c, T_ambient);
  }
  r.stored_workpiece = s.workpiece_heat_content();
  r.stored_tool = s.tool_heat_content();
  r.heat_lost = s.boundary_heat_loss();
  r.heat_sunk = s.heat_sunk();
  const double generated = r.plastic_heat + r.friction_heat;
  r.heat_imbalance =
      generated > 0.0 ? (generated - r.stored_workpiece - r.stored_tool - r.heat_lost - r.heat_sunk) / generated
                      : 0.0;
}

}  // namespace

namespace {
// The workpiece lattice of a cutting run (dx = height / (particles_over_height - 1)) and its
// clamped layers at the bottom and the far end.
struct Workpiece {
  double dx = 0.0;
  std::size_t nx = 0;
  std::vector<Vec2> x;
  std::vector<char> fixed;
};

Workpiece cutting_workpiece(const CuttingSetup& c) {
  if (c.particles_over_height < 4) throw InputError("particles_over_height", "needs at least 4");
  if (!(c.uncut_thickness > 0.0 && c.uncut_thickness < c.height)) throw InputError(glossary::kDepthOfCut, "must be in (0, height)");
  if (!(c.cut_distance > 0.0 && c.cut_distance < c.length)) throw InputError("cut_distance", "must be in (0, length)");
  Workpiece w;
  w.dx = c.height / static_cast<double>(c.particles_over_height - 1);
  w.nx = static_cast<std::size_t>(std::lround(c.length / w.dx)) + 1;
  const auto ny = static_cast<std::size_t>(c.particles_over_height);
  w.x = rectangle_lattice(w.nx, ny, 0.0, w.dx * static_cast<double>(w.nx - 1), 0.0, c.height);
  w.fixed.assign(w.x.size(), 0);
  const double lim = (static_cast<double>(c.fixed_layers) - 0.5) * w.dx;
  for (std::size_t i = 0; i < w.x.size(); ++i) w.fixed[i] = w.x[i].y() < lim || w.x[i].x() < lim;
  if (c.lattice_jitter > 0.0) {  // the clamped layers stay on the lattice
    std::vector<Vec2> shifted = w.x;
    jitter(shifted, c.lattice_jitter * w.dx, static_cast<std::uint64_t>(c.lattice_seed));
    for (std::size_t i = 0; i < w.x.size(); ++i)
      if (!w.fixed[i]) w.x[i] = shifted[i];
  }
  return w;
}

// One cutting run as the shared driver sees it: the SPH solid with the tool and its heat, the
// force windows, the steady-part force split by tool face, the rake-face temperature sample and
// the snapshot schedule; the whole state saved for checkpoints.
class CuttingRun final : public SteppedRun {
public:
  CuttingRun(const CuttingSetup& c, const ProgressFn& progress)
      : c_(c), progress_(progress), w_(cutting_workpiece(c)), in_(cutting_inputs(c)),
        s_(w_.x, w_.dx, in_.material, in_.options, in_.h_over_dx), y_low_(c.height - c.uncut_thickness),
        tool_(cutting_tool(c.rake, c.clearance, c.edge_radius, Vec2::Zero(), 10.0 * c.height)),
        t_end_(c.cut_distance / c.speed), window_(std::max(c.history_window, 1e-12)), t_next_(window_),
        t_steady_(c.steady_from * t_end_),
        // contact normals of the rake and clearance faces (out of the tool, see cutting_tool)
        n_rake_(-std::cos(c.rake), std::sin(c.rake)), n_flank_(std::sin(c.clearance), -std::cos(c.clearance)),
        n_snap_(std::max(1, c.snapshots)) {
    const double dx = w_.dx;
    s_.set_fixed(w_.fixed);
    s_.enable_thermal(in_.thermal, w_.fixed);
    const double x_tool = dx * static_cast<double>(w_.nx - 1) + 0.5 * dx + c.edge_radius + 0.5 * dx;
    s_.set_tool(cutting_tool(c.rake, c.clearance, c.edge_radius, Vec2::Zero(), 10.0 * c.height), Vec2(x_tool, y_low_),
                Vec2(-c.speed, 0.0), in_.contact);
    if (c.tool_conduction) s_.set_tool_thermal(in_.tool_heat, std::max(c.tool_depth, 8.0 * dx));
    r_.dx = dx;
    r_.particles = w_.x.size();
  }

  bool done() const override { return stopped_ || !(s_.time() < t_end_); }
  std::size_t steps() const override { return static_cast<std::size_t>(s_.steps()); }

  void advance() override {
    // No step shorter than half the stable one: the penalty stiffness alpha m / dt^2 of a sliver
    // step at the end of the cut would kick the contact particles (measured: the contact springs
    // held 4.4 J/m after a final sliver step, 0.12 J/m before it). The cut ends within half a step.
    const double dt_stable = s_.stable_time_step(), left = t_end_ - s_.time();
    if (!(left > 0.5 * dt_stable)) {
      stopped_ = true;
      if (acc_t_ > 0.0) record_window();
      return;
    }
    const double dt = std::min(dt_stable, left);
    s_.step(dt);
    const double fc = s_.tool_force().x(), ft = s_.tool_force().y();  // force on the tool
    // tool moves in -x: the cutting force resists it (+x on the tool); thrust pushes it up (+y)
    acc_fc_ += fc * dt;
    acc_ft_ += ft * dt;
    acc_t_ += dt;
    if (s_.time() >= t_steady_) add_steady(fc, ft, dt);
    if (snap_taken_ < n_snap_ - 1 && s_.time() >= t_end_ * static_cast<double>(snap_taken_ + 1) / n_snap_) {
      r_.snapshots.push_back(workpiece_snapshot(s_, w_.x.size(), *tool_, w_.dx));
      ++snap_taken_;
    }
    if (s_.time() >= t_next_ || s_.time() >= t_end_) record_window();
  }

  // The solver state and every accumulator of the loop.
  void save(BinaryWriter& w) const override {
    s_.save_state(w);
    loop_state(*this, [&](double d) { w.f64(d); }, [&](const std::vector<double>& v) { w.vec(v); });
    w.u64(static_cast<std::uint64_t>(rake_avg_n_));
    w.u64(static_cast<std::uint64_t>(snap_taken_));
    w.u64(r_.snapshots.size());
    for (const auto& sn : r_.snapshots) write_snapshot(w, sn);
  }
  void load(BinaryReader& rd) override {
    s_.load_state(rd);
    loop_state(*this, [&](double& d) { d = rd.f64(); }, [&](std::vector<double>& v) { v = rd.vec(); });
    rake_avg_n_ = static_cast<int>(rd.u64());
    snap_taken_ = static_cast<int>(rd.u64());
    r_.snapshots.clear();
    for (auto k = rd.u64(); k > 0; --k) r_.snapshots.push_back(read_snapshot(rd));
  }

  // The result once the driver is done: steady-part means, temperatures, snapshots, chip metrics
  // and the heat audit.
  CuttingResult finish(const DriveReport& report) {
    CuttingResult& r = r_;
    r.drive = report;
    r.steps = s_.steps();
    r.fc_mean = steady_t_ > 0.0 ? steady_fc_ / steady_t_ : nan_value();
    r.ft_mean = steady_t_ > 0.0 ? steady_ft_ / steady_t_ : nan_value();
    if (steady_t_ > 0.0) {
      r.force_rake = zone_force_[0] / steady_t_;
      r.force_edge = zone_force_[1] / steady_t_;
      r.force_flank = zone_force_[2] / steady_t_;
    }
    r.rake_friction_ratio = rake_fn_ > 0.0 ? rake_ft_ / rake_fn_ : nan_value();
    r.rake_slip_fraction = rake_count_ > 0.0 ? rake_slip_ / rake_count_ : nan_value();
    r.T_max = 0.0;
    double chip_top = 0.0;
    for (std::size_t i = 0; i < w_.x.size(); ++i) {
      const Vec2& p = s_.positions()[i];
      if (s_.temperature()[i] > r.T_max) {
        r.T_max = s_.temperature()[i];
        r.T_max_at = p - s_.tool_position();
      }
      chip_top = std::max(chip_top, p.y());
    }
    r.rake_temperature = rake_face_temperature();
    r.rake_temperature_avg = rake_avg_n_ ? rake_avg_sum_ / rake_avg_n_ : nan_value();
    tool_temperatures(c_, s_, *tool_, w_.dx, r);
    r.chip_height = chip_top - c_.height;
    r.snapshot = workpiece_snapshot(s_, w_.x.size(), *tool_, w_.dx);
    surface_metrics(c_, w_.x, w_.fixed, s_, r);
    r.snapshots.push_back(r.snapshot);
    r.tool_snapshot = tool_snapshot(s_);
    r.friction_heat = s_.friction_heat();
    r.friction_heat_tool = s_.friction_heat_to_tool();
    r.tool_share = s_.tool_heat_share();
    const double rho_c = in_.thermal.heat.density * in_.thermal.heat.specific_heat;
    chip_metrics(c_, w_.x, s_, rho_c, in_.thermal.boundary.T_ambient, r);
    heat_audit(w_.x, w_.fixed, s_, y_low_, rho_c, in_.thermal.boundary.T_ambient, r);
    return std::move(r_);
  }

private:
  // Rake-face temperature: free particles within 1.5 dx of the tool whose contact normal points
  // against the cut (the rake face), above the edge (mean; NaN when none).
  double rake_face_temperature() const {
    return rake_face_mean_temperature(s_, w_.fixed, *tool_, w_.dx, c_.edge_radius);
  }

  // The steady part: mean forces and the force split by the tool face of each contact normal
  // (rake face, rounded edge, clearance face), with the rake-face friction use.
  void add_steady(double fc, double ft, double dt) {
    steady_fc_ += fc * dt;
    steady_ft_ += ft * dt;
    steady_t_ += dt;
    for (const auto& k : s_.contacts()) {
      const int zone = k.normal.dot(n_rake_) > 0.9999 ? 0 : (k.normal.dot(n_flank_) > 0.9999 ? 2 : 1);
      zone_force_[zone] -= (k.fn + k.ft) * dt;
      if (zone == 0) {
        rake_fn_ += k.fn.norm();
        rake_ft_ += k.ft.norm();
        rake_count_ += 1.0;
        if (k.ft.norm() >= 0.999 * k.limit) rake_slip_ += 1.0;
      }
    }
  }

  // One force window: its means, and the rake-face temperature sample of the steady part.
  void record_window() {
    r_.t.push_back(s_.time());
    r_.cut.push_back(s_.time() * c_.speed);
    r_.fc.push_back(acc_fc_ / acc_t_);
    r_.ft.push_back(acc_ft_ / acc_t_);
    acc_fc_ = acc_ft_ = acc_t_ = 0.0;
    t_next_ += window_;
    const SolidSph::EnergyLedger& e = s_.energy();
    r_.e_tool.push_back(e.tool_work);
    r_.e_kinetic.push_back(s_.kinetic_energy());
    r_.e_elastic.push_back(s_.strain_energy());
    r_.e_plastic.push_back(e.plastic);
    r_.e_friction.push_back(e.friction);
    r_.e_viscous.push_back(e.viscous);
    r_.e_art.push_back(e.artificial_stress);
    r_.e_spring.push_back(s_.contact_spring_energy());
    r_.e_stress.push_back(e.stress_work);
    r_.e_internal.push_back(e.internal_work);
    r_.e_xsph.push_back(e.xsph_contact);
    if (s_.time() >= t_steady_) {  // time average of the rake-face sample over the steady part
      const double tr = rake_face_temperature();
      if (std::isfinite(tr)) {
        rake_avg_sum_ += tr;
        ++rake_avg_n_;
      }
    }
    if (progress_)
      progress_(s_.time() / t_end_, "cut " + std::to_string(s_.time() * c_.speed * 1e3) + " mm, step " +
                                        std::to_string(s_.steps()));
  }

  // Every accumulator of the loop, in checkpoint order (Self: const to save, mutable to load).
  template <class Self, class F64, class Vec>
  static void loop_state(Self& self, F64&& f64, Vec&& vec) {
    for (auto* d : {&self.acc_fc_, &self.acc_ft_, &self.acc_t_, &self.t_next_, &self.steady_fc_, &self.steady_ft_,
                    &self.steady_t_, &self.rake_ft_, &self.rake_fn_, &self.rake_slip_, &self.rake_count_,
                    &self.rake_avg_sum_, &self.zone_force_[0].x(), &self.zone_force_[0].y(), &self.zone_force_[1].x(),
                    &self.zone_force_[1].y(), &self.zone_force_[2].x(), &self.zone_force_[2].y()})
      f64(*d);
    for (auto* v : {&self.r_.t, &self.r_.cut, &self.r_.fc, &self.r_.ft, &self.r_.e_tool, &self.r_.e_kinetic, &self.r_.e_elastic,
                    &self.r_.e_plastic, &self.r_.e_friction, &self.r_.e_viscous, &self.r_.e_art, &self.r_.e_spring,
                    &self.r_.e_stress, &self.r_.e_internal, &self.r_.e_xsph})
      vec(*v);
  }

  const CuttingSetup& c_;
  const ProgressFn& progress_;
  const Workpiece w_;
  const CuttingInputs in_;
  SolidSph s_;
  const double y_low_;
  const std::unique_ptr<RoundedPolygon> tool_;  // the tool's shape, for the rake-face measurements
  CuttingResult r_;
  const double t_end_, window_;
  double acc_fc_ = 0.0, acc_ft_ = 0.0, acc_t_ = 0.0, t_next_;
  double steady_fc_ = 0.0, steady_ft_ = 0.0, steady_t_ = 0.0;
  const double t_steady_;
  const Vec2 n_rake_, n_flank_;
  Vec2 zone_force_[3] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};  // rake, edge, flank (x dt)
  double rake_ft_ = 0.0, rake_fn_ = 0.0, rake_slip_ = 0.0, rake_count_ = 0.0;
  double rake_avg_sum_ = 0.0;
  int rake_avg_n_ = 0;
  const int n_snap_;
  int snap_taken_ = 0;
  bool stopped_ = false;
};
}  // namespace

CuttingResult run_cutting(const CuttingSetup& c, const ProgressFn& progress) {
  CuttingRun run(c, progress);
  const DriveReport report = drive(run, "sph_cutting");
  return run.finish(report);
}

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Every parameter of sph_cutting, declared once with its member of the setup.
const DeclaredParams<CuttingSetup>& cutting_declaration() {
  using S = CuttingSetup;
  static const DeclaredParams<S> d = [] {
    const S def;
    DeclaredParams<S> p;
    p.bind(integer_param("particles_over_height", "particles over the workpiece height", def.particles_over_height, 4, 400), &S::particles_over_height)
        .bind(param("length", Dim::length, "workpiece length", def.length, 1e-6, 1.0), &S::length)
        .bind(param("height", Dim::length, "workpiece height", def.height, 1e-6, 1.0), &S::height)
        .bind(param(glossary::kDepthOfCut, Dim::length, "uncut chip thickness t_u", def.uncut_thickness, 1e-7, 1.0), &S::uncut_thickness)
        .bind(param("cut_distance", Dim::length, "cut distance", def.cut_distance, 1e-7, 1.0), &S::cut_distance)
        .bind(param(glossary::kCuttingSpeed, Dim::velocity, "cutting speed v_c", def.speed, 1e-3, 1e3), &S::speed)
        .bind(param(glossary::kFriction, Dim::dimensionless, "Coulomb friction coefficient", def.friction, 0.0, 2.0), &S::friction)
        .bind(param(glossary::kRakeAngle, Dim::angle, "rake angle", def.rake, -60 * kDeg, 60 * kDeg), &S::rake)
        .bind(param(glossary::kClearanceAngle, Dim::angle, "clearance angle", def.clearance, 0.5 * kDeg, 45 * kDeg), &S::clearance)
        .bind(param("edge_radius", Dim::length, "cutting-edge radius", def.edge_radius, 0.0, 1e-3), &S::edge_radius)
        .bind(switch_param("enhanced_thermal", "true: FMFS + convection/radiation (paper); false: the reference model", true), &S::enhanced_thermal)
        .bind(switch_param("brookshaw_band", "true: Brookshaw on a 2h band at surfaces (energy-conserving); false: the paper's mix (Brookshaw on surface particles only)", true), &S::brookshaw_band)
        .bind(integer_param("fixed_layers", "clamped particle layers at the bottom and the far end", def.fixed_layers, 1, 20), &S::fixed_layers)
        .bind(switch_param("tool_conduction", "tool particles conduct heat", true), &S::tool_conduction)
        .bind(param("tool_density", Dim::density, "tool density (not in the paper; WC-Co assumed)", def.tool_density, 1.0, 1e5), &S::tool_density)
        .bind(param("tool_depth", Dim::length, "size of the discretised tool band around the edge", def.tool_depth, 1e-6, 1.0), &S::tool_depth)
        .bind(switch_param("penalty_contact", "true: penalty + stick-slip friction; false: velocity-level contact", true), &S::penalty_contact)
        .bind(param("contact_offset", Dim::dimensionless, "contact surface offset in particle spacings", def.contact_offset, 0.0, 1.0), &S::contact_offset)
        .bind(integer_param("snapshots", "number of workpiece snapshots (equally spaced, last at the end)", 1.0, 1.0, 1000.0), &S::snapshots)
        .bind(param("steady_from", Dim::dimensionless, "fraction of the cut after which forces are averaged", def.steady_from, 0.0, 0.99), &S::steady_from)
        .bind(param("tool_heat_share", Dim::dimensionless, "share of the friction heat put into the tool; -1: effusivity partition sqrt(k rho c) (default)", def.tool_heat_share, -1.0, 1.0), &S::tool_heat_share)
        .bind(param("contact_stiffness", Dim::dimensionless, "penalty contact stiffness alpha (f_N = -alpha m g / dt^2; assumed, not in the paper)", def.contact_stiffness, 0.001, 1.0), &S::contact_stiffness)
        .bind(param("alpha_visc", Dim::dimensionless, "Monaghan artificial viscosity alpha (assumed, not in the paper)", def.alpha_visc, 0.0, 10.0), &S::alpha_visc)
        .bind(param("beta_visc", Dim::dimensionless, "Monaghan artificial viscosity beta (assumed, not in the paper)", def.beta_visc, 0.0, 10.0), &S::beta_visc)
        .bind(param("artificial_stress", Dim::dimensionless, "Gray artificial stress epsilon, 0 = off (assumed, not in the paper)", def.artificial_stress, 0.0, 1.0), &S::artificial_stress)
        .bind(param("xsph", Dim::dimensionless, "XSPH position smoothing epsilon, 0 = off (assumed, not in the paper)", def.xsph, 0.0, 1.0), &S::xsph)
        .add(option_param("flow_law", "flow stress of the workpiece",
                          {{"johnson_cook", "Johnson-Cook with the paper's Table 1 constants (Eq. 9)"},
                           {"sima_ozel", "Sima and Oezel (2010) Johnson-Cook with temperature-dependent strain softening, their Ti6Al4V constants (the law of the authors' ref. [20] for the Fig. 10 cut)"}},
                          "johnson_cook"),
             [](S& s, double v) { s.flow_law = static_cast<int>(v); })
        .bind(param("lattice_jitter", Dim::dimensionless, "random displacement of the free particles of the initial lattice, as a fraction of dx (scatter studies; 0 = regular lattice)", def.lattice_jitter, 0.0, 0.25), &S::lattice_jitter)
        .bind(integer_param("lattice_seed", "random seed of lattice_jitter", def.lattice_seed, 0.0, 4294967295.0), &S::lattice_seed)
        .bind(switch_param("shear_cap", "true: cap the friction stress at the chip's shear flow stress (Zorev); false: Coulomb only (paper)", false), &S::shear_cap);
    return p;
  }();
  return d;
}

std::vector<ParamSpec> cutting_params() { return cutting_declaration().specs(); }

std::vector<OutputSpec> cutting_scalars() {
  return {{"F_c", Dim::force_per_width, "mean cutting force per unit width (steady part)"},
               {"F_t", Dim::force_per_width, "mean thrust force per unit width (steady part)"},
               {"F_c_rake", Dim::force_per_width, "part of F_c from contacts on the rake face"},
               {"F_t_rake", Dim::force_per_width, "part of F_t from contacts on the rake face"},
               {"F_c_edge", Dim::force_per_width, "part of F_c from contacts on the rounded edge"},
               {"F_t_edge", Dim::force_per_width, "part of F_t from contacts on the rounded edge"},
               {"F_c_flank", Dim::force_per_width, "part of F_c from contacts on the clearance face"},
               {"F_t_flank", Dim::force_per_width, "part of F_t from contacts on the clearance face"},
               {"rake_friction_ratio", Dim::dimensionless, "sum |f_t| / sum |f_n| over rake-face contacts (steady part)"},
               {"rake_slip_fraction", Dim::dimensionless, "share of rake-face contacts at the Coulomb limit (steady part)"},
               {"rake_temperature", Dim::temperature, "mean temperature of particles on the rake face at the end"},
               {"rake_temperature_avg", Dim::temperature, "rake-face mean temperature averaged over the history windows of the steady part"},
               {"T_max", Dim::temperature, "maximum temperature at the end"},
               {"tool_rake_temperature", Dim::temperature, "mean temperature of tool particles on the rake face (up to 2 t_u)"},
               {"tool_T_max", Dim::temperature, "maximum tool temperature"},
               {"chip_height", Dim::length, "highest particle above the original surface"},
               {"steps", Dim::dimensionless, "time steps"},
               {"particles", Dim::dimensionless, "workpiece particles (particle-steps = particles x steps; the tool particles only conduct heat)"},
               {"heat_generated", Dim::force_per_width, "plastic + friction heat, J per metre of depth"},
               {"heat_imbalance", Dim::dimensionless, "(generated - stored - lost - sunk) / generated"},
               {"friction_heat", Dim::force_per_width, "friction heat, J per metre of depth"},
               {"heat_lost_fraction", Dim::dimensionless, "heat lost to the air by convection and radiation / heat generated"},
               {"friction_heat_tool_share", Dim::dimensionless, "fraction of the friction heat put into the tool"},
               {"plastic_heat_below_fraction", Dim::dimensionless, "share of the plastic heat generated in particles that started below the cut line"},
               {"stored_layer_fraction", Dim::dimensionless, "heat content at the end of the particles that started in the uncut layer / heat generated"},
               {"stored_below_fraction", Dim::dimensionless, "heat content at the end of the particles that started below the cut line / heat generated"},
               {"stored_chip_fraction", Dim::dimensionless, "heat content at the end of the chip columns / heat generated"},
               {"stored_tool_fraction", Dim::dimensionless, "heat content of the tool at the end / heat generated"},
               {"T_max_x", Dim::length, "x of the hottest workpiece particle relative to the lowest tool edge point"},
               {"T_max_y", Dim::length, "y of the hottest workpiece particle relative to the lowest tool edge point"},
               {"chip_thickness", Dim::length, "chip area / length of the chip's column-centroid line"},
               {"chip_T_mean", Dim::temperature, "mean temperature of the chip particles (lifted particles of the chip columns) at the end"},
               {"chip_ratio", Dim::dimensionless, "chip thickness / uncut thickness"},
               {"chip_curl", Dim::angle, "turning angle of the chip centroid line, first to last third"},
               {"chip_segments", Dim::dimensionless, "peaks of the column-mean eps_p profile along the uncut layer after 2 t_u of cut (3-column mean, hysteresis 0.2 x mean)"},
               {"serration_pitch", Dim::length, "mean distance between eps_p peaks along the uncut layer (NaN below 2 peaks)"},
               {"serration_cv", Dim::dimensionless, "std / mean of the smoothed column-mean eps_p profile after 2 t_u of cut"},
               {"tooth_segments", Dim::dimensionless, "teeth of the chip's free surface: peaks of the column thickness across the chip against the position along the uncut layer after 2 t_u of cut (3-column mean, hysteresis 0.1 x mean thickness)"},
               {"tooth_pitch", Dim::length, "mean distance between the teeth along the uncut layer (NaN below 2 teeth)"},
               {"tooth_amplitude", Dim::length, "half the mean height of a tooth over the thinnest column before the next one (NaN below 2 teeth)"},
               {"surface_top_fraction", Dim::dimensionless, "share of the lattice columns more than 3 t_u ahead of the tool whose top particle is detected as surface (NaN without surface detection)"},
               {"surface_second_fraction", Dim::dimensionless, "share of those columns whose second particle from the top is detected as surface too"},
               {"tool_work", Dim::force_per_width, "work of the tool on the workpiece over the run, J per metre of depth"},
               {"energy_residual", Dim::dimensionless, "first law at the end: (tool work - kinetic - elastic - plastic - friction - viscous + artificial-stress work - contact springs - contact work along the XSPH drift) / tool work"},
               {"kinetic_fraction", Dim::dimensionless, "kinetic energy at the end / tool work"},
               {"elastic_fraction", Dim::dimensionless, "stored elastic energy at the end / tool work"},
               {"plastic_fraction", Dim::dimensionless, "plastic dissipation sum V sigma_y d(eps_p) / tool work"},
               {"friction_fraction", Dim::dimensionless, "slip dissipation at the tool / tool work"},
               {"viscous_fraction", Dim::dimensionless, "artificial-viscosity dissipation / tool work"},
               {"artificial_stress_fraction", Dim::dimensionless, "work of the artificial-stress pair forces on the particles / tool work"},
               {"xsph_contact_fraction", Dim::dimensionless, "work of the penalty contact forces along the XSPH part of the drift / tool work (< 0: energy the XSPH drift lets the contact give the particles)"},
               {"conjugacy_error", Dim::dimensionless, "(work of the stress pair forces + constitutive power sum V sigma:D) / tool work: energy created (> 0) by the discrete divergence / gradient pair"},
               {"constitutive_error", Dim::dimensionless, "(constitutive power - elastic - plastic) / tool work: the stress update's own energy error"}};
}

CuttingSetup cutting_setup_from(const Values& v) {
  CuttingSetup c = cutting_declaration().make(v);
  c.history_window = c.cut_distance / c.speed / 200.0;
  return c;
}

// First law at window k: tool work - (kinetic + elastic + plastic + friction + viscous - work of the
// artificial stress + contact springs + contact work along the XSPH drift); the workpiece starts at
// rest and unstressed.
double energy_residual(const CuttingResult& r, std::size_t k) {
  return r.e_tool[k] - (r.e_kinetic[k] + r.e_elastic[k] + r.e_plastic[k] + r.e_friction[k] + r.e_viscous[k] - r.e_art[k] +
                        r.e_spring[k] + r.e_xsph[k]);
}

RunOutput cutting_output(const CuttingSetup& c, const CuttingResult& r) {
  RunOutput out;
  out.notes = drive_notes(r.drive, "sph_cutting");
  Table t;
  t.name = "forces";
  t.add("t", "s", r.t);
  t.add("cut_distance", "m", r.cut);
  t.add("F_c", "N/m", r.fc);
  t.add("F_t", "N/m", r.ft);
  out.tables.push_back(std::move(t));
  Table chip;
  chip.name = "chip";
  chip.add("x0", "m", r.chip_x0);
  chip.add("u", "m", r.chip_u);
  chip.add("s", "m", r.chip_s);
  chip.add("eps_p", "1", r.chip_eps);
  chip.add("cx", "m", r.chip_cx);
  chip.add("cy", "m", r.chip_cy);
  chip.add("thickness", "m", r.chip_t);
  out.tables.push_back(std::move(chip));
  Table en;
  en.name = "energy";
  en.add("t", "s", r.t);
  en.add("tool_work", "J/m", r.e_tool);
  en.add("kinetic", "J/m", r.e_kinetic);
  en.add("elastic", "J/m", r.e_elastic);
  en.add("plastic", "J/m", r.e_plastic);
  en.add("friction", "J/m", r.e_friction);
  en.add("viscous", "J/m", r.e_viscous);
  en.add("artificial_stress_work", "J/m", r.e_art);
  en.add("contact_springs", "J/m", r.e_spring);
  en.add("stress_work", "J/m", r.e_stress);
  en.add("internal_work", "J/m", r.e_internal);
  en.add("xsph_contact_work", "J/m", r.e_xsph);
  std::vector<double> residual;
  for (std::size_t k = 0; k < r.e_tool.size(); ++k) residual.push_back(energy_residual(r, k));
  en.add("residual", "J/m", residual);
  out.tables.push_back(std::move(en));
  out.snapshots = r.snapshots;
  if (!r.tool_snapshot.x.empty()) out.snapshots.push_back(r.tool_snapshot);
  const double generated = r.plastic_heat + r.friction_heat;
  const auto share = [generated](double q) { return generated > 0.0 ? q / generated : 0.0; };
  out.scalars = {{"F_c", r.fc_mean}, {"F_t", r.ft_mean}, {"rake_temperature", r.rake_temperature},
                 {"rake_temperature_avg", r.rake_temperature_avg},
                 {"T_max", r.T_max}, {"chip_height", r.chip_height}, {"steps", static_cast<double>(r.steps)},
                 {"particles", static_cast<double>(r.particles)},
                 {"tool_rake_temperature", r.tool_rake_temperature}, {"tool_T_max", r.tool_T_max},
                 {"heat_generated", r.plastic_heat + r.friction_heat}, {"heat_imbalance", r.heat_imbalance},
                 {"friction_heat", r.friction_heat},
                 {"heat_lost_fraction", r.plastic_heat + r.friction_heat > 0.0 ? r.heat_lost / (r.plastic_heat + r.friction_heat) : 0.0},
                 {"friction_heat_tool_share", r.friction_heat > 0.0 ? r.friction_heat_tool / r.friction_heat : 0.0},
                 {"plastic_heat_below_fraction", r.plastic_heat > 0.0 ? r.plastic_heat_below / r.plastic_heat : 0.0},
                 {"stored_layer_fraction", share(r.stored_layer)}, {"stored_below_fraction", share(r.stored_below)},
                 {"stored_chip_fraction", share(r.stored_chip)}, {"stored_tool_fraction", share(r.stored_tool)},
                 {"T_max_x", r.T_max_at.x()}, {"T_max_y", r.T_max_at.y()},
                 {"chip_thickness", r.chip_thickness}, {"chip_T_mean", r.chip_T_mean}, {"chip_ratio", r.chip_thickness / c.uncut_thickness},
                 {"chip_curl", r.chip_curl * 3.14159265358979323846 / 180.0}, {"chip_segments", r.chip_segments},
                 {"serration_pitch", r.serration_pitch}, {"serration_cv", r.serration_cv},
                 {"tooth_segments", r.tooth_segments}, {"tooth_pitch", r.tooth_pitch}, {"tooth_amplitude", r.tooth_amplitude},
                 {"surface_top_fraction", r.surface_top_fraction}, {"surface_second_fraction", r.surface_second_fraction},
                 {"F_c_rake", r.force_rake.x()}, {"F_t_rake", r.force_rake.y()},
                 {"F_c_edge", r.force_edge.x()}, {"F_t_edge", r.force_edge.y()},
                 {"F_c_flank", r.force_flank.x()}, {"F_t_flank", r.force_flank.y()},
                 {"rake_friction_ratio", r.rake_friction_ratio}, {"rake_slip_fraction", r.rake_slip_fraction}};

  out.scalar_units = {{"F_c", "N/m"}, {"F_t", "N/m"}, {"rake_temperature", "K"}, {"rake_temperature_avg", "K"}, {"T_max", "K"},
                      {"chip_height", "m"}, {"steps", "1"}, {"particles", "1"}, {"tool_rake_temperature", "K"}, {"tool_T_max", "K"},
                      {"heat_generated", "J/m"}, {"heat_imbalance", "1"}, {"friction_heat", "J/m"}, {"heat_lost_fraction", "1"},
                      {"friction_heat_tool_share", "1"}, {"plastic_heat_below_fraction", "1"}, {"stored_layer_fraction", "1"},
                      {"stored_below_fraction", "1"}, {"stored_chip_fraction", "1"}, {"stored_tool_fraction", "1"}, {"T_max_x", "m"}, {"T_max_y", "m"},
                      {"chip_thickness", "m"}, {"chip_T_mean", "K"}, {"chip_ratio", "1"}, {"chip_curl", "rad"}, {"chip_segments", "1"},
                      {"serration_pitch", "m"}, {"serration_cv", "1"}, {"surface_top_fraction", "1"}, {"surface_second_fraction", "1"},
                      {"tooth_segments", "1"}, {"tooth_pitch", "m"}, {"tooth_amplitude", "m"},
                      {"F_c_rake", "N/m"}, {"F_t_rake", "N/m"}, {"F_c_edge", "N/m"}, {"F_t_edge", "N/m"},
                      {"F_c_flank", "N/m"}, {"F_t_flank", "N/m"}, {"rake_friction_ratio", "1"}, {"rake_slip_fraction", "1"}};
  {  // first-law audit at the end of the run, as fractions of the tool's work
    const std::size_t k = r.e_tool.size();
    const double W = k > 0 ? r.e_tool[k - 1] : 0.0;
    const auto frac = [W](double e) { return W > 0.0 ? e / W : nan_value(); };
    const double nan = nan_value();
    out.scalars["tool_work"] = k > 0 ? W : nan;
    out.scalars["energy_residual"] = k > 0 ? frac(energy_residual(r, k - 1)) : nan;
    out.scalars["kinetic_fraction"] = k > 0 ? frac(r.e_kinetic[k - 1]) : nan;
    out.scalars["elastic_fraction"] = k > 0 ? frac(r.e_elastic[k - 1]) : nan;
    out.scalars["plastic_fraction"] = k > 0 ? frac(r.e_plastic[k - 1]) : nan;
    out.scalars["friction_fraction"] = k > 0 ? frac(r.e_friction[k - 1]) : nan;
    out.scalars["viscous_fraction"] = k > 0 ? frac(r.e_viscous[k - 1]) : nan;
    out.scalars["artificial_stress_fraction"] = k > 0 ? frac(r.e_art[k - 1]) : nan;
    out.scalars["xsph_contact_fraction"] = k > 0 ? frac(r.e_xsph[k - 1]) : nan;
    // the discrete stress divergence and velocity gradient are not conjugate: stress work on the
    // particles + constitutive power = energy the pair of operators creates (> 0) or loses
    out.scalars["conjugacy_error"] = k > 0 ? frac(r.e_stress[k - 1] + r.e_internal[k - 1]) : nan;
    // constitutive power - (elastic + plastic): the stress update's own error (Jaumann rotation,
    // radial return, the density update)
    out.scalars["constitutive_error"] = k > 0 ? frac(r.e_internal[k - 1] - r.e_elastic[k - 1] - r.e_plastic[k - 1]) : nan;
    for (const char* key : {"energy_residual", "kinetic_fraction", "elastic_fraction", "plastic_fraction", "friction_fraction",
                            "viscous_fraction", "artificial_stress_fraction", "xsph_contact_fraction", "conjugacy_error", "constitutive_error"})
      out.scalar_units[key] = "1";
    out.scalar_units["tool_work"] = "J/m";
  }
  out.notes.push_back("Snapshots: the workpiece states in time order, then (if the tool conducts) the "
                      "final tool particles with their temperature.");
  out.notes.push_back("Tool is rigid; its particles conduct heat (k 88 W/mK, c_p 292 J/kgK, density "
                      "assumed) and exchange heat with the workpiece by harmonic-mean Brookshaw pairs; "
                      "the friction heat (eta = 1) is split between tool and chip by the effusivity partition (default). Stabiliser "
                      "parameters (artificial viscosity 1/1, artificial stress 0.3, XSPH 0.5) are "
                      "assumed, the paper does not list them.");
  return out;
}

}  // namespace

SolverSpec detail::cutting_spec() {
  SolverSpec s;
  s.name = "sph_cutting";
  s.description = "Thermo-mechanical SPH orthogonal cutting of Ti6Al4V (rigid tool, Coulomb friction); "
                  "reference (Brookshaw, adiabatic) or enhanced (FMFS + convection/radiation) thermal model";
  s.source = "Afrasiabi et al. (2021) Appl. Sci. 11:1020, Sec. 5.2, Fig. 4, Table 1";
  s.params = cutting_params();
  s.tables = {{"forces",
               "tool force history (window means)",
               {{"t", "s", "time"},
                {"cut_distance", "m", "tool travel"},
                {"F_c", "N/m", "cutting force per unit width"},
                {"F_t", "N/m", "thrust force per unit width"}}},
              {"chip",
               "chip columns at the end: one row per column of the uncut layer",
               {{"x0", "m", "initial x of the column"},
                {"u", "m", "lift of the column"},
                {"s", "m", "arc length along the chip's centroid line"},
                {"eps_p", "1", "column-mean equivalent plastic strain"},
                {"cx", "m", "x of the column centroid"},
                {"cy", "m", "y of the column centroid"},
                {"thickness", "m", "span of the column's lifted particles across the chip (normal to the smoothed centroid line) plus dx"}}},
              {"energy",
               "first-law audit at the end of each force window (from the start of the run)",
               {{"t", "s", "time"},
                {"tool_work", "J/m", "work of the tool on the workpiece"},
                {"kinetic", "J/m", "kinetic energy"},
                {"elastic", "J/m", "stored elastic energy sum V (p^2/2K + S:S/4G)"},
                {"plastic", "J/m", "plastic dissipation sum V sigma_y d(eps_p)"},
                {"friction", "J/m", "slip dissipation at the tool"},
                {"viscous", "J/m", "artificial-viscosity dissipation"},
                {"artificial_stress_work", "J/m", "work of the artificial-stress pair forces on the particles"},
                {"contact_springs", "J/m", "energy in the penalty contact springs"},
                {"stress_work", "J/m", "work of the stress pair forces on the particles"},
                {"internal_work", "J/m", "constitutive power sum V sigma:D, integrated"},
                {"xsph_contact_work", "J/m", "work of the penalty contact forces along the XSPH part of the drift (< 0: energy the contact gives the particles without work of the tool)"},
                {"residual", "J/m", "tool work - kinetic - elastic - plastic - friction - viscous + artificial-stress work - springs - contact work along the XSPH drift"}}}};
  s.scalars = cutting_scalars();
  s.checkpoints = true;
  s.footprint = [](const Values& v) {
    // the workpiece lattice (tool particles are fewer); about 2 kB per particle: state, rates,
    // the neighbour list (about 30 neighbours in 2h) and the pair caches
    const double n = v.at("particles_over_height");
    const double particles = n * (v.at("length") / (v.at("height") / (n - 1.0)) + 1.0);
    return Footprint{particles, 2048.0 * particles, "particles"};
  };
  s.run = [](const Values& v, const ProgressFn& progress) {
    const CuttingSetup c = cutting_setup_from(v);
    return cutting_output(c, run_cutting(c, progress));
  };
  return s;
}

}  // namespace cutbench::sph

namespace cutbench::sph {

// sph_cutting_inputs: the values sph_cutting runs with by default (CuttingSetup defaults turned into
// solver inputs by cutting_inputs()), for the Table 1 case to compare with the paper.
SolverSpec detail::cutting_inputs_spec() {
  SolverSpec s;
  s.name = "sph_cutting_inputs";
  s.description = "Default inputs of sph_cutting (geometry, material, thermal, contact) as used by the runner";
  s.source = "Afrasiabi et al. (2021) Appl. Sci. 11:1020, Table 1 and Sec. 5.2";
  struct Item {
    const char* name;
    Dim dim;
    const char* unit;
    const char* what;
  };
  static const Item items[] = {
      {"tool_clearance", Dim::angle, "rad", "clearance angle"}, {"tool_rake", Dim::angle, "rad", "rake angle"},
      {"tool_edge_radius", Dim::length, "m", "edge radius"}, {"vc", Dim::velocity, "m/s", "cutting speed"},
      {"tool_k", Dim::conductivity, "W/m/K", "tool conductivity"}, {"tool_cp", Dim::specific_heat, "J/kg/K", "tool specific heat"},
      {"wp_lx", Dim::length, "m", "workpiece length"}, {"wp_ly", Dim::length, "m", "workpiece height"},
      {"tu", Dim::length, "m", "uncut chip thickness"}, {"lc", Dim::length, "m", "cut distance"},
      {"wp_rho", Dim::density, "kg/m^3", "workpiece density"}, {"wp_E", Dim::stress, "Pa", "Young's modulus"},
      {"wp_nu", Dim::dimensionless, "1", "Poisson ratio"}, {"wp_k", Dim::conductivity, "W/m/K", "workpiece conductivity"},
      {"wp_cp", Dim::specific_heat, "J/kg/K", "workpiece specific heat"}, {"Tr", Dim::temperature, "K", "J-C reference temperature"},
      {"Tm", Dim::temperature, "K", "J-C melting temperature"}, {"mu", Dim::dimensionless, "1", "friction coefficient"},
      {"chi", Dim::dimensionless, "1", "plastic work to heat"}, {"eta", Dim::dimensionless, "1", "friction work to heat"},
      {"hc", Dim::heat_transfer, "W/m^2/K", "convection coefficient (enhanced model)"},
      {"emissivity", Dim::dimensionless, "1", "emissivity (enhanced model)"},
      {"jc_A", Dim::stress, "Pa", "J-C A"}, {"jc_B", Dim::stress, "Pa", "J-C B"}, {"jc_C", Dim::dimensionless, "1", "J-C C"},
      {"jc_m", Dim::dimensionless, "1", "J-C m"}, {"jc_n", Dim::dimensionless, "1", "J-C n"},
      {"T_inf", Dim::temperature, "K", "ambient and clamped-layer temperature"},
      {"particles_along_ly", Dim::dimensionless, "1", "particles over the height"},
      {"surface_lambda", Dim::dimensionless, "1", "surface-detection eigenvalue threshold"},
      {"h_over_dx", Dim::dimensionless, "1", "smoothing length / particle spacing"},
  };
  for (const auto& it : items) s.scalars.push_back({it.name, it.dim, it.what});
  s.run = [](const Values&, const ProgressFn&) {
    const CuttingSetup c;
    const CuttingInputs in = cutting_inputs(c);
    const auto& jc = in.material.jc;
    const std::map<std::string, double> v = {
        {"tool_clearance", c.clearance}, {"tool_rake", c.rake}, {"tool_edge_radius", c.edge_radius},
        {"vc", c.speed}, {"tool_k", in.tool_heat.conductivity}, {"tool_cp", in.tool_heat.specific_heat},
        {"wp_lx", c.length}, {"wp_ly", c.height}, {"tu", c.uncut_thickness}, {"lc", c.cut_distance},
        {"wp_rho", in.material.density}, {"wp_E", in.material.young}, {"wp_nu", in.material.poisson},
        {"wp_k", in.thermal.heat.conductivity}, {"wp_cp", in.thermal.heat.specific_heat}, {"Tr", jc.T_ref},
        {"Tm", jc.T_melt}, {"mu", in.contact.friction}, {"chi", in.thermal.taylor_quinney},
        {"eta", in.contact.heat_fraction}, {"hc", in.thermal.boundary.h_conv},
        {"emissivity", in.thermal.boundary.emissivity}, {"jc_A", jc.A}, {"jc_B", jc.B}, {"jc_C", jc.C},
        {"jc_m", jc.m}, {"jc_n", jc.n}, {"T_inf", in.thermal.boundary.T_ambient},
        {"particles_along_ly", static_cast<double>(c.particles_over_height)},
        {"surface_lambda", in.thermal.surface.lambda_interior}, {"h_over_dx", in.h_over_dx},
    };
    RunOutput out;
    for (const auto& it : items) out.set_scalar(it.name, v.at(it.name), it.unit);
    // consistency of the runner's own values that must agree between the solid and the heat model
    if (in.thermal.heat.density != in.material.density)
      throw NumericalError("sph_cutting_inputs: mechanical and thermal densities differ");
    out.notes.push_back("Values are read from CuttingSetup{} through cutting_inputs(), the same path run_cutting() uses.");
    return out;
  };
  return s;
}

}  // namespace cutbench::sph
