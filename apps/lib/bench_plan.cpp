#include "apps/lib/bench_plan.h"

#include <fstream>
#include <sstream>

#include "apps/lib/subprocess.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "sim/sequence_name.h"
#include "sim/sim_config.h"

namespace fs = std::filesystem;

namespace rpvio::apps {

const std::set<std::string> kBenchOptions = {
    "suite",      "duration",   "seed",       "profile",  "modes",    "sequences",
    "runs",       "jobs",       "config-dir", "out",      "executor", "partition",
    "time-limit", "sbatch-arg", "collect",    "run-task", "index"};
const std::set<std::string> kBenchFlags = {"generate", "submit-only", "resubmit-failed"};

namespace {

const std::vector<std::string> kModes = {"vins-mono", "mask-vins", "rpvio-single", "rpvio-multi",
                                         "rpvio-auto"};

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

/// The arguments rpvio-bench was started with, paths made absolute, so that --collect rebuilds
/// the same plan from anywhere.
std::vector<std::string> savedArguments(const CommandLine& cli, const BenchPlan& plan) {
  std::vector<std::string> args;
  for (const std::string& option : kBenchOptions) {
    if (!cli.has(option) || option == "collect") continue;
    for (const std::string& value : cli.values(option))
      args.insert(args.end(), {"--" + option, value});
  }
  for (const auto& [option, path] :
       {std::pair<std::string, std::string>{"suite", plan.setup.suite_dir},
        {"out", plan.out.string()},
        {"config-dir", plan.config_dir.string()}})
    args.insert(args.end(), {"--" + option, path});  // the last value counts
  return args;
}

std::vector<std::string> readLines(const fs::path& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(path.string(), "", "not an rpvio-bench output folder (no bench/args.txt)");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

CommandLine parse(const std::vector<std::string>& args) {
  std::vector<char*> argv = {const_cast<char*>("rpvio-bench")};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  return CommandLine(static_cast<int>(argv.size()), argv.data(), kBenchOptions, kBenchFlags);
}

}  // namespace

BenchPlan planFrom(const CommandLine& cli) {
  BenchPlan plan;
  BenchSetup& setup = plan.setup;
  setup.suite_dir = fs::absolute(cli.value("suite")).lexically_normal().string();
  plan.out = fs::absolute(cli.value("out")).lexically_normal();
  plan.config_dir = fs::absolute(cli.valueOr("config-dir", "config")).lexically_normal();
  setup.modes = cli.has("modes") ? splitList(cli.value("modes")) : kModes;
  const std::string profile = cli.valueOr("profile", "paper");
  try {
    sim::SimConfig::profile(profile);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--profile: ") + e.what());
  }
  setup.sequences =
      cli.has("sequences") ? splitList(cli.value("sequences")) : sim::suiteSequences(profile);
  setup.runs = cli.count("runs", 1);
  const std::string executor = cli.valueOr("executor", "local");
  if (executor != "local" && executor != "slurm")
    throw UsageError("--executor must be local or slurm, not '" + executor + "'");
  plan.slurm = executor == "slurm";
  setup.jobs = cli.count("jobs", 1);
  plan.slurm_options.max_running = cli.has("jobs") ? setup.jobs : 0;
  plan.slurm_options.partition = cli.valueOr("partition", "");
  plan.slurm_options.time_limit_min = cli.has("time-limit") ? cli.count("time-limit", 1) : 0;
  if (cli.has("sbatch-arg")) plan.slurm_options.sbatch_args = cli.values("sbatch-arg");
  if (setup.modes.empty() || setup.sequences.empty()) throw UsageError("no mode or no sequence");
  for (const auto& s : setup.sequences) checkSequenceName(s);  // before any work
  for (const auto& mode : setup.modes)
    if (!fs::exists(plan.config_dir / (mode + ".ini")))
      throw InputError((plan.config_dir / (mode + ".ini")).string(), "",
                       "no such mode config (run from the repository root or pass --config-dir)");

  const std::string bin = executableDir();
  for (const auto& sequence : setup.sequences) {
    const fs::path dir = fs::path(setup.suite_dir) / sequence;
    BenchTask task{"simulate " + sequence,
                   "",
                   (fs::path(setup.suite_dir) / (sequence + ".log")).string(),
                   (plan.out / "bench" / "status" / ("simulate_" + sequence + ".json")).string(),
                   {bin + "/rpvio-sim", "--sequence", sequence, "--out", dir.string()}};
    for (const char* option : {"duration", "seed", "profile"})
      if (cli.has(option))
        task.argv.insert(task.argv.end(), {std::string("--") + option, cli.value(option)});
    plan.sim_tasks.push_back(task);
  }
  for (const auto& sequence : setup.sequences)
    for (const auto& mode : setup.modes)
      for (int k = 0; k < setup.runs; ++k) {
        BenchRun r;
        r.sequence = sequence;
        r.mode = mode;
        r.run = k;
        r.dir = (plan.out / "runs" / sequence / mode / ("run" + std::to_string(k))).string();
        plan.runs.push_back(r);
        const fs::path seq = fs::path(setup.suite_dir) / sequence;
        plan.slam_tasks.push_back(
            {sequence + " " + mode + " run " + std::to_string(k),
             r.dir,
             (fs::path(r.dir) / "log.txt").string(),
             (fs::path(r.dir) / "task.json").string(),
             {bin + "/rpvio-slam", "--config", (plan.config_dir / (mode + ".ini")).string(),
              "--calib", (seq / "calib.ini").string(), "--rawlog", (seq / "seq.rawlog").string(),
              "--out", r.dir, "--quiet"}});
      }
  return plan;
}

fs::path manifestPath(const BenchPlan& plan, const std::string& kind) {
  return plan.out / "bench" / (kind + ".tsv");
}

void savePlan(const CommandLine& cli, const BenchPlan& plan) {
  fs::create_directories(plan.out / "bench");
  writeFileAtomically((plan.out / "bench" / "args.txt").string(), [&](std::ostream& out) {
    for (const std::string& a : savedArguments(cli, plan)) out << a << "\n";
  });
  fs::remove(plan.out / "bench" / "jobs.tsv");
  // A task that never starts (cancelled while pending) must not report an earlier run's status.
  for (const auto* tasks : {&plan.sim_tasks, &plan.slam_tasks})
    for (const BenchTask& task : *tasks) fs::remove(task.status);
  writeManifest(manifestPath(plan, "rpvio-sim").string(), plan.sim_tasks);
  writeManifest(manifestPath(plan, "rpvio-slam").string(), plan.slam_tasks);
}

BenchPlan loadPlan(const fs::path& out, const std::vector<std::string>& more_args) {
  std::vector<std::string> args = readLines(out / "bench" / "args.txt");
  args.insert(args.end(), more_args.begin(), more_args.end());
  BenchPlan plan = planFrom(parse(args));
  plan.slam_tasks = readManifest(manifestPath(plan, "rpvio-slam").string());
  if (plan.slam_tasks.size() != plan.runs.size())
    throw InputError(
        manifestPath(plan, "rpvio-slam").string(), "",
        "does not match bench/args.txt (" + std::to_string(plan.runs.size()) + " runs)");
  return plan;
}

void recordJob(const BenchPlan& plan, const std::string& kind, const std::string& job_id,
               const std::vector<size_t>& indices) {
  std::ofstream out(plan.out / "bench" / "jobs.tsv", std::ios::app);
  out << kind << '\t' << job_id << '\t';
  for (size_t k = 0; k < indices.size(); ++k) out << (k ? "," : "") << indices[k];
  out << '\n';
}

std::string jobOfTask(const BenchPlan& plan, const std::string& kind, size_t index) {
  std::ifstream in(plan.out / "bench" / "jobs.tsv");
  std::string job;
  for (std::string line; std::getline(in, line);) {
    std::stringstream fields(line);
    std::string k, id, list;
    std::getline(fields, k, '\t');
    std::getline(fields, id, '\t');
    std::getline(fields, list, '\t');
    for (const std::string& i : splitList(list))
      if (k == kind && i == std::to_string(index)) job = id;
  }
  return job;
}

std::vector<size_t> allIndices(size_t count) {
  std::vector<size_t> indices(count);
  for (size_t k = 0; k < count; ++k) indices[k] = k;
  return indices;
}

std::vector<size_t> unfinished(const std::vector<BenchTask>& tasks,
                               const std::vector<size_t>& indices) {
  std::vector<size_t> out;
  for (size_t k : indices) {
    const auto status = readTaskStatus(tasks[k]);
    if (!status || status->exit_code != 0) out.push_back(k);
  }
  return out;
}

std::vector<size_t> stillQueued(const BenchPlan& plan, const std::string& kind,
                                const std::vector<size_t>& indices) {
  std::vector<size_t> queued;
  for (size_t k : indices) {
    const std::string job = jobOfTask(plan, kind, k);
    if (job.empty()) continue;
    const std::string state = taskState(job, k);
    if (state == "PENDING" || state == "RUNNING" || state == "CONFIGURING" ||
        state == "COMPLETING" || state == "REQUEUED" || state == "SUSPENDED")
      queued.push_back(k);
  }
  return queued;
}

std::string taskReport(const BenchPlan& plan, const std::string& kind,
                       const std::vector<BenchTask>& tasks, size_t k) {
  const auto status = readTaskStatus(tasks[k]);
  std::string report =
      tasks[k].name + ": " +
      (status ? "exited with " + std::to_string(status->exit_code) : std::string("did not finish"));
  const std::string job = jobOfTask(plan, kind, k);
  if (!job.empty())
    report +=
        " (Slurm job " + job + "_" + std::to_string(k) + ": " + taskState(job, k) + ", Slurm log " +
        (plan.out / "bench" / "logs" / (kind + "_" + std::to_string(k) + ".out")).string() + ")";
  return report + ", log " + tasks[k].log;
}

}  // namespace rpvio::apps
