#pragma once
// The paper-resolution tier on a Slurm cluster: `cutbench runs --case C... | --paper P --compute
// --slurm` writes a job array (one task per run the shared store lacks, each computing exactly that
// run into the store with its checkpoints) and a job that depends on it and records the cases the
// store then completes, and submits both with sbatch (--dry-run: prints them, writes nothing).
#include <string>
#include <vector>

namespace cutbench::cli {

struct SlurmOptions {
  bool enabled = false, dry_run = false;
  std::string partition, account, time = "24:00:00", job_name = "cutbench";
  std::string records = "reports/full_tier";  // where the record job writes (record_full_tier.py --into)
  int cpus_per_task = 1;
};

struct SlurmPlan {
  std::string store;                  // the shared run store (made absolute)
  std::vector<std::string> case_ids;  // the cases the runs belong to
  std::string tier;
  std::vector<std::string> runs;      // run files the store lacks, one array task each
  double checkpoint_minutes = 10.0;
};

// The two batch scripts (array, record) of a plan, as submitted.
std::string slurm_array_script(const SlurmPlan& plan, const SlurmOptions& o, const std::string& cutbench,
                               const std::string& workdir);
std::string slurm_record_script(const SlurmPlan& plan, const SlurmOptions& o, const std::string& cutbench,
                                const std::string& workdir);

// Writes the scripts into <store>/slurm/ and submits them (the record job with
// --dependency=afterany on the array); --dry-run prints them instead. Returns the exit code.
int submit_slurm(const SlurmPlan& plan, const SlurmOptions& o);

}  // namespace cutbench::cli
