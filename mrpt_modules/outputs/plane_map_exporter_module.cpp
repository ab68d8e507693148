#include "mrpt_modules/outputs/plane_map_exporter_module.h"

#include <mrpt/core/initializer.h>

#include <filesystem>

#include "mrpt_modules/loop/loop_closure_module.h"
#include "mrpt_modules/outputs/trajectory_writer_module.h"
#include "planes_map/plane_map_exporters.h"
#include "planes_map/planes_map.h"

IMPLEMENTS_MRPT_OBJECT(PlaneMapExporterModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_PlaneMapExporterModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::PlaneMapExporterModule));
}

namespace rpvio {

void PlaneMapExporterModule::initialize(const IniFile& ini, const std::string& section,
                                        PipelineContext& context) {
  options_ = loadOptions<PlaneMapExportOptions>(ini, section);
  output_dir_ = context.output_dir;
  context.bus.subscribe<StateEstimate>([this](const StateEstimate& s) { odometry_.push_back(s); });
  context.bus.subscribe<MapSummary>([this](const MapSummary& s) { summary_ = s; });
  context.bus.subscribe<LoopClosureSummary>(
      [this](const LoopClosureSummary& s) { loop_planes_ = s.planes; });
  setOptionsText("[" + section + "]\n" + describeOptions(options_));
}

void PlaneMapExporterModule::finish() {
  if (output_dir_.empty() || !summary_ || !summary_->planes_map) return;
  const auto path = [&](const char* name) {
    return (std::filesystem::path(output_dir_) / name).string();
  };
  const std::vector<Plane> planes = summary_->planes_map->confirmedPlanes();
  writePlanesYaml(path("planes.yaml"), planes);
  if (loop_planes_) writePlanesYaml(path("planes_loop.yaml"), *loop_planes_);
  writePlanesPly(path("planes.ply"), planes);
  writePlanesOctomap(path("planes.bt"), planes, options_.octomap_resolution_m);
  writePlanesScene(path("planes.3Dscene"), planes);
  // The planes are the refinement's when it ran: drawn with its trajectory.
  writePlanesTopView(
      path("planes_topview.png"), planes,
      toTrajectory(summary_->refined_trajectory.empty() ? odometry_
                                                        : summary_->refined_trajectory));
}

}  // namespace rpvio
