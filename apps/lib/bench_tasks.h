#pragma once
// rpvio-bench's units of work — one rpvio-sim or rpvio-slam run each — as a manifest file that any
// executor can run from: the local one runs its lines in threads, the Slurm one as a job array
// whose task k runs line k (`rpvio-bench --run-task MANIFEST --index k`). A task leaves a status
// file (exit code, wall time, host) beside its outputs; collecting reads those.
#include <optional>
#include <string>
#include <vector>

namespace rpvio::apps {

struct BenchTask {
  std::string name;               // "C4 rpvio-single run 0", "simulate C4"
  std::string dir;                // emptied and created before the run; "" for none
  std::string log;                // the program's stdout and stderr
  std::string status;             // JSON written when the program has exited
  std::vector<std::string> argv;  // argv[0]: the program's path
};

struct TaskStatus {
  int exit_code = -1;
  double wall_s = 0;
};

/// One task per line: name, dir, log, status, argv..., separated by tabs. Throws InputError on a
/// field that contains a tab or a line break.
void writeManifest(const std::string& path, const std::vector<BenchTask>& tasks);
/// Throws InputError naming the file and line on a malformed line.
std::vector<BenchTask> readManifest(const std::string& path);

/// A whole file's text ("" when it cannot be read).
std::string readText(const std::string& path);

/// Runs the task, writes its status file, returns the program's exit code.
int runTask(const BenchTask& task);
/// The task's status, if it has finished.
std::optional<TaskStatus> readTaskStatus(const BenchTask& task);

}  // namespace rpvio::apps
