#include "apps/lib/subprocess.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

extern char** environ;

namespace rpvio::apps {

int runProcess(const std::vector<std::string>& argv, const std::string& log_path) {
  if (argv.empty()) throw std::runtime_error("runProcess: empty command");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const int flags = O_WRONLY | O_CREAT | O_APPEND;
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(), flags, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(error));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw std::runtime_error("waiting for " + argv[0] + ": " + std::strerror(errno));
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WEXITSTATUS(status);
}

int runProcessForOutput(const std::vector<std::string>& argv, std::string& output) {
  char path[] = "/tmp/rpvio-output-XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0)
    throw std::runtime_error(std::string("cannot create a temporary file: ") +
                             std::strerror(errno));
  close(fd);
  int code = 0;
  try {
    code = runProcess(argv, path);
  } catch (...) {
    std::filesystem::remove(path);
    throw;
  }
  std::ifstream in(path, std::ios::binary);
  output.assign(std::istreambuf_iterator<char>(in), {});
  std::filesystem::remove(path);
  return code;
}

std::string executableDir() {
  return std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
}

}  // namespace rpvio::apps
