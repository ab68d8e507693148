// Fuzzes the streaming rawlog reader (rawlog_io/rawlog_reader.h) the way a consumer uses it: every
// entry read, images loaded (from `<stem>_Images/`, absent here), IMU and ground-truth converted.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#include "rawlog_io/rawlog_reader.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

// MRPT's deserialization trusts the 32-bit lengths in the stream (`std::string::resize(n)` before
// reading n bytes), so a corrupt length asks for up to 4 GB. Under ASan `new` aborts instead of
// throwing; these replacements throw std::bad_alloc above 64 MB, like a process short of memory,
// and the reader must turn that into an InputError. (Array and aligned forms stay ASan's own.)
namespace {
constexpr std::size_t kMaxAllocation = std::size_t{64} << 20;
void* allocate(std::size_t size) noexcept {
  return size <= kMaxAllocation ? std::malloc(size == 0 ? 1 : size) : nullptr;
}
}  // namespace

void* operator new(std::size_t size) {
  if (void* p = allocate(size)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::InputFile file(data, size, "seq.rawlog");
  fuzz::readExpectingOnlyInputError([&] {
    RawlogReader reader(file.path());
    while (auto obs = reader.next()) {
      if (auto image = std::dynamic_pointer_cast<mrpt::obs::CObservationImage>(obs))
        loadGrayImage(*image, reader);
      if (auto imu = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(obs)) {
        const ImuSample s = toImuSample(*imu, reader);
        fuzz::require(s.gyro.allFinite() && s.accel.allFinite(), "IMU sample not finite");
      }
      if (auto pose = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(obs))
        toStampedPose(*pose);
    }
  });
  return 0;
}
