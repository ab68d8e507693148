#pragma once
// A small `--option value` / `--flag` parser for the rpvio apps. Unknown options and missing
// values are usage errors (exit 2), reported on one line.
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace rpvio::apps {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Thrown for --help / -h: runApp prints the usage on stdout and exits 0.
struct HelpRequested {};

class CommandLine {
 public:
  /// `options` take a value (may repeat), `flags` do not; positional arguments are kept in order.
  CommandLine(int argc, char** argv, const std::set<std::string>& options,
              const std::set<std::string>& flags);

  bool has(const std::string& name) const;
  /// The last value given for `name`; UsageError when required and absent.
  std::string value(const std::string& name) const;
  std::string valueOr(const std::string& name, const std::string& fallback) const;
  double number(const std::string& name, double fallback) const;
  /// A whole number >= 1 (`fallback` when absent); UsageError otherwise.
  int count(const std::string& name, int fallback) const;
  const std::vector<std::string>& values(const std::string& name) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::vector<std::string>> values_;
  std::vector<std::string> positional_;
};

/// Runs `body`, turning InputError/UsageError/std::exception into a one-line message on stderr
/// and exit code 2 (bad input or usage) or 1 (anything else). `usage` is printed on UsageError.
int runApp(const std::string& app, const std::string& usage, const std::function<int()>& body);

}  // namespace rpvio::apps
