// Fuzzes the calibration INI loader (loadCalibration, rawlog_io/calibration.h, through
// common/ini_file.h); a loaded calibration must have a positive image size and focal lengths.
#include <cstddef>
#include <cstdint>

#include "rawlog_io/calibration.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::InputFile file(data, size, "calib.ini");
  fuzz::readExpectingOnlyInputError([&] {
    const Calibration c = loadCalibration(file.path());
    const CameraIntrinsics& cam = c.camera;
    fuzz::require(cam.width > 0 && cam.height > 0 && cam.fx > 0 && cam.fy > 0,
                  "image size or focal length not positive");
    fuzz::require(std::isfinite(cam.fx) && std::isfinite(cam.fy) && std::isfinite(cam.cx) &&
                      std::isfinite(cam.cy),
                  "intrinsics not finite");
    fuzz::require(fuzz::isRotation(c.T_BC.linear()) && c.T_BC.translation().allFinite(),
                  "T_BC not a rigid transform");
  });
  return 0;
}
