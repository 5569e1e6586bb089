#include "cutbench/mpm/problem.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "cutbench/common/errors.hpp"
#include "cutbench/mpm/shape.hpp"

namespace cutbench::mpm {

namespace {
// this thread's number inside a parallel region (0 without OpenMP)
inline int thread_id() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
constexpr int kFields = 3;
constexpr std::uint8_t kRigid = 2;
constexpr double kHuge = 1e300;
}  // namespace

MpmProblem::MpmProblem(MpmConfig cfg) : cfg_(std::move(cfg)) {
  const auto& g = cfg_.grid;
  if (!(g.dx > 0.0) || g.nx < 2 || g.ny < 2) throw InputError("grid", "needs dx > 0 and at least 2x2 cells");
  nnx_ = g.nx + 1;
  nny_ = g.ny + 1;
  nn_ = nnx_ * nny_;
  lp_ = 0.25 * g.dx;
  ugx_ = UgimpGrid(g.x0, g.dx, lp_);
  ugy_ = UgimpGrid(g.y0, g.dx, lp_);
}

void MpmProblem::add_particle(double x, double y, double volume, bool rigid, double vx, double vy) {
  if (setup_done_) throw std::logic_error("MpmProblem::add_particle after setup()");
  x_.push_back(x);
  y_.push_back(y);
  X0_.push_back(x);
  Y0_.push_back(y);
  vx_.push_back(rigid ? 0.0 : vx);
  vy_.push_back(rigid ? 0.0 : vy);
  vol0_.push_back(volume);
  mass_.push_back(cfg_.material.rho * volume);
  J_.push_back(1.0);
  alpha_.push_back(0.0);
  Fxx_.push_back(1.0);
  Fxy_.push_back(0.0);
  Fyx_.push_back(0.0);
  Fyy_.push_back(1.0);
  bxx_.push_back(1.0);
  bxy_.push_back(0.0);
  byy_.push_back(1.0);
  bzz_.push_back(1.0);
  txx_.push_back(0.0);
  txy_.push_back(0.0);
  tyy_.push_back(0.0);
  tzz_.push_back(0.0);
  rigid_.push_back(rigid ? 1 : 0);
  side_.push_back(cfg_.crack.enabled && y < cfg_.crack.y ? 0 : 1);
  frozen_.push_back(0);
  left_.push_back(0);
  id_.push_back(id_.size());
}

void MpmProblem::setup() {
  if (setup_done_) return;
  const std::size_t np = x_.size();
  if (np == 0) throw InputError("particles", "no particles");
#ifdef _OPENMP
  nthreads_ = cfg_.numerics.threads > 0 ? cfg_.numerics.threads : std::max(1, omp_get_max_threads());
  if (cfg_.numerics.min_particles_per_thread > 0) {
    const long cap = std::max(1L, static_cast<long>(np) / cfg_.numerics.min_particles_per_thread);
    nthreads_ = static_cast<int>(std::min<long>(nthreads_, cap));
  }
#endif
  double mmax = 0.0;
  for (std::size_t p = 0; p < np; ++p) {
    if (!rigid_[p]) {
      ++n_deformable_;
      mass_deformable_ += mass_[p];
    }
    mmax = std::max(mmax, mass_[p]);
  }
  mmin_ = cfg_.numerics.min_mass_fraction * mmax;
  dt_ = cfg_.dt > 0.0 ? cfg_.dt : cfg_.numerics.cfl * cfg_.grid.dx / cfg_.material.p_wave_speed();
  // A rigid body moving faster than the wave speed is not resolved.
  const double vmax = cfg_.tool.velocity.norm();
  if (vmax > 0.0) dt_ = std::min(dt_, cfg_.numerics.cfl * cfg_.grid.dx / (vmax + cfg_.material.p_wave_speed()));

  i0_.assign(np, 0);
  j0_.assign(np, 0);
  wx_.assign(3 * np, 0.0);
  wy_.assign(3 * np, 0.0);
  dwx_.assign(3 * np, 0.0);
  dwy_.assign(3 * np, 0.0);
  fid_.assign(9 * np, 0);
  perm_.assign(np, 0);
  count_.assign(static_cast<std::size_t>(cfg_.grid.nx) * static_cast<std::size_t>(cfg_.grid.ny) + 2, 0);
  dscratch_.assign(np, 0.0);
  bscratch_.assign(np, 0);
  sscratch_.assign(np, 0);
  iscratch_.assign(np, 0);
  const bool avg = cfg_.numerics.strain_update == Numerics::StrainUpdate::usavg;
  for (auto* v : {&Lxx_, &Lxy_, &Lyx_, &Lyy_}) v->assign(avg ? np : 0, 0.0);
  wp_.assign(np, 0.0);
  sp_.assign(np, 0.0);
  thread_sum_.assign(static_cast<std::size_t>(nthreads_), Eigen::Vector2d::Zero());

  nodes_.assign(kFields * static_cast<std::size_t>(nn_), NodeData{});
  tbuf_.assign(static_cast<std::size_t>(nthreads_), std::vector<NodeData>(nodes_.size(), NodeData{}));
  vnew_.assign(nodes_.size(), Eigen::Vector2d::Zero());
  acc_.assign(nodes_.size(), Eigen::Vector2d::Zero());
  vstrain_.assign(nodes_.size(), Eigen::Vector2d::Zero());
  grid_sums_.assign(static_cast<std::size_t>(nthreads_), GridSums{});
  coh_impulses_.clear();
  fixed_.assign(static_cast<std::size_t>(nn_), 0);
  cohesive_opening_.assign(static_cast<std::size_t>(nnx_), 1e30);
  if (cfg_.fixed_mask) {
    for (int j = 0; j < nny_; ++j) {
      for (int i = 0; i < nnx_; ++i) {
        fixed_[static_cast<std::size_t>(i + j * nnx_)] =
            cfg_.fixed_mask(cfg_.grid.x0 + i * cfg_.grid.dx, cfg_.grid.y0 + j * cfg_.grid.dx);
      }
    }
  }

  // Crack surface: pairs of points (top, bottom) at segment centres along the crack line.
  if (cfg_.crack.enabled) {
    const auto& c = cfg_.crack;
    const double len = c.seg_len > 0.0 ? c.seg_len : 0.5 * cfg_.grid.dx;
    cfg_.crack.seg_len = len;
    const int nseg = static_cast<int>(std::floor((c.x_end - c.x_begin) / len + 1e-9));
    for (int k = 0; k < nseg; ++k) {
      const double xc = c.x_begin + (k + 0.5) * len;
      crack_.xc.push_back(xc);
      crack_.top.emplace_back(xc, c.y);
      crack_.bot.emplace_back(xc, c.y);
      CohesiveState s;
      const bool is_free = !c.cohesive || xc < c.x_free_end;
      s.failed = is_free;
      crack_.state.push_back(s);
      crack_.free.push_back(is_free ? 1 : 0);
    }
  }
  setup_done_ = true;
  if (cfg_.numerics.sort_interval > 0) sort_particles();
  coh_impulses_.reserve(18 * crack_.xc.size() + 1);  // two points a segment, nine nodes each: no allocation in step()
  initial_energy_ = kinetic_energy() + strain_energy();
}

int MpmProblem::field_of(double xp, double yp, int side_p, double xi, double yi) const {
  const auto& c = cfg_.crack;
  const int side_n = yi > c.y ? 1 : 0;
  if (side_n == side_p) return 0;
  double xc = 0.5 * (xp + xi);
  const double dy = yi - yp;
  if ((yp - c.y) * (yi - c.y) < 0.0 && std::fabs(dy) > 0.0) xc = xp + (xi - xp) * (c.y - yp) / dy;
  return xc <= c.x_end ? 1 : 0;
}

std::string MpmProblem::fault() const {
  const double limit = cfg_.numerics.leave_limit * static_cast<double>(n_deformable_);
  if (frozen_count_ > 0 && static_cast<double>(frozen_count_) > limit) {
    std::ostringstream os;
    os << frozen_count_ << " particles have left the grid (limit " << cfg_.numerics.leave_limit
       << " of the " << n_deformable_ << " deformable particles) at step " << steps_ << ", t = " << time_ << " s";
    for (std::size_t p = 0; p < x_.size(); ++p) {
      if (left_[p]) {
        os << "; the first in storage order: particle " << id_[p] << (rigid_[p] ? " (tool)" : "");
        break;
      }
    }
    return os.str();
  }
  for (std::size_t p = 0; p < x_.size(); ++p) {
    const bool finite = std::isfinite(x_[p]) && std::isfinite(y_[p]) && std::isfinite(vx_[p]) && std::isfinite(vy_[p]) &&
                        std::isfinite(txx_[p]) && std::isfinite(txy_[p]) && std::isfinite(tyy_[p]) &&
                        std::isfinite(tzz_[p]);
    if (!finite || frozen_[p]) {
      std::ostringstream os;
      os << "particle " << id_[p] << (rigid_[p] ? " (tool)" : "") << " at (" << x_[p] << ", " << y_[p] << ") m "
         << (finite ? "left the grid and could not be returned" : "has a non-finite position, velocity or stress")
         << " at step " << steps_ << ", t = " << time_ << " s";
      return os.str();
    }
  }
  return {};
}

namespace {
constexpr std::uint64_t kStateVersion = 6;
}  // namespace

void MpmProblem::save_state(BinaryWriter& w) const {
  w.u64(kStateVersion);
  w.u64(x_.size());
  w.f64(time_);
  w.u64(static_cast<std::uint64_t>(steps_));
  w.u64(static_cast<std::uint64_t>(frozen_count_));
  for (const auto* v : {&x_, &y_, &X0_, &Y0_, &vx_, &vy_, &mass_, &vol0_, &J_, &alpha_, &Fxx_, &Fxy_, &Fyx_, &Fyy_,
                        &bxx_, &bxy_, &byy_, &bzz_, &txx_, &txy_, &tyy_, &tzz_, &wp_, &sp_}) {
    w.vec(*v);
  }
  for (const auto* v : {&rigid_, &side_, &frozen_, &left_}) w.pods(*v);
  w.pods(id_);
  w.vec(crack_.xc);
  w.pods(crack_.top);
  w.pods(crack_.bot);
  w.pods(crack_.free);
  w.u64(crack_.state.size());
  for (const auto& c : crack_.state) {
    w.f64(c.dn_max);
    w.f64(c.dt_max);
    w.u64(c.failed ? 1 : 0);
    w.f64(c.JI);
    w.f64(c.JII);
  }
  w.pods(std::vector<Eigen::Vector2d>{forces_.total, forces_.below, rigid_disp_});
  w.f64(forces_.normal_below);
  w.f64(alpha_fb_);
  w.vec({audit_.tool_work, audit_.pic_damping, audit_.feedback_loss, audit_.increment_loss, audit_.tool_contact_loss,
         audit_.crack_contact_loss, audit_.internal_work, audit_.cohesive_work});
  w.vec(cohesive_opening_);  // USAVG: the openings of the strain-last extrapolation, for its redo
}

void MpmProblem::load_state(BinaryReader& r) {
  if (!setup_done_) setup();
  if (r.u64() != kStateVersion) throw std::runtime_error("MPM state: another format version");
  const std::size_t np = x_.size();
  if (r.u64() != np) throw std::runtime_error("MPM state: another number of particles");
  time_ = r.f64();
  steps_ = static_cast<long>(r.u64());
  frozen_count_ = static_cast<long>(r.u64());
  auto sized = [&](auto v, std::size_t n, const char* what) {
    if (v.size() != n) throw std::runtime_error(std::string("MPM state: wrong size of ") + what);
    return v;
  };
  for (auto* v : {&x_, &y_, &X0_, &Y0_, &vx_, &vy_, &mass_, &vol0_, &J_, &alpha_, &Fxx_, &Fxy_, &Fyx_, &Fyy_, &bxx_,
                  &bxy_, &byy_, &bzz_, &txx_, &txy_, &tyy_, &tzz_, &wp_, &sp_}) {
    *v = sized(r.vec(), np, "a particle field");
  }
  for (auto* v : {&rigid_, &side_, &frozen_, &left_}) *v = sized(r.pods<std::uint8_t>(), np, "a particle flag");
  id_ = sized(r.pods<std::size_t>(), np, "the particle ids");
  const std::size_t ns = crack_.xc.size();
  crack_.xc = sized(r.vec(), ns, "the crack segments");
  crack_.top = sized(r.pods<Eigen::Vector2d>(), ns, "the crack surfaces");
  crack_.bot = sized(r.pods<Eigen::Vector2d>(), ns, "the crack surfaces");
  crack_.free = sized(r.pods<std::uint8_t>(), ns, "the crack segments");
  if (r.u64() != ns) throw std::runtime_error("MPM state: wrong size of the cohesive states");
  for (auto& c : crack_.state) {
    c.dn_max = r.f64();
    c.dt_max = r.f64();
    c.failed = r.u64() != 0;
    c.JI = r.f64();
    c.JII = r.f64();
  }
  const auto vecs = sized(r.pods<Eigen::Vector2d>(), 3, "the forces");
  forces_.total = vecs[0];
  forces_.below = vecs[1];
  rigid_disp_ = vecs[2];
  forces_.normal_below = r.f64();
  alpha_fb_ = r.f64();
  const auto a = sized(r.vec(), 8, "the energy audit");
  audit_ = EnergyAudit{a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]};
  cohesive_opening_ = sized(r.vec(), cohesive_opening_.size(), "the crack openings");
  extrapolated_ = false;  // the next step extrapolates the loaded particles afresh
}

bool MpmProblem::compute_shape(std::size_t p, long& newly_left) {
  const auto& g = cfg_.grid;
  const bool crack = cfg_.crack.enabled;
  if (frozen_[p]) return false;
  int i0 = ugimp_axis(x_[p], ugx_, &wx_[3 * p], &dwx_[3 * p]);
  int j0 = ugimp_axis(y_[p], ugy_, &wy_[3 * p], &dwy_[3 * p]);
  if (i0 < 0 || j0 < 0 || i0 + 2 > g.nx || j0 + 2 > g.ny || !std::isfinite(x_[p]) || !std::isfinite(y_[p])) {
    if (!std::isfinite(x_[p]) || !std::isfinite(y_[p]) || !return_to_grid(p)) {
      frozen_[p] = 1;  // a non-finite position, or no valid cell to return to: a fault
      return false;
    }
    if (!left_[p]) {
      left_[p] = 1;
      ++newly_left;
    }
    i0 = ugimp_axis(x_[p], ugx_, &wx_[3 * p], &dwx_[3 * p]);
    j0 = ugimp_axis(y_[p], ugy_, &wy_[3 * p], &dwy_[3 * p]);
  }
  i0_[p] = i0;
  j0_[p] = j0;
  // fast path: all three node rows on the particle's side of the crack line (or no crack)
  const double ylo = g.y0 + j0 * g.dx, yhi = ylo + 2.0 * g.dx;
  const std::uint8_t uniform = rigid_[p] ? kRigid : std::uint8_t{0};
  const bool same_side = !crack || rigid_[p] || (side_[p] == 1 ? ylo > cfg_.crack.y : yhi <= cfg_.crack.y);
  if (same_side) {
    for (int q = 0; q < 9; ++q) fid_[9 * p + static_cast<std::size_t>(q)] = uniform;
    return true;
  }
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      fid_[9 * p + static_cast<std::size_t>(a + 3 * b)] = static_cast<std::uint8_t>(
          field_of(x_[p], y_[p], side_[p], g.x0 + (i0 + a) * g.dx, g.y0 + (j0 + b) * g.dx));
    }
  }
  return true;
}

bool MpmProblem::valid_position(double x, double y) const {
  const auto& g = cfg_.grid;
  double w[3], dw[3];
  const int i0 = ugimp_axis(x, ugx_, w, dw);
  const int j0 = ugimp_axis(y, ugy_, w, dw);
  return i0 >= 0 && j0 >= 0 && i0 + 2 <= g.nx && j0 + 2 <= g.ny;
}

// NairnMPM's ReturnToElement: back along the particle's velocity by one step, or else (NairnMPM:
// its element's centroid) the nearest point of the grid whose stencils are all inside it, then ten
// bisections towards where it went, keeping the last valid point.
bool MpmProblem::return_to_grid(std::size_t p) {
  const auto& g = cfg_.grid;
  double ox = x_[p], oy = y_[p];
  double ix = ox - dt_ * vx_[p], iy = oy - dt_ * vy_[p];
  if (!valid_position(ix, iy)) {
    ix = std::clamp(ox, g.x0 + g.dx, g.x0 + (g.nx - 1) * g.dx);
    iy = std::clamp(oy, g.y0 + g.dx, g.y0 + (g.ny - 1) * g.dx);
    if (!valid_position(ix, iy)) return false;
  }
  for (int pass = 0; pass < 10; ++pass) {
    const double mx = 0.5 * (ox + ix), my = 0.5 * (oy + iy);
    if (valid_position(mx, my)) {
      ix = mx;
      iy = my;
    } else {
      ox = mx;
      oy = my;
    }
  }
  x_[p] = ix;
  y_[p] = iy;
  return true;
}

template <class Add, class Store>
void MpmProblem::reduce_node_buffers(std::size_t nfield, Add&& add, Store&& store) {
#pragma omp for schedule(static)
  for (long il = 0; il < static_cast<long>(nfield); ++il) {
    const auto i = static_cast<std::size_t>(il);
    NodeData acc = tbuf_[0][i];
    for (std::size_t t = 1; t < tbuf_.size(); ++t) add(i, acc, tbuf_[t][i]);
    store(i, acc);
  }
}

void MpmProblem::particles_to_grid(bool with_forces) {
  const long np = static_cast<long>(x_.size());
  const Eigen::Vector2d grav = cfg_.gravity;
  const std::size_t nsz = nodes_.size();
  const bool ext = cfg_.contact.detection == 2;
  const Eigen::Vector2d na = cfg_.contact.n_above, nb = cfg_.contact.n_below;
  long newly_left = 0;
#pragma omp parallel num_threads(nthreads_)
  {
    const int tid = thread_id();
    std::vector<NodeData>& buf = tbuf_[static_cast<std::size_t>(tid)];
    std::fill(buf.begin(), buf.end(), NodeData{});
    if (ext) {  // max for material fields, min for the rigid field
      for (std::size_t i = 0; i < nsz; ++i) {
        const bool rig_field = i >= 2 * static_cast<std::size_t>(nn_);
        buf[i].e0 = buf[i].e1 = rig_field ? kHuge : -kHuge;
      }
    }
#pragma omp for schedule(static) reduction(+ : newly_left)
    for (long pl = 0; pl < np; ++pl) {
      const auto p = static_cast<std::size_t>(pl);
      if (!compute_shape(p, newly_left)) continue;
      const double m = mass_[p];
      const bool rig = rigid_[p] != 0;
      const double v0 = vol0_[p];
      const double sxx = txx_[p] * v0, sxy = txy_[p] * v0, syy = tyy_[p] * v0;
      // domain extents along the contact normals: far edge of material, near edges of the tool
      double ea = 0.0, eb = 0.0;
      if (ext) {
        if (rig) {
          ea = x_[p] * na.x() + y_[p] * na.y() - lp_ * (std::fabs(na.x()) + std::fabs(na.y()));
          eb = x_[p] * nb.x() + y_[p] * nb.y() - lp_ * (std::fabs(nb.x()) + std::fabs(nb.y()));
        } else {
          const Eigen::Vector2d& nn = side_[p] ? na : nb;
          // half-extent of the parallelogram F * square along nn: lp (|F^T nn|_1)
          const double gx = Fxx_[p] * nn.x() + Fyx_[p] * nn.y(), gy = Fxy_[p] * nn.x() + Fyy_[p] * nn.y();
          ea = x_[p] * nn.x() + y_[p] * nn.y() + lp_ * (std::fabs(gx) + std::fabs(gy));
        }
      }
      for (int b = 0; b < 3; ++b) {
        const double wyb = wy_[3 * p + static_cast<std::size_t>(b)];
        const double dwyb = dwy_[3 * p + static_cast<std::size_t>(b)];
        for (int a = 0; a < 3; ++a) {
          const double wxa = wx_[3 * p + static_cast<std::size_t>(a)];
          const double s = wxa * wyb;
          if (s <= 0.0) continue;
          const int n = (i0_[p] + a) + (j0_[p] + b) * nnx_;
          const std::size_t f = fid_[9 * p + static_cast<std::size_t>(a + 3 * b)];
          NodeData& nd = buf[f * static_cast<std::size_t>(nn_) + static_cast<std::size_t>(n)];
          const double ms = m * s;
          nd.m += ms;
          nd.mx += ms * x_[p];
          nd.my += ms * y_[p];
          if (ext) {
            if (rig) {
              nd.e0 = std::min(nd.e0, ea);
              nd.e1 = std::min(nd.e1, eb);
            } else {
              nd.e0 = std::max(nd.e0, ea);
            }
          }
          if (rig) continue;
          const double gx = dwx_[3 * p + static_cast<std::size_t>(a)] * wyb;
          const double gy = wxa * dwyb;
          nd.px += ms * vx_[p];
          nd.py += ms * vy_[p];
          if (!with_forces) continue;
          nd.fx += -(sxx * gx + sxy * gy) + ms * grav.x();
          nd.fy += -(sxy * gx + syy * gy) + ms * grav.y();
        }
      }
    }
    // implicit barrier; the rigid field's extents reduce with min, the material fields' with max
    const std::size_t nmat = 2 * static_cast<std::size_t>(nn_);
    reduce_node_buffers(
        nsz,
        [&](std::size_t i, NodeData& acc, const NodeData& o) {
          acc.m += o.m;
          acc.px += o.px;
          acc.py += o.py;
          acc.fx += o.fx;
          acc.fy += o.fy;
          acc.mx += o.mx;
          acc.my += o.my;
          if (ext) {
            const bool rig_field = i >= nmat;
            acc.e0 = rig_field ? std::min(acc.e0, o.e0) : std::max(acc.e0, o.e0);
            acc.e1 = rig_field ? std::min(acc.e1, o.e1) : std::max(acc.e1, o.e1);
          }
        },
        [&](std::size_t i, const NodeData& acc) { nodes_[i] = acc; });
  }
  frozen_count_ += newly_left;
}

template <class F>
void MpmProblem::for_point_nodes(const Eigen::Vector2d& pt, int side, F&& fn) const {
  const auto& g = cfg_.grid;
  double wx[3], wy[3], dwx[3], dwy[3];
  const int i0 = ugimp_axis(pt.x(), ugx_, wx, dwx);
  const int j0 = ugimp_axis(pt.y(), ugy_, wy, dwy);
  if (i0 < 0 || j0 < 0 || i0 + 2 > g.nx || j0 + 2 > g.ny) return;
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      const double s = wx[a] * wy[b];
      if (s <= 0.0) continue;
      const int i = i0 + a, j = j0 + b;
      const int f = field_of(pt.x(), pt.y(), side, g.x0 + i * g.dx, g.y0 + j * g.dx);
      const std::size_t k = static_cast<std::size_t>(f) * static_cast<std::size_t>(nn_) +
                            static_cast<std::size_t>(i + j * nnx_);
      if (nodes_[k].m <= mmin_) continue;
      fn(k, s);
    }
  }
}

void MpmProblem::update_crack_openings() {
  std::fill(cohesive_opening_.begin(), cohesive_opening_.end(), 1e30);
  for (std::size_t k = 0; k < crack_.xc.size(); ++k) {
    // opening seen by crack contact at the nearest node column
    const int col = static_cast<int>(std::lround((crack_.xc[k] - cfg_.grid.x0) / cfg_.grid.dx));
    if (col >= 0 && col < nnx_) {
      double& o = cohesive_opening_[static_cast<std::size_t>(col)];
      o = std::min(o, crack_.top[k].y() - crack_.bot[k].y());
    }
  }
}

void MpmProblem::cohesive_forces() {
  if (!cfg_.crack.enabled) return;
  const auto& c = cfg_.crack;
  const std::size_t ns = crack_.xc.size();
  update_crack_openings();
  for (std::size_t k = 0; k < ns; ++k) {
    const Eigen::Vector2d d = crack_.top[k] - crack_.bot[k];
    CohesiveState& st = crack_.state[k];
    if (st.failed) continue;
    const CohesiveTraction t = cohesive_update(c.mode1, c.mode2, d.y(), d.x(), st);
    if (st.failed) continue;
    const Eigen::Vector2d force(t.tt * c.seg_len, t.tn * c.seg_len);  // pulls top down/back
    for (int sidx = 0; sidx < 2; ++sidx) {
      const Eigen::Vector2d& pt = sidx == 0 ? crack_.top[k] : crack_.bot[k];
      const int side = sidx == 0 ? 1 : 0;
      const Eigen::Vector2d fvec = sidx == 0 ? Eigen::Vector2d(-force) : force;
      // Mass-weighted spreading (share S_i m_i / sum S m): every node of the field gets the same
      // acceleration, so nodes that hold only a sliver of a particle are not kicked.
      double wsum = 0.0;
      for_point_nodes(pt, side, [&](std::size_t kk, double s) { wsum += s * nodes_[kk].m; });
      if (wsum <= 0.0) continue;
      for_point_nodes(pt, side, [&](std::size_t kk, double s) {
        const double share = s * nodes_[kk].m / wsum;
        nodes_[kk].fx += fvec.x() * share;
        nodes_[kk].fy += fvec.y() * share;
        coh_impulses_.emplace_back(kk, fvec * share);  // for the audit's cohesive work
      });
    }
  }
}

void MpmProblem::resolve_contacts(std::size_t n, Eigen::Vector2d p[2], const bool has[2], const Eigen::Vector2d& V,
                                  Eigen::Vector2d& imp, Eigen::Vector2d& impb, Eigen::Vector2d dp_crack[2]) const {
  const double dt = dt_;
  const auto& ct = cfg_.contact;
  const double gapmax = ct.gap_factor * cfg_.grid.dx;
  const bool crack = cfg_.crack.enabled;
  const auto nnz = static_cast<std::size_t>(nn_);
  const int i = static_cast<int>(n % static_cast<std::size_t>(nnx_));
  const double yn = cfg_.grid.y0 + static_cast<double>(n / static_cast<std::size_t>(nnx_)) * cfg_.grid.dx;
  const int node_side = (!crack || yn > cfg_.crack.y) ? 1 : 0;
  imp.setZero();
  impb.setZero();
  dp_crack[0].setZero();
  dp_crack[1].setZero();
  // crack contact (frictionless) between the two sides when the crack is closed
  auto crack_contact = [&]() {
    if (!crack || !has[0] || !has[1]) return;
    const int fa = node_side == 1 ? 0 : 1;  // field holding material from above the crack
    const int fb = 1 - fa;
    const double ma = nodes_[static_cast<std::size_t>(fa) * nnz + n].m;
    const double mb = nodes_[static_cast<std::size_t>(fb) * nnz + n].m;
    const double vrel = p[fa].y() / ma - p[fb].y() / mb;
    if (cohesive_opening_[static_cast<std::size_t>(i)] + vrel * dt < 0.0) {
      const double vcm = (p[fa].y() + p[fb].y()) / (ma + mb);
      dp_crack[fa].y() = ma * vcm - p[fa].y();
      dp_crack[fb].y() = mb * vcm - p[fb].y();
      p[fa].y() = ma * vcm;
      p[fb].y() = mb * vcm;
    }
  };
  if (!ct.tool_contact_first) crack_contact();
  // rigid-body contact with prescribed normals
  const NodeData& rd = nodes_[kRigid * nnz + n];
  if (rd.m > mmin_) {
    const Eigen::Vector2d cr(rd.mx / rd.m, rd.my / rd.m);
    for (int f = 0; f < 2; ++f) {
      if (!has[f]) continue;
      const NodeData& nd = nodes_[static_cast<std::size_t>(f) * nnz + n];
      const int mat_side = f == 0 ? node_side : 1 - node_side;
      const Eigen::Vector2d& nrm = mat_side == 1 ? ct.n_above : ct.n_below;
      if (ct.detection == 1 && gapmax > 0.0) {
        const Eigen::Vector2d cm(nd.mx / nd.m, nd.my / nd.m);
        if ((cr - cm).dot(nrm) > gapmax) continue;
      } else if (ct.detection == 2) {
        const double tool_edge = mat_side == 1 ? rd.e0 : rd.e1;
        if (nd.e0 < tool_edge - gapmax) continue;  // domains apart
      }
      const Eigen::Vector2d dv = p[f] / nd.m - V;
      const double dvn = dv.dot(nrm);
      if (dvn <= 0.0) continue;
      Eigen::Vector2d dp = -nd.m * dvn * nrm;
      const Eigen::Vector2d vt = dv - dvn * nrm;
      const double vtn = vt.norm();
      if (vtn > 0.0) {
        const double fric = std::min(ct.mu * nd.m * dvn, nd.m * vtn);
        dp -= fric * vt / vtn;
      }
      p[f] += dp;
      imp += dp;
      if (mat_side == 0) impb += dp;
    }
  }
  if (ct.tool_contact_first) crack_contact();
}

void MpmProblem::grid_update() {
  const double dt = dt_;
  const double alpha = alpha_fb_;
  const Eigen::Vector2d V = cfg_.tool.at(time_ + dt);
  const Eigen::Vector2d grav = cfg_.gravity;
  const auto& ct = cfg_.contact;
  const auto nnz = static_cast<std::size_t>(nn_);
  // sums over the nodes: per thread over its static block in node order, then over the threads in
  // order (deterministic for a thread count; with one thread the plain node-order sum)
#pragma omp parallel num_threads(nthreads_)
  {
  const int tid = thread_id();
  GridSums loc;
#pragma omp for schedule(static)
  for (long nl = 0; nl < nn_; ++nl) {
    const auto n = static_cast<std::size_t>(nl);
    Eigen::Vector2d vold[2], p[2];
    bool has[2];
    const int fm = fixed_[n];
    double dfb = 0.0;  // energy audit: work of the damping force at the extrapolated velocity
    for (int f = 0; f < 2; ++f) {
      NodeData& nd = nodes_[static_cast<std::size_t>(f) * nnz + n];
      has[f] = nd.m > mmin_;
      if (!has[f]) {
        nd.m = 0.0;
        vold[f].setZero();
        p[f].setZero();
        continue;
      }
      vold[f] = Eigen::Vector2d(nd.px, nd.py) / nd.m;
      p[f] = Eigen::Vector2d(nd.px + (nd.fx - alpha * nd.px) * dt, nd.py + (nd.fy - alpha * nd.py) * dt);
      dfb += alpha * dt * (nd.px * nd.px + nd.py * nd.py) / nd.m;
    }
    // impulses other than the contacts' (forces, damping), for the audit's split by impulse
    const Eigen::Vector2d p_forces[2] = {p[0], p[1]};
    Eigen::Vector2d imp, impb, dpc[2];
    resolve_contacts(n, p, has, V, imp, impb, dpc);
    loc.imp += imp;
    loc.impb += impb;
    // fixed nodes
    double ke = 0.0, dinc = 0.0, tool_loss = 0.0, crack_loss = 0.0, wforces = 0.0;
    for (int f = 0; f < 2; ++f) {
      const std::size_t k = static_cast<std::size_t>(f) * nnz + n;
      if (!has[f]) {
        vnew_[k].setZero();
        acc_[k].setZero();
        continue;
      }
      if (fm & 1) {
        p[f].x() = 0.0;
        vold[f].x() = 0.0;
      }
      if (fm & 2) {
        p[f].y() = 0.0;
        vold[f].y() = 0.0;
      }
      const double m = nodes_[k].m;
      vnew_[k] = p[f] / m;
      acc_[k] = (vnew_[k] - vold[f]) / dt;
      const double vn2 = vnew_[k].squaredNorm();
      ke += 0.5 * m * vn2;
      dinc += 0.5 * m * (vnew_[k] - vold[f]).squaredNorm();  // grid side of the increment loss
      // The step's impulses at the mean velocity (fixed components are zero in both velocities, so
      // their reactions do no work). All of them together: m/2 (|v_new|^2 - |v_old|^2); less the
      // contacts' and the damping's, the grid forces' dt (f_int + f_coh + m g) . v_mid.
      const Eigen::Vector2d vmid = 0.5 * (vnew_[k] + vold[f]);
      Eigen::Vector2d dp_tool = p[f] - p_forces[f] - dpc[f];
      if (fm & 1) dp_tool.x() = 0.0;
      if (fm & 2) dp_tool.y() = 0.0;
      tool_loss += dp_tool.dot(V - vmid);
      crack_loss -= dpc[f].dot(vmid);
      const NodeData& nd = nodes_[k];
      wforces += 0.5 * m * (vn2 - vold[f].squaredNorm()) - (dp_tool + dpc[f]).dot(vmid) +
                 alpha * dt * Eigen::Vector2d(nd.px, nd.py).dot(vmid) - dt * m * grav.dot(vmid);
    }
    loc.ke += ke;
    const double node_audit[6] = {imp.dot(V), dfb, dinc, tool_loss, crack_loss, wforces};
    for (std::size_t q = 0; q < loc.au.size(); ++q) loc.au[q] += node_audit[q];
  }
  grid_sums_[static_cast<std::size_t>(tid)] = loc;
  }
  GridSums tot;
  for (const GridSums& g : grid_sums_) {
    tot.imp += g.imp;
    tot.impb += g.impb;
    tot.ke += g.ke;
    for (std::size_t q = 0; q < tot.au.size(); ++q) tot.au[q] += g.au[q];
  }
  const Eigen::Vector2d imp = tot.imp, impb = tot.impb;
  const double ke = tot.ke;
  const std::array<double, 6>& au = tot.au;
  audit_.tool_work += au[0];
  audit_.feedback_loss += au[1];
  audit_.increment_loss += au[2];  // less the particles' side, in grid_to_particles
  audit_.tool_contact_loss += au[3];
  audit_.crack_contact_loss += au[4];
  // the cohesive forces' work at the mean velocities of the nodes they act on; the internal
  // forces' is the grid forces' less it
  double wcoh = 0.0;
  for (const auto& [k, fc] : coh_impulses_) {
    if (nodes_[k].m > mmin_) wcoh -= dt * fc.dot(vnew_[k] - 0.5 * dt * acc_[k]);
  }
  coh_impulses_.clear();
  audit_.cohesive_work += wcoh;
  audit_.internal_work += -au[5] - wcoh;
  // the paper's "summing the momentum changes imposed by the contact algorithm on the rigid tool":
  // those of the momentum update only, as NairnMPM sums them (its rigid-contact routine adds the
  // contact force only in the momentum-update pass; the contact on the extrapolated momenta of
  // USAVG does work, counted in the audit, but is not part of the force)
  forces_.total = imp / dt;
  forces_.below = impb / dt;
  forces_.normal_below = -forces_.below.dot(ct.n_below);
  // feedback damping on grid kinetic energy
  const auto& fb = cfg_.damping;
  if (fb.gain > 0.0 && time_ + dt < fb.t_off && mass_deformable_ > 0.0) {
    const double ke_ref = 0.5 * mass_deformable_ * fb.v_ref * fb.v_ref;
    alpha_fb_ = std::clamp(alpha_fb_ + dt * fb.gain * ke / ke_ref, 0.0, 0.5 / dt);
  } else {
    alpha_fb_ = 0.0;
  }
}

void MpmProblem::update_strain(std::size_t p, const Eigen::Matrix2d& L, double h) {
  const Eigen::Matrix2d l = L * h;
  // stress power booked over the increment at the mean of the stresses before and after it (the
  // hyperelastic energy change to second order; the stress at the start alone under-books by
  // dtau : l / 2 in every step, loading or unloading)
  const double lsym01 = l(0, 1) + l(1, 0);
  const double power_n = txx_[p] * l(0, 0) + tyy_[p] * l(1, 1) + txy_[p] * lsym01;
  const double F00 = Fxx_[p], F01 = Fxy_[p], F10 = Fyx_[p], F11 = Fyy_[p];
  Fxx_[p] = F00 + l(0, 0) * F00 + l(0, 1) * F10;
  Fxy_[p] = F01 + l(0, 0) * F01 + l(0, 1) * F11;
  Fyx_[p] = F10 + l(1, 0) * F00 + l(1, 1) * F10;
  Fyy_[p] = F11 + l(1, 0) * F01 + l(1, 1) * F11;
  const double J = Fxx_[p] * Fyy_[p] - Fxy_[p] * Fyx_[p];
  J_[p] = J;
  double b[4] = {bxx_[p], bxy_[p], byy_[p], bzz_[p]};
  double tau[4];
  const double alpha0 = alpha_[p];
  update_stress_plane_strain(cfg_.material, l, J, b, alpha_[p], tau);
  // plastic work of the return (per reference volume): |s_{n+1}| dlambda = sigma_y(alpha_{n+1}) d alpha
  if (alpha_[p] > alpha0) wp_[p] += vol0_[p] * (cfg_.material.sigma_y0 + cfg_.material.Ep * alpha_[p]) * (alpha_[p] - alpha0);
  bxx_[p] = b[0];
  bxy_[p] = b[1];
  byy_[p] = b[2];
  bzz_[p] = b[3];
  txx_[p] = tau[0];
  txy_[p] = tau[1];
  tyy_[p] = tau[2];
  tzz_[p] = tau[3];
  sp_[p] += 0.5 * vol0_[p] * (power_n + tau[0] * l(0, 0) + tau[2] * l(1, 1) + tau[1] * lsym01);
}

namespace {
// Velocity gradient sum_i v_i (x) grad S_i over a particle's 9 nodes from a nodal velocity array.
template <class Idx>
inline Eigen::Matrix2d velocity_gradient(const double* wx, const double* wy, const double* dwx, const double* dwy,
                                         const std::vector<Eigen::Vector2d>& vel, Idx&& node_index) {
  Eigen::Matrix2d L = Eigen::Matrix2d::Zero();
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      if (wx[a] * wy[b] <= 0.0) continue;
      const Eigen::Vector2d& v = vel[node_index(a, b)];
      const double gx = dwx[a] * wy[b], gy = wx[a] * dwy[b];
      L(0, 0) += v.x() * gx;
      L(0, 1) += v.x() * gy;
      L(1, 0) += v.y() * gx;
      L(1, 1) += v.y() * gy;
    }
  }
  return L;
}
}  // namespace

void MpmProblem::grid_to_particles() {
  const long np = static_cast<long>(x_.size());
  const double dt = dt_;
  const double beta = cfg_.numerics.pic_fraction;
  const int order = cfg_.numerics.position_order;
  const auto scheme = cfg_.numerics.strain_update;
  const Eigen::Vector2d V = cfg_.tool.at(time_ + dt);
  const auto nnz = static_cast<std::size_t>(nn_);
  std::fill(thread_sum_.begin(), thread_sum_.end(), Eigen::Vector2d::Zero());
#pragma omp parallel num_threads(nthreads_)
  {
  const int tid = thread_id();
  double pic_damping = 0.0, increment_p = 0.0;
#pragma omp for schedule(static)
  for (long pl = 0; pl < np; ++pl) {
    const auto p = static_cast<std::size_t>(pl);
    if (frozen_[p]) continue;
    if (rigid_[p]) {
      x_[p] += V.x() * dt;
      y_[p] += V.y() * dt;
      vx_[p] = V.x();
      vy_[p] = V.y();
      continue;
    }
    auto idx = [&](int a, int b) {
      return fid_[9 * p + static_cast<std::size_t>(a + 3 * b)] * nnz +
             static_cast<std::size_t>((i0_[p] + a) + (j0_[p] + b) * nnx_);
    };
    Eigen::Vector2d vg = Eigen::Vector2d::Zero(), ag = Eigen::Vector2d::Zero();
    for (int b = 0; b < 3; ++b) {
      for (int a = 0; a < 3; ++a) {
        const double s = wx_[3 * p + static_cast<std::size_t>(a)] * wy_[3 * p + static_cast<std::size_t>(b)];
        if (s <= 0.0) continue;
        const std::size_t k = idx(a, b);
        vg += s * vnew_[k];
        ag += s * acc_[k];
      }
    }
    const Eigen::Vector2d vp(vx_[p], vy_[p]);
    const Eigen::Vector2d vgn = vg - ag * dt;  // v_{g->p}^{(n)}
    const Eigen::Vector2d vflip = vp + ag * dt;
    const Eigen::Vector2d vnew = vflip - beta * (vp - vgn);
    pic_damping += 0.5 * mass_[p] * (vflip.squaredNorm() - vnew.squaredNorm());  // removed by the PIC part
    increment_p += 0.5 * mass_[p] * (ag * dt).squaredNorm();
    Eigen::Vector2d dx;
    if (order == 0) {
      dx = dt * vg;
    } else if (order == 1) {
      dx = dt * (vg - 0.5 * beta * (vp - vgn));
    } else {
      dx = dt * (vgn + 0.5 * (vnew - vp));
    }
    x_[p] += dx.x();
    y_[p] += dx.y();
    vx_[p] = vnew.x();
    vy_[p] = vnew.y();
    if (scheme == Numerics::StrainUpdate::usl) {  // gradient of the updated grid velocities
      update_strain(p, velocity_gradient(&wx_[3 * p], &wy_[3 * p], &dwx_[3 * p], &dwy_[3 * p], vnew_, idx), dt);
    }
  }
  thread_sum_[static_cast<std::size_t>(tid)] = Eigen::Vector2d(pic_damping, increment_p);
  }
  // the increment loss sum_I m_I/2 |dv_I|^2 - sum_p m_p/2 |sum_I S_Ip dv_I|^2 (>= 0, Jensen): the
  // nodes' part is added in grid_update
  for (const Eigen::Vector2d& e : thread_sum_) {
    audit_.pic_damping += e[0];
    audit_.increment_loss -= e[1];
  }
  rigid_disp_ += V * dt;
  if (scheme != Numerics::StrainUpdate::musl) return;
  remap_momenta();
#pragma omp parallel for schedule(static) num_threads(nthreads_)
  for (long pl = 0; pl < np; ++pl) {
    const auto p = static_cast<std::size_t>(pl);
    if (frozen_[p] || rigid_[p]) continue;
    auto idx = [&](int a, int b) {
      return fid_[9 * p + static_cast<std::size_t>(a + 3 * b)] * nnz +
             static_cast<std::size_t>((i0_[p] + a) + (j0_[p] + b) * nnx_);
    };
    update_strain(p, velocity_gradient(&wx_[3 * p], &wy_[3 * p], &dwx_[3 * p], &dwy_[3 * p], vstrain_, idx), dt);
  }
}

void MpmProblem::constrained_velocities(std::size_t n, const Eigen::Vector2d& V, bool contact, Eigen::Vector2d pm[2],
                                         Eigen::Vector2d& imp, Eigen::Vector2d& impb) {
  const auto nnz = static_cast<std::size_t>(nn_);
  bool has[2];
  for (int f = 0; f < 2; ++f) {
    const NodeData& nd = nodes_[static_cast<std::size_t>(f) * nnz + n];
    has[f] = nd.m > mmin_;
    pm[f] = has[f] ? Eigen::Vector2d(nd.px, nd.py) : Eigen::Vector2d::Zero();
  }
  imp.setZero();
  impb.setZero();
  Eigen::Vector2d dpc[2];
  if (contact) resolve_contacts(n, pm, has, V, imp, impb, dpc);
  const int fm = fixed_[n];
  for (int f = 0; f < 2; ++f) {
    const std::size_t k = static_cast<std::size_t>(f) * nnz + n;
    if (!has[f]) {
      vstrain_[k].setZero();
      continue;
    }
    if (fm & 1) pm[f].x() = 0.0;
    if (fm & 2) pm[f].y() = 0.0;
    vstrain_[k] = pm[f] / nodes_[k].m;
  }
}

void MpmProblem::remap_momenta() {
  const long np = static_cast<long>(x_.size());
  const Eigen::Vector2d V = cfg_.tool.at(time_ + dt_);
  const auto nnz = static_cast<std::size_t>(nn_);
  const long nfield = 2 * static_cast<long>(nnz);
#pragma omp parallel num_threads(nthreads_)
  {
    const int tid = thread_id();
    std::vector<NodeData>& buf = tbuf_[static_cast<std::size_t>(tid)];
    for (long i = 0; i < nfield; ++i) {
      buf[static_cast<std::size_t>(i)].px = 0.0;
      buf[static_cast<std::size_t>(i)].py = 0.0;
    }
#pragma omp for schedule(static)
    for (long pl = 0; pl < np; ++pl) {
      const auto p = static_cast<std::size_t>(pl);
      if (frozen_[p] || rigid_[p]) continue;
      const double m = mass_[p];
      for (int b = 0; b < 3; ++b) {
        for (int a = 0; a < 3; ++a) {
          const double s = wx_[3 * p + static_cast<std::size_t>(a)] * wy_[3 * p + static_cast<std::size_t>(b)];
          if (s <= 0.0) continue;
          NodeData& nd = buf[fid_[9 * p + static_cast<std::size_t>(a + 3 * b)] * nnz +
                             static_cast<std::size_t>((i0_[p] + a) + (j0_[p] + b) * nnx_)];
          nd.px += m * s * vx_[p];
          nd.py += m * s * vy_[p];
        }
      }
    }
    reduce_node_buffers(
        static_cast<std::size_t>(nfield),
        [](std::size_t, NodeData& acc, const NodeData& o) {
          acc.px += o.px;
          acc.py += o.py;
        },
        [&](std::size_t i, const NodeData& acc) {
          nodes_[i].px = acc.px;
          nodes_[i].py = acc.py;
        });
#pragma omp for schedule(static)
    for (long nl = 0; nl < nn_; ++nl) {
      Eigen::Vector2d pm[2], imp, impb;
      constrained_velocities(static_cast<std::size_t>(nl), V, cfg_.numerics.musl_recontact, pm, imp, impb);
    }
  }
}

Eigen::Vector2d MpmProblem::field_velocity(const Eigen::Vector2d& pt, int side,
                                           const std::vector<Eigen::Vector2d>& vel) const {
  Eigen::Vector2d v = Eigen::Vector2d::Zero();
  double wsum = 0.0;
  for_point_nodes(pt, side, [&](std::size_t k, double s) {  // momentum-weighted, see cohesive_forces()
    v += s * nodes_[k].m * vel[k];
    wsum += s * nodes_[k].m;
  });
  return wsum > 0.0 ? Eigen::Vector2d(v / wsum) : Eigen::Vector2d::Zero();
}

void MpmProblem::move_crack_surfaces() {
  if (!cfg_.crack.enabled) return;
  const std::vector<Eigen::Vector2d>& vel =
      cfg_.numerics.strain_update == Numerics::StrainUpdate::usl ? vnew_ : vstrain_;
  const long ns = static_cast<long>(crack_.xc.size());
#pragma omp parallel for schedule(static) num_threads(nthreads_) if (ns > 2000)
  for (long kl = 0; kl < ns; ++kl) {
    const auto k = static_cast<std::size_t>(kl);
    const Eigen::Vector2d vt = field_velocity(crack_.top[k], 1, vel);
    const Eigen::Vector2d vb = field_velocity(crack_.bot[k], 0, vel);
    crack_.top[k] += dt_ * vt;
    crack_.bot[k] += dt_ * vb;
  }
}

void MpmProblem::constrain_extrapolated(bool count, double t, bool fresh_openings) {
  if (fresh_openings && cfg_.crack.enabled) update_crack_openings();
  const Eigen::Vector2d V = cfg_.tool.at(t);
  const auto nnz = static_cast<std::size_t>(nn_);
#pragma omp parallel num_threads(nthreads_)
  {
  const int tid = thread_id();
  GridSums loc;
#pragma omp for schedule(static)
  for (long nl = 0; nl < nn_; ++nl) {
    const auto n = static_cast<std::size_t>(nl);
    Eigen::Vector2d pm[2], imp, impb;
    constrained_velocities(n, V, true, pm, imp, impb);
    for (int f = 0; f < 2; ++f) {  // in place (NairnMPM's post-extrapolation contact)
      NodeData& nd = nodes_[static_cast<std::size_t>(f) * nnz + n];
      if (nd.m <= mmin_) continue;
      nd.px = pm[f].x();
      nd.py = pm[f].y();
    }
    loc.au[0] += imp.dot(V);
  }
  grid_sums_[static_cast<std::size_t>(tid)] = loc;
  }
  double au = 0.0;
  for (const GridSums& g : grid_sums_) au += g.au[0];
  if (count) audit_.tool_work += au;
  const long np = static_cast<long>(x_.size());
#pragma omp parallel for schedule(static) num_threads(nthreads_)
  for (long pl = 0; pl < np; ++pl) {
    const auto p = static_cast<std::size_t>(pl);
    if (frozen_[p] || rigid_[p]) continue;
    auto idx = [&](int a, int b) {
      return fid_[9 * p + static_cast<std::size_t>(a + 3 * b)] * nnz +
             static_cast<std::size_t>((i0_[p] + a) + (j0_[p] + b) * nnx_);
    };
    const Eigen::Matrix2d L = velocity_gradient(&wx_[3 * p], &wy_[3 * p], &dwx_[3 * p], &dwy_[3 * p], vstrain_, idx);
    Lxx_[p] = L(0, 0);
    Lxy_[p] = L(0, 1);
    Lyx_[p] = L(1, 0);
    Lyy_[p] = L(1, 1);
  }
}

void MpmProblem::usavg_half(bool first) {
  const long np = static_cast<long>(x_.size());
  const double h = 0.5 * dt_;
  if (!first) {
#pragma omp parallel for schedule(static) num_threads(nthreads_)
    for (long pl = 0; pl < np; ++pl) {
      const auto p = static_cast<std::size_t>(pl);
      if (frozen_[p] || rigid_[p]) continue;
      update_strain(p, stored_L(p), h);
    }
    return;
  }
  // the first half, then the grid forces from the stresses after it
  const Eigen::Vector2d grav = cfg_.gravity;
  const std::size_t nfield = 2 * static_cast<std::size_t>(nn_);
#pragma omp parallel num_threads(nthreads_)
  {
    const int tid = thread_id();
    std::vector<NodeData>& buf = tbuf_[static_cast<std::size_t>(tid)];
    for (std::size_t i = 0; i < nfield; ++i) buf[i].fx = buf[i].fy = 0.0;
#pragma omp for schedule(static)
    for (long pl = 0; pl < np; ++pl) {
      const auto p = static_cast<std::size_t>(pl);
      if (frozen_[p] || rigid_[p]) continue;
      update_strain(p, stored_L(p), h);
      const double m = mass_[p], v0 = vol0_[p];
      const double sxx = txx_[p] * v0, sxy = txy_[p] * v0, syy = tyy_[p] * v0;
      for (int b = 0; b < 3; ++b) {
        const double wyb = wy_[3 * p + static_cast<std::size_t>(b)];
        const double dwyb = dwy_[3 * p + static_cast<std::size_t>(b)];
        for (int a = 0; a < 3; ++a) {
          const double wxa = wx_[3 * p + static_cast<std::size_t>(a)];
          const double sh = wxa * wyb;
          if (sh <= 0.0) continue;
          NodeData& nd = buf[fid_[9 * p + static_cast<std::size_t>(a + 3 * b)] * static_cast<std::size_t>(nn_) +
                             static_cast<std::size_t>((i0_[p] + a) + (j0_[p] + b) * nnx_)];
          const double gx = dwx_[3 * p + static_cast<std::size_t>(a)] * wyb;
          const double gy = wxa * dwyb;
          nd.fx += -(sxx * gx + sxy * gy) + m * sh * grav.x();
          nd.fy += -(sxy * gx + syy * gy) + m * sh * grav.y();
        }
      }
    }
    reduce_node_buffers(
        nfield,
        [](std::size_t, NodeData& acc, const NodeData& o) {
          acc.fx += o.fx;
          acc.fy += o.fy;
        },
        [&](std::size_t i, const NodeData& acc) {
          nodes_[i].fx = acc.fx;
          nodes_[i].fy = acc.fy;
        });
  }
}

void MpmProblem::step() {
  if (!setup_done_) setup();
  if (cfg_.numerics.sort_interval > 0 && steps_ > 0 && steps_ % cfg_.numerics.sort_interval == 0) {
    sort_particles();
    extrapolated_ = false;  // redone in the new particle order
  }
  const bool avg = cfg_.numerics.strain_update == Numerics::StrainUpdate::usavg;
  if (!avg) {
    particles_to_grid(true);  // computes the shape functions too
  } else {
    if (!extrapolated_) {  // the first step; else a redo of the last step's extrapolation (counted there)
      const bool count = steps_ == 0;
      particles_to_grid(false);
      constrain_extrapolated(count, time_, count);  // a redo: the crack openings the extrapolation saw
    }
    usavg_half(true);
  }
  cohesive_forces();
  grid_update();
  grid_to_particles();  // MUSL: and its strain pass
  if (!avg) {
    move_crack_surfaces();
  } else {  // strain last: the updated particles extrapolated at their new positions
    particles_to_grid(false);
    constrain_extrapolated(true, time_ + dt_, true);
    move_crack_surfaces();
    usavg_half(false);
    extrapolated_ = true;
  }
  time_ += dt_;
  ++steps_;
}

void MpmProblem::sort_particles() {
  const auto& g = cfg_.grid;
  const std::size_t np = x_.size();
  const std::size_t ncell = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny);
  std::fill(count_.begin(), count_.end(), 0);
  auto cell_of = [&](std::size_t p) -> std::size_t {
    const long i = static_cast<long>(std::floor((x_[p] - g.x0) / g.dx));
    const long j = static_cast<long>(std::floor((y_[p] - g.y0) / g.dx));
    if (frozen_[p] || i < 0 || j < 0 || i >= g.nx || j >= g.ny) return ncell;  // last bucket
    return static_cast<std::size_t>(i + j * g.nx);
  };
  for (std::size_t p = 0; p < np; ++p) ++count_[cell_of(p) + 1];
  for (std::size_t c = 1; c < count_.size(); ++c) count_[c] += count_[c - 1];
  for (std::size_t p = 0; p < np; ++p) perm_[count_[cell_of(p)]++] = p;  // stable
  auto apply_d = [&](std::vector<double>& v) {
    for (std::size_t q = 0; q < np; ++q) dscratch_[q] = v[perm_[q]];
    v.swap(dscratch_);
  };
  auto apply_b = [&](std::vector<std::uint8_t>& v) {
    for (std::size_t q = 0; q < np; ++q) bscratch_[q] = v[perm_[q]];
    v.swap(bscratch_);
  };
  for (auto* v : {&x_, &y_, &X0_, &Y0_, &vx_, &vy_, &mass_, &vol0_, &J_, &alpha_, &Fxx_, &Fxy_, &Fyx_, &Fyy_, &bxx_, &bxy_,
                  &byy_, &bzz_, &txx_, &txy_, &tyy_, &tzz_, &wp_}) {
    apply_d(*v);
  }
  for (auto* v : {&rigid_, &side_, &frozen_, &left_}) apply_b(*v);
  for (std::size_t q = 0; q < np; ++q) sscratch_[q] = id_[perm_[q]];
  id_.swap(sscratch_);
}

// ------------------------------------------------------------------ observers
double MpmProblem::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < x_.size(); ++p) {
    if (!rigid_[p]) e += 0.5 * mass_[p] * (vx_[p] * vx_[p] + vy_[p] * vy_[p]);
  }
  return e;
}

double MpmProblem::strain_energy() const {
  double e = 0.0;
  Eigen::Matrix3d b = Eigen::Matrix3d::Zero();
  for (std::size_t p = 0; p < x_.size(); ++p) {
    if (rigid_[p]) continue;
    b << bxx_[p], bxy_[p], 0.0, bxy_[p], byy_[p], 0.0, 0.0, 0.0, bzz_[p];
    e += vol0_[p] * strain_energy_density(cfg_.material, b, J_[p]);
  }
  return e;
}

Eigen::Vector2d MpmProblem::momentum() const {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (std::size_t p = 0; p < x_.size(); ++p) {
    if (!rigid_[p]) m += mass_[p] * Eigen::Vector2d(vx_[p], vy_[p]);
  }
  return m;
}

Eigen::Vector2d MpmProblem::grid_momentum() const {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < 2 * static_cast<std::size_t>(nn_); ++k) {
    if (!extrapolated_) {
      m += nodes_[k].m * vnew_[k];
    } else if (nodes_[k].m > mmin_) {  // USAVG: the grid holds the strain-last extrapolation
      m += Eigen::Vector2d(nodes_[k].px, nodes_[k].py);
    }
  }
  return m;
}

Eigen::Matrix2d MpmProblem::deformation_gradient(std::size_t p) const {
  Eigen::Matrix2d F;
  F << Fxx_[p], Fxy_[p], Fyx_[p], Fyy_[p];
  return F;
}

Eigen::Matrix3d MpmProblem::cauchy_stress(std::size_t p) const {
  Eigen::Matrix3d s;
  s << txx_[p], txy_[p], 0.0, txy_[p], tyy_[p], 0.0, 0.0, 0.0, tzz_[p];
  return s / J_[p];
}

double MpmProblem::crack_tip_x(double x_from) const {
  for (std::size_t k = 0; k < crack_.xc.size(); ++k) {
    if (!crack_.state[k].failed && crack_.xc[k] >= x_from) return crack_.xc[k];
  }
  return cfg_.crack.x_end;
}

std::size_t MpmProblem::intact_segments_behind(double x) const {
  std::size_t n = 0;
  for (std::size_t k = 0; k < crack_.xc.size(); ++k) n += !crack_.state[k].failed && crack_.xc[k] < x ? 1 : 0;
  return n;
}

double MpmProblem::released_energy() const {
  double e = 0.0;
  for (std::size_t k = 0; k < crack_.xc.size(); ++k) {
    if (crack_.state[k].failed && !crack_.free[k]) e += (crack_.state[k].JI + crack_.state[k].JII) * cfg_.crack.seg_len;
  }
  return e;
}

double MpmProblem::cohesive_energy() const {
  const auto& c = cfg_.crack;
  double e = 0.0;
  for (std::size_t k = 0; k < crack_.xc.size(); ++k) {
    if (crack_.free[k]) continue;
    const CohesiveState& st = crack_.state[k];
    if (st.failed) {
      e += (st.JI + st.JII) * c.seg_len;
      continue;
    }
    // intact: dissipated (area to the largest opening less the secant's triangle) plus the
    // energy held at the present opening on the secant
    const Eigen::Vector2d d = crack_.top[k] - crack_.bot[k];
    auto part = [](const TractionLaw& law, double dmax, double now) {
      if (dmax <= 0.0) return 0.0;
      const double held = 0.5 * law.traction(now, dmax) * now;
      return law.area(dmax) - 0.5 * law.envelope(dmax) * dmax + held;
    };
    e += (part(c.mode1, st.dn_max, std::max(0.0, d.y())) + part(c.mode2, st.dt_max, std::fabs(d.x()))) * c.seg_len;
  }
  return e;
}

double MpmProblem::plastic_work() const {
  double e = 0.0;
  for (std::size_t p = 0; p < x_.size(); ++p) e += wp_[p];
  return e;
}

double MpmProblem::stress_power() const {
  double e = 0.0;
  for (std::size_t p = 0; p < x_.size(); ++p) e += sp_[p];
  return e;
}

EnergyBalance MpmProblem::energy_balance() const {
  EnergyBalance b;
  b.audit = audit_;
  b.kinetic = kinetic_energy();
  b.strain = strain_energy();
  b.plastic = plastic_work();
  b.cohesive = cohesive_energy();
  b.stress_power = stress_power();
  b.stress_lag = audit_.internal_work - b.stress_power;
  b.cohesive_lag = audit_.cohesive_work - b.cohesive;
  b.numerical = audit_.pic_damping + audit_.feedback_loss + audit_.increment_loss + audit_.tool_contact_loss +
                audit_.crack_contact_loss + b.stress_lag + b.cohesive_lag;
  b.residual = initial_energy_ + audit_.tool_work - (b.kinetic + b.strain + b.plastic + b.cohesive + b.numerical);
  return b;
}

double MpmProblem::mode1_fraction() const {
  double a = 0.0, b = 0.0;
  for (std::size_t k = 0; k < crack_.xc.size(); ++k) {
    if (crack_.state[k].failed && !crack_.free[k]) {
      a += crack_.state[k].JI;
      b += crack_.state[k].JI + crack_.state[k].JII;
    }
  }
  return b > 0.0 ? a / b : std::nan("");
}

}  // namespace cutbench::mpm
