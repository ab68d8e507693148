#pragma once
// Outputs appear complete or not at all: write to `<path>.tmp`, then rename onto `path`.
#include <functional>
#include <ostream>
#include <string>

namespace rpvio {

/// Calls `write` on a stream opened at `<path>.tmp`, then renames it to `path`. Throws
/// std::runtime_error naming the path when the file cannot be written; the temporary is removed.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Renames `<path>.tmp` (already written) onto `path`; throws std::runtime_error on failure.
void commitTemporary(const std::string& path);
std::string temporaryPathFor(const std::string& path);

/// The folder `path` will be written into ("." for a bare name); InputError(path) when it does
/// not exist, so that a run fails before reading its inputs.
std::string existingOutputFolder(const std::string& path);

}  // namespace rpvio
