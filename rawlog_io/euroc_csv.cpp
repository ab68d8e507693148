#include "rawlog_io/euroc_csv.h"

#include "common/input_error.h"
#include "common/text_table.h"
#include "rawlog_io/nanosecond_stamps.h"

namespace rpvio {
namespace {

void checkIncreasing(double t, double previous, const std::string& path, int line, bool first) {
  if (!first && t <= previous)
    throw InputError(path, "line " + std::to_string(line), "timestamps not increasing");
}

}  // namespace

std::vector<ImuSample> readEurocImuCsv(const std::string& csv) {
  std::vector<ImuSample> samples;
  forEachTextRow(csv, [&](const std::vector<std::string>& f, int line) {
    const auto v = parseNumberRow(f, 7, 7, csv, line);
    ImuSample s;
    s.t = secondsOfNanosecondText(f[0], csv, line);
    checkIncreasing(s.t, samples.empty() ? 0 : samples.back().t, csv, line, samples.empty());
    s.gyro = {v[1], v[2], v[3]};
    s.accel = {v[4], v[5], v[6]};
    samples.push_back(s);
  });
  return samples;
}

std::vector<EurocStateSample> readEurocStateCsv(const std::string& csv) {
  std::vector<EurocStateSample> states;
  forEachTextRow(csv, [&](const std::vector<std::string>& f, int line) {
    const auto v = parseNumberRow(f, 17, 17, csv, line);
    EurocStateSample s;
    s.t = secondsOfNanosecondText(f[0], csv, line);
    checkIncreasing(s.t, states.empty() ? 0 : states.back().t, csv, line, states.empty());
    s.p = {v[1], v[2], v[3]};
    s.q = unitQuaternion(v[4], v[5], v[6], v[7], csv, line);
    s.v = {v[8], v[9], v[10]};
    s.gyro_bias = {v[11], v[12], v[13]};
    s.accel_bias = {v[14], v[15], v[16]};
    states.push_back(s);
  });
  return states;
}

}  // namespace rpvio
