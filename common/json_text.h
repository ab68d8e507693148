#pragma once
// A tiny JSON writer for the flat files the apps write (summary.json, results.json), and a reader
// of one number for their tests and the benchmark.
#include <sstream>
#include <string>

namespace rpvio {

/// `s` as a JSON string literal (quotes, backslashes and control characters escaped).
std::string jsonString(const std::string& s);

/// A JSON object written one member per line: `{\n  "key": value,\n  ...\n}\n`. Numbers are
/// written as a default std::ostream writes a double.
class JsonObject {
 public:
  JsonObject& number(const std::string& key, double value);
  JsonObject& text(const std::string& key, const std::string& value);
  JsonObject& flag(const std::string& key, bool value);
  /// `value` must already be JSON (an array or object built by the caller).
  JsonObject& raw(const std::string& key, const std::string& value);
  std::string str() const { return out_.str() + (empty_ ? "{}\n" : "\n}\n"); }

 private:
  std::ostringstream out_;
  bool empty_ = true;
};

/// The number after `"key":` in a flat JSON text; NaN when the key is absent.
double jsonNumber(const std::string& json, const std::string& key);

}  // namespace rpvio
