// rpvio-import: converts a dataset into an rpvio rawlog (see rawlog_io/euroc_import.h).
#include <unistd.h>
#include <cstdio>
#include <iostream>

#include "apps/lib/command_line.h"
#include "rawlog_io/euroc_import.h"
#include "rawlog_io/rawlog_summary.h"

namespace {
const char* kUsage =
    "usage: rpvio-import euroc --mav0 DIR [--gt FILE] [--masks DIR] --out FILE.rawlog\n"
    "  Converts an EuRoC (ASL) folder: cam0 images -> CAM0, imu0 -> IMU, optional masks folder\n"
    "  (PNG named like the images) -> PLANE_MASK, optional ground truth (TUM or EuRoC CSV) ->\n"
    "  GROUND_TRUTH; writes calib.ini beside the rawlog.\n"
    "usage: rpvio-import verify --rawlog FILE\n"
    "  Streams a rawlog, loading every image and IMU sample, and prints the counts per label.\n"
    "Exit code 2 on bad input, with a one-line message naming the file and position.\n";
}

int main(int argc, char** argv) {
  using namespace rpvio;
  return apps::runApp("rpvio-import", kUsage, [&] {
    const apps::CommandLine cli(argc, argv, {"mav0", "gt", "masks", "out", "rawlog"}, {});
    const std::string command = cli.positional().size() == 1 ? cli.positional()[0] : "";
    if (command == "verify") {
      const auto summary = summarizeRawlog(cli.value("rawlog"));
      std::printf("%s: %.6f .. %.6f s\n", cli.value("rawlog").c_str(), summary.first_t,
                  summary.last_t);
      for (const auto& [label, count] : summary.observations_per_label)
        std::printf("  %-14s %zu\n", label.c_str(), count);
      return 0;
    }
    if (command != "euroc") throw apps::UsageError("expected the command 'euroc' or 'verify'");
    EurocImportOptions opt;
    opt.mav0_dir = cli.value("mav0");
    opt.output_rawlog = cli.value("out");
    opt.groundtruth_file = cli.valueOr("gt", "");
    opt.masks_dir = cli.valueOr("masks", "");
    const bool terminal = isatty(STDERR_FILENO);
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
