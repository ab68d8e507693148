#pragma once
// Opening an input file with an error that says what is wrong with the path: missing, a
// directory, or something else than a regular file (InputError naming the path).
#include <fstream>
#include <string>

namespace rpvio {

/// InputError unless `path` is a regular file: "<what> not found", "<what> expected, found a
/// directory" or "<what> expected, found a special file".
void requireRegularFile(const std::string& path, const std::string& what = "file");

/// The file opened for reading, after requireRegularFile; InputError "cannot open <what>" when the
/// open fails (permissions).
std::ifstream openInputFile(const std::string& path, const std::string& what = "file");

}  // namespace rpvio
