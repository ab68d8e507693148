// rpvio-export: writes an rpvio rawlog in another system's format (rosbag_io/bag_export.h).
#include <unistd.h>

#include <cstdio>

#include "apps/lib/command_line.h"
#include "rawlog_io/euroc_export.h"
#include "rosbag_io/bag_export.h"

namespace {
const char* kUsage =
    "usage: rpvio-export euroc --rawlog FILE.rawlog --out DIR\n"
    "  An EuRoC (ASL) folder: DIR/mav0/cam0, imu0, state_groundtruth_estimate0 (velocity by\n"
    "  central differences, biases 0) with sensor.yaml files, masks (if any) in DIR/masks/. Read\n"
    "  back with: rpvio-import euroc --mav0 DIR/mav0 [--masks DIR/masks] --gt DIR/mav0/\n"
    "  state_groundtruth_estimate0/data.csv\n"
    "usage: rpvio-export rosbag --rawlog FILE.rawlog --out FILE.bag\n"
    "  A ROS1 bag in the RP-VIO simulated-warehouse layout: /image (mono8), /mask (mono8, plane\n"
    "  id, 0 = none), /imu; groundtruth.txt (TUM) and the rawlog's calib.ini beside the bag.\n"
    "  Read back with: rpvio-import rosbag --bag FILE.bag --preset rpvio-sim --calib calib.ini\n"
    "Exit code 2 on bad input, with a one-line message naming the file and position.\n";
}

int main(int argc, char** argv) {
  using namespace rpvio;
  return apps::runApp("rpvio-export", kUsage, [&] {
    const apps::CommandLine cli(argc, argv, {"rawlog", "out"}, {});
    const std::string command = cli.positional().size() == 1 ? cli.positional()[0] : "";
    const bool terminal = isatty(STDERR_FILENO);
    const auto progress = [&](size_t n) {
      if (terminal) std::fprintf(stderr, "\rexporting: %zu entries", n);
    };
    if (command == "euroc") {
      const EurocExportCounts counts = exportEuroc(cli.value("rawlog"), cli.value("out"), progress);
      if (terminal) std::fprintf(stderr, "\n");
      std::printf(
          "wrote %s: %zu cam0 images, %zu masks, %zu imu0 samples, %zu ground-truth states\n",
          cli.value("out").c_str(), counts.images, counts.masks, counts.imu, counts.groundtruth);
      return 0;
    }
    if (command != "rosbag") throw apps::UsageError("expected the command 'euroc' or 'rosbag'");
    const BagExportCounts counts = exportBag(cli.value("rawlog"), cli.value("out"), progress);
    if (terminal) std::fprintf(stderr, "\n");
    std::printf("wrote %s: %zu /image, %zu /mask, %zu /imu; %zu ground-truth poses\n",
                cli.value("out").c_str(), counts.images, counts.masks, counts.imu,
                counts.groundtruth);
    return 0;
  });
}
