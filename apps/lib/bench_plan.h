#pragma once
// rpvio-bench's plan: the runs a command line asks for, as task manifests any executor runs from
// (bench_tasks.h), saved in OUTDIR/bench/ so that `rpvio-bench --collect OUTDIR` rebuilds it later
// and from anywhere, and the Slurm jobs that ran its tasks.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "apps/lib/bench_results.h"
#include "apps/lib/bench_tasks.h"
#include "apps/lib/command_line.h"
#include "apps/lib/slurm_executor.h"

namespace rpvio::apps {

/// What the command line asks for. Paths are absolute: tasks run wherever Slurm starts them.
struct BenchPlan {
  BenchSetup setup;
  std::filesystem::path out, config_dir;
  bool slurm = false;
  SlurmOptions slurm_options;
  std::vector<BenchRun> runs;
  std::vector<BenchTask> sim_tasks, slam_tasks;  // slam_tasks[k] makes runs[k]
};

/// rpvio-bench's options (taking a value) and flags.
extern const std::set<std::string> kBenchOptions, kBenchFlags;

/// UsageError or InputError on a bad option, an unknown sequence or a missing mode file.
BenchPlan planFrom(const CommandLine& cli);
/// OUTDIR/bench/<kind>.tsv, kind rpvio-sim or rpvio-slam.
std::filesystem::path manifestPath(const BenchPlan& plan, const std::string& kind);
/// Writes OUTDIR/bench/: the arguments (paths made absolute) and both manifests.
void savePlan(const CommandLine& cli, const BenchPlan& plan);
/// The plan saved in `out`, with `more_args` over its arguments (the last value of an option
/// counts). InputError when `out` holds none.
BenchPlan loadPlan(const std::filesystem::path& out, const std::vector<std::string>& more_args);

/// Slurm job arrays submitted for the plan (bench/jobs.tsv: kind, job id, task indices).
void recordJob(const BenchPlan& plan, const std::string& kind, const std::string& job_id,
               const std::vector<size_t>& indices);
/// The Slurm job that last ran task `index` of `kind`, or "".
std::string jobOfTask(const BenchPlan& plan, const std::string& kind, size_t index);

std::vector<size_t> allIndices(size_t count);
/// The tasks of `tasks` (by index) that failed or have not finished.
std::vector<size_t> unfinished(const std::vector<BenchTask>& tasks,
                               const std::vector<size_t>& indices);
/// The tasks of `indices` whose last Slurm job still has them pending or running.
std::vector<size_t> stillQueued(const BenchPlan& plan, const std::string& kind,
                                const std::vector<size_t>& indices);
/// What went wrong with task k of `kind`: exit code or Slurm state, and where its logs are.
std::string taskReport(const BenchPlan& plan, const std::string& kind,
                       const std::vector<BenchTask>& tasks, size_t k);

}  // namespace rpvio::apps
