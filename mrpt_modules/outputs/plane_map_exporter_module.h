#pragma once
// Output module: the finished plane map (MapSummary) exported into the pipeline's output
// folder: planes.yaml, planes.ply, planes.bt (OctoMap), planes.3Dscene and planes_topview.png
// (drawn with the refined trajectory when there is one, else the odometry's); with the loop
// closure, planes_loop.yaml: the map in trajectory_loop.tum's frame (LoopClosureSummary::planes).
// Options: section [PlaneMapExporterModule] (PlaneMapExportOptions).
#include <optional>

#include "common/options.h"

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/map_sink.h"

namespace rpvio {

struct PlaneMapExportOptions {
  double octomap_resolution_m = 0.1;  // voxel size of planes.bt (m)

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, octomap_resolution_m);
  }
  void validate(const OptionsLoader& loader) const {
    loader.require(octomap_resolution_m > 0, "octomap_resolution_m", "must be positive");
  }
};

class PlaneMapExporterModule : public Module {
  DEFINE_MRPT_OBJECT(PlaneMapExporterModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  PlaneMapExportOptions options_;
  std::string output_dir_;
  std::vector<StateEstimate> odometry_;
  std::optional<MapSummary> summary_;
  std::optional<std::vector<Plane>> loop_planes_;
};

}  // namespace rpvio
