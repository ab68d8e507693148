#include "common/text_table.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/input_error.h"
#include "common/input_file.h"

namespace rpvio {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> splitTextFields(const std::string& line) {
  std::vector<std::string> fields;
  std::string token;
  std::istringstream ss(line);
  if (line.find(',') != std::string::npos) {
    while (std::getline(ss, token, ',')) fields.push_back(trim(token));
  } else {
    while (ss >> token) fields.push_back(token);
  }
  return fields;
}

namespace {
bool isData(const std::string& trimmed) {
  return !trimmed.empty() && trimmed[0] != '#' && trimmed[0] != '%';
}
}  // namespace

std::string firstTextRow(const std::string& path, int& line_number) {
  std::ifstream in = openInputFile(path);
  std::string line;
  for (line_number = 1; std::getline(in, line); ++line_number)
    if (isData(trim(line))) return trim(line);
  throw InputError(path, "", "no data lines in file");
}

void forEachTextRow(const std::string& path,
                    const std::function<void(const std::vector<std::string>&, int)>& row) {
  std::ifstream in = openInputFile(path);
  std::string line;
  int rows = 0;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const std::string s = trim(line);
    if (!isData(s)) continue;
    row(splitTextFields(s), line_no);
    ++rows;
  }
  if (rows == 0) throw InputError(path, "", "no data lines in file");
}

double parseFiniteNumber(const std::string& token, const std::string& path, int line) {
  char* end = nullptr;
  const double x = std::strtod(token.c_str(), &end);
  // `end` must reach the end of the token: a NUL byte inside it would stop strtod early.
  if (token.empty() || end != token.c_str() + token.size() || !std::isfinite(x))
    throw InputError(path, "line " + std::to_string(line), "not a finite number: '" + token + "'");
  return x;
}

std::vector<double> parseNumberRow(const std::vector<std::string>& fields, size_t min_count,
                                   size_t max_count, const std::string& path, int line) {
  if (fields.size() < min_count || fields.size() > max_count)
    throw InputError(
        path, "line " + std::to_string(line),
        "expected " + std::to_string(min_count) + " values, got " + std::to_string(fields.size()));
  std::vector<double> values;
  values.reserve(fields.size());
  for (const auto& f : fields) values.push_back(parseFiniteNumber(f, path, line));
  return values;
}

Eigen::Quaterniond unitQuaternion(double w, double x, double y, double z, const std::string& path,
                                  int line) {
  // The stable norm: with coefficients near 1e200 the plain sum of squares overflows, and
  // normalizing by infinity gave a zero quaternion.
  const Eigen::Vector4d coeffs(x, y, z, w);  // Eigen's storage order
  if (coeffs.stableNorm() < 1e-6)
    throw InputError(path, "line " + std::to_string(line), "zero quaternion");
  return Eigen::Quaterniond(coeffs.stableNormalized());
}

}  // namespace rpvio
