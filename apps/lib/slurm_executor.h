#pragma once
// Running a task manifest (bench_tasks.h) on a Slurm cluster: one job array per manifest, task k
// running line k through `rpvio-bench --run-task`. Talks to Slurm through its commands only
// (sbatch, squeue, scontrol, sacct); no daemon of our own. The output folder, the suite and the
// binaries must be on a filesystem every node shares (docs/tools.md).
#include <string>
#include <vector>

namespace rpvio::apps {

struct SlurmOptions {
  std::string partition;   // "" = the cluster's default
  int time_limit_min = 0;  // per task; 0 = the partition's limit
  int max_running = 0;     // tasks of an array running at once (--array=...%K); 0 = any
  std::vector<std::string> sbatch_args;  // passed on as they are (--account=..., --qos=...)
  double poll_s = 3;                     // how often squeue is asked while waiting
};

/// "0-3,7,9-10" for {0, 1, 2, 3, 7, 9, 10}.
std::string arrayRanges(const std::vector<size_t>& indices);

/// Submits the array of `indices` of `manifest`; returns the job id. `after_ok`: a job id that
/// must complete successfully first (the array is cancelled if it does not), or "". Slurm's own
/// log of task k goes to `log_dir`/`job_name`_k.out. Throws std::runtime_error with sbatch's
/// message when the submission is refused.
std::string submitArray(const SlurmOptions& options, const std::string& manifest,
                        const std::vector<size_t>& indices, const std::string& job_name,
                        const std::string& log_dir, const std::string& after_ok = "");

/// Waits until no task of the job is pending or running, with a progress line on stderr whenever
/// the counts change.
void waitForJob(const SlurmOptions& options, const std::string& job_id, const std::string& what,
                size_t tasks);

/// Slurm's state of task `index` of the array `job_id` (COMPLETED, FAILED, TIMEOUT, CANCELLED,
/// PENDING, ...), or "unknown to Slurm" once it has forgotten the job.
std::string taskState(const std::string& job_id, size_t index);

}  // namespace rpvio::apps
