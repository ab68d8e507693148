#pragma once
// Line-oriented numeric text files (TUM, KITTI, EuRoC CSV): comment/blank lines skipped, fields
// split on commas (when the line has one) or whitespace. Errors name the file and the line.
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

namespace rpvio {

/// Calls `row(fields, line_number)` for every data line; throws InputError when the file is
/// missing or has no data line.
void forEachTextRow(const std::string& path,
                    const std::function<void(const std::vector<std::string>&, int)>& row);

/// The first data line (trimmed) and its number; InputError when missing or without data.
std::string firstTextRow(const std::string& path, int& line_number);
/// Splits a data line on commas (when it has one) or whitespace.
std::vector<std::string> splitTextFields(const std::string& line);

/// The text without leading and trailing blanks (spaces, tabs, carriage returns).
std::string trim(const std::string& s);

/// A finite number, or InputError(path, "line N").
double parseFiniteNumber(const std::string& token, const std::string& path, int line);

/// All fields as finite numbers, between min_count and max_count of them.
std::vector<double> parseNumberRow(const std::vector<std::string>& fields, size_t min_count,
                                   size_t max_count, const std::string& path, int line);

/// The rotation of the quaternion (w, x, y, z) as a unit quaternion, or InputError(path, "line N")
/// when it is zero (norm below 1e-6).
Eigen::Quaterniond unitQuaternion(double w, double x, double y, double z, const std::string& path,
                                  int line);

}  // namespace rpvio
