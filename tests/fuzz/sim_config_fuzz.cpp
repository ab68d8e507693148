// Fuzzes the simulator's scene file reader (sim/sim_config.h: SimConfig::load, as rpvio-sim reads
// --config over a profile): INI sections and keys, every value's parse and range check, unknown
// keys. A configuration it returns must describe itself as a scene file that loads back to the
// same description (what describe() promises), and give a calibration.
#include <cstddef>
#include <cstdint>
#include <fstream>

#include "sim/sim_config.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::InputFile file(data, size, "scene.ini");
  fuzz::readExpectingOnlyInputError([&] {
    const sim::SimConfig config =
        sim::SimConfig::load(file.path(), sim::SimConfig::profile("hard"));
    const std::string described = config.describe();
    const std::string again = file.path() + ".described.ini";
    std::ofstream(again) << described;
    fuzz::require(sim::SimConfig::load(again).describe() == described,
                  "the description does not load back to itself");
    config.calibration();
  });
  return 0;
}
