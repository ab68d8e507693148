#include "apps/lib/eval_app.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <utility>

#include "apps/lib/command_line.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/json_text.h"
#include "evaluation/trajectory_plot.h"
#include "planes_map/plane_map_exporters.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/trajectory_io.h"

namespace rpvio::apps {
namespace {

const char* kUsage =
    "usage: rpvio-eval --gt FILE --est FILE [--est FILE2 ...] [--label NAME ...]\n"
    "                  [--align se3|sim3|posyaw|none] [--max-dt SEC] [--format tum|kitti|euroc]\n"
    "                  [--rpe-distance M] [--rpe-frames N] [--plot OUT.png] [--json OUT.json]\n"
    "                  [--planes planes.yaml --gt-planes groundtruth_planes.yaml\n"
    "                   [--rawlog seq.rawlog [--config config/<mode>.ini]]]\n"
    "  Formats are recognized from the content unless --format is given. KITTI files associate by\n"
    "  index, others by nearest timestamp within --max-dt (default 0.01 s). Default alignment "
    "se3.\n"
    "  --planes: the plane map of the first estimate, matched to the true planes by mask label\n"
    "  (discovered planes, rpvio-auto's: to the nearest within 10 deg and 0.3 m) and moved by\n"
    "  that estimate's alignment: map entries per true plane, normal and offset errors, and the\n"
    "  standard deviations the map's covariance gives them. --rawlog: the\n"
    "  sequence's plane masks; the true planes without a map entry that were trackable for more\n"
    "  than 2 s (10 KLT windows of pixels with no other label within the tracker's margin: room\n"
    "  for 10 tracks one window apart) are listed as missing, those only seen (10 KLT windows of\n"
    "  pixels) as untrackable. The KLT window and margin are the front-end's of the run's mode\n"
    "  (--config: klt_window, window_margin of [FeatureTrackerModule]; default 21 and 10 px).\n";

Trajectory readWithFormat(const std::string& path, const std::string& format) {
  if (format.empty()) return readTrajectory(path);
  if (format == "tum") return readTum(path);
  if (format == "kitti") return readKitti(path);
  if (format == "euroc") return readEurocCsv(path);
  throw UsageError("unknown --format '" + format + "' (tum, kitti, euroc)");
}

/// Every PLANE_MASK of `rawlog` (InputError naming the file and entry on bad input) into a
/// PlaneVisibility with the tracker's KLT window and margin.
std::map<int, eval::LabelVisibility> planeVisibleSeconds(const EvalAppOptions& opt) {
  RawlogReader reader(opt.masks_rawlog);
  eval::PlaneVisibility visibility(eval::minVisiblePlanePixels(opt.tracker_klt_window),
                                   opt.tracker_window_margin);
  while (const auto obs = reader.next()) {
    if (obs->sensorLabel != labels::kPlaneMask) continue;
    const auto* image = dynamic_cast<const mrpt::obs::CObservationImage*>(obs.get());
    if (!image) continue;
    visibility.addMask(toSeconds(obs->timestamp), loadGrayImage(*image, reader));
  }
  return visibility.seconds();
}

constexpr int kExactDigits = 17;  // a double's value exactly

JsonObject statsJson(const eval::ErrorStats& s) {
  return JsonObject(kExactDigits)
      .number("rmse", s.rmse)
      .number("mean", s.mean)
      .number("median", s.median)
      .number("std", s.std)
      .number("min", s.min)
      .number("max", s.max)
      .integer("count", static_cast<long long>(s.count));
}

JsonObject estimateJson(const EvalAppOptions& opt, const std::string& label,
                        const std::string& file, const eval::EvalResult& r) {
  auto rpe = [](const char* delta_key, double delta, const eval::RelativeError& e) {
    return JsonObject()
        .number(delta_key, delta)
        .object("translation", statsJson(e.translation))
        .object("rotation_deg", statsJson(e.rotation_deg));
  };
  const auto& a = r.alignment;
  return JsonObject()
      .text("label", label)
      .text("file", file)
      .integer("pairs", static_cast<long long>(r.pairs.size()))
      .number("coverage", r.coverage)
      .object("ate", statsJson(r.ate))
      .number("ate_rotation_rmse_deg", r.ate_rotation_rmse_deg)
      .object("rpe_distance", rpe("delta_m", opt.eval.rpe_distance, r.rpe_distance))
      .object("rpe_frames", rpe("delta_frames", opt.eval.rpe_frames, r.rpe_frames))
      .object(
          "alignment",
          JsonObject().number("scale", a.s).numbers("translation", {a.t.x(), a.t.y(), a.t.z()}));
}

JsonObject planeMapJson(const EvalAppOptions& opt, const EvalAppResult& res) {
  const auto& m = *res.plane_map;
  std::vector<JsonObject> planes;
  for (const auto& p : m.planes)
    planes.push_back(JsonObject()
                         .integer("id", p.true_id)
                         .integer("map_entries", static_cast<long long>(p.map_entries))
                         .number("normal_error_deg", p.normal_error_deg)
                         .number("distance_error_m", p.distance_error_m)
                         .number("seen_s", p.seen_s)
                         .number("normal_sigma_deg", p.normal_sigma_deg)
                         .number("distance_sigma_m", p.distance_sigma_m));
  JsonObject json;
  json.text("file", opt.planes_file)
      .integer("map_planes", static_cast<long long>(m.map_planes))
      .integer("true_planes", static_cast<long long>(m.planes.size()))
      .integer("duplicates", static_cast<long long>(m.duplicates))
      .integer("mixed", static_cast<long long>(m.mixed))
      .integer("unmatched", static_cast<long long>(m.unmatched))
      .integer("on_moving", static_cast<long long>(m.on_moving))
      .integer("discovered", static_cast<long long>(m.discovered))
      .objects("planes", planes);
  if (res.visible_s) {
    const auto& missing = res.missing_planes;
    for (const auto& [name, list] :
         {std::pair{"missing", &missing.missing}, std::pair{"untrackable", &missing.untrackable}}) {
      std::vector<JsonObject> entries;
      for (const auto& plane : *list)
        entries.push_back(JsonObject()
                              .integer("id", plane.true_id)
                              .number("seen_s", plane.visible.seen_s)
                              .number("trackable_s", plane.visible.trackable_s));
      json.objects(name, entries);
    }
  }
  return json;
}

void writeJson(const EvalAppOptions& opt, const EvalAppResult& res) {
  std::vector<JsonObject> estimates;
  for (size_t k = 0; k < res.results.size(); ++k)
    estimates.push_back(estimateJson(opt, res.labels[k], opt.est_files[k], res.results[k]));
  JsonObject json;
  json.text("ground_truth", opt.gt_file)
      .text("alignment", eval::toString(opt.eval.align))
      .number("max_dt", opt.eval.max_dt)
      .objects("estimates", estimates);
  if (res.plane_map) json.object("plane_map", planeMapJson(opt, res));
  writeFileAtomically(opt.json_file, [&](std::ostream& out) { out << json.str(); });
}

std::string formatPlaneMapReport(const eval::PlaneMapAccuracy& m) {
  std::vector<double> normal, distance;
  for (const auto& p : m.planes)
    normal.push_back(p.normal_error_deg), distance.push_back(p.distance_error_m);
  const eval::ErrorStats n = eval::computeStats(normal), d = eval::computeStats(distance);
  std::ostringstream out;
  char line[400];
  std::snprintf(line, sizeof(line),
                "\nplane map: %zu entries for %zu true planes (duplicates %zu, mixed %zu, "
                "unmatched %zu, on moving objects %zu, from discovery %zu); normal error median "
                "%.2f max %.2f deg, offset error median %.3f max %.3f m\n%6s %8s %11s %11s %8s "
                "%11s %11s\n",
                m.map_planes, m.planes.size(), m.duplicates, m.mixed, m.unmatched, m.on_moving,
                m.discovered, n.median, n.max, d.median, d.max, "plane", "entries", "normal deg",
                "offset m", "seen s", "sigma deg", "sigma m");
  out << line;
  for (const auto& p : m.planes) {
    std::snprintf(line, sizeof(line), "%6d %8zu %11.2f %11.3f %8.1f %11.2f %11.3f\n", p.true_id,
                  p.map_entries, p.normal_error_deg, p.distance_error_m, p.seen_s,
                  p.normal_sigma_deg, p.distance_sigma_m);
    out << line;
  }
  return out.str();
}

std::string formatMissingPlanes(const std::map<int, eval::LabelVisibility>& visible_s,
                                const eval::MissingPlanes& missing) {
  const auto trackable = std::count_if(visible_s.begin(), visible_s.end(), [](const auto& v) {
    return v.second.trackable_s > eval::kMinVisibleSeconds;
  });
  std::ostringstream out;
  out << "missing: " << missing.missing.size() << " of the " << trackable
      << " labels trackable for more than 2 s have no map entry";
  char item[96];
  for (const auto& m : missing.missing) {
    std::snprintf(item, sizeof(item), "%s%d (%.1f s)", &m == &missing.missing.front() ? ": " : ", ",
                  m.true_id, m.visible.trackable_s);
    out << item;
  }
  out << "\nuntrackable: " << missing.untrackable.size()
      << " more labels seen for more than 2 s, trackable for at most 2 s, have no map entry";
  for (const auto& m : missing.untrackable) {
    std::snprintf(item, sizeof(item), "%s%d (seen %.1f s, trackable %.1f s)",
                  &m == &missing.untrackable.front() ? ": " : ", ", m.true_id, m.visible.seen_s,
                  m.visible.trackable_s);
    out << item;
  }
  out << "\n";
  return out.str();
}

}  // namespace

EvalAppResult runEvaluation(const EvalAppOptions& opt) {
  const Trajectory gt = readWithFormat(opt.gt_file, opt.format);
  EvalAppResult res;
  for (size_t k = 0; k < opt.est_files.size(); ++k) {
    const std::string& file = opt.est_files[k];
    eval::EvalOptions eval_opt = opt.eval;
    if (!opt.format.empty() ? opt.format == "kitti"
                            : detectTrajectoryFormat(file) == TrajectoryFormat::Kitti)
      eval_opt.associate_by_index = true;
    try {
      res.results.push_back(eval::evaluate(gt, readWithFormat(file, opt.format), eval_opt));
    } catch (const InputError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw InputError(file, "", e.what());
    }
    res.labels.push_back(k < opt.labels.size() ? opt.labels[k]
                                               : std::filesystem::path(file).stem().string());
  }
  if (!opt.planes_file.empty()) {
    const std::vector<Plane> truth = readPlanesYaml(opt.gt_planes_file);
    res.plane_map = eval::evaluatePlaneMap(readPlanesYaml(opt.planes_file), truth,
                                           res.results.front().alignment);
    if (!opt.masks_rawlog.empty()) {
      res.visible_s = planeVisibleSeconds(opt);
      res.missing_planes = eval::missingPlanes(*res.plane_map, truth, *res.visible_s);
    }
  }
  if (!opt.plot_png.empty()) {
    std::vector<eval::PlottedEstimate> plotted;
    for (size_t k = 0; k < res.results.size(); ++k)
      plotted.push_back({res.labels[k], &res.results[k]});
    eval::writeTrajectoryPlot(opt.plot_png, gt, plotted,
                              "alignment: " + eval::toString(opt.eval.align) + "   ground truth: " +
                                  std::filesystem::path(opt.gt_file).filename().string());
  }
  if (!opt.json_file.empty()) writeJson(opt, res);
  return res;
}

std::string formatEvaluationReport(const EvalAppOptions& opt, const EvalAppResult& res) {
  std::ostringstream out;
  char line[320];
  for (const auto& r : res.results) {
    std::snprintf(line, sizeof(line), "ATE_RMSE %.9f\n", r.ate.rmse);
    out << line;
  }
  std::snprintf(line, sizeof(line), "%-20s %7s %9s %9s %9s %9s %9s %8s %10s %9s\n", "estimate",
                "pairs", "coverage", "ATE rmse", "mean", "median", "max", "rot deg", "RPE@dist",
                "RPE@1fr");
  out << "\n" << line;
  for (size_t k = 0; k < res.results.size(); ++k) {
    const auto& r = res.results[k];
    std::snprintf(line, sizeof(line),
                  "%-20s %7zu %8.1f%% %9.4f %9.4f %9.4f %9.4f %8.3f %10.4f %9.4f\n",
                  res.labels[k].substr(0, 20).c_str(), r.pairs.size(), 100 * r.coverage, r.ate.rmse,
                  r.ate.mean, r.ate.median, r.ate.max, r.ate_rotation_rmse_deg,
                  r.rpe_distance.translation.rmse, r.rpe_frames.translation.rmse);
    out << line;
  }
  out << "(metres; alignment " << eval::toString(opt.eval.align) << "; RPE@dist over "
      << opt.eval.rpe_distance << " m, RPE@1fr over " << opt.eval.rpe_frames << " frame(s))\n";
  if (res.plane_map) out << formatPlaneMapReport(*res.plane_map);
  if (res.visible_s) out << formatMissingPlanes(*res.visible_s, res.missing_planes);
  return out.str();
}

int evalMain(int argc, char** argv) {
  return runApp("rpvio-eval", kUsage, [&] {
    const CommandLine cli(argc, argv,
                          {"gt", "est", "label", "align", "max-dt", "format", "plot", "json",
                           "rpe-distance", "rpe-frames", "planes", "gt-planes", "rawlog", "config"},
                          {});
    EvalAppOptions opt;
    opt.gt_file = cli.value("gt");
    opt.est_files = cli.values("est");
    if (opt.est_files.empty()) throw UsageError("missing required option --est");
    opt.labels = cli.values("label");
    opt.format = cli.valueOr("format", "");
    try {
      opt.eval.align = eval::parseAlignMode(cli.valueOr("align", "se3"));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    opt.eval.max_dt = cli.number("max-dt", 0.01);
    opt.eval.rpe_distance = cli.number("rpe-distance", 10.0);
    opt.eval.rpe_frames = static_cast<int>(cli.number("rpe-frames", 1));
    opt.plot_png = cli.valueOr("plot", "");
    opt.json_file = cli.valueOr("json", "");
    opt.planes_file = cli.valueOr("planes", "");
    opt.gt_planes_file = cli.valueOr("gt-planes", "");
    if (opt.planes_file.empty() != opt.gt_planes_file.empty())
      throw UsageError("--planes and --gt-planes go together");
    opt.masks_rawlog = cli.valueOr("rawlog", "");
    if (!opt.masks_rawlog.empty() && opt.planes_file.empty())
      throw UsageError("--rawlog needs --planes and --gt-planes");
    if (cli.has("config")) {
      const TrackerOptions tracker =
          TrackerOptions::load(IniFile(cli.value("config")), "FeatureTrackerModule");
      opt.tracker_klt_window = tracker.klt_window;
      opt.tracker_window_margin = tracker.window_margin;
    }
    const EvalAppResult res = runEvaluation(opt);
    std::cout << formatEvaluationReport(opt, res);
    if (!opt.plot_png.empty()) std::cout << "plot: " << opt.plot_png << "\n";
    if (!opt.json_file.empty()) std::cout << "json: " << opt.json_file << "\n";
    return 0;
  });
}

}  // namespace rpvio::apps
