#include "apps/lib/bench_tasks.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/lib/subprocess.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/json_text.h"

namespace fs = std::filesystem;

namespace rpvio::apps {
namespace {

std::vector<std::string> fieldsOf(const BenchTask& task) {
  std::vector<std::string> fields = {task.name, task.dir, task.log, task.status};
  fields.insert(fields.end(), task.argv.begin(), task.argv.end());
  return fields;
}

}  // namespace

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeManifest(const std::string& path, const std::vector<BenchTask>& tasks) {
  std::string text;
  for (const BenchTask& task : tasks) {
    std::string line;
    for (const std::string& field : fieldsOf(task)) {
      if (field.find_first_of("\t\n\r") != std::string::npos)
        throw InputError(path, "", "'" + field + "' contains a tab or a line break");
      line += (line.empty() ? "" : "\t") + field;
    }
    text += line + "\n";
  }
  fs::create_directories(fs::path(path).parent_path());
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

std::vector<BenchTask> readManifest(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the task manifest");
  std::vector<BenchTask> tasks;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    std::vector<std::string> fields;
    std::stringstream fields_in(line);
    for (std::string field; std::getline(fields_in, field, '\t');) fields.push_back(field);
    if (fields.size() < 5)
      throw InputError(path, "line " + std::to_string(line_number),
                       "a task needs name, dir, log, status and a command (tab-separated)");
    BenchTask task{fields[0], fields[1], fields[2], fields[3], {}};
    task.argv.assign(fields.begin() + 4, fields.end());
    tasks.push_back(task);
  }
  return tasks;
}

int runTask(const BenchTask& task) {
  if (!task.dir.empty()) {
    fs::remove_all(task.dir);
    fs::create_directories(task.dir);
  }
  fs::remove(task.status);
  fs::remove(task.log);
  fs::create_directories(fs::path(task.log).parent_path());
  fs::create_directories(fs::path(task.status).parent_path());
  const auto start = std::chrono::steady_clock::now();
  const int code = runProcess(task.argv, task.log);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char host[256] = "";
  gethostname(host, sizeof host - 1);
  writeFileAtomically(task.status, [&](std::ostream& out) {
    out << JsonObject()
               .integer("exit_code", code)
               .number("wall_s", wall_s)
               .text("host", host)
               .str();
  });
  return code;
}

std::optional<TaskStatus> readTaskStatus(const BenchTask& task) {
  if (!fs::exists(task.status)) return std::nullopt;
  const std::string json = readText(task.status);
  TaskStatus status;
  const double code = jsonNumber(json, "exit_code");
  if (!std::isfinite(code)) return std::nullopt;  // not a status this program wrote
  status.exit_code = static_cast<int>(code);
  status.wall_s = jsonNumber(json, "wall_s");
  return status;
}

}  // namespace rpvio::apps
