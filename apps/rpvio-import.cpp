// rpvio-import: converts a dataset into an rpvio rawlog (see rawlog_io/euroc_import.h).
#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <filesystem>
#include <stdexcept>
#include "apps/lib/command_line.h"

#include "rawlog_io/advio_import.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/euroc_import.h"
#include "rawlog_io/rawlog_summary.h"
#include "rosbag_io/bag_import.h"

namespace {

/// --accel-scale S: a nonzero factor.
double accelScale(const rpvio::apps::CommandLine& cli) {
  const double scale = cli.number("accel-scale", 0);
  if (!std::isfinite(scale) || scale == 0)
    throw rpvio::apps::UsageError(
        "--accel-scale: a nonzero factor (9.80665: readings in g; -9.80665: CoreMotion's g)");
  return scale;
}

rpvio::BagImportOptions bagOptions(const rpvio::apps::CommandLine& cli) {
  using namespace rpvio;
  BagPreset preset;
  try {
    preset = bagPreset(cli.value("preset"));
  } catch (const std::invalid_argument& e) {
    throw apps::UsageError(std::string("--preset: ") + e.what());
  }
  BagImportOptions opt;
  opt.bag_path = cli.value("bag");
  opt.output_rawlog = cli.value("out");
  opt.topics.image = cli.valueOr("image-topic", preset.topics.image);
  opt.topics.imu = cli.valueOr("imu-topic", preset.topics.imu);
  opt.topics.mask = cli.valueOr("mask-topic", preset.topics.mask);
  opt.topics.groundtruth = cli.valueOr("gt-topic", preset.topics.groundtruth);
  opt.topics.accel = cli.valueOr("accel-topic", preset.topics.accel);
  opt.mask_colours = preset.mask_colours;
  if (opt.topics.image.empty() || opt.topics.imu.empty())
    throw apps::UsageError(
        "the preset names no image or IMU topic: give --image-topic, --imu-topic");
  if (cli.has("calib"))
    opt.calibration = loadCalibration(cli.value("calib"));
  else if (preset.calibration)
    opt.calibration = *preset.calibration;
  else
    throw apps::UsageError("the preset has no calibration: give --calib calib.ini");
  opt.imu_rate_hz = cli.number("imu-rate", preset.imu_rate_hz);
  if (cli.has("accel-scale")) opt.accel_scale = accelScale(cli);
  const auto beside =
      std::filesystem::path(opt.bag_path).parent_path() / preset.groundtruth_beside_bag;
  if (cli.has("gt")) {
    opt.groundtruth_file = cli.value("gt");
    opt.topics.groundtruth.clear();
  } else if (!preset.groundtruth_beside_bag.empty() && std::filesystem::is_regular_file(beside))
    opt.groundtruth_file = beside.string();
  return opt;
}

rpvio::AdvioImportOptions advioOptions(const rpvio::apps::CommandLine& cli) {
  using namespace rpvio;
  AdvioImportOptions opt;
  opt.sequence_dir = cli.value("seq");
  opt.output_rawlog = cli.value("out");
  opt.every = cli.count("every", 1);
  try {
    opt.rotation = frameRotationFromName(cli.valueOr("rotate", "cw"));
  } catch (const std::invalid_argument& e) {
    throw apps::UsageError(std::string("--rotate: ") + e.what());
  }
  if (cli.has("calib")) opt.calibration = loadCalibration(cli.value("calib"));
  if (cli.valueOr("accel-scale", "auto") != "auto") opt.accel_scale = accelScale(cli);
  opt.subtract_batch_bias = !cli.has("keep-bias");
  return opt;
}

const char* kUsage =
    "usage: rpvio-import euroc --mav0 DIR [--gt FILE] [--masks DIR] --out FILE.rawlog\n"
    "  Converts an EuRoC (ASL) folder: cam0 images -> CAM0, imu0 -> IMU, optional masks folder\n"
    "  (PNG named like the images) -> PLANE_MASK, optional ground truth (TUM or EuRoC CSV) ->\n"
    "  GROUND_TRUTH; writes calib.ini beside the rawlog.\n"
    "usage: rpvio-import rosbag --bag FILE.bag --preset rpvio-sim|viode|openloris|advio|generic\n"
    "                    [--image-topic T] [--imu-topic T] [--accel-topic T] [--mask-topic T]\n"
    "                    [--gt-topic T] [--calib calib.ini] [--imu-rate HZ] [--accel-scale S]\n"
    "                    [--gt FILE.tum]\n"
    "                    --out FILE.rawlog\n"
    "  Converts a ROS1 bag (no ROS needed): image topic -> CAM0 (mono8, rgb8, bgr8, rgba8, bgra8,\n"
    "  mono16), mask topic -> PLANE_MASK (mono8 plane ids, paired by identical stamp), IMU topic\n"
    "  (decimated to --imu-rate by timestamp) -> IMU, TUM file or pose topic -> GROUND_TRUTH;\n"
    "  header stamps; writes calib.ini beside the rawlog. The preset gives topics, calibration and "
    "IMU\n"
    "  rate (rpvio-sim: /image, /mask, /imu at 200 Hz, groundtruth.txt beside the bag; viode:\n"
    "  /cam0/image_raw, /imu0, /cam0/segmentation colours of ground, wall, road as planes 1-3,\n"
    "  /odometry as ground truth; openloris: /d400/color/image_raw, /d400/gyro/sample and\n"
    "  /d400/accel/sample merged, /gt, the market scenes' calibration; advio: the RP-VIO\n"
    "  authors' ADVIO bags, /cam0/image_raw, /imu0, /cam0/mask, the iPhone of sequences 1-12);\n"
    "  options override it;\n"
    "  generic needs every topic and --calib.\n"
    "usage: rpvio-import advio --seq DIR [--every N] [--rotate cw|ccw|180|none] [--calib "
    "calib.ini]\n"
    "                   [--accel-scale auto|S] [--keep-bias] --out FILE.rawlog\n"
    "  Converts an ADVIO sequence folder (advio-NN): iphone/frames.mov with the stamps of\n"
    "  frames.csv -> CAM0 (grey, every N-th frame, turned upright: cw by default), iphone/\n"
    "  accelerometer.csv and gyro.csv merged -> IMU (the batch's published biases subtracted\n"
    "  unless --keep-bias; specific force = S x reading, S detected from the readings' size and\n"
    "  direction unless given), ground-truth/pose.csv -> GROUND_TRUTH. Calibration: the batch\n"
    "  of NN unless --calib; writes calib.ini beside the rawlog.\n"
    "usage: rpvio-import verify --rawlog FILE\n"
    "  Streams a rawlog, loading every image and IMU sample, and prints the counts per label.\n"
    "Exit code 2 on bad input, with a one-line message naming the file and position.\n";
}  // namespace

int main(int argc, char** argv) {
  using namespace rpvio;
  return apps::runApp("rpvio-import", kUsage, [&] {
    const apps::CommandLine cli(
        argc, argv,
        {"mav0", "gt", "masks", "out", "rawlog", "bag", "preset", "image-topic", "imu-topic",
         "mask-topic", "gt-topic", "accel-topic", "calib", "imu-rate", "seq", "every", "rotate",
         "accel-scale"},
        {"keep-bias"});
    const std::string command = cli.positional().size() == 1 ? cli.positional()[0] : "";
    if (command == "verify") {
      const auto summary = summarizeRawlog(cli.value("rawlog"));
      std::printf("%s: %.6f .. %.6f s\n", cli.value("rawlog").c_str(), summary.first_t,
                  summary.last_t);
      for (const auto& [label, count] : summary.observations_per_label)
        std::printf("  %-14s %zu\n", label.c_str(), count);
      return 0;
    }
    const bool terminal = isatty(STDERR_FILENO);
    if (command == "rosbag") {
      const BagImportOptions opt = bagOptions(cli);
      const BagImportCounts counts = importBag(opt, [&](size_t n) {
        if (terminal) std::fprintf(stderr, "\rimporting: %zu images and masks", n);
      });
      if (terminal) std::fprintf(stderr, "\n");
      std::printf("wrote %s: %zu CAM0, %zu PLANE_MASK, %zu IMU, %zu GROUND_TRUTH%s\n",
                  opt.output_rawlog.c_str(), counts.images, counts.masks, counts.imu,
                  counts.groundtruth,
                  counts.unpaired_masks ? ("; " + std::to_string(counts.unpaired_masks) +
                                           " masks without an image of the same stamp dropped")
                                              .c_str()
                                        : "");
      return 0;
    }
    if (command == "advio") {
      const AdvioImportOptions opt = advioOptions(cli);
      const AdvioImportCounts counts = importAdvio(opt, [&](size_t frames) {
        if (terminal) std::fprintf(stderr, "\rimporting: %zu video frames read", frames);
      });
      if (terminal) std::fprintf(stderr, "\n");
      std::printf("wrote %s: %zu CAM0, %zu IMU, %zu GROUND_TRUTH\n", opt.output_rawlog.c_str(),
                  counts.images, counts.imu, counts.groundtruth);
      std::printf("  calibration: %s; accelerometer: x %.5f (%s)\n",
                  opt.calibration ? "--calib" : ("batch " + std::to_string(counts.batch)).c_str(),
                  counts.accel_scale, counts.accel_scale_reason.c_str());
      if (counts.frames_without_stamp || counts.stamps_without_frame)
        std::printf("  %zu video frames without a stamp and %zu stamps without a frame dropped\n",
                    counts.frames_without_stamp, counts.stamps_without_frame);
      return 0;
    }
    if (command != "euroc")
      throw apps::UsageError("expected the command 'euroc', 'rosbag', 'advio' or 'verify'");
    EurocImportOptions opt;
    opt.mav0_dir = cli.value("mav0");
    opt.output_rawlog = cli.value("out");
    opt.groundtruth_file = cli.valueOr("gt", "");
    opt.masks_dir = cli.valueOr("masks", "");
    const auto counts = importEuroc(opt, [&](size_t done, size_t total) {
      if (terminal) std::fprintf(stderr, "\rimporting %zu/%zu entries", done, total);
    });
    if (terminal) std::fprintf(stderr, "\n");
    std::cout << "wrote " << opt.output_rawlog << ": " << counts.images << " CAM0, " << counts.masks
              << " PLANE_MASK, " << counts.imu << " IMU, " << counts.groundtruth
              << " GROUND_TRUTH\n";
    return 0;
  });
}
