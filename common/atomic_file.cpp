#include "common/atomic_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/input_error.h"

namespace rpvio {

std::string temporaryPathFor(const std::string& path) { return path + ".tmp"; }

void commitTemporary(const std::string& path) {
  const std::string tmp = temporaryPathFor(path);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": cannot rename the completed temporary file into place");
  }
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string tmp = temporaryPathFor(path);
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    write(out);
    out.flush();
    if (!out) {
      out.close();
      std::remove(tmp.c_str());
      throw std::runtime_error(path + ": write failed");
    }
  }
  commitTemporary(path);
}

std::string existingOutputFolder(const std::string& path) {
  const std::filesystem::path p(path);
  const std::filesystem::path folder = p.has_parent_path() ? p.parent_path() : ".";
  if (!std::filesystem::is_directory(folder)) throw InputError(path, "", "output folder not found");
  return folder.string();
}

}  // namespace rpvio
