#include "apps/lib/command_line.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

#include "common/input_error.h"

namespace rpvio::apps {

CommandLine::CommandLine(int argc, char** argv, const std::set<std::string>& options,
                         const std::set<std::string>& flags) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") throw HelpRequested{};
    if (arg.rfind("--", 0) != 0) {
      positional_.push_back(arg);
      continue;
    }
    const std::string name = arg.substr(2);
    if (flags.count(name)) {
      values_[name].push_back("");
    } else if (options.count(name)) {
      if (i + 1 >= argc) throw UsageError("option " + arg + " needs a value");
      values_[name].push_back(argv[++i]);
    } else {
      throw UsageError("unknown option " + arg);
    }
  }
}

bool CommandLine::has(const std::string& name) const { return values_.count(name) > 0; }

std::string CommandLine::value(const std::string& name) const {
  if (!has(name)) throw UsageError("missing required option --" + name);
  return values_.at(name).back();
}

std::string CommandLine::valueOr(const std::string& name, const std::string& fallback) const {
  return has(name) ? values_.at(name).back() : fallback;
}

double CommandLine::number(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  const std::string& text = values_.at(name).back();
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') throw UsageError("--" + name + " needs a number, got " + text);
  return x;
}

int CommandLine::count(const std::string& name, int fallback) const {
  const double x = number(name, fallback);
  if (!(x >= 1 && x <= std::numeric_limits<int>::max()) || x != std::floor(x))
    throw UsageError("--" + name + " must be a whole number >= 1, got " + values_.at(name).back());
  return static_cast<int>(x);
}

const std::vector<std::string>& CommandLine::values(const std::string& name) const {
  static const std::vector<std::string> kNone;
  auto it = values_.find(name);
  return it == values_.end() ? kNone : it->second;
}

int runApp(const std::string& app, const std::string& usage, const std::function<int()>& body) {
  try {
    return body();
  } catch (const HelpRequested&) {
    std::cout << usage;
    return 0;
  } catch (const UsageError& e) {
    std::cerr << app << ": error: " << e.what() << "\n" << usage;
    return kExitBadInput;
  } catch (const InputError& e) {
    std::cerr << app << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::string what = e.what();
    std::cerr << app << ": error: " << what.substr(0, what.find('\n')) << "\n";
    return 1;
  }
}

}  // namespace rpvio::apps
