// Can every counted check fail? The audit perturbs the computed data a check's value reads and
// re-evaluates the check: a check whose verdict no perturbation changes cannot fail (or cannot
// pass), whatever the solver computes. Static rules catch what needs no data: a literal value, a
// value and a reference that select the same data, a value that echoes an input of its series.
#include "cutbench/framework/audit.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "cutbench/common/units.hpp"

namespace cutbench::framework {
namespace {

// One column a value selector reads: series, run (-1: the series table; -2: every run), table and column.
struct Leaf {
  std::string series;
  long run = -1;
  std::string table, column;
  bool operator<(const Leaf& o) const {
    return std::tie(series, run, table, column) < std::tie(o.series, o.run, o.table, o.column);
  }
};

constexpr long kEveryRun = -2;  // a leaf of run = "each": the same table of every run

void collect_leaves(const json& sel, std::set<Leaf>& out) {
  if (!sel.is_object()) return;
  for (const char* op : {"ratio", "difference", "product"}) {
    if (sel.contains(op) && sel[op].is_array()) {
      for (const auto& s : sel[op]) collect_leaves(s, out);
      return;
    }
  }
  if (!sel.contains("series") || !sel.contains("output") || !sel["series"].is_string() || !sel["output"].is_string()) {
    return;
  }
  Leaf l;
  l.series = sel["series"].get<std::string>();
  l.column = sel["output"].get<std::string>();
  if (sel.contains("run") && (sel["run"].is_number_integer() || sel["run"] == "each")) {
    l.run = sel["run"] == "each" ? kEveryRun : sel["run"].get<long>();
    l.table = sel.value("table", std::string());
  }
  out.insert(l);
}

std::vector<double>* find_column(std::vector<SeriesResult>& series, const Leaf& l) {
  for (auto& s : series) {
    if (s.name != l.series) continue;
    Table* t = nullptr;
    if (l.run < 0) {
      t = &s.table;
    } else if (static_cast<std::size_t>(l.run) < s.runs.size()) {
      for (auto& tab : s.runs[static_cast<std::size_t>(l.run)].tables) {
        if (tab.name == l.table) t = &tab;
      }
    }
    if (!t) return nullptr;
    auto it = t->columns.find(l.column);
    return it == t->columns.end() ? nullptr : &it->second;
  }
  return nullptr;
}


// The scale of a column's shifts: its mean's size or its range, whichever is larger.
double column_span(const std::vector<double>& y) {
  double lo = INFINITY, hi = -INFINITY, mean = 0.0;
  std::size_t n = 0;
  for (double v : y) {
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    mean += v;
    ++n;
  }
  if (n == 0) return 1e-30;
  mean /= static_cast<double>(n);
  return std::max({std::abs(mean), hi - lo, 1e-30});
}

// The perturbations applied to one column, each a function of the column.
std::vector<std::vector<double>> perturbations(const std::vector<double>& y,
                                               const std::vector<double>& factors,
                                               const std::vector<double>& offsets) {
  std::vector<std::vector<double>> out;
  if (std::none_of(y.begin(), y.end(), [](double v) { return std::isfinite(v); })) return out;
  const double span = column_span(y);
  std::vector<double> ks = {-1.0, 0.0, 0.5, 0.9, 0.99, 1.01, 1.1, 2.0, 10.0, 1e3};
  for (double f : factors) {
    if (std::isfinite(f)) ks.push_back(f);
  }
  for (double k : ks) {
    std::vector<double> p = y;
    for (auto& v : p) v *= k;
    out.push_back(std::move(p));
  }
  for (double d : {-10.0, -1.0, -0.1, 0.1, 1.0, 10.0}) {
    std::vector<double> p = y;
    for (auto& v : p) v += d * span;
    out.push_back(std::move(p));
  }
  for (double d : offsets) {  // in the check's units: right for an unscaled value, a guess otherwise
    if (!std::isfinite(d)) continue;
    std::vector<double> p = y;
    for (auto& v : p) v += d;
    out.push_back(std::move(p));
  }
  if (y.size() > 1) {
    std::vector<double> p(y.rbegin(), y.rend());
    out.push_back(std::move(p));
    // a spike and a dip at each point in turn (at most 64 of them, spread over the column): moves a
    // maximum, a minimum or a drop to any place, as a different computed curve would
    const std::size_t step = std::max<std::size_t>(1, y.size() / 64);
    for (std::size_t k = 0; k < y.size(); k += step) {
      for (const double sign : {1.0, -1.0}) {
        std::vector<double> q = y;
        q[k] += sign * 10.0 * span;
        out.push_back(std::move(q));
      }
    }
  }
  return out;
}

}  // namespace

std::string audit_static(const CaseSpec& spec, const CheckSpec& cs) {
  if (cs.value.is_number()) return "input echo: the value is a literal number, not a computed quantity";
  if (cs.value == cs.reference) return "same data: the value and the reference select the same data";
  for (const char* op : {"ratio", "difference"}) {
    if (cs.value.is_object() && cs.value.contains(op) && cs.value[op].is_array() && cs.value[op].size() == 2 &&
        cs.value[op][0] == cs.value[op][1]) {
      return std::string("same data: the ") + op + " of a selector with itself";
    }
  }
  std::set<Leaf> leaves;
  collect_leaves(cs.value, leaves);
  if (cs.metric == "curve_max_norm" && cs.reference.is_object() && cs.reference.contains("series") &&
      cs.value.is_object() && cs.value.value("series", std::string()) == cs.reference.value("series", std::string()) &&
      cs.value.value("output", std::string()) == cs.reference.value("output", std::string())) {
    return "same data: the computed and the reference curve are the same series output";
  }
  for (const auto& l : leaves) {
    if (l.run != -1) continue;  // a run's history, not an input of the series
    for (const auto& s : spec.series) {
      const auto inputs = varied_params(s);
      if (s.name == l.series && std::find(inputs.begin(), inputs.end(), l.column) != inputs.end()) {
        return "input echo: '" + l.column + "' is an input varied by series '" + s.name + "'";
      }
    }
  }
  return {};
}

std::string audit_check(const CaseSpec& spec, const CheckSpec& cs, const CheckRecord& base,
                        std::vector<SeriesResult>& series, ReferenceCache& refs) {
  if (std::string s = audit_static(spec, cs); !s.empty()) return s;
  // nothing to perturb: no verdict, or a quantity the run does not define
  if ((base.status != "PASS" && base.status != "FAIL") || !base.has_value) return {};
  std::set<Leaf> collected, leaves;
  collect_leaves(cs.value, collected);
  for (const auto& l : collected) {  // run = "each": perturb each run's table in turn
    if (l.run != kEveryRun) {
      leaves.insert(l);
      continue;
    }
    for (const auto& s : series) {
      if (s.name != l.series) continue;
      for (std::size_t k = 0; k < s.runs.size(); ++k) {
        Leaf one = l;
        one.run = static_cast<long>(k);
        leaves.insert(one);
      }
    }
  }
  if (leaves.empty()) return {};
  CaseSpec one = spec;
  one.checks = {cs};
  one.plots = json::array();
  one.tables = json::array();
  bool can_pass = base.status == "PASS", can_fail = base.status == "FAIL";
  // scalings that move a value of degree one in the data onto the reference and across each
  // boundary (a mean, an interpolated point, a ratio's numerator)
  std::vector<double> factors, offsets, targets_for_solve;
  if (base.has_value) {
    std::vector<double> targets;
    if (base.is_range) {
      targets = {0.5 * (base.lower + base.upper), base.lower, base.upper};
    } else if (base.metric == "curve_max_norm") {
      targets = {};
    } else {
      const double half = base.relative_tol ? base.tolerance * std::abs(base.reference) : base.tolerance;
      targets = {base.reference, base.reference - half, base.reference + half};
    }
    // offsets are added to SI data: the record is in the check's units
    const double unit = from_si(1.0, cs.units, "audit") - from_si(0.0, cs.units, "audit");
    targets_for_solve = targets;
    for (double t : targets) {
      for (double m : {0.999, 1.0, 1.001}) {
        if (base.value != 0.0) factors.push_back(m * t / base.value);
        if (unit != 0.0) offsets.push_back((m * t - base.value) / unit);
      }
    }
  }
  for (const auto& l : leaves) {
    std::vector<double>* col = find_column(series, l);
    if (!col) continue;
    const std::vector<double> saved = *col;
    for (auto& p : perturbations(saved, factors, offsets)) {
      *col = std::move(p);
      std::string st;
      try {
        st = evaluate_checks(one, series, refs).front().status;
      } catch (const std::exception&) {
        st.clear();
      }
      if (st == "INCONCLUSIVE") st = "PASS";  // the scatter band is not a verdict change
      can_pass = can_pass || st == "PASS";
      can_fail = can_fail || st == "FAIL";
      if (can_pass && can_fail) break;
    }
    *col = saved;
    if (can_pass && can_fail) return {};
  }
  // A value that is not of degree one in the data (1 - min/F, a slope, a ratio's denominator) can
  // sit between the fixed scalings: solve for the scale and the shift of each column that put the
  // value on each target, by bracketing on a grid and bisecting.
  if (!targets_for_solve.empty()) {
    for (const auto& l : leaves) {
      std::vector<double>* col = find_column(series, l);
      if (!col) continue;
      const std::vector<double> saved = *col;
      const double span = column_span(saved);
      for (int family = 0; family < 2 && !(can_pass && can_fail); ++family) {
        // family 0: y * s, s in +-[0.01, 100]; family 1: y + s * span, s in [-20, 20]
        auto apply = [&](double s) {
          *col = saved;
          for (auto& v : *col) v = family == 0 ? v * s : v + s * span;
        };
        auto eval = [&](double s, double& value) -> std::string {
          apply(s);
          try {
            const CheckRecord r = evaluate_checks(one, series, refs).front();
            if (!r.has_value || !std::isfinite(r.value)) return {};
            value = r.value;
            return r.status == "INCONCLUSIVE" ? std::string("PASS") : r.status;
          } catch (const std::exception&) {
            return {};
          }
        };
        std::vector<double> grid;
        for (int i = -60; i <= 60; ++i) {
          const double s = family == 0 ? std::pow(10.0, i / 30.0) : 20.0 * i / 60.0;
          grid.push_back(s);
          if (family == 0) grid.push_back(-s);
        }
        std::sort(grid.begin(), grid.end());
        std::vector<double> vals(grid.size(), NAN);
        for (std::size_t i = 0; i < grid.size(); ++i) {
          double v = NAN;
          const std::string st = eval(grid[i], v);
          vals[i] = v;
          can_pass = can_pass || st == "PASS";
          can_fail = can_fail || st == "FAIL";
        }
        for (double t : targets_for_solve) {
          for (std::size_t i = 0; i + 1 < grid.size() && !(can_pass && can_fail); ++i) {
            if (!std::isfinite(vals[i]) || !std::isfinite(vals[i + 1])) continue;
            if ((vals[i] - t) * (vals[i + 1] - t) > 0.0) continue;
            double a = grid[i], b = grid[i + 1], fa = vals[i] - t;
            std::string st;
            for (int it = 0; it < 50; ++it) {
              const double m = 0.5 * (a + b);
              double v = NAN;
              st = eval(m, v);
              can_pass = can_pass || st == "PASS";
              can_fail = can_fail || st == "FAIL";
              if (!std::isfinite(v)) break;
              if ((v - t) * fa > 0.0) {
                a = m;
                fa = v - t;
              } else {
                b = m;
              }
            }
          }
        }
      }
      *col = saved;
      if (can_pass && can_fail) return {};
    }
  }
  if (!can_fail) {
    return "cannot fail: no perturbation of the data it reads (scaled, shifted, reversed, a spike or dip at any point) "
           "makes it FAIL";
  }
  return "cannot pass: no perturbation of the data it reads makes it PASS";
}

}  // namespace cutbench::framework
