#pragma once
// Running the other rpvio apps as child processes (rpvio-bench runs many at once).
#include <string>
#include <vector>

namespace rpvio::apps {

/// Runs `argv` (argv[0] an executable path, or a name looked up in PATH) with stdout and stderr
/// appended to `log_path`, waits, and returns its exit code (128 + signal number when killed by a
/// signal). Throws std::runtime_error when the process cannot be started or the log cannot be
/// opened.
int runProcess(const std::vector<std::string>& argv, const std::string& log_path);

/// Runs `argv` and returns its exit code; `output` gets its stdout and stderr.
int runProcessForOutput(const std::vector<std::string>& argv, std::string& output);

/// The folder of the running executable (the other apps are installed beside it).
std::string executableDir();

}  // namespace rpvio::apps
