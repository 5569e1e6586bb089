#include "slurm.hpp"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "cutbench/common/errors.hpp"

namespace cutbench::cli {
namespace fs = std::filesystem;

namespace {
// A word for a bash script, single-quoted.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string header(const SlurmOptions& o, const std::string& name, const std::string& log) {
  std::ostringstream h;
  h << "#!/bin/bash\n"
    << "#SBATCH --job-name=" << name << "\n"
    << "#SBATCH --cpus-per-task=" << o.cpus_per_task << "\n"
    << "#SBATCH --time=" << o.time << "\n"
    << "#SBATCH --output=" << log << "\n";
  if (!o.partition.empty()) h << "#SBATCH --partition=" << o.partition << "\n";
  if (!o.account.empty()) h << "#SBATCH --account=" << o.account << "\n";
  return h.str();
}

std::string case_args(const SlurmPlan& plan) {
  std::string a;
  for (const auto& id : plan.case_ids) a += " --case " + quoted(id);
  return a;
}

// Run a command, its standard output captured; throws when it fails.
std::string capture(const std::string& cmd) {
  std::array<char, 256> buf{};
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("cannot run: " + cmd);
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) out += buf.data();
  const int rc = ::pclose(p);
  if (rc != 0) throw std::runtime_error("'" + cmd + "' failed (status " + std::to_string(rc) + "): " + out);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}
}  // namespace

std::string slurm_array_script(const SlurmPlan& plan, const SlurmOptions& o, const std::string& cutbench,
                               const std::string& workdir) {
  std::ostringstream s;
  s << header(o, o.job_name, plan.store + "/slurm/" + o.job_name + "-%A_%a.out")
    << "#SBATCH --array=0-" << plan.runs.size() - 1 << "\n"
    << "# One task per run the store lacks: the task computes exactly that run into the store, with a\n"
    << "# checkpoint every " << plan.checkpoint_minutes << " min (a task killed at its time limit resumes when resubmitted).\n"
    << "set -euo pipefail\n"
    << "cd " << quoted(workdir) << "\n"
    << "runs=(";
  for (const auto& r : plan.runs) s << "\n  " << quoted(r);
  s << "\n)\n"
    << "export OMP_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-" << o.cpus_per_task << "}\"\n"
    << "exec " << quoted(cutbench) << " runs " << quoted(plan.store) << case_args(plan) << " --tier " << plan.tier
    << " --compute --run \"${runs[$SLURM_ARRAY_TASK_ID]}\" -j \"$OMP_NUM_THREADS\" --checkpoint-minutes "
    << plan.checkpoint_minutes << "\n";
  return s.str();
}

std::string slurm_record_script(const SlurmPlan& plan, const SlurmOptions& o, const std::string& cutbench,
                                const std::string& workdir) {
  std::ostringstream s;
  const std::string out = plan.store + "/slurm/" + o.job_name + "-results";
  s << header(o, o.job_name + "-record", plan.store + "/slurm/" + o.job_name + "-record-%j.out")
    << "# After the array (--dependency=afterany): evaluate the cases from the stored runs only and\n"
    << "# record those the store completes (a case with a missing run is NOT RUN and not recorded).\n"
    << "set -uo pipefail\n"
    << "cd " << quoted(workdir) << "\n"
    << "rm -rf " << quoted(out) << "\n"
    << quoted(cutbench) << " run";
  for (const auto& id : plan.case_ids) s << " " << quoted(id);
  s << " --tier " << plan.tier << " --run-cache " << quoted(plan.store) << " --stored-only --out " << quoted(out)
    << " -j 1\n"
    << "rc=$?\n"
    << "if [ \"$rc\" -ne 0 ] && [ \"$rc\" -ne 1 ]; then exit \"$rc\"; fi  # 1: checks fail, still a verdict\n"
    << "exec /usr/bin/python3 reports/record_full_tier.py --results " << quoted(out) << " --into " << quoted(o.records)
    << " --complete-only --how "
    << "\"Slurm job ${SLURM_JOB_ID:-?} after the array " << o.job_name << ": cutbench runs --compute --slurm, "
    << o.cpus_per_task << " thread(s) per run, " << quoted(cutbench) << "\"\n";
  return s.str();
}

int submit_slurm(const SlurmPlan& plan, const SlurmOptions& o) {
  if (plan.runs.empty()) {
    std::cout << "slurm: the store holds every run of these cases; nothing to submit\n";
    return 0;
  }
  const std::string cutbench = fs::read_symlink("/proc/self/exe").string();
  const std::string workdir = fs::current_path().string();
  const std::string array = slurm_array_script(plan, o, cutbench, workdir);
  const std::string record = slurm_record_script(plan, o, cutbench, workdir);
  if (o.dry_run) {
    std::cout << "# --- " << o.job_name << ".array.sh (sbatch --parsable) ---\n" << array
              << "# --- " << o.job_name << ".record.sh (sbatch --parsable --dependency=afterany:<array job>) ---\n"
              << record;
    return 0;
  }
  const fs::path dir = fs::path(plan.store) / "slurm";
  fs::create_directories(dir);
  const fs::path a = dir / (o.job_name + ".array.sh"), r = dir / (o.job_name + ".record.sh");
  std::ofstream(a) << array;
  std::ofstream(r) << record;
  const std::string job = capture("sbatch --parsable " + quoted(a.string()));
  const std::string jid = job.substr(0, job.find(';'));
  const std::string rec = capture("sbatch --parsable --dependency=afterany:" + jid + " " + quoted(r.string()));
  std::cout << "slurm: submitted array job " << jid << " (" << plan.runs.size() << " runs) and record job "
            << rec.substr(0, rec.find(';')) << "; scripts and logs in " << dir.string() << "\n";
  return 0;
}

}  // namespace cutbench::cli
