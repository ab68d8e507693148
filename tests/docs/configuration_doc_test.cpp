// docs/configuration.md against the code: every key it documents can be set, and every key that
// can be set is documented (module options, the simulator's scene file, calib.ini).
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "mrpt_modules/core/pipeline.h"
#include "mrpt_modules/estimator/estimator_module.h"
#include "mrpt_modules/frontend/feature_tracker_module.h"
#include "rawlog_io/calibration.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

using SectionKeys = std::map<std::string, std::set<std::string>>;

/// Keys per `[section]` of an INI text (comments and values ignored).
SectionKeys iniKeys(const std::string& text) {
  SectionKeys keys;
  std::istringstream in(text);
  std::string section;
  const std::regex header(R"(^\s*\[([^\]]+)\].*)"), entry(R"(^\s*([A-Za-z0-9_]+)\s*=.*)");
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    if (std::regex_match(line, m, header))
      section = m[1];
    else if (std::regex_match(line, m, entry) && !section.empty())
      keys[section].insert(m[1]);
  }
  return keys;
}

/// Keys per part (the `# ` heading: "" before the first) and `## [section]` of the document:
/// the first column of its tables, in backticks.
std::map<std::string, SectionKeys> documentedKeys() {
  std::map<std::string, SectionKeys> doc;
  std::istringstream in(test::readFile(std::string(RPVIO_SOURCE_DIR) + "/docs/configuration.md"));
  std::string part, section;
  const std::regex part_heading(R"(^# (.*))"), section_heading(R"(^## \[([^\]]+)\].*)"),
      row(R"(^\| `([A-Za-z0-9_]+)` \|.*)");
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    if (std::regex_match(line, m, part_heading)) {
      part = m[1];
      section.clear();
    } else if (std::regex_match(line, m, section_heading)) {
      section = m[1];
    } else if (std::regex_match(line, m, row) && !section.empty()) {
      doc[part][section].insert(m[1]);
    }
  }
  return doc;
}

void expectSameKeys(const SectionKeys& documented, const SectionKeys& code,
                    const std::string& what) {
  for (const auto& [section, keys] : code)
    for (const auto& key : keys)
      EXPECT_TRUE(documented.count(section) && documented.at(section).count(key))
          << what << ": [" << section << "] " << key << " can be set but is not documented";
  for (const auto& [section, keys] : documented)
    for (const auto& key : keys)
      EXPECT_TRUE(code.count(section) && code.at(section).count(key))
          << what << ": [" << section << "] " << key << " is documented but cannot be set";
}

TEST(ConfigurationDoc, ModuleOptionsAreTheLoadableOnes) {
  // Every module of every mode: the keys of the effective configuration are the loadable ones
  // (a key absent from it is refused as unknown).
  SectionKeys code;
  for (const char* mode : {"vins-mono", "rpvio-multi"}) {
    const Pipeline pipeline(std::string(RPVIO_SOURCE_DIR) + "/config/" + mode + ".ini",
                            Calibration{}, mrpt::system::LVL_WARN);
    for (const auto& [section, keys] : iniKeys(pipeline.effectiveConfig()))
      code[section].insert(keys.begin(), keys.end());
  }
  const auto doc = documentedKeys();
  SectionKeys modules;
  for (const auto& [heading, sections] : doc)
    if (heading.find("Simulator") == std::string::npos &&
        heading.find("Calibration") == std::string::npos)
      for (const auto& [section, keys] : sections)
        modules[section].insert(keys.begin(), keys.end());
  ASSERT_GT(modules.size(), 3u) << "no module sections found in docs/configuration.md";
  expectSameKeys(modules, code, "module options");
}

TEST(ConfigurationDoc, SimulatorAndCalibrationKeysAreTheLoadableOnes) {
  const auto doc = documentedKeys();
  SectionKeys sim, calib;
  for (const auto& [heading, sections] : doc) {
    if (heading.find("Simulator") != std::string::npos) sim = sections;
    if (heading.find("Calibration") != std::string::npos) calib = sections;
  }
  // The scene file lists every key the simulator reads (and it refuses any other).
  expectSameKeys(
      sim, iniKeys(test::readFile(std::string(RPVIO_SOURCE_DIR) + "/config/sim/warehouse.ini")),
      "simulator scene");
  // A written calib.ini with distortion and a camera height has every key.
  test::TempDir dir;
  Calibration c;
  c.camera.width = 640;
  c.camera.height = 480;
  c.camera.fx = c.camera.fy = 320;
  c.camera.model = DistortionModel::RadTan;
  c.camera_height = 1.65;  // optional, written when known
  saveCalibration(dir.file("calib.ini"), c);
  expectSameKeys(calib, iniKeys(test::readFile(dir.file("calib.ini"))), "calib.ini");
}

}  // namespace
}  // namespace rpvio
