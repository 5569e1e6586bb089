#include "cutbench/common/glossary.hpp"
#include "cutbench/limit/cutting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "cutbench/common/errors.hpp"

namespace cutbench::limit {

using Eigen::Vector2d;
using Eigen::VectorXd;

double chip_thickness(double t1, double phi, double alpha) { return t1 * std::cos(phi - alpha) / std::sin(phi); }

double merchant_force_bar(double phi, double alpha, double mu) {
  const double beta = std::atan(mu);
  return std::cos(beta - alpha) / (std::sin(phi) * std::cos(phi + beta - alpha));
}


namespace {

// The workpiece block below the cutting line (depth > 0): its top edge carries the work region's
// x-grid on [−Lw, 0] (conforming along the cutting line) and a uniform grid of about n/2 cells per
// t1 up to the exit; in y the cells are 1/n next to the cutting line and grow by 1.15 downward
// (the last one takes the remainder), so that the mesh at the cutting line does not change with
// the depth.
Mesh workpiece_block(const CuttingSetup& c, double Lw, const std::vector<double>& xw) {
  const double t1 = c.t1, D = c.depth * t1, X = c.exit_length * t1;
  std::vector<double> xs;
  for (double u : xw) xs.push_back(-Lw + u * Lw);
  const int nr = std::max(2, static_cast<int>(std::ceil(c.n * c.exit_length * 0.5)));
  for (int i = 1; i <= nr; ++i) xs.push_back(X * i / nr);
  std::vector<double> xi;
  for (double x : xs) xi.push_back((x + Lw) / (Lw + X));
  std::vector<double> depths{0.0};  // below the cutting line
  for (double h = t1 / c.n; depths.back() < D;) {
    const double next = depths.back() + h;
    if (next > D - 0.5 * h) {
      depths.push_back(D);
      break;
    }
    depths.push_back(next);
    h *= 1.15;
  }
  std::vector<double> eta;  // from the bottom (η = 0 at y = −D) to the cutting line
  for (auto it = depths.rbegin(); it != depths.rend(); ++it) eta.push_back(1.0 - *it / D);
  eta.front() = 0.0;
  eta.back() = 1.0;
  return structured_quad({-Lw, -D}, {X, -D}, {X, 0.0}, {-Lw, 0.0}, xi, eta, Pattern::union_jack);
}

// (σ_n, τ) per contact (order of model.contacts) from the element stress field, see CuttingResult.
std::vector<Vector2d> contact_traction_field(const LimitModel& m, const LimitSolution& sol) {
  std::map<int, int> contact_of;
  for (std::size_t i = 0; i < m.contacts.size(); ++i) contact_of[m.contacts[i].node] = static_cast<int>(i);
  std::vector<Vector2d> sum(m.contacts.size(), Vector2d::Zero());
  std::vector<int> count(m.contacts.size(), 0);
  for (const auto& e : boundary_edges(m.mesh)) {
    const auto mid = contact_of.find(e.m);
    if (mid == contact_of.end()) continue;
    const auto& cn = m.contacts[static_cast<std::size_t>(mid->second)];
    const Vector2d n = cn.normal, t(-n.y(), n.x());
    const auto& el = m.mesh.elements[static_cast<std::size_t>(e.element)];
    Vector2d end[2];
    for (int k = 0; k < 2; ++k) {
      const int node = k == 0 ? e.a : e.b;
      const int local = static_cast<int>(std::find(el.begin(), el.begin() + 3, node) - el.begin());
      const auto row = sol.stress.row(3 * e.element + local);
      const Vector2d T(row(0) * n.x() + row(2) * n.y(), row(2) * n.x() + row(1) * n.y());
      end[k] = Vector2d(n.dot(T), t.dot(T));
      const auto it = contact_of.find(node);
      if (it == contact_of.end()) continue;
      sum[static_cast<std::size_t>(it->second)] += end[k];
      ++count[static_cast<std::size_t>(it->second)];
    }
    sum[static_cast<std::size_t>(mid->second)] += 0.5 * (end[0] + end[1]);
    ++count[static_cast<std::size_t>(mid->second)];
  }
  for (std::size_t i = 0; i < sum.size(); ++i)
    if (count[i] > 0) sum[i] /= count[i];
  return sum;
}

Mesh with_block(Mesh m, const CuttingSetup& c, double Lw, const std::vector<double>& xw) {
  if (c.depth <= 0.0) return m;
  return merge(m, workpiece_block(c, Lw, xw), 1e-9 * c.t1);
}

// The free chip beyond l of a turned chip (η1, η2 or the curl set): its tool-side face from
// C = l r and its back from D1, as polylines (the two ends of the straight parallelogram; one
// chord per cell of the curled chip), the grid of the cells along it, and its direction at the end.
struct FreeChip {
  std::vector<Vector2d> tool, back;
  std::vector<double> grid;
  Vector2d r_end, n_end;  // direction of the chip at its end, and the normal toward the tool side
};

// Where the free chip starts: the rake direction r and its normal nr, the free chip's direction r2
// and normal n2 (η2), its tool-side start C = l r and back start D1 (η1), and its length Lf.
struct ChipStart {
  double t2, Lf;
  Vector2d r, nr, r2, n2, C, D1;
};

ChipStart chip_start(const CuttingSetup& c) {
  const double t1 = c.t1, t2 = chip_thickness(t1, c.phi, c.alpha), l = c.contact_length;
  ChipStart s;
  s.t2 = t2;
  s.Lf = c.chip_extra * t2;  // the free chip's length (its tool side, along the arc)
  s.r = Vector2d(std::sin(c.alpha), std::cos(c.alpha));
  s.nr = Vector2d(std::cos(c.alpha), -std::sin(c.alpha));
  const Vector2d S(-t1 / std::tan(c.phi), t1);
  s.r2 = std::cos(c.eta2) * s.r - std::sin(c.eta2) * s.nr;
  s.n2 = std::cos(c.eta2) * s.nr + std::sin(c.eta2) * s.r;
  s.C = l * s.r;
  s.D1 = S + l * (s.r - std::tan(c.eta1) * s.nr);
  return s;
}

FreeChip free_chip(const CuttingSetup& c) {
  const ChipStart cs = chip_start(c);
  const double Lf = cs.Lf;
  const int nc2 = std::max(2, static_cast<int>(std::ceil(c.n * Lf / c.t1 * 0.5)));
  const Vector2d &r2 = cs.r2, &n2 = cs.n2, &C = cs.C, &D1 = cs.D1;
  FreeChip f;
  f.grid = graded_grid(nc2, 1.1, 0.0);
  if (c.curl == 0.0) {
    f.tool = {C, C + Lf * r2};
    f.back = {D1, D1 + Lf * r2};
    f.r_end = r2;
    f.n_end = n2;
    return f;
  }
  if (!(std::abs(c.curl) <= 150.0 * M_PI / 180.0)) throw InputError("chip_curl", "must be in [-150, 150] deg");
  const double kappa = c.curl / Lf;
  if (kappa > 0.0 && !((C - D1).dot(n2) < 0.9 / kappa))
    throw InputError("chip_curl", "the centre of the curl must lie beyond the chip back: chip_curl < 0.9 x free-chip length / chip thickness");
  const Vector2d P = C - n2 / kappa;
  auto turn = [&](const Vector2d& x, double th) {
    const Vector2d d = x - P;
    return Vector2d(P.x() + std::cos(th) * d.x() - std::sin(th) * d.y(), P.y() + std::sin(th) * d.x() + std::cos(th) * d.y());
  };
  for (double g : f.grid) {
    f.tool.push_back(turn(C, c.curl * g));
    f.back.push_back(turn(D1, c.curl * g));
  }
  f.r_end = std::cos(c.curl) * r2 + std::sin(c.curl) * Vector2d(-r2.y(), r2.x());
  f.n_end = std::cos(c.curl) * n2 + std::sin(c.curl) * Vector2d(-n2.y(), n2.x());
  return f;
}

// Whether x lies on the polyline (within tol of one of its chords).
bool on_polyline(const std::vector<Vector2d>& pl, const Vector2d& x, double tol) {
  for (std::size_t k = 0; k + 1 < pl.size(); ++k) {
    const Vector2d d = pl[k + 1] - pl[k];
    const double u = (x - pl[k]).dot(d) / d.squaredNorm();
    if (u >= -1e-9 && u <= 1.0 + 1e-9 && (pl[k] + u * d - x).norm() < tol) return true;
  }
  return false;
}

}  // namespace

double max_chip_curl(const CuttingSetup& c) {
  const ChipStart cs = chip_start(c);
  const double thickness = (cs.C - cs.D1).dot(cs.n2);
  return thickness > 0.0 ? 0.9 * 0.9 * c.chip_extra * cs.t2 / thickness : std::numeric_limits<double>::infinity();
}

LimitModel cutting_model(const CuttingSetup& c) {
  if (!(c.t1 > 0.0)) throw InputError("t1", "must be positive");
  if (!(c.phi > 0.0 && c.phi < 0.5 * M_PI)) throw InputError("phi", "shear angle must be in (0, 90) deg");
  if (!(std::abs(c.alpha) < 0.5 * M_PI - c.phi + 0.5 * M_PI)) throw InputError(glossary::kRakeAngle, "rake angle out of range");
  if (!(c.contact_length > 0.0)) throw InputError("contact_length", "must be positive");
  if (c.n < 2) throw InputError("n", "need at least 2 cells across t1");
  if (!(c.depth == 0.0 || (c.depth >= 0.25 && c.depth <= 20.0)))
    throw InputError("workpiece_depth", "workpiece depth below the cutting line must be 0 (layer only) or in [0.25, 20] t1");
  if (!(c.exit_length >= 0.5 && c.exit_length <= 20.0)) throw InputError("exit_length", "must be in [0.5, 20] t1");
  const double t1 = c.t1, t2 = chip_thickness(t1, c.phi, c.alpha);
  const Vector2d O(0.0, 0.0), r(std::sin(c.alpha), std::cos(c.alpha));
  const Vector2d S(-t1 / std::tan(c.phi), t1);
  const double Lw = c.inflow_length * t1 - S.x();  // inflow boundary at x = −Lw
  const double Lc = c.contact_length + c.chip_extra * t2;
  const int ny = c.n;
  // cells: work region along x graded toward the shear plane; chip along r with a break at l
  const int nxw = std::max(2, static_cast<int>(std::ceil(c.n * Lw / t1 * 0.5)));
  const int nc1 = std::max(2, static_cast<int>(std::ceil(c.n * c.contact_length / t1)));
  const int nc2 = std::max(2, static_cast<int>(std::ceil(c.n * (Lc - c.contact_length) / t1 * 0.5)));
  const auto eta = uniform_grid(ny);
  const auto xw = graded_grid(nxw, 1.1, 1.0);
  const double lb = c.contact_length / Lc;
  const auto xc = piecewise_grid({0.0, lb, 1.0}, {uniform_grid(nc1), graded_grid(nc2, 1.1, 0.0)});
  const Mesh work = structured_quad({-Lw, 0.0}, O, S, {-Lw, t1}, xw, eta, Pattern::union_jack);
  if (c.eta2 == 0.0 && c.eta1 == 0.0 && c.curl == 0.0) {
    const Mesh chip = structured_quad(O, O + Lc * r, S + Lc * r, S, xc, eta, Pattern::union_jack);
    return cutting_model_on_mesh(with_block(merge(work, chip, 1e-9 * t1), c, Lw, xw), c);
  }
  if (!(std::abs(c.eta2) < 0.25 * M_PI)) throw InputError("eta2", "stream angle must be in (-45, 45) deg");
  if (!(std::abs(c.eta1) < 0.25 * M_PI)) throw InputError("eta1", "stream angle must be in (-45, 45) deg");
  const double l = c.contact_length, Lf = Lc - l;
  if (!(t2 + l * std::tan(c.eta1) > 0.1 * t2))
    throw InputError("eta1", "the chip back over the contact must leave a thickness of at least 0.1 t2 at its end: eta1 > atan(-0.9 t2 / l)");
  if (c.eta1 != 0.0 && c.streamline >= 2)
    throw InputError("eta1", "a chip back at eta1 is free: streamline \"none\" or \"top\"");
  // contact part O, C = l r, D1, S (D1 = S + l r when η1 = 0); free part turned by η2 about C–D1
  const Vector2d nr(std::cos(c.alpha), -std::sin(c.alpha));
  const Vector2d r2 = std::cos(c.eta2) * r - std::sin(c.eta2) * nr;
  const Vector2d C = l * r, D1 = S + l * (r - std::tan(c.eta1) * nr);
  const Mesh chip1 = structured_quad(O, C, D1, S, uniform_grid(nc1), eta, Pattern::union_jack);
  Mesh chip = merge(work, chip1, 1e-9 * t1);
  if (c.curl == 0.0) {
    chip = merge(chip, structured_quad(C, C + Lf * r2, D1 + Lf * r2, D1, graded_grid(nc2, 1.1, 0.0), eta, Pattern::union_jack), 1e-9 * t1);
  } else {  // one trapezoid per chord of the curled free chip
    const FreeChip f = free_chip(c);
    for (std::size_t k = 0; k + 1 < f.tool.size(); ++k)
      chip = merge(chip, structured_quad(f.tool[k], f.tool[k + 1], f.back[k + 1], f.back[k], {0.0, 1.0}, eta, Pattern::union_jack),
                   1e-9 * t1);
  }
  return cutting_model_on_mesh(with_block(chip, c, Lw, xw), c);
}

LimitModel cutting_model_on_mesh(Mesh mesh, const CuttingSetup& c) {
  const double t1 = c.t1;
  const Vector2d r(std::sin(c.alpha), std::cos(c.alpha));
  const Vector2d S(-t1 / std::tan(c.phi), t1);
  const double Lw = c.inflow_length * t1 - S.x();  // inflow boundary at x = −Lw
  LimitModel m;
  m.mesh = std::move(mesh);
  m.k = c.k;

  const double tol = 1e-8 * t1;
  std::vector<int> contact;
  if (c.streamline < 0 || c.streamline > 3) throw InputError("streamline", "must be 0, 1, 2 or 3");
  std::vector<char> on_boundary(m.mesh.nodes.size(), 0);
  for (const auto& e : boundary_edges(m.mesh))
    for (int nd : {e.a, e.m, e.b}) on_boundary[static_cast<std::size_t>(nd)] = 1;
  const Vector2d nr(std::cos(c.alpha), -std::sin(c.alpha));  // rake-face normal, out of the chip
  const bool block = c.depth > 0.0;
  for (int i = 0; i < m.mesh.num_nodes(); ++i) {
    const Vector2d& x = m.mesh.nodes[static_cast<std::size_t>(i)];
    if (x.norm() < tol && !block) {  // tool tip: stagnation
      m.fix(i, 0);
      m.fix(i, 1);
      continue;
    }
    if (std::abs(x.x() + Lw) < tol) {  // inflow: unit velocity
      m.fix(i, 0, 1.0);
      m.fix(i, 1, 0.0);
      continue;
    }
    if (!block && std::abs(x.y()) < tol && x.x() < 0.0) {  // cutting line: smooth
      m.fix(i, 1);
      continue;
    }
    if (block && std::abs(x.y() + c.depth * t1) < tol) {  // bottom of the workpiece: horizontal movement
      m.fix(i, 1);
      continue;
    }
    const double along = x.dot(r), off = x.dot(nr);
    if (std::abs(off) < tol && (along > 0.0 || (block && along > -tol)) && along <= c.contact_length + tol) {
      contact.push_back(i);
      continue;
    }
    if (!on_boundary[static_cast<std::size_t>(i)] || c.streamline == 0) continue;
    if (std::abs(x.y() - t1) < tol && x.x() < S.x() - tol) {  // uncut top surface: v_y = 0
      m.sliders.emplace_back(i, Vector2d(0.0, 1.0));
    } else if (c.streamline >= 2 && std::abs(off - S.dot(nr)) < tol && (x - S).dot(r) > tol &&
               (c.streamline == 2 || x.dot(r) > c.contact_length + tol)) {  // chip back
      m.sliders.emplace_back(i, -nr);
    }
  }
  m.add_contact(contact, c.mu, nr);
  return m;
}

void contact_statistics(CuttingResult& res, double l_max) {
  // stick fraction: share of the contact length (by tributary weights) where the node sticks;
  // apparent friction per zone from the nodal reactions (lumped stress × tributary length)
  double total = 0.0, stuck = 0.0, st_t = 0.0, st_n = 0.0, sl_t = 0.0, sl_n = 0.0, Ft = 0.0, Fn = 0.0;
  res.stick.assign(res.s.size(), 0);
  for (std::size_t i = 0; i < res.s.size(); ++i) {
    if (res.s[i] > l_max * (1.0 + 1e-12)) continue;
    const double tl = res.trib[i], rt = res.tau[i] * tl, rn = res.sigma_n[i] * tl;
    total += tl;
    Ft += rt;
    Fn += rn;
    const bool st = std::abs(res.slip[i]) < res.stick_tol * res.v_chip;
    res.stick[i] = st ? 1 : 0;
    if (st) {
      stuck += tl;
      st_t += std::abs(rt);
      st_n += std::abs(rn);
    } else {
      sl_t += std::abs(rt);
      sl_n += std::abs(rn);
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  res.stick_fraction = total > 0.0 ? stuck / total : 0.0;
  // the stick zone from the tip, ended where |w_t| first reaches the threshold (linear between points)
  {
    const double thr = res.stick_tol * res.v_chip;
    double end = 0.0, last = 0.0;  // last: the contact length, the largest s <= l_max
    for (double si : res.s)
      if (si <= l_max * (1.0 + 1e-12)) last = std::max(last, si);
    bool crossed = false;
    for (std::size_t i = 0; i < res.s.size() && res.s[i] <= l_max * (1.0 + 1e-12); ++i) {
      const double a = std::abs(res.slip[i]);
      if (a < thr) continue;
      if (i == 0) {
        end = res.s[0];
      } else {
        const double a0 = std::abs(res.slip[i - 1]);
        end = res.s[i - 1] + (thr - a0) / (a - a0) * (res.s[i] - res.s[i - 1]);
      }
      crossed = true;
      break;
    }
    const double len = std::isfinite(l_max) ? std::min(l_max, last) : last;
    res.stick_length_fraction = len > 0.0 ? (crossed ? end / len : 1.0) : 0.0;
  }
  // the tangential-stress plateau and its drop, from the field traction (when the profile has it)
  if (res.tau_field.size() == res.s.size()) {
    std::size_t n = 0, imax = 0;
    while (n < res.s.size() && res.s[n] <= l_max * (1.0 + 1e-12)) ++n;
    for (std::size_t i = 0; i < n; ++i)
      if (std::abs(res.tau_field[i]) > std::abs(res.tau_field[imax])) imax = i;
    const double level = kTauPlateauLevel * (n > 0 ? std::abs(res.tau_field[imax]) : 0.0);
    // s where |tau| crosses the level between points a (at or above it) and b (below it)
    auto crossing = [&](std::size_t a, std::size_t b) {
      const double ta = std::abs(res.tau_field[a]), tb = std::abs(res.tau_field[b]);
      return res.s[a] + (ta - level) / (ta - tb) * (res.s[b] - res.s[a]);
    };
    double start = 0.0, drop = n > 0 ? res.s[n - 1] : 0.0;
    for (std::size_t i = imax + 1; i < n; ++i) {
      if (std::abs(res.tau_field[i]) < level) {
        drop = crossing(i - 1, i);
        break;
      }
    }
    for (std::size_t i = imax; i-- > 0;) {
      if (std::abs(res.tau_field[i]) < level) {
        start = crossing(i + 1, i);
        break;
      }
    }
    const double len = n > 0 ? res.s[n - 1] : 0.0;
    res.tau_plateau_start = len > 0.0 ? start / len : 0.0;
    res.tau_drop = len > 0.0 ? drop / len : 1.0;
  }
  res.mu_sticking = st_n > 0.0 ? st_t / st_n : nan;
  res.mu_sliding = sl_n > 0.0 ? sl_t / sl_n : nan;
  res.mu_app = std::abs(Fn) > 0.0 ? std::abs(Ft) / std::abs(Fn) : nan;
}

void truncate_contact(CuttingResult& res, double l_max) {
  std::size_t keep = 0;
  while (keep < res.s.size() && res.s[keep] <= l_max * (1.0 + 1e-12)) ++keep;
  for (auto* v : {&res.s, &res.sigma_n, &res.tau, &res.slip, &res.trib, &res.sigma_n_field, &res.tau_field}) v->resize(keep);
  contact_statistics(res, l_max);
}

CuttingResult solve_cutting(const CuttingSetup& c, const SocpSettings& settings) {
  return solve_cutting_on(cutting_model(c), c, settings);
}

namespace {
// distance of a contact node along the rake face, the coordinate of CuttingSetup::coulomb_start
double rake_coordinate(const LimitModel& m, const ContactNode& cn, double alpha) {
  return m.mesh.nodes[static_cast<std::size_t>(cn.node)].dot(Vector2d(std::sin(alpha), std::cos(alpha)));
}
}  // namespace

VectorXd coulomb_start_on(const LimitModel& m, const CuttingSetup& c) {
  const auto& prof = c.coulomb_start;
  if (prof.empty()) return {};
  VectorXd x(static_cast<Eigen::Index>(m.contacts.size()));
  for (std::size_t i = 0; i < m.contacts.size(); ++i) {
    const double s = rake_coordinate(m, m.contacts[i], c.alpha);
    auto hi = std::lower_bound(prof.begin(), prof.end(), s, [](const auto& a, double v) { return a.first < v; });
    double v;
    if (hi == prof.begin()) v = hi->second;
    else if (hi == prof.end()) v = prof.back().second;
    else {
      const auto lo = std::prev(hi);
      const double w = hi->first > lo->first ? (s - lo->first) / (hi->first - lo->first) : 0.0;
      v = lo->second + w * (hi->second - lo->second);
    }
    x[static_cast<Eigen::Index>(i)] = v;
  }
  return x;
}

std::vector<std::pair<double, double>> coulomb_profile(const CuttingResult& r, const CuttingSetup& c) {
  std::vector<std::pair<double, double>> prof;
  const auto& it = r.coulomb.iterate;
  if (it.size() != static_cast<Eigen::Index>(r.model.contacts.size())) return prof;
  for (std::size_t i = 0; i < r.model.contacts.size(); ++i)
    prof.emplace_back(rake_coordinate(r.model, r.model.contacts[i], c.alpha), it[static_cast<Eigen::Index>(i)]);
  std::sort(prof.begin(), prof.end());
  return prof;
}

CuttingResult solve_cutting_on(LimitModel model, const CuttingSetup& c, const SocpSettings& settings) {
  CuttingResult res;
  res.model = std::move(model);
  res.t2 = chip_thickness(c.t1, c.phi, c.alpha);
  if ((c.mu > 0.0 || c.unilateral) && c.coulomb_fixed_point) {
    CoulombOptions co;
    co.anderson_depth = c.coulomb_anderson_depth;
    co.relaxation = c.coulomb_anderson_depth > 0 ? c.coulomb_anderson_mixing : c.coulomb_relaxation;
    co.max_iter = c.coulomb_max_iter;
    if (c.coulomb_on_slip && c.mu > 0.0) co.variable = CoulombVariable::slip;
    if (co.variable == CoulombVariable::slip) co.start = coulomb_start_on(res.model, c);
    res.solution = solve_limit_coulomb(res.model, settings, co, &res.coulomb);
  } else {
    res.solution = solve_limit(res.model, settings);
  }
  const auto& sol = res.solution;
  res.cutting_force = sol.collapse;
  // force on the tool = − Σ contact reactions on the body (+ the tip node's reaction)
  Vector2d ftool(0.0, 0.0);
  const Vector2d r(std::sin(c.alpha), std::cos(c.alpha));
  std::vector<std::pair<double, int>> order;
  for (std::size_t i = 0; i < res.model.contacts.size(); ++i) {
    const auto& cn = res.model.contacts[i];
    const Vector2d t(-cn.normal.y(), cn.normal.x());
    ftool -= sol.contact_rn[static_cast<Eigen::Index>(i)] * cn.normal + sol.contact_rt[static_cast<Eigen::Index>(i)] * t;
    order.emplace_back(res.model.mesh.nodes[static_cast<std::size_t>(cn.node)].dot(r), static_cast<int>(i));
  }
  res.feed_force = ftool.y();
  res.fc_bar = res.cutting_force / (c.k * c.t1);
  res.ff_bar = res.feed_force / (c.k * c.t1);
  // lumped contact stresses: nodal reaction / tributary length (1/6, 4/6, 1/6 weights of T6 edges)
  std::map<int, double> trib;
  for (const auto& e : boundary_edges(res.model.mesh)) {
    const Vector2d& xm = res.model.mesh.nodes[static_cast<std::size_t>(e.m)];
    if (c.depth > 0.0 && std::abs(xm.y()) < 1e-8 * c.t1 && xm.x() > 0.0) continue;  // machined surface: not the rake's
    const double L = (res.model.mesh.nodes[static_cast<std::size_t>(e.b)] - res.model.mesh.nodes[static_cast<std::size_t>(e.a)]).norm();
    trib[e.a] += L / 6.0;
    trib[e.b] += L / 6.0;
    trib[e.m] += 4.0 * L / 6.0;
  }
  std::sort(order.begin(), order.end());
  const auto field = contact_traction_field(res.model, sol);
  for (const auto& [s, i] : order) {
    const auto& cn = res.model.contacts[static_cast<std::size_t>(i)];
    const double tl = trib[cn.node];
    res.s.push_back(s);
    res.sigma_n.push_back(sol.contact_rn[i] / tl);
    res.tau.push_back(sol.contact_rt[i] / tl);
    res.slip.push_back(sol.contact_wt[i]);
    res.trib.push_back(tl);
    res.sigma_n_field.push_back(field[static_cast<std::size_t>(i)].x());
    res.tau_field.push_back(field[static_cast<std::size_t>(i)].y());
  }
  res.v_chip = std::sin(c.phi) / std::cos(c.phi - c.alpha);
  res.stick_tol = c.stick_tol;
  contact_statistics(res, std::numeric_limits<double>::infinity());
  // fluxes through the free surfaces (exact for the quadratic edge velocity: Simpson)
  {
    const auto& mesh = res.model.mesh;
    const Vector2d nr(std::cos(c.alpha), -std::sin(c.alpha));
    const Vector2d S(-c.t1 / std::tan(c.phi), c.t1);
    const double tol = 1e-6 * c.t1;
    // the chip back over the contact, S to D1 (direction r1, normal n1 out of the chip), and the
    // free chip beyond l (turned by η2, curled by Θ) from C–D1: its back and tool-side faces as
    // polylines, its end the line C–D1 carried to the end of the free chip
    const double l = c.contact_length;
    const Vector2d r1 = std::cos(c.eta1) * r - std::sin(c.eta1) * nr, n1 = std::cos(c.eta1) * nr + std::sin(c.eta1) * r;
    const Vector2d D1 = S + l * (r - std::tan(c.eta1) * nr);
    const double back1 = (D1 - S).norm();
    res.back_contact_length = back1;
    const bool turned = c.eta1 != 0.0 || c.eta2 != 0.0 || c.curl != 0.0;
    // the chip end: parallel to C–D1 (to OS when η1 = 0), its normal along the free chip
    Vector2d r_end = r, n_tool = nr, n_end(-(D1 - l * r).y(), (D1 - l * r).x());
    FreeChip fc;
    if (turned) {
      fc = free_chip(c);
      r_end = fc.r_end;
      n_tool = fc.n_end;
      n_end = Vector2d(-(fc.back.back() - fc.tool.back()).y(), (fc.back.back() - fc.tool.back()).x());
      double lt = 0.0, lb = 0.0;
      for (std::size_t k = 0; k + 1 < fc.tool.size(); ++k) {
        lt += (fc.tool[k + 1] - fc.tool[k]).norm();
        lb += (fc.back[k + 1] - fc.back[k]).norm();
      }
      res.free_face_length = 0.5 * (lt + lb);
    }
    n_end.normalize();
    if (n_end.dot(r_end) < 0.0) n_end = -n_end;
    Vector2d v_end(0.0, 0.0);  // ∫ v ds over the chip end (Simpson)
    for (const auto& e : boundary_edges(mesh)) {
      const Vector2d n = boundary_normal(mesh, e);
      const Vector2d& xm = mesh.nodes[static_cast<std::size_t>(e.m)];
      const double L = (mesh.nodes[static_cast<std::size_t>(e.b)] - mesh.nodes[static_cast<std::size_t>(e.a)]).norm();
      auto vn = [&](int nd) { return sol.velocity[2 * nd] * n.x() + sol.velocity[2 * nd + 1] * n.y(); };
      const double f = L * (vn(e.a) + 4.0 * vn(e.m) + vn(e.b)) / 6.0;
      const double a1 = (xm - S).dot(r1);
      if (c.depth > 0.0 && ((std::abs(xm.y()) < tol && xm.x() > 0.0) || (std::abs(xm.x() - c.exit_length * c.t1) < tol && xm.y() < 0.0)))
        res.flux_under += f;  // machined surface and the block's exit
      else if (std::abs(xm.y() - c.t1) < tol && xm.x() < S.x()) res.flux_top += f;
      else if (std::abs((xm - S).dot(n1)) < tol && a1 > 0.0 && (!turned || a1 < back1)) {
        res.flux_back += f;  // the chip back (over the contact; the whole straight back when not turned)
        if (a1 < back1) res.flux_back_contact += f;
      }
      else if (turned && on_polyline(fc.back, xm, tol)) {  // the free chip's back
        res.flux_back += f;
        res.flux_back_free += f;
      }
      else if (turned && on_polyline(fc.tool, xm, tol) && (xm - l * r).norm() > tol) {  // its tool side
        res.flux_rake_free += f;
        res.flux_tool_free += f;
      }
      else if ((turned && on_polyline({fc.tool.back(), fc.back.back()}, xm, tol)) ||
               (!turned && std::abs(n.dot(n_end) - 1.0) < 1e-9 && xm.dot(r) > l)) {  // the chip end
        res.flux_end += f;
        auto v = [&](int nd) { return Vector2d(sol.velocity[2 * nd], sol.velocity[2 * nd + 1]); };
        v_end += L * (v(e.a) + 4.0 * v(e.m) + v(e.b)) / 6.0;
      }
      else if (std::abs(xm.dot(nr)) < tol && xm.dot(r) > 0.0) res.flux_rake_free += f;  // separation or free part
    }
    res.flux_under -= c.depth * c.t1;  // the block's own inflow
    res.chip_exit_angle = std::atan2(-v_end.dot(n_tool), v_end.dot(r_end));  // relative to the chip's end direction
    if (turned) {  // the free chip's start: ∫ v ds over the nodes on C–D1 (trapezoids), against η2's direction
      const Vector2d C = fc.tool.front(), d = D1 - C;
      std::vector<std::pair<double, int>> line;
      for (int i = 0; i < mesh.num_nodes(); ++i) {
        const Vector2d& x = mesh.nodes[static_cast<std::size_t>(i)];
        const double u = (x - C).dot(d) / d.squaredNorm();
        if (u >= -1e-9 && u <= 1.0 + 1e-9 && (C + u * d - x).norm() < tol) line.emplace_back(u, i);
      }
      std::sort(line.begin(), line.end());
      Vector2d v_start(0.0, 0.0);
      for (std::size_t k = 0; k + 1 < line.size(); ++k) {
        const int a = line[k].second, b = line[k + 1].second;
        const Vector2d va(sol.velocity[2 * a], sol.velocity[2 * a + 1]), vb(sol.velocity[2 * b], sol.velocity[2 * b + 1]);
        v_start += 0.5 * (line[k + 1].first - line[k].first) * d.norm() * (va + vb);
      }
      const Vector2d r2 = std::cos(c.eta2) * r - std::sin(c.eta2) * nr, n2 = std::cos(c.eta2) * nr + std::sin(c.eta2) * r;
      res.chip_start_angle = std::atan2(-v_start.dot(n2), v_start.dot(r2));
    }
    double rn = 0.0;
    for (Eigen::Index i = 0; i < sol.slider_rn.size(); ++i) rn += std::abs(sol.slider_rn[i]);
    res.streamline_force = rn / (c.k * c.t1);
  }
  return res;
}

CuttingResult adapt_cutting(const CuttingSetup& c, int steps, double fraction, std::vector<CuttingAdaptStep>* history,
                            const SocpSettings& settings) {
  AdaptOptions opt;
  opt.steps = steps;
  opt.fraction = fraction;
  return adapt_cutting(c, opt, history, settings);
}

CuttingResult adapt_cutting(const CuttingSetup& c, const AdaptOptions& opt, std::vector<CuttingAdaptStep>* history,
                            const SocpSettings& settings) {
  if (opt.steps < 0) throw InputError("adapt_steps", "must be >= 0");
  if (!(opt.fraction > 0.0 && opt.fraction <= 1.0)) throw InputError("fraction", "must be in (0, 1]");
  Mesh mesh = cutting_model(c).mesh;
  std::vector<CuttingAdaptStep> refinement;
  CuttingSetup cs = c;
  for (int step = 0;; ++step) {
    CuttingResult r = solve_cutting_on(cutting_model_on_mesh(mesh, cs), cs, settings);
    if (c.coulomb_warm_start && c.coulomb_on_slip && c.mu > 0.0) cs.coulomb_start = coulomb_profile(r, c);
    refinement.push_back({mesh.num_elements(), r.fc_bar, r.stick_fraction, r.stick_length_fraction});
    if (history) history->push_back(refinement.back());
    if (step == opt.steps) {
      r.refinement = std::move(refinement);
      return r;
    }
    mesh = adapt_mesh(mesh, r.solution, opt);
  }
}

double end_normal_stress(const CuttingResult& r, double contact_length, double fraction) {
  // tributary-weighted mean of σ_n over s ≥ (1 − fraction) l (lumped nodal values)
  double num = 0.0, den = 0.0;
  const double s0 = (1.0 - fraction) * contact_length;
  for (std::size_t i = 0; i < r.s.size(); ++i) {
    if (r.s[i] < s0 - 1e-12) continue;
    const double w = (i + 1 < r.s.size() ? r.s[i + 1] : r.s[i]) - (i > 0 ? r.s[i - 1] : 0.0);
    num += w * r.sigma_n[i];
    den += w;
  }
  return den > 0.0 ? num / den : 0.0;
}

ContactLengthResult search_contact_length(CuttingSetup c, const ContactLengthOptions& opt, const SocpSettings& settings) {
  ContactLengthResult out;
  auto eval = [&](double l) {
    c.contact_length = l;
    CuttingResult r = solve_cutting(c, settings);
    const double sn = end_normal_stress(r, l) / c.k;
    out.lengths.push_back(l);
    out.end_stress.push_back(sn);
    out.fc_bar.push_back(r.fc_bar);
    return std::make_pair(sn, std::move(r));
  };
  const double l0 = c.t1 / std::cos(c.alpha);
  double lo = l0;
  auto [s_lo, r_lo] = eval(lo);
  if (s_lo >= -opt.tol) {  // already unloaded at the minimum length
    out.contact_length = lo;
    out.final = std::move(r_lo);
    return out;
  }
  double hi = lo;
  CuttingResult r_hi;
  bool found = false;
  while (hi + opt.step * c.t1 <= opt.max_length * c.t1 + 1e-12) {
    hi += opt.step * c.t1;
    auto [s_hi, r] = eval(hi);
    if (s_hi >= -opt.tol) {
      found = true;
      r_hi = std::move(r);
      break;
    }
    lo = hi;
    r_lo = std::move(r);
  }
  if (!found) {
    out.restricted = true;
    out.contact_length = lo;
    out.final = std::move(r_lo);
    return out;
  }
  for (int b = 0; b < opt.bisections; ++b) {
    const double mid = 0.5 * (lo + hi);
    auto [s_mid, r] = eval(mid);
    if (s_mid >= -opt.tol) {
      hi = mid;
      r_hi = std::move(r);
    } else {
      lo = mid;
    }
  }
  out.contact_length = hi;
  out.final = std::move(r_hi);
  return out;
}

NaturalContactResult natural_contact_length(CuttingSetup c, double max_length, double tol, const SocpSettings& settings) {
  if (!(max_length > 0.0)) throw InputError("max_length", "must be positive (in t1)");
  if (!(tol > 0.0)) throw InputError("tol", "must be positive (in k)");
  NaturalContactResult out;
  c.contact_length = max_length * c.t1;
  c.unilateral = true;
  out.long_contact = solve_cutting(c, settings);
  const auto& r = out.long_contact;
  double l = 0.0;
  for (std::size_t i = 0; i < r.s.size(); ++i)
    if (r.sigma_n[i] < -tol * c.k) l = r.s[i];
  if (!(l > 0.0)) throw NumericalError("natural_contact_length: no compressed contact node");
  out.contact_length = l;
  return out;
}

double measured_shear_angle(const CuttingSetup& c, const CuttingResult& r) {
  // Walk along the free surface (uncut top y = t1 up to S, then the chip back) and find where the
  // direction of the material velocity is halfway between the inflow (0) and the rake face
  // direction (90° − α); φ* is the angle of the line from the tool tip to that point.
  const auto& mesh = r.model.mesh;
  const Vector2d rr(std::sin(c.alpha), std::cos(c.alpha)), nr(std::cos(c.alpha), -std::sin(c.alpha));
  const Vector2d S(-c.t1 / std::tan(c.phi), c.t1);
  const double tol = 1e-8 * c.t1;
  std::vector<std::pair<double, int>> path;  // (arc length from the inflow end, node)
  std::vector<char> on(mesh.nodes.size(), 0);
  for (const auto& e : boundary_edges(mesh)) {
    for (int nd : {e.a, e.m, e.b}) on[static_cast<std::size_t>(nd)] = 1;
  }
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    if (!on[static_cast<std::size_t>(i)]) continue;
    const Vector2d& x = mesh.nodes[static_cast<std::size_t>(i)];
    if (std::abs(x.y() - c.t1) < tol && x.x() <= S.x() + tol) {
      path.emplace_back(x.x() - S.x(), i);  // ≤ 0 before S
    } else if (std::abs(x.dot(nr) - S.dot(nr)) < tol && (x - S).dot(rr) > tol) {
      path.emplace_back((x - S).dot(rr), i);  // > 0 along the chip back
    }
  }
  std::sort(path.begin(), path.end());
  const double target = 0.5 * (0.5 * M_PI - c.alpha);
  double prev_s = 0.0, prev_t = 0.0;
  bool have = false;
  for (const auto& [sv, i] : path) {
    const double vx = r.solution.velocity[2 * i], vy = r.solution.velocity[2 * i + 1];
    const double th = std::atan2(vy, vx);
    if (have && prev_t < target && th >= target) {
      const double f = (target - prev_t) / (th - prev_t);
      const double sp = prev_s + f * (sv - prev_s);
      const Vector2d P = sp <= 0.0 ? Vector2d(S.x() + sp, c.t1) : Vector2d(S + sp * rr);
      return std::atan2(P.y(), -P.x());
    }
    prev_s = sv;
    prev_t = th;
    have = true;
  }
  throw NumericalError("measured_shear_angle: the free-surface velocity never turns toward the rake face");
}

SteadyStateResult steady_state(CuttingSetup c, const SteadyStateOptions& opt, const SocpSettings& settings) {
  SteadyStateResult out;
  const double phi_m = merchant_shear_angle(c.alpha, c.mu);
  for (int it = 0; it < opt.max_iter; ++it) {
    CuttingResult r = solve_cutting(c, settings);
    const double ps = measured_shear_angle(c, r);
    out.phi.push_back(c.phi);
    out.phi_star.push_back(ps);
    out.fc_bar.push_back(r.fc_bar);
    // Molinari & Moufki: φ* ≥ φ_M → φ_M minimises F_c; otherwise φ = φ*
    const double target = std::min(ps, phi_m);
    const double next = c.phi + opt.relaxation * (target - c.phi);
    out.final = std::move(r);
    if (std::abs(next - c.phi) < opt.tol) {
      out.converged = true;
      break;
    }
    c.phi = next;
  }
  return out;
}

}  // namespace cutbench::limit
