#include "cutbench/framework/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "cutbench/analytic/models.hpp"
#include "cutbench/framework/audit.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/framework/run_cache.hpp"
#include "cutbench/common/checkpoint.hpp"
#include "cutbench/framework/methods.hpp"

namespace cutbench::framework {

namespace {
int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

}  // namespace

void register_all() {
  analytic::register_models(ModelRegistry::instance());
  SolverRegistry& registry = SolverRegistry::instance();
  for (const auto& m : detail::compiled_methods()) {
    // register_solvers is idempotent: a second call adds nothing and keeps the identities
    const std::size_t before = registry.all().size();
    m.register_solvers(registry);
    for (std::size_t k = before; k < registry.all().size(); ++k) {
      set_solver_identity(registry.all()[k].name, m.source_identity(), m.build_settings());
    }
  }
}

std::string solver_sources(const std::string& method) {
  for (const auto& m : detail::compiled_methods()) {
    if (method == m.name) return m.sources_digest();
  }
  return {};
}

RunOutput solver_run(const SolverSpec& sv, const Values& params, const ProgressFn& progress, bool* reused,
                     std::string* path) {
  if (reused) *reused = false;
  const std::string& cache = run_cache_dir();
  if (cache.empty()) return sv.run(params, progress);
  RunOutput run;
  const std::string key = run_key(sv.name, params);
  const std::string cache_path = cache + "/" + run_file_name(sv.name, key);
  if (path) *path = cache_path;
  std::string problem;
  if (load_run(cache_path, key, run, &problem)) {
    if (progress) progress(1.0, "reused from the run cache");
    if (reused) *reused = true;
    return run;
  }
  if (run_cache_stored_only()) throw RunNotStored("run " + run_file_name(sv.name, key) + " is not in " + cache);
  // one process computes a run of a shared store; another waits and reads what it stored
  const RunLock lock(cache_path, [&](const std::string& msg) {
    if (progress) progress(0.0, msg);
  });
  if (lock.waited() && load_run(cache_path, key, run, &problem)) {
    if (progress) progress(1.0, "reused from the run cache (computed by another process)");
    if (reused) *reused = true;
    return run;
  }
  if (problem.rfind("damaged", 0) == 0) {  // reported, never read back; the recomputed run replaces it
    std::fprintf(stderr, "cutbench: stored run %s is %s: computing it again\n", cache_path.c_str(), problem.c_str());
  }
  // solvers that support checkpoints resume from, and write, <run file>.ckpt
  const CheckpointSpec ck{cache_path.substr(0, cache_path.size() - 4) + ".ckpt", key, checkpoint_interval(), false};
  const auto started = std::chrono::steady_clock::now();
  ProgressLog plog(cache_path);  // the fraction done that `cutbench runs` shows
  {
    CheckpointScope scope(ck);
    run = sv.run(params, [&](double f, const std::string& msg) {
      plog.note(f);
      if (progress) progress(f, msg);
    });
  }
  if (!problem.empty() && problem.rfind("damaged", 0) == 0) {
    run.notes.push_back("the stored file of this run was " + problem + "; computed again");
  }
  // provenance of a stored run, which later builds of the same solver sources may reuse
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  run.notes.push_back("run stored in the run cache: computed by cutbench " + software_version() + ", finished " +
                      utc_now_iso() + ", " + std::to_string(max_threads()) + " thread(s), " +
                      std::to_string(static_cast<long>(std::lround(wall))) +
                      " s wall in its last process (a resumed run counts from its checkpoint); build: " +
                      (solver_build_settings(sv.name).empty() ? "executable " + build_identity()
                                                              : solver_build_settings(sv.name)));
  try {
    save_run(cache_path, key, run);
    remove_checkpoint(ck);
    plog.remove();
  } catch (const std::exception& e) {  // the finished run is kept; only its storage failed
    run.notes.push_back(std::string("run cache: not stored (") + e.what() + ")");
  }
  return run;
}

namespace {

const ParamSpec* find_param(const std::vector<ParamSpec>& params, const std::string& name) {
  for (const auto& p : params) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

// A solver run whose histories hold a non-finite value has faulted (a blow-up the solver's own
// guards missed): the series is an ERROR, never a source of NOT RUN checks. (A NaN scalar is a
// quantity the run does not define, e.g. mu_sticking without a sticking zone: a check reading it
// FAILs with that reason.)
void require_finite(const RunOutput& run, const std::string& where) {
  for (const auto& t : run.tables) {
    for (const auto& [name, col] : t.columns) {
      for (std::size_t i = 0; i < col.size(); ++i) {
        if (!std::isfinite(col[i])) {
          throw std::runtime_error(where + ": non-finite value in history '" + t.name + "', column '" + name +
                                   "', row " + std::to_string(i));
        }
      }
    }
  }
}

// A run keeps to its solver's declaration (the seam: outputs are declared in the solver alone);
// anything else is a fault of the solver, an ERROR of the series.
void require_declared(const SolverSpec& sv, const RunOutput& run, const std::string& where) {
  const auto extra = undeclared_outputs(sv, run);
  if (extra.empty()) return;
  std::string list;
  for (const auto& e : extra) list += (list.empty() ? "" : ", ") + e;
  throw std::runtime_error(where + ": the run returned outputs " + sv.name + " does not declare: " + list);
}

SeriesResult run_series(const SeriesSpec& s, ReferenceCache& refs, const ProgressFn& progress,
                        double frac0, double frac1) {
  SeriesResult out;
  out.name = s.name;
  out.model = s.model;
  out.solver = s.solver;
  out.table.name = s.name;
  const auto points = series_points(s, refs);
  const auto varied = varied_params(s);

  if (!s.solver) {
    const ModelSpec& m = ModelRegistry::instance().get(s.model);
    for (const auto& v : varied) {
      std::vector<double> col;
      for (const auto& p : points) col.push_back(p.at(v));
      out.table.add(v, si_unit(find_param(m.params, v)->dim), col);
    }
    std::map<std::string, std::vector<double>> outs;
    std::vector<double> applicable;
    for (const auto& p : points) {
      ModelResult r = evaluate_model(m, p);
      for (const auto& o : m.outputs) {
        auto it = r.outputs.find(o.name);
        outs[o.name].push_back(it == r.outputs.end() ? nan_value() : it->second);
      }
      applicable.push_back(r.applicable ? 1.0 : 0.0);
      if (!r.applicable && !r.note.empty() &&
          std::find(out.notes.begin(), out.notes.end(), r.note) == out.notes.end()) {
        out.notes.push_back(r.note);
      }
    }
    for (const auto& o : m.outputs) {
      if (std::find(varied.begin(), varied.end(), o.name) == varied.end()) {
        out.table.add(o.name, si_unit(o.dim), outs[o.name]);
      }
    }
    out.table.add("applicable", "1", applicable);
    return out;
  }

  const SolverSpec* sv = SolverRegistry::instance().find(s.model);
  for (const auto& v : varied) {
    std::vector<double> col;
    for (const auto& p : points) col.push_back(p.at(v));
    out.table.add(v, si_unit(find_param(sv->params, v)->dim), col);
  }
  std::map<std::string, std::vector<double>> scal;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Values params = validate_params(ModelSpec{sv->name, "", "", sv->params, {}, {}}, points[k]);
    const double a = frac0 + (frac1 - frac0) * static_cast<double>(k) / static_cast<double>(points.size());
    const double b = frac0 + (frac1 - frac0) * static_cast<double>(k + 1) / static_cast<double>(points.size());
    ProgressFn inner = [&](double f, const std::string& msg) {
      if (progress) progress(a + (b - a) * f, s.name + " point " + std::to_string(k + 1) + "/" +
                                                  std::to_string(points.size()) + ": " + msg);
    };
    bool reused = false;
    std::string cache_path;
    RunOutput run = solver_run(*sv, params, inner, &reused, &cache_path);
    require_finite(run, s.name + " point " + std::to_string(k + 1));
    require_declared(*sv, run, s.name + " point " + std::to_string(k + 1));
    if (reused) {
      run.notes.push_back("point " + std::to_string(k + 1) + " of series '" + s.name + "' reused from the run cache (" +
                          std::filesystem::path(cache_path).filename().string() + ")");
    }
    for (const auto& o : sv->scalars) {
      auto it = run.scalars.find(o.name);
      scal[o.name].push_back(it == run.scalars.end() ? nan_value() : it->second);
    }
    for (const auto& n : run.notes) {
      if (std::find(out.notes.begin(), out.notes.end(), n) == out.notes.end()) out.notes.push_back(n);
    }
    out.runs.push_back(std::move(run));
  }
  for (const auto& o : sv->scalars) out.table.add(o.name, si_unit(o.dim), scal[o.name]);
  return out;
}

}  // namespace

std::string case_status(const CaseSpec& spec, const std::vector<CheckRecord>& checks) {
  if (!spec.implemented()) return "NOT IMPLEMENTED";
  int pass = 0, fail = 0, not_run = 0, pending = 0, error = 0, inconclusive = 0;
  for (const auto& c : checks) {
    if (c.status == "FAIL") ++fail;  // a documented known failure is still a FAIL (it only spares the gate)
    else if (c.status == "PASS") ++pass;
    else if (c.status == "ERROR") ++error;
    else if (c.status == "INCONCLUSIVE") ++inconclusive;
    else if (c.status == "NOT RUN") ++not_run;
    else ++pending;
  }
  if (error) return "ERROR";
  if (fail) return "FAIL";
  if (inconclusive) return "INCONCLUSIVE";
  if (pass) return "PASS";
  if (not_run) return "NOT RUN";
  return pending ? "NOT IMPLEMENTED" : "NOT RUN";
}

std::vector<PlannedRun> planned_runs(const CaseSpec& spec) {
  std::vector<PlannedRun> out;
  if (!spec.implemented()) return out;
  ReferenceCache refs;
  for (const auto& s : spec.series) {
    if (!s.solver || !s.pending.empty()) continue;
    const SolverSpec* sv = SolverRegistry::instance().find(s.model);
    if (!sv) throw InputError("series '" + s.name + "'.model", "a registered solver ('" + s.model + "' is not)");
    const auto points = series_points(s, refs);
    for (std::size_t k = 0; k < points.size(); ++k) {
      PlannedRun p;
      p.series = s.name;
      p.point = k + 1;
      p.solver = sv->name;
      if (!s.links.empty()) {
        p.linked = "needs series '" + s.links.begin()->second.first + "'";
      } else {
        p.params = validate_params(ModelSpec{sv->name, "", "", sv->params, {}, {}}, points[k]);
        p.key = run_key(sv->name, p.params);
        p.file = run_file_name(sv->name, p.key);
      }
      out.push_back(std::move(p));
    }
  }
  return out;
}

std::string planned_run_state(const PlannedRun& run, const std::map<std::string, StoredRun>& store) {
  if (!run.linked.empty()) return run.linked;
  const auto holds = [&](const std::string& file) {
    const auto it = store.find(file);
    return it != store.end() && it->second.key == run.key && it->second.state == "current";
  };
  if (holds(run.file)) return "stored";
  if (holds(run.file.substr(0, run.file.size() - 4) + ".ckpt")) return "checkpoint";
  return "to compute";
}

CaseResult run_case(const CaseSpec& spec, const std::string& tier, const ProgressFn& progress) {
  CaseResult r;
  r.case_id = spec.id;
  r.tier = tier;
  r.date = utc_now_iso();
  r.threads = max_threads();
  const auto t0 = std::chrono::steady_clock::now();
  ReferenceCache refs;
  bool not_stored = false;  // stored runs only: a series whose runs the store lacks
  if (spec.implemented()) {
    const std::size_t n = spec.series.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double f0 = static_cast<double>(i) / static_cast<double>(n);
      const double f1 = static_cast<double>(i + 1) / static_cast<double>(n);
      if (!spec.series[i].pending.empty()) {
        SeriesResult pend;
        pend.name = spec.series[i].name;
        pend.model = spec.series[i].model;
        pend.pending = spec.series[i].pending;
        r.series.push_back(std::move(pend));
        continue;
      }
      try {
        SeriesSpec linked = spec.series[i];
        std::string pending;
        std::size_t n_points = series_points(linked, refs).size();
        for (const auto& [param, from] : linked.links) {
          const SeriesResult* src = nullptr;
          for (const auto& prev : r.series) {
            if (prev.name == from.first) src = &prev;
          }
          if (!src || !src->pending.empty() || !src->error.empty()) {
            pending = "needs series '" + from.first + "'" + (src && !src->pending.empty() ? ": " + src->pending : "");
            break;
          }
          auto it = src->table.columns.find(from.second);
          if (it == src->table.columns.end()) {
            throw InputError("series '" + linked.name + "'.link." + param,
                             "series '" + from.first + "' has no output '" + from.second + "'");
          }
          const auto& vals = it->second;
          if (vals.size() == 1) {
            linked.params[param] = vals[0];
          } else if (vals.size() == n_points && linked.sweep) {
            linked.zip[param] = vals;
          } else {
            throw InputError("series '" + linked.name + "'.link." + param,
                             "series '" + from.first + "' has " + std::to_string(vals.size()) + " rows, this series " +
                                 std::to_string(n_points) + " points");
          }
        }
        if (!pending.empty()) {
          SeriesResult pend;
          pend.name = linked.name;
          pend.model = linked.model;
          pend.pending = pending;
          r.series.push_back(std::move(pend));
          continue;
        }
        r.series.push_back(run_series(linked, refs, progress, f0, f1));
      } catch (const InputError&) {
        throw;
      } catch (const RunNotStored&) {
        not_stored = true;  // stored runs only: the series is not evaluated
        continue;
      } catch (const std::exception& e) {
        SeriesResult failed;
        failed.name = spec.series[i].name;
        failed.model = spec.series[i].model;
        failed.error = e.what();
        r.series.push_back(std::move(failed));
      }
    }
  }
  r.checks = evaluate_checks(spec, r.series, refs);
  for (std::size_t k = 0; k < r.checks.size(); ++k) {  // can each check fail? (audit.cpp)
    r.checks[k].audit = audit_check(spec, spec.checks[k], r.checks[k], r.series, refs);
  }
  r.status = case_status(spec, r.checks);
  // a series that faulted makes the case an ERROR even when no check reads it
  for (const auto& s : r.series) {
    if (!s.error.empty()) r.status = "ERROR";
  }
  if (not_stored && r.status != "ERROR") r.status = "NOT RUN";  // incomplete: no verdict
  if (spec.solver != "analytic") r.solver_sources = solver_sources(spec.solver);
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace cutbench::framework
