// Fuzzes the EuRoC CSV readers (rawlog_io/euroc_csv.h): the same bytes read as an IMU CSV and as
// a ground-truth state CSV; returned samples must be finite, time-ordered, with unit quaternions.
#include <cstddef>
#include <cstdint>

#include "rawlog_io/euroc_csv.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::InputFile file(data, size, "data.csv");
  fuzz::readExpectingOnlyInputError([&] {
    const auto imu = readEurocImuCsv(file.path());
    for (size_t i = 0; i < imu.size(); ++i) {
      fuzz::require(std::isfinite(imu[i].t) && imu[i].gyro.allFinite() && imu[i].accel.allFinite(),
                    "IMU sample not finite");
      fuzz::require(i == 0 || imu[i].t > imu[i - 1].t, "IMU timestamps not increasing");
    }
  });
  fuzz::readExpectingOnlyInputError([&] {
    const auto states = readEurocStateCsv(file.path());
    for (size_t i = 0; i < states.size(); ++i) {
      const EurocStateSample& s = states[i];
      fuzz::require(std::isfinite(s.t) && s.p.allFinite() && s.v.allFinite() &&
                        s.gyro_bias.allFinite() && s.accel_bias.allFinite(),
                    "state not finite");
      fuzz::require(fuzz::isUnit(s.q), "state quaternion not unit");
      fuzz::require(i == 0 || s.t > states[i - 1].t, "state timestamps not increasing");
    }
  });
  return 0;
}
