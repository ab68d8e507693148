#include "apps/lib/bench_app.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "apps/lib/bench_plan.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/json_text.h"
#include "evaluation/trajectory_metrics.h"
#include "evaluation/trajectory_plot.h"
#include "rawlog_io/trajectory_io.h"

namespace fs = std::filesystem;

namespace rpvio::apps {
namespace {

const char* kUsage =
    "usage: rpvio-bench --suite DIR [--generate] [--profile P] [--duration SEC] [--seed "
    "S]\n"
    "                   [--modes vins-mono,mask-vins,rpvio-single,rpvio-multi,rpvio-auto]\n"
    "                   [--sequences static,C1,C2,C4,C6,C8] [--runs N] [--jobs J]\n"
    "                   [--config-dir config] [--executor local|slurm] --out OUTDIR\n"
    "       rpvio-bench --collect OUTDIR [--resubmit-failed]\n"
    "  Runs every mode (config-dir/<mode>.ini) on every sequence DIR/<sequence>/ (seq.rawlog,\n"
    "  calib.ini, groundtruth.tum) N times, J runs at a time, evaluates them (SE(3)-aligned ATE,\n"
    "  coverage) and writes OUTDIR/results.md, OUTDIR/results.json, OUTDIR/plots/<sequence>.png\n"
    "  and every run's outputs in OUTDIR/runs/<sequence>/<mode>/run<k>/. --generate (re)writes "
    "the\n"
    "  sequences first with rpvio-sim (--profile, --duration, --seed passed on; sequence CN has N\n"
    "  characters, static none, MP moving planar objects, MP-CN both). --sequences defaults to "
    "the\n"
    "  profile's suite (hard: also MP, MP-C4). The pipeline is deterministic: runs of a pair "
    "repeat\n"
    "  exactly.\n"
    "  --executor slurm: one Slurm job array for the runs (and one for --generate, which the runs\n"
    "  wait for), at most J tasks at a time when --jobs is given; [--partition P] [--time-limit\n"
    "  MIN] [--sbatch-arg ARG]... go to sbatch. Waits and collects, or returns after the\n"
    "  submission with --submit-only. OUTDIR, the suite and the binaries must be on a filesystem\n"
    "  every node shares.\n"
    "  --collect OUTDIR: the results of the runs that have finished; names the failed or missing\n"
    "  ones with their Slurm state and logs; --resubmit-failed runs only those again first.\n";

/// Runs `jobs` tasks at a time; `task(k)` for k in [0, count). The first exception a task throws
/// is rethrown once every worker has stopped (the others take no new task).
void runParallel(size_t count, int jobs, const std::function<void(size_t)>& task) {
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::vector<std::thread> workers;
  for (int j = 0; j < std::max(1, jobs); ++j)
    workers.emplace_back([&] {
      for (size_t k; (k = next++) < count;) {
        try {
          task(k);
        } catch (...) {
          std::lock_guard<std::mutex> lock(error_mutex);
          if (!error) error = std::current_exception();
          next = count;
        }
      }
    });
  for (auto& w : workers) w.join();
  if (error) std::rethrow_exception(error);
}

/// One line per finished task on stderr: what finished, elapsed time and an estimate of the rest.
class Progress {
 public:
  Progress(std::string what, size_t total)
      : what_(std::move(what)), total_(total), start_(std::chrono::steady_clock::now()) {}
  void done(const std::string& line) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = s / static_cast<double>(done_) * static_cast<double>(total_ - done_);
    std::fprintf(stderr, "[%s %zu/%zu] %s  (elapsed %.0f s, ETA %.0f s)\n", what_.c_str(), done_,
                 total_, line.c_str(), s, eta);
  }

 private:
  std::string what_;
  size_t total_, done_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
};

/// Fills the run's evaluation and timing from its output folder; the evaluation itself when there
/// is one (for the plots).
std::optional<eval::EvalResult> evaluateRun(BenchRun& run, const Trajectory& gt) {
  const fs::path dir(run.dir);
  const std::string summary = readText(dir / "summary.json");
  auto number = [&](const char* key) {
    const double v = jsonNumber(summary, key);
    return std::isfinite(v) ? v : 0.0;
  };
  run.initialized_at = number("initialized_at");
  run.resets = number("resets");
  run.frontend_ms_median = number("frontend_ms_median");
  run.frontend_ms_p95 = number("frontend_ms_p95");
  run.optimization_ms_median = number("optimization_ms_median");
  run.optimization_ms_p95 = number("optimization_ms_p95");
  run.total_ms_median = number("total_ms_median");
  run.total_ms_p95 = number("total_ms_p95");
  run.load_ms_median = number("load_ms_median");
  run.processing_ms_median = number("processing_ms_median");
  run.processing_ms_p95 = number("processing_ms_p95");
  run.real_time_factor = number("real_time_factor");
  run.peak_memory_mb = number("peak_memory_mb");
  if (run.exit_code != 0) {
    run.error = "rpvio-slam exited with " + std::to_string(run.exit_code);
    return std::nullopt;
  }
  try {
    eval::EvalResult r = eval::evaluate(gt, readTum((dir / "trajectory.tum").string()), {});
    run.ate_rmse = r.ate.rmse;
    run.ate_rotation_deg = r.ate_rotation_rmse_deg;
    run.coverage = r.coverage;
    run.evaluated = true;
    const fs::path refined = dir / "trajectory_refined.tum";
    if (fs::exists(refined))
      run.refined_ate_rmse = eval::evaluate(gt, readTum(refined.string()), {}).ate.rmse;
    return r;
  } catch (const std::exception& e) {
    run.error = e.what();
    return std::nullopt;
  }
}

/// `first_runs[k]`: the evaluation of runs[k] when it is an evaluated run 0.
void writePlots(const BenchSetup& setup, const std::vector<BenchRun>& runs,
                const std::vector<std::optional<eval::EvalResult>>& first_runs,
                const std::map<std::string, Trajectory>& gts, const fs::path& out) {
  fs::create_directories(out / "plots");
  for (const auto& sequence : setup.sequences) {
    std::vector<eval::PlottedEstimate> plotted;
    for (size_t k = 0; k < runs.size(); ++k)
      if (runs[k].sequence == sequence && first_runs[k])
        plotted.push_back({runs[k].mode, &*first_runs[k]});
    eval::writeTrajectoryPlot((out / "plots" / (sequence + ".png")).string(), gts.at(sequence),
                              plotted, sequence + " (run 0 of each mode, SE(3) alignment)");
  }
}

std::string evaluatedLine(const BenchRun& r) {
  char line[256];
  if (r.evaluated)
    std::snprintf(line, sizeof line, "%s %s run %d: ATE %.3f m, coverage %.0f%%, %.0f s",
                  r.sequence.c_str(), r.mode.c_str(), r.run, r.ate_rmse, 100 * r.coverage,
                  r.wall_s);
  else
    std::snprintf(line, sizeof line, "%s %s run %d: %s", r.sequence.c_str(), r.mode.c_str(), r.run,
                  r.error.c_str());
  return line;
}

/// Runs `indices` of the plan's simulations and then its SLAM runs (simulations: all or none),
/// here or on Slurm. Returns false when only submitted.
std::map<std::string, Trajectory> readGroundTruths(const BenchSetup& setup) {
  std::map<std::string, Trajectory> gts;
  for (const auto& s : setup.sequences)
    gts[s] = readTum((fs::path(setup.suite_dir) / s / "groundtruth.tum").string());
  return gts;
}

/// The run's exit code and wall time from its task's status, then its evaluation (evaluateRun).
std::optional<eval::EvalResult> evaluateTask(BenchRun& run, const BenchTask& task,
                                             const Trajectory& gt) {
  const auto status = readTaskStatus(task);
  run.exit_code = status ? status->exit_code : -1;
  run.wall_s = status ? status->wall_s : 0;
  auto evaluation = evaluateRun(run, gt);
  if (!status) run.error = "did not finish";
  return evaluation;
}

bool execute(BenchPlan& plan, bool simulate, const std::vector<size_t>& slam_indices,
             bool submit_only) {
  std::string slam_job;  // Slurm's
  if (!plan.slurm) {
    if (simulate) {
      Progress progress("simulate", plan.sim_tasks.size());
      runParallel(plan.sim_tasks.size(), plan.setup.jobs, [&](size_t k) {
        fs::create_directories(plan.setup.suite_dir);
        const int code = runTask(plan.sim_tasks[k]);
        progress.done(plan.sim_tasks[k].name + (code == 0 ? ": written" : ": FAILED"));
      });
    }
  } else {
    std::string sim_job;
    if (simulate) {
      fs::create_directories(plan.setup.suite_dir);
      const auto all = allIndices(plan.sim_tasks.size());
      sim_job = submitArray(plan.slurm_options, manifestPath(plan, "rpvio-sim"), all, "rpvio-sim",
                            (plan.out / "bench" / "logs").string());
      recordJob(plan, "rpvio-sim", sim_job, all);
    }
    slam_job = submitArray(plan.slurm_options, manifestPath(plan, "rpvio-slam"), slam_indices,
                           "rpvio-slam", (plan.out / "bench" / "logs").string(), sim_job);
    recordJob(plan, "rpvio-slam", slam_job, slam_indices);
    std::fprintf(stderr, "rpvio-bench: submitted %s%s job %s (%zu runs)\n",
                 sim_job.empty() ? "" : ("simulation job " + sim_job + " and ").c_str(), "SLAM",
                 slam_job.c_str(), slam_indices.size());
    if (submit_only) return false;
    if (simulate) waitForJob(plan.slurm_options, sim_job, "simulate", plan.sim_tasks.size());
  }
  if (simulate) {
    std::string failures;
    for (size_t k : unfinished(plan.sim_tasks, allIndices(plan.sim_tasks.size())))
      failures += "\n  " + taskReport(plan, "rpvio-sim", plan.sim_tasks, k);
    if (!failures.empty()) throw std::runtime_error("simulation failed:" + failures);
  }
  if (plan.slurm) {
    waitForJob(plan.slurm_options, slam_job, "SLAM runs", slam_indices.size());
    return true;
  }
  const auto gts = readGroundTruths(plan.setup);
  Progress progress("run", slam_indices.size());
  runParallel(slam_indices.size(), plan.setup.jobs, [&](size_t i) {
    const size_t k = slam_indices[i];
    runTask(plan.slam_tasks[k]);
    BenchRun r = plan.runs[k];
    evaluateTask(r, plan.slam_tasks[k], gts.at(r.sequence));
    progress.done(evaluatedLine(r));
  });
  return true;
}

/// The report of every run that has finished; names the others on stderr.
int collect(BenchPlan& plan, double wall_s) {
  BenchSetup& setup = plan.setup;
  const auto gts = readGroundTruths(setup);
  for (const auto& s : setup.sequences) {
    const fs::path dir = fs::path(setup.suite_dir) / s;
    setup.dynamic_fraction[s] =
        fs::exists(dir / "sequence.json")
            ? jsonNumber(readText((dir / "sequence.json").string()), "dynamic_fraction_median")
            : NAN;
  }
  std::vector<std::optional<eval::EvalResult>> first_runs(plan.runs.size());  // for the plots
  for (size_t k = 0; k < plan.runs.size(); ++k) {
    BenchRun& r = plan.runs[k];
    auto evaluation = evaluateTask(r, plan.slam_tasks[k], gts.at(r.sequence));
    if (r.run == 0) first_runs[k] = std::move(evaluation);
  }
  const auto failed = unfinished(plan.slam_tasks, allIndices(plan.slam_tasks.size()));
  if (!failed.empty()) {
    std::fprintf(stderr, "rpvio-bench: %zu of %zu runs failed or did not finish:\n", failed.size(),
                 plan.slam_tasks.size());
    for (size_t k : failed)
      std::fprintf(stderr, "  %s\n", taskReport(plan, "rpvio-slam", plan.slam_tasks, k).c_str());
    std::fprintf(stderr, "  to run only those again: rpvio-bench --collect %s --resubmit-failed\n",
                 plan.out.c_str());
  }
  setup.wall_s = wall_s;
  writePlots(setup, plan.runs, first_runs, gts, plan.out);
  writeFileAtomically((plan.out / "results.json").string(),
                      [&](std::ostream& s) { s << resultsJson(setup, plan.runs); });
  const std::string markdown = resultsMarkdown(setup, plan.runs);
  writeFileAtomically((plan.out / "results.md").string(), [&](std::ostream& s) { s << markdown; });
  std::printf("%s\nresults: %s, %s; plots in %s\n", markdown.c_str(),
              (plan.out / "results.md").c_str(), (plan.out / "results.json").c_str(),
              (plan.out / "plots").c_str());
  return 0;
}

void checkSuite(const BenchSetup& setup) {
  for (const auto& s : setup.sequences)
    for (const char* file : {"seq.rawlog", "calib.ini", "groundtruth.tum"}) {
      const fs::path path = fs::path(setup.suite_dir) / s / file;
      if (!fs::exists(path))
        throw InputError(path.string(), "",
                         "missing (generate the suite with --generate or rpvio-sim --suite)");
    }
}

int run(int argc, char** argv) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const CommandLine cli(argc, argv, kBenchOptions, kBenchFlags);
  if (cli.has("run-task")) {  // one task of a Slurm array
    const auto tasks = readManifest(cli.value("run-task"));
    const double index = cli.number("index", -1);
    if (!(index >= 0 && index < static_cast<double>(tasks.size())) || index != std::floor(index))
      throw UsageError("--index must name a line of " + cli.value("run-task"));
    return runTask(tasks[static_cast<size_t>(index)]);
  }
  if (cli.has("collect")) {  // the saved plan; options given now take precedence
    BenchPlan plan =
        loadPlan(cli.value("collect"), std::vector<std::string>(argv + 1, argv + argc));
    if (cli.has("resubmit-failed")) {
      const auto failed = unfinished(plan.slam_tasks, allIndices(plan.slam_tasks.size()));
      const auto queued = stillQueued(plan, "rpvio-slam", failed);
      if (!queued.empty())
        throw UsageError(
            std::to_string(queued.size()) + " run(s) still pending or running on Slurm (e.g. " +
            plan.slam_tasks[queued.front()].name + "): collect without --resubmit-failed, or wait");
      std::fprintf(stderr, "rpvio-bench: running %zu failed or unfinished run(s) again\n",
                   failed.size());
      if (!failed.empty() && !execute(plan, false, failed, cli.has("submit-only"))) return 0;
    }
    return collect(plan, elapsed());
  }

  BenchPlan plan = planFrom(cli);
  const bool generate = cli.has("generate");
  if (!generate) checkSuite(plan.setup);
  savePlan(cli, plan);
  if (!execute(plan, generate, allIndices(plan.slam_tasks.size()), cli.has("submit-only"))) {
    std::printf("submitted; when the jobs have finished: rpvio-bench --collect %s\n",
                plan.out.c_str());
    return 0;
  }
  checkSuite(plan.setup);
  return collect(plan, elapsed());
}

}  // namespace

int benchMain(int argc, char** argv) {
  return runApp("rpvio-bench", kUsage, [&] { return run(argc, argv); });
}

}  // namespace rpvio::apps
