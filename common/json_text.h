#pragma once
// A tiny JSON writer for the files the apps write (summary.json, results.json, eval.json), and a
// reader of one number for their tests and the benchmark.
#include <string>
#include <utility>
#include <vector>

namespace rpvio {

/// `s` as a JSON string literal (quotes, backslashes and control characters escaped).
std::string jsonString(const std::string& s);

/// A JSON object; members keep the order they were added in. str() writes the document: one
/// top-level member per line, arrays of objects one element per line, anything else on one line
/// (`{"a": 1, "b": [1, 2]}`).
class JsonObject {
 public:
  /// Numbers are written with `significant_digits` (6: as a default std::ostream writes a double);
  /// a number that is not finite is written as null.
  explicit JsonObject(int significant_digits = 6) : digits_(significant_digits) {}

  JsonObject& number(const std::string& key, double value);
  /// A time stamp (s) with 9 decimals (stampText); not finite: null.
  JsonObject& stamp(const std::string& key, double seconds);
  JsonObject& integer(const std::string& key, long long value);
  JsonObject& text(const std::string& key, const std::string& value);
  JsonObject& flag(const std::string& key, bool value);
  JsonObject& null(const std::string& key);
  JsonObject& numbers(const std::string& key, const std::vector<double>& values);
  JsonObject& object(const std::string& key, const JsonObject& value);
  JsonObject& objects(const std::string& key, const std::vector<JsonObject>& values);

  std::string str() const;      // the document, ending in a newline
  std::string oneLine() const;  // on one line, no newline

 private:
  struct Member {
    std::string key, value;             // value: JSON on one line
    std::vector<std::string> elements;  // an array of objects: each on one line
    bool is_object_array = false;
  };
  std::string formatNumber(double value) const;
  JsonObject& add(const std::string& key, std::string value);

  int digits_;
  std::vector<Member> members_;
};

/// The number after `"key":` in a JSON text (the first such key); NaN when the key is absent or
/// its value is not a number (null).
double jsonNumber(const std::string& json, const std::string& key);

}  // namespace rpvio
