// Check evaluation: value selectors over computed series, references from literals, reference
// CSVs or other series, and the metrics of DESIGN.md.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "cutbench/common/errors.hpp"
#include "cutbench/framework/runner.hpp"

namespace cutbench::framework {
namespace {

// Thrown when a check cannot be evaluated for lack of input: the check is NOT RUN.
struct NotRun {
  std::string why;
};
// Thrown when a check depends on a series that is declared but not implemented yet.
struct Pending {
  std::string why;
};
// Thrown when a completed solver run does not define the quantity a check reads (no stick zone, no
// serration to measure): the run does not show what the paper reports, so the check FAILs.
struct Undefined {
  std::string why;
};
// Thrown when a check depends on a computation that faulted (a series that threw, a non-finite
// solver output, a blow-up guard): the check is ERROR, never NOT RUN.
struct Fault {
  std::string why;
};

struct Curve {
  std::vector<double> x, y;  // SI
};

const SeriesResult& find_series(const std::vector<SeriesResult>& series, const std::string& name) {
  for (const auto& s : series) {
    if (s.name == name) {
      if (!s.pending.empty()) throw Pending{"series '" + name + "' not implemented yet: " + s.pending};
      if (!s.error.empty()) throw Fault{"series '" + name + "' failed: " + s.error};
      return s;
    }
  }
  throw NotRun{"series '" + name + "' was not computed"};
}

const Table& find_table(const SeriesResult& s, const json& sel) {
  if (!sel.contains("run")) return s.table;
  const auto k = sel["run"].get<std::size_t>();
  if (k >= s.runs.size()) throw NotRun{"series '" + s.name + "' has no run " + std::to_string(k)};
  const std::string tname = sel.value("table", std::string());
  for (const auto& t : s.runs[k].tables) {
    if (t.name == tname) return t;
  }
  throw NotRun{"run " + std::to_string(k) + " of '" + s.name + "' has no table '" + tname + "'"};
}

const std::vector<double>& column(const Table& t, const std::string& name, const std::string& field) {
  auto it = t.columns.find(name);
  if (it == t.columns.end()) {
    std::string known;
    for (const auto& c : t.order) known += (known.empty() ? "" : ", ") + c;
    throw InputError(field, "no output '" + name + "' in '" + t.name + "' (has: " + known + ")");
  }
  return it->second;
}

Dim column_dim(const Table& t, const std::string& name, const std::string& field) {
  return unit_info(t.units.at(name), field).dim;
}

double qty(const json& v, Dim dim, const std::string& field) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) return parse_quantity(v.get<std::string>(), dim, field);
  throw InputError(field, "expected a number or a \"value unit\" string");
}

// A `where = { column = value }` table as text to match reference rows (numbers as written).
std::map<std::string, std::string> where_of(const json& where) {
  std::map<std::string, std::string> out;
  for (const auto& [k, v] : where.items()) out[k] = v.is_string() ? v.get<std::string>() : v.dump();
  return out;
}

double interp(const std::vector<double>& x, const std::vector<double>& y, double at) {
  // x need not be sorted; use the sorted order of finite pairs.
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) idx.push_back(i);
  }
  if (idx.empty()) throw NotRun{"no finite points to interpolate"};
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  const double tol = 1e-9 * std::max(1.0, std::abs(at));
  if (at < x[idx.front()] - tol || at > x[idx.back()] + tol) throw NotRun{"point outside the computed range"};
  for (std::size_t k = 0; k + 1 < idx.size(); ++k) {
    const double x0 = x[idx[k]], x1 = x[idx[k + 1]];
    if (at >= x0 - tol && at <= x1 + tol) {
      if (x1 == x0) return y[idx[k]];
      const double w = std::clamp((at - x0) / (x1 - x0), 0.0, 1.0);
      return (1 - w) * y[idx[k]] + w * y[idx[k + 1]];
    }
  }
  return y[idx.back()];
}

Curve get_curve(const std::vector<SeriesResult>& series, const json& sel, const std::string& field) {
  const auto& s = find_series(series, sel.at("series").get<std::string>());
  const Table& t = find_table(s, sel);
  Curve c;
  c.x = column(t, sel.at("x").get<std::string>(), field + ".x");
  c.y = column(t, sel.at("output").get<std::string>(), field + ".output");
  return c;
}

double linear_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) {
      mx += x[i];
      my += y[i];
      ++n;
    }
  }
  if (n < 2) throw NotRun{"fewer than two finite points for a slope"};
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) {
      sxy += (x[i] - mx) * (y[i] - my);
      sxx += (x[i] - mx) * (x[i] - mx);
    }
  }
  return sxy / sxx;
}

// Evaluate a value selector to one SI number.
double select(const std::vector<SeriesResult>& series, const json& sel, const std::string& field) {
  if (sel.is_number()) return sel.get<double>();
  if (!sel.is_object()) throw InputError(field, "expected a selector table");
  if (sel.contains("ratio") || sel.contains("difference") || sel.contains("product")) {
    const std::string op = sel.contains("ratio") ? "ratio" : sel.contains("difference") ? "difference" : "product";
    const json& ab = sel[op];
    if (!ab.is_array() || ab.size() != 2) throw InputError(field + "." + op, "expected [a, b]");
    const double a = select(series, ab[0], field + "." + op + "[0]");
    const double b = select(series, ab[1], field + "." + op + "[1]");
    return op == "ratio" ? a / b : op == "difference" ? a - b : a * b;
  }
  if (!sel.contains("series")) throw InputError(field, "selector needs 'series' (or ratio/difference)");
  const auto& s = find_series(series, sel["series"].get<std::string>());
  if (sel.contains("run") && sel["run"].is_string()) {
    // run = "each": the selector on every run of the series, then one number across the runs
    if (sel["run"].get<std::string>() != "each") throw InputError(field + ".run", "a run index or \"each\"");
    if (s.runs.empty()) throw NotRun{"series '" + s.name + "' has no runs"};
    const std::string across = sel.value("across_runs", std::string("max_abs"));
    std::vector<double> vs;
    for (std::size_t k = 0; k < s.runs.size(); ++k) {
      json one = sel;
      one["run"] = k;
      one.erase("across_runs");
      vs.push_back(select(series, one, field + " (run " + std::to_string(k) + ")"));
    }
    if (across == "max") return *std::max_element(vs.begin(), vs.end());
    if (across == "min") return *std::min_element(vs.begin(), vs.end());
    if (across == "mean") return std::accumulate(vs.begin(), vs.end(), 0.0) / static_cast<double>(vs.size());
    if (across == "max_abs") {
      double m = 0.0;
      for (double v : vs) m = std::max(m, std::abs(v));
      return m;
    }
    throw InputError(field + ".across_runs", "unknown reduction '" + across + "' (max, min, max_abs, mean)");
  }
  if (sel.contains("across_runs")) throw InputError(field + ".across_runs", "needs run = \"each\"");
  const Table& t = find_table(s, sel);
  if (!sel.contains("output")) throw InputError(field + ".output", "missing");
  const std::string out = sel["output"].get<std::string>();
  const auto& y = column(t, out, field + ".output");
  if (y.empty()) throw NotRun{"series '" + s.name + "' is empty"};

  auto finite_or_notrun = [&](double v) {
    // a solver's histories are finite (run_series refuses others): a NaN scalar is an output the
    // run does not define (e.g. no serration to measure, no sticking zone)
    if (!std::isfinite(v) && s.solver) throw Undefined{"the solver run does not define '" + out + "'"};
    if (!std::isfinite(v)) {
      std::string why = "'" + out + "' is not finite (model not applicable)";
      if (!s.notes.empty()) why += ": " + s.notes.front();
      throw NotRun{why};
    }
    return v;
  };

  if (sel.contains("row")) {
    auto r = sel["row"].get<long>();
    if (r < 0) r += static_cast<long>(y.size());
    if (r < 0 || static_cast<std::size_t>(r) >= y.size()) throw InputError(field + ".row", "out of range");
    return finite_or_notrun(y[static_cast<std::size_t>(r)]);
  }
  if (sel.contains("at")) {
    const json& at = sel["at"];
    if (!at.is_object() || at.size() != 1) throw InputError(field + ".at", "expected { param = value }");
    const std::string xn = at.begin().key();
    const auto& x = column(t, xn, field + ".at");
    const double xv = qty(at.begin().value(), column_dim(t, xn, field + ".at"), field + ".at." + xn);
    return finite_or_notrun(interp(x, y, xv));
  }
  // Optional x column and window restrict the points.
  std::vector<double> xs, ys;
  const bool has_x = sel.contains("x");
  const std::vector<double>* xcol = has_x ? &column(t, sel["x"].get<std::string>(), field + ".x") : nullptr;
  double lo = -INFINITY, hi = INFINITY;
  if (sel.contains("window")) {
    if (!has_x) throw InputError(field + ".window", "needs x");
    const Dim xd = column_dim(t, sel["x"].get<std::string>(), field + ".x");
    lo = qty(sel["window"].at(0), xd, field + ".window[0]");
    hi = qty(sel["window"].at(1), xd, field + ".window[1]");
  }
  if (sel.contains("window_fraction")) {  // fractions of the table's x range (shape checked at load)
    const json& wf = sel["window_fraction"];
    double xmin = INFINITY, xmax = -INFINITY;
    for (double xv : *xcol) {
      if (!std::isfinite(xv)) continue;
      xmin = std::min(xmin, xv);
      xmax = std::max(xmax, xv);
    }
    if (!(xmax >= xmin)) throw NotRun{"no finite '" + sel["x"].get<std::string>() + "' to place the window in"};
    lo = xmin + wf[0].get<double>() * (xmax - xmin);
    hi = xmin + wf[1].get<double>() * (xmax - xmin);
  }
  std::size_t undefined = 0;  // points in the window whose value is not finite
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double xv = has_x ? (*xcol)[i] : static_cast<double>(i);
    if (!(xv >= lo && xv <= hi && std::isfinite(xv))) continue;
    if (!std::isfinite(y[i])) {
      ++undefined;
      continue;
    }
    xs.push_back(xv);
    ys.push_back(y[i]);
  }
  // as for a single value: a solver run that leaves the output undefined at every selected point
  // (no sticking zone to average over, no serration to measure) has not produced what the paper
  // reports, a FAIL; an empty window is NOT RUN
  if (ys.empty() && undefined > 0 && s.solver)
    throw Undefined{"the solver run does not define '" + out + "' (non-finite at every selected point)"};
  if (ys.empty()) throw NotRun{"no finite points of '" + out + "' in the selected window"};
  if (sel.contains("feature")) {
    const std::string f = sel["feature"].get<std::string>();
    if (!has_x) throw InputError(field + ".feature", "needs x");
    std::vector<std::size_t> idx(xs.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return xs[a] < xs[b]; });
    if (f == "slope") return linear_slope(xs, ys);
    if (f == "slope_sign") {
      const double sl = linear_slope(xs, ys);
      return sl > 0 ? 1.0 : (sl < 0 ? -1.0 : 0.0);
    }
    if (f == "argmax" || f == "argmin") {
      std::size_t best = idx[0];
      for (auto i : idx) {
        if (f == "argmax" ? ys[i] > ys[best] : ys[i] < ys[best]) best = i;
      }
      return xs[best];
    }
    if (f == "largest_drop_location" || f == "largest_drop_fraction") {
      if (idx.size() < 2) throw NotRun{"fewer than two points"};
      double best = -INFINITY;
      std::size_t k = 0;
      for (std::size_t j = 0; j + 1 < idx.size(); ++j) {
        const double d = ys[idx[j]] - ys[idx[j + 1]];
        if (d > best) {
          best = d;
          k = j;
        }
      }
      if (f == "largest_drop_location") return 0.5 * (xs[idx[k]] + xs[idx[k + 1]]);
      return best / ys[idx[k]];
    }
    if (f == "monotonic_increasing" || f == "monotonic_decreasing") {
      for (std::size_t j = 0; j + 1 < idx.size(); ++j) {
        const double d = ys[idx[j + 1]] - ys[idx[j]];
        if (f == "monotonic_increasing" ? d < 0 : d > 0) return 0.0;
      }
      return 1.0;
    }
    throw InputError(field + ".feature", "unknown feature '" + f +
                                             "' (slope, slope_sign, argmax, argmin, largest_drop_location, "
                                             "largest_drop_fraction, monotonic_increasing, monotonic_decreasing)");
  }
  const bool windowed = sel.contains("window") || sel.contains("window_fraction");
  const std::string reduce = sel.value("reduce", std::string(windowed ? "mean" : ""));
  if (reduce == "drift") {
    // (mean over the second half of the window - mean over its first half) / |mean over the window|
    // the halves split at the middle of the window's part that holds data
    const double mid = 0.5 * (std::max(lo, *std::min_element(xs.begin(), xs.end())) +
                              std::min(hi, *std::max_element(xs.begin(), xs.end())));
    double s1 = 0.0, s2 = 0.0;
    std::size_t n1 = 0, n2 = 0;
    for (std::size_t i = 0; i < ys.size(); ++i) {
      if (xs[i] < mid) {
        s1 += ys[i];
        ++n1;
      } else {
        s2 += ys[i];
        ++n2;
      }
    }
    if (n1 < 2 || n2 < 2) throw NotRun{"a half of the window holds fewer than two points"};
    const double all = (s1 + s2) / static_cast<double>(n1 + n2);
    if (all == 0.0) throw NotRun{"the mean over the window is zero"};
    return (s2 / static_cast<double>(n2) - s1 / static_cast<double>(n1)) / std::abs(all);
  }
  if (reduce.empty()) {
    if (ys.size() != 1) throw InputError(field, "selects " + std::to_string(ys.size()) + " points: give row, at, reduce or feature");
    return ys[0];
  }
  const double n = static_cast<double>(ys.size());
  const double mean = std::accumulate(ys.begin(), ys.end(), 0.0) / n;
  if (reduce == "mean") return mean;
  if (reduce == "max") return *std::max_element(ys.begin(), ys.end());
  if (reduce == "min") return *std::min_element(ys.begin(), ys.end());
  if (reduce == "max_abs") {
    double m = 0.0;
    for (double v : ys) m = std::max(m, std::abs(v));
    return m;
  }
  if (reduce == "first") return ys.front();
  if (reduce == "last") return ys.back();
  if (reduce == "std" || reduce == "cv") {
    double ss = 0;
    for (double v : ys) ss += (v - mean) * (v - mean);
    const double sd = std::sqrt(ss / std::max(1.0, n - 1));
    return reduce == "std" ? sd : sd / std::abs(mean);
  }
  throw InputError(field + ".reduce", "unknown reduction '" + reduce + "' (mean, max, min, max_abs, first, last, std, cv, drift)");
}

// Reference value in SI (or throws NotRun for an explicitly unavailable reference).
double reference_value(const CaseSpec& spec, const std::vector<SeriesResult>& series, const json& ref,
                       Dim dim, ReferenceCache& refs, const std::string& field, const std::string& units) {
  if (ref.is_number()) return to_si(ref.get<double>(), units, field);  // a bare number is in the check's units
  if (ref.is_string()) return qty(ref, dim, field);
  if (ref.is_object() && ref.contains("unavailable")) throw NotRun{ref["unavailable"].get<std::string>()};
  if (ref.is_object() && ref.contains("file")) {
    const auto path = source_root() / "reference_data" / spec.paper / ref["file"].get<std::string>();
    const ReferenceTable& t = refs.get(path, field + ".file");
    const std::string col = ref.at("column").get<std::string>();
    std::size_t row = 0;
    if (ref.contains("where")) {
      const auto rows = t.select(where_of(ref["where"]));
      if (rows.size() != 1) {
        throw InputError(field + ".where", "matches " + std::to_string(rows.size()) + " rows of " +
                                               t.path.filename().string() + " (need exactly 1)");
      }
      row = rows[0];
    } else if (ref.contains("row")) {
      auto r = ref["row"].get<long>();  // negative counts from the end, as in series selectors
      if (r < 0) r += static_cast<long>(t.rows);
      if (r < 0 || static_cast<std::size_t>(r) >= t.rows) {
        throw InputError(field + ".row", "in -" + std::to_string(t.rows) + ".." + std::to_string(t.rows) + " - 1 (" +
                                             t.path.filename().string() + " has " + std::to_string(t.rows) + " rows)");
      }
      row = static_cast<std::size_t>(r);
    } else if (t.rows != 1) {
      throw InputError(field, "give where or row: " + t.path.filename().string() + " has several rows");
    }
    const auto& c = t.column(col);
    if (!same_dimension(unit_info(c.unit, field).dim, dim)) {
      throw InputError(field + ".column", "column '" + col + "' is in " + c.unit + ", check is in " + dim_name(dim));
    }
    return t.si_value(col, row);
  }
  if (ref.is_object()) return select(series, ref, field);
  throw InputError(field, "expected a number, \"value unit\", [lo, hi], a file reference or a selector");
}

// A verdict that the measured run-to-run scatter of the value could flip is INCONCLUSIVE: the value
// lies within `scatter` of a pass/fail boundary.
void apply_scatter(CheckRecord& r) {
  if (!(r.scatter > 0) || (r.status != "PASS" && r.status != "FAIL")) return;
  std::vector<double> bounds;
  if (r.is_range) {
    bounds = {r.lower, r.upper};
  } else if (r.metric == "curve_max_norm") {
    bounds = {r.tolerance};
  } else {
    const double half = r.relative_tol ? r.tolerance * std::abs(r.reference) : r.tolerance;
    bounds = {r.reference - half, r.reference + half};
  }
  double nearest = bounds[0];
  for (double b : bounds) {
    if (std::isfinite(b) && std::abs(r.value - b) < std::abs(r.value - nearest)) nearest = b;
  }
  if (std::isfinite(nearest) && std::abs(r.value - nearest) < r.scatter) {
    std::ostringstream os;
    os << std::setprecision(4) << "value " << r.value << " lies " << std::abs(r.value - nearest)
       << " from the boundary " << nearest << " " << r.units << ", inside the measured scatter " << r.scatter
       << " (would be " << r.status << ")";
    r.status = "INCONCLUSIVE";
    r.message = os.str();
  }
}

// A check's record before evaluation: identity, texts, units and scatter from the case file.
CheckRecord record_header(const CaseSpec& spec, const CheckSpec& cs) {
  CheckRecord r;
  r.case_id = spec.id;
  r.key = cs.key;
  r.kind = cs.kind;
  r.metric = cs.metric;
  r.units = cs.units;
  r.source = cs.source;
  r.known_failure = cs.known_failure;
  r.description = cs.description;
  r.finding = cs.finding;
  r.tolerance_source = cs.tolerance_source;
  const std::string field = "check '" + cs.key + "'";
  const Dim dim = unit_info(cs.units, field + ".units").dim;
  if (cs.scatter.is_number()) {  // a number is in the check's units, as a tolerance
    r.scatter = cs.scatter.get<double>();
    r.scatter_source = cs.scatter_source;
  } else if (!cs.scatter.is_null()) {  // a spread: a temperature scatter is a difference, not a level
    r.scatter = from_si(qty(cs.scatter, dim, field + ".scatter"), cs.units, field) -
                (dim == Dim::temperature ? from_si(0.0, cs.units, field) : 0.0);
    r.scatter_source = cs.scatter_source;
  }
  return r;
}

// Tolerance: relative number or absolute quantity (in the check's units).
void set_tolerance(CheckRecord& r, const CheckSpec& cs) {
  const std::string field = "check '" + cs.key + "'";
  const Dim dim = unit_info(cs.units, field + ".units").dim;
  auto disp = [&](double si) { return from_si(si, cs.units, field + ".units"); };
  const json& tol = cs.tolerance;
  if (tol.is_null()) throw InputError(field + ".tolerance", "missing");
  if (tol.is_object()) {
    if (tol.contains("relative")) {
      r.relative_tol = true;
      r.tolerance = tol["relative"].get<double>();
    } else if (tol.contains("absolute")) {
      r.tolerance = disp(qty(tol["absolute"], dim, field + ".tolerance.absolute")) -
                    (dim == Dim::temperature ? disp(0.0) : 0.0);
    } else {
      throw InputError(field + ".tolerance", "expected { relative = x } or { absolute = x }");
    }
  } else if (cs.metric == "relative" || cs.metric == "windowed_mean") {
    r.relative_tol = true;
    r.tolerance = tol.get<double>();
  } else {
    r.tolerance = tol.is_string() ? disp(qty(tol, dim, field + ".tolerance")) : tol.get<double>();
  }
  if (!(r.tolerance >= 0)) throw InputError(field + ".tolerance", "must be >= 0");
}

// PASS or FAIL from the value against a range, or against the reference and tolerance.
void judge(CheckRecord& r) {
  if (r.is_range) {
    if (r.lower > r.upper) std::swap(r.lower, r.upper);
    r.error = r.value < r.lower ? r.value - r.lower : (r.value > r.upper ? r.value - r.upper : 0.0);
    r.status = (r.value >= r.lower && r.value <= r.upper) ? "PASS" : "FAIL";
  } else if (r.relative_tol) {
    r.error = r.reference != 0.0 ? (r.value - r.reference) / std::abs(r.reference) : r.value;
    r.status = std::abs(r.error) <= r.tolerance * (1 + 1e-12) ? "PASS" : "FAIL";
  } else {
    r.error = r.value - r.reference;
    r.status = std::abs(r.error) <= r.tolerance * (1 + 1e-12) ? "PASS" : "FAIL";
  }
  apply_scatter(r);
}

// A check compared with an interval [lower, upper] rather than a reference and a tolerance.
bool is_range_check(const CheckSpec& cs) {
  return cs.metric == "within" || (cs.reference.is_array() && cs.reference.size() == 2);
}

}  // namespace

std::vector<CheckRecord> evaluate_checks(const CaseSpec& spec, const std::vector<SeriesResult>& series,
                                         ReferenceCache& refs) {
  std::vector<CheckRecord> records;
  for (const auto& cs : spec.checks) {
    CheckRecord r = record_header(spec, cs);
    const std::string field = "check '" + cs.key + "'";
    const Dim dim = unit_info(cs.units, field + ".units").dim;
    auto disp = [&](double si) { return from_si(si, cs.units, field + ".units"); };
    auto set_tolerance = [&]() { framework::set_tolerance(r, cs); };
    // the paper's number of a check that could not be judged, when it is a literal or a file value
    auto show_literal_reference = [&]() {
      try {
        if (!cs.reference.is_array() && !(cs.reference.is_object() && cs.reference.contains("series"))) {
          r.reference = disp(reference_value(spec, series, cs.reference, dim, refs, field + ".reference", cs.units));
          r.has_reference = std::isfinite(r.reference);
        }
      } catch (const NotRun&) {
      } catch (const Pending&) {
      } catch (const Fault&) {
      }
    };

    if (!spec.implemented()) {
      r.status = "NOT IMPLEMENTED";
      r.message = spec.reason;
      // Still show the paper's number when it is a literal or a file reference.
      try {
        if (cs.reference.is_array() && cs.reference.size() == 2) {
          r.is_range = true;
          r.lower = disp(reference_value(spec, series, cs.reference[0], dim, refs, field + ".reference[0]", cs.units));
          r.upper = disp(reference_value(spec, series, cs.reference[1], dim, refs, field + ".reference[1]", cs.units));
          r.has_reference = true;
        } else if (!(cs.reference.is_object() && (cs.reference.contains("series") || cs.reference.contains("ratio")))) {
          r.reference = disp(reference_value(spec, series, cs.reference, dim, refs, field + ".reference", cs.units));
          r.has_reference = true;
        }
      } catch (const NotRun&) {
      }
      if (!cs.tolerance.is_null() && !(cs.reference.is_array())) set_tolerance();
      records.push_back(r);
      continue;
    }
    try {
      if (cs.metric == "curve_max_norm") {
        set_tolerance();
        const Curve v = get_curve(series, cs.value, field + ".value");
        Curve ref;
        if (cs.reference.contains("file")) {
          const auto path = source_root() / "reference_data" / spec.paper / cs.reference["file"].get<std::string>();
          const ReferenceTable& t = refs.get(path, field + ".reference.file");
          std::vector<std::size_t> rows;
          if (cs.reference.contains("where")) {
            rows = t.select(where_of(cs.reference["where"]));
          } else {
            for (std::size_t i = 0; i < t.rows; ++i) rows.push_back(i);
          }
          for (auto i : rows) {
            ref.x.push_back(t.si_value(cs.reference.at("x").get<std::string>(), i));
            ref.y.push_back(t.si_value(cs.reference.at("y").get<std::string>(), i));
          }
        } else {
          ref = get_curve(series, cs.reference, field + ".reference");
        }
        double worst = 0.0, scale = 0.0;
        std::size_t used = 0;
        for (std::size_t i = 0; i < ref.x.size(); ++i) {
          if (!std::isfinite(ref.y[i])) continue;
          double vi;
          try {
            vi = interp(v.x, v.y, ref.x[i]);
          } catch (const NotRun&) {
            continue;
          }
          worst = std::max(worst, std::abs(disp(vi) - disp(ref.y[i])));
          scale = std::max(scale, std::abs(disp(ref.y[i])));
          ++used;
        }
        if (used == 0) throw NotRun{"no overlap between the computed and the reference curve"};
        r.value = r.relative_tol ? worst / scale : worst;
        r.reference = 0.0;
        r.error = r.value;
        r.has_value = r.has_reference = true;
        r.status = r.value <= r.tolerance ? "PASS" : "FAIL";
        r.message = "max-norm over " + std::to_string(used) + " reference points";
        apply_scatter(r);
      } else {
        r.value = disp(select(series, cs.value, field + ".value"));
        r.has_value = true;
        if (!std::isfinite(r.value)) throw Fault{"value is not finite"};
        if (is_range_check(cs)) {
          r.is_range = true;
          r.lower = disp(reference_value(spec, series, cs.reference.at(0), dim, refs, field + ".reference[0]", cs.units));
          r.upper = disp(reference_value(spec, series, cs.reference.at(1), dim, refs, field + ".reference[1]", cs.units));
          r.has_reference = true;
        } else {
          set_tolerance();
          r.reference = disp(reference_value(spec, series, cs.reference, dim, refs, field + ".reference", cs.units));
          r.has_reference = true;
          if (!std::isfinite(r.reference)) throw Fault{"reference is not finite"};
        }
        judge(r);
      }
      if (r.status == "PASS" && !r.known_failure.empty()) {
        r.message = "passes although declared a known failure: revisit known_failure";
      }
    } catch (const Fault& f) {
      r.status = "ERROR";
      r.message = f.why;
    } catch (const Undefined& u) {
      r.status = "FAIL";
      r.has_value = false;
      r.message = u.why;
      // the check's tolerance and literal reference, as a judged check would carry them
      if (!is_range_check(cs)) {
        set_tolerance();
        show_literal_reference();
      }
    } catch (const NotRun& nr) {
      r.status = "NOT RUN";
      r.message = nr.why;
    } catch (const Pending& p) {
      r.status = "NOT IMPLEMENTED";
      r.message = p.why;
      show_literal_reference();
    }
    records.push_back(r);
  }
  return records;
}

CheckRecord rejudge_check(const CaseSpec& spec, const CheckSpec& cs, const json& recorded, ReferenceCache& refs) {
  CheckRecord r = record_header(spec, cs);
  const std::string field = "check '" + cs.key + "'";
  const Dim dim = unit_info(cs.units, field + ".units").dim;
  auto disp = [&](double si) { return from_si(si, cs.units, field + ".units"); };
  const std::vector<SeriesResult> none;
  // a literal or a reference-file value is read from the case file as it is now; a reference that a
  // selector computed from the run's data is kept as recorded
  auto from_case = [](const json& ref) {
    return ref.is_number() || ref.is_string() || (ref.is_object() && (ref.contains("file") || ref.contains("unavailable")));
  };
  const bool range = is_range_check(cs);
  if (!range) set_tolerance(r, cs);
  const json& rv = recorded.value("value", json());
  if (!rv.is_number()) {
    r.status = recorded.value("status", std::string("NOT RUN"));
    r.message = recorded.value("message", std::string());
    // a solver output the run did not define was recorded as NOT RUN: it is a FAIL (Undefined)
    const std::string series = cs.value.is_object() ? cs.value.value("series", std::string()) : std::string();
    const bool solver = std::any_of(spec.series.begin(), spec.series.end(),
                                    [&](const SeriesSpec& ss) { return ss.name == series && ss.solver; });
    if (r.status == "NOT RUN" && solver && r.message.find("is not finite") != std::string::npos) {
      r.status = "FAIL";
      r.message = "the solver run does not define '" + cs.value.value("output", std::string()) + "'";
    }
    return r;
  }
  r.value = rv.get<double>();
  r.has_value = true;
  try {
    if (cs.metric == "curve_max_norm") {
      r.reference = 0.0;
      r.error = r.value;
      r.has_reference = true;
      r.status = r.value <= r.tolerance ? "PASS" : "FAIL";
      r.message = recorded.value("message", std::string());
      apply_scatter(r);
      return r;
    }
    const json& rref = recorded.value("reference", json());
    if (range) {
      r.is_range = true;
      for (int k = 0; k < 2; ++k) {
        const json& ref = cs.reference.at(static_cast<std::size_t>(k));
        double& bound = k == 0 ? r.lower : r.upper;
        if (from_case(ref)) {
          bound = disp(reference_value(spec, none, ref, dim, refs, field + ".reference", cs.units));
        } else if (rref.is_array() && rref.size() == 2 && rref[static_cast<std::size_t>(k)].is_number()) {
          bound = rref[static_cast<std::size_t>(k)].get<double>();
        } else {
          throw NotRun{"the record holds no reference bound"};
        }
      }
    } else {
      if (from_case(cs.reference)) {
        r.reference = disp(reference_value(spec, none, cs.reference, dim, refs, field + ".reference", cs.units));
      } else if (rref.is_number()) {
        r.reference = rref.get<double>();
      } else {
        throw NotRun{"the record holds no reference"};
      }
    }
    r.has_reference = true;
    judge(r);
    if (r.status == "PASS" && !r.known_failure.empty()) {
      r.message = "passes although declared a known failure: revisit known_failure";
    }
  } catch (const NotRun& nr) {
    r.status = "NOT RUN";
    r.message = nr.why;
  }
  return r;
}

}  // namespace cutbench::framework
