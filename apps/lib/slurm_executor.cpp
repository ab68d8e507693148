#include "apps/lib/slurm_executor.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "apps/lib/subprocess.h"

namespace fs = std::filesystem;

namespace rpvio::apps {
namespace {

std::string shellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string trimmed(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t\r\n") - begin + 1);
}

std::string firstLine(const std::string& text) { return trimmed(text.substr(0, text.find('\n'))); }

}  // namespace

std::string arrayRanges(const std::vector<size_t>& indices) {
  std::string ranges;
  for (size_t i = 0; i < indices.size();) {
    size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    ranges += (ranges.empty() ? "" : ",") + std::to_string(indices[i]) +
              (j > i ? "-" + std::to_string(indices[j]) : "");
    i = j + 1;
  }
  return ranges;
}

std::string submitArray(const SlurmOptions& options, const std::string& manifest,
                        const std::vector<size_t>& indices, const std::string& job_name,
                        const std::string& log_dir, const std::string& after_ok) {
  fs::create_directories(log_dir);
  std::string array = arrayRanges(indices);
  if (options.max_running > 0) array += "%" + std::to_string(options.max_running);
  std::vector<std::string> argv = {"sbatch",
                                   "--parsable",
                                   "--job-name=" + job_name,
                                   "--array=" + array,
                                   "--output=" + log_dir + "/" + job_name + "_%a.out",
                                   "--chdir=" + fs::current_path().string()};
  if (!options.partition.empty()) argv.push_back("--partition=" + options.partition);
  if (options.time_limit_min > 0)
    argv.push_back("--time=" + std::to_string(options.time_limit_min));
  if (!after_ok.empty())
    argv.insert(argv.end(), {"--dependency=afterok:" + after_ok, "--kill-on-invalid-dep=yes"});
  argv.insert(argv.end(), options.sbatch_args.begin(), options.sbatch_args.end());
  argv.push_back("--wrap=" + shellQuoted(executableDir() + "/rpvio-bench") + " --run-task " +
                 shellQuoted(manifest) + " --index \"$SLURM_ARRAY_TASK_ID\"");
  std::string output;
  const int code = runProcessForOutput(argv, output);
  const std::string job_id = firstLine(output).substr(0, firstLine(output).find(';'));
  if (code != 0 || job_id.empty() || job_id.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error("sbatch refused the " + job_name + " array: " + firstLine(output));
  return job_id;
}

void waitForJob(const SlurmOptions& options, const std::string& job_id, const std::string& what,
                size_t tasks) {
  const auto start = std::chrono::steady_clock::now();
  std::string last_line;
  int failed_queries = 0;
  for (;;) {
    std::string output;
    const int code = runProcessForOutput({"squeue", "-h", "-r", "-j", job_id, "-o", "%T"}, output);
    if (code != 0) {
      if (output.find("Invalid job id") != std::string::npos) return;  // finished and forgotten
      if (++failed_queries >= 10)
        throw std::runtime_error("squeue keeps failing for job " + job_id + ": " +
                                 firstLine(output));
    } else {
      failed_queries = 0;
      size_t pending = 0, running = 0;
      std::istringstream lines(output);
      for (std::string state; std::getline(lines, state);) {
        state = trimmed(state);
        if (state.empty()) continue;
        (state == "PENDING" ? pending : running) += 1;
      }
      if (pending + running == 0) return;
      const size_t finished = tasks > pending + running ? tasks - pending - running : 0;
      char line[160];
      std::snprintf(line, sizeof line,
                    "[slurm %s, job %s] %zu/%zu finished, %zu running, %zu pending", what.c_str(),
                    job_id.c_str(), finished, tasks, running, pending);
      if (line != last_line) {
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "%s  (elapsed %.0f s)\n", line, s);
        last_line = line;
      }
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(options.poll_s));
  }
}

std::string taskState(const std::string& job_id, size_t index) {
  const std::string task = job_id + "_" + std::to_string(index);
  std::string output;
  if (runProcessForOutput({"scontrol", "show", "job", "-o", task}, output) == 0) {
    const auto at = output.find("JobState=");
    if (at != std::string::npos) {
      const auto begin = at + std::string("JobState=").size();
      return output.substr(begin, output.find_first_of(" \n", begin) - begin);
    }
  }
  if (runProcessForOutput({"sacct", "-n", "-X", "-P", "-o", "State", "-j", task}, output) == 0 &&
      !firstLine(output).empty())
    return firstLine(output);
  return "unknown to Slurm";
}

}  // namespace rpvio::apps
