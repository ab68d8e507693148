#include "apps/lib/bench_app.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include "apps/lib/bench_results.h"
#include "apps/lib/command_line.h"
#include "apps/lib/subprocess.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/json_text.h"
#include "evaluation/trajectory_metrics.h"
#include "evaluation/trajectory_plot.h"
#include "rawlog_io/trajectory_io.h"
#include "sim/sequence_name.h"

namespace fs = std::filesystem;

namespace rpvio::apps {
namespace {

const char* kUsage =
    "usage: rpvio-bench --suite DIR [--generate] [--profile paper|hard] [--duration SEC] [--seed "
    "S]\n"
    "                   [--modes vins-mono,mask-vins,rpvio-single,rpvio-multi]\n"
    "                   [--sequences static,C1,C2,C4,C6,C8] [--runs N] [--jobs J]\n"
    "                   [--config-dir config] --out OUTDIR\n"
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
    "  exactly.\n";

const std::vector<std::string> kModes = {"vins-mono", "mask-vins", "rpvio-single", "rpvio-multi"};

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

void checkSequenceName(const std::string& sequence) {
  if (!sim::parseSequenceName(sequence))
    throw UsageError("unknown sequence '" + sequence + "' (static, C<N>, MP or MP-C<N>, e.g. C4)");
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Runs `jobs` tasks at a time; `task(k)` for k in [0, count).
void runParallel(size_t count, int jobs, const std::function<void(size_t)>& task) {
  std::atomic<size_t> next{0};
  std::vector<std::thread> workers;
  for (int j = 0; j < std::max(1, jobs); ++j)
    workers.emplace_back([&] {
      for (size_t k; (k = next++) < count;) task(k);
    });
  for (auto& w : workers) w.join();
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

void generateSequences(const CommandLine& cli, const std::string& suite,
                       const std::vector<std::string>& sequences, int jobs) {
  const std::string sim = executableDir() + "/rpvio-sim";
  Progress progress("simulate", sequences.size());
  std::vector<std::string> failures(sequences.size());
  runParallel(sequences.size(), jobs, [&](size_t k) {
    const fs::path dir = fs::path(suite) / sequences[k];
    fs::create_directories(dir.parent_path());
    std::vector<std::string> argv = {sim, "--sequence", sequences[k], "--out", dir.string()};
    for (const char* option : {"duration", "seed", "profile"})
      if (cli.has(option)) argv.insert(argv.end(), {std::string("--") + option, cli.value(option)});
    const std::string log = (fs::path(suite) / (sequences[k] + ".log")).string();
    fs::remove(log);
    const int code = runProcess(argv, log);
    if (code != 0)
      failures[k] =
          sequences[k] + ": rpvio-sim exited with " + std::to_string(code) + " (log " + log + ")";
    progress.done(sequences[k] + (code == 0 ? " written" : " FAILED"));
  });
  for (const auto& f : failures)
    if (!f.empty()) throw std::runtime_error("simulation failed: " + f);
}

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

int run(int argc, char** argv) {
  const CommandLine cli(argc, argv,
                        {"suite", "duration", "seed", "profile", "modes", "sequences", "runs",
                         "jobs", "config-dir", "out"},
                        {"generate"});
  BenchSetup setup;
  setup.suite_dir = cli.value("suite");
  const fs::path out = cli.value("out");
  const std::string config_dir = cli.valueOr("config-dir", "config");
  setup.modes = cli.has("modes") ? splitList(cli.value("modes")) : kModes;
  const std::string profile = cli.valueOr("profile", "paper");
  if (profile != "paper" && profile != "hard")
    throw UsageError("--profile must be paper or hard, not '" + profile + "'");
  setup.sequences =
      cli.has("sequences") ? splitList(cli.value("sequences")) : sim::suiteSequences(profile);
  setup.runs = cli.count("runs", 1);
  setup.jobs = cli.count("jobs", 1);
  if (setup.modes.empty() || setup.sequences.empty()) throw UsageError("no mode or no sequence");
  for (const auto& s : setup.sequences) checkSequenceName(s);  // before any work
  for (const auto& mode : setup.modes)
    if (!fs::exists(fs::path(config_dir) / (mode + ".ini")))
      throw InputError((fs::path(config_dir) / (mode + ".ini")).string(), "",
                       "no such mode config (run from the repository root or pass --config-dir)");

  const auto start = std::chrono::steady_clock::now();
  if (cli.has("generate")) generateSequences(cli, setup.suite_dir, setup.sequences, setup.jobs);
  std::map<std::string, Trajectory> gts;
  for (const auto& s : setup.sequences) {
    const fs::path dir = fs::path(setup.suite_dir) / s;
    for (const char* file : {"seq.rawlog", "calib.ini", "groundtruth.tum"})
      if (!fs::exists(dir / file))
        throw InputError((dir / file).string(), "",
                         "missing (generate the suite with --generate or rpvio-sim --suite)");
    gts[s] = readTum((dir / "groundtruth.tum").string());
    setup.dynamic_fraction[s] =
        fs::exists(dir / "sequence.json")
            ? jsonNumber(readText(dir / "sequence.json"), "dynamic_fraction_median")
            : NAN;
  }

  std::vector<BenchRun> runs;
  for (const auto& s : setup.sequences)
    for (const auto& mode : setup.modes)
      for (int k = 0; k < setup.runs; ++k) {
        BenchRun r;
        r.sequence = s;
        r.mode = mode;
        r.run = k;
        r.dir = (out / "runs" / s / mode / ("run" + std::to_string(k))).string();
        runs.push_back(r);
      }
  const std::string slam = executableDir() + "/rpvio-slam";
  Progress progress("run", runs.size());
  std::vector<std::optional<eval::EvalResult>> first_runs(runs.size());  // kept for the plots
  runParallel(runs.size(), setup.jobs, [&](size_t k) {
    BenchRun& r = runs[k];
    const fs::path seq = fs::path(setup.suite_dir) / r.sequence;
    fs::remove_all(r.dir);
    fs::create_directories(r.dir);
    const auto t0 = std::chrono::steady_clock::now();
    r.exit_code = runProcess({slam, "--config", (fs::path(config_dir) / (r.mode + ".ini")).string(),
                              "--calib", (seq / "calib.ini").string(), "--rawlog",
                              (seq / "seq.rawlog").string(), "--out", r.dir, "--quiet"},
                             (fs::path(r.dir) / "log.txt").string());
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    auto evaluation = evaluateRun(r, gts.at(r.sequence));
    if (r.run == 0) first_runs[k] = std::move(evaluation);
    char line[256];
    if (r.evaluated)
      std::snprintf(line, sizeof line, "%s %s run %d: ATE %.3f m, coverage %.0f%%, %.0f s",
                    r.sequence.c_str(), r.mode.c_str(), r.run, r.ate_rmse, 100 * r.coverage,
                    r.wall_s);
    else
      std::snprintf(line, sizeof line, "%s %s run %d: %s", r.sequence.c_str(), r.mode.c_str(),
                    r.run, r.error.c_str());
    progress.done(line);
  });
  setup.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  writePlots(setup, runs, first_runs, gts, out);
  writeFileAtomically((out / "results.json").string(),
                      [&](std::ostream& s) { s << resultsJson(setup, runs); });
  const std::string markdown = resultsMarkdown(setup, runs);
  writeFileAtomically((out / "results.md").string(), [&](std::ostream& s) { s << markdown; });
  std::printf("%s\nresults: %s, %s; plots in %s\n", markdown.c_str(), (out / "results.md").c_str(),
              (out / "results.json").c_str(), (out / "plots").c_str());
  return 0;
}

}  // namespace

int benchMain(int argc, char** argv) {
  return runApp("rpvio-bench", kUsage, [&] { return run(argc, argv); });
}

}  // namespace rpvio::apps
