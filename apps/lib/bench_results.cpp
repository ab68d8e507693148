#include "apps/lib/bench_results.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

#include "common/json_text.h"
#include "evaluation/error_stats.h"

namespace rpvio::apps {
namespace {

// RP-VIO's ATE RMSE (m) on RPVIO-Sim in the paper (Ram et al. 2021, Table I), as quoted in issue 7.
const std::vector<std::pair<std::string, double>> kPaperRpvio = {
    {"static", 0.19}, {"C1", 0.23}, {"C2", 0.18}, {"C4", 0.56}, {"C6", 0.54}, {"C8", 0.85}};

std::string number(double value, int decimals) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

std::vector<const BenchRun*> select(const std::vector<BenchRun>& runs, const std::string& mode,
                                    const std::string& sequence) {
  std::vector<const BenchRun*> out;
  for (const BenchRun& r : runs)
    if (r.mode == mode && (sequence.empty() || r.sequence == sequence)) out.push_back(&r);
  return out;
}

double medianOf(const std::vector<const BenchRun*>& runs,
                const std::function<double(const BenchRun&)>& field) {
  std::vector<double> values;
  for (const BenchRun* r : runs) values.push_back(field(*r));
  return eval::computeStats(values).median;
}

/// One table: a row per mode, a column per sequence, `cell` formats the runs of one pair.
void table(std::ostream& out, const BenchSetup& setup, const std::vector<BenchRun>& runs,
           const std::function<std::string(const std::vector<const BenchRun*>&)>& cell) {
  out << "| mode |";
  for (const auto& s : setup.sequences) out << " " << s << " |";
  out << "\n|---|";
  for (size_t k = 0; k < setup.sequences.size(); ++k) out << "---:|";
  out << "\n";
  for (const auto& mode : setup.modes) {
    out << "| " << mode << " |";
    for (const auto& s : setup.sequences) out << " " << cell(select(runs, mode, s)) << " |";
    out << "\n";
  }
}

}  // namespace

bool tracked(const BenchRun& run, const BenchSetup& setup) {
  return run.evaluated && run.coverage >= setup.min_coverage;
}

std::string resultsMarkdown(const BenchSetup& setup, const std::vector<BenchRun>& runs) {
  std::ostringstream out;
  out << "# rpvio-bench results\n\n"
      << "Suite `" << setup.suite_dir << "`, " << setup.runs << " run(s) per pair, " << setup.jobs
      << " parallel job(s), wall time " << number(setup.wall_s / 60, 1) << " min.\n\n"
      << "## ATE RMSE (m), median of " << setup.runs << " run(s)\n\n"
      << "SE(3) alignment of the whole estimate to the ground truth. X: tracking lost (coverage < "
      << number(100 * setup.min_coverage, 0) << "% of the sequence, or the run failed).\n\n";
  table(out, setup, runs, [&](const std::vector<const BenchRun*>& pair) -> std::string {
    if (pair.empty()) return "-";
    std::vector<const BenchRun*> ok;
    for (const BenchRun* r : pair)
      if (tracked(*r, setup)) ok.push_back(r);
    if (ok.size() * 2 <= pair.size()) return "X";
    return number(medianOf(ok, [](const BenchRun& r) { return r.ate_rmse; }), 3);
  });
  out << "| paper RP-VIO |";
  for (const auto& s : setup.sequences) {
    const auto it = std::find_if(kPaperRpvio.begin(), kPaperRpvio.end(),
                                 [&](const auto& p) { return p.first == s; });
    out << " " << (it == kPaperRpvio.end() ? "-" : number(it->second, 2)) << " |";
  }
  out << "\n| moving things (median % of the image) |";
  for (const auto& s : setup.sequences) {
    const auto it = setup.dynamic_fraction.find(s);
    const bool known = it != setup.dynamic_fraction.end() && std::isfinite(it->second);
    out << " " << (known ? number(100 * it->second, 1) : "-") << " |";
  }
  out << "\n\n## Coverage (% of the sequence with a pose), median\n\n";
  table(out, setup, runs, [&](const std::vector<const BenchRun*>& pair) -> std::string {
    if (pair.empty()) return "-";
    return number(100 * medianOf(pair, [](const BenchRun& r) { return r.coverage; }), 0);
  });
  out << "\n## ATE RMSE (m) after the batch refinement, median\n\n"
      << "The keyframes of `trajectory_refined.tum` (one bundle adjustment over the whole run, at "
         "its end), same alignment, tracked runs only. -: no refinement.\n\n";
  table(out, setup, runs, [&](const std::vector<const BenchRun*>& pair) -> std::string {
    std::vector<const BenchRun*> refined;
    for (const BenchRun* r : pair)
      if (tracked(*r, setup) && r->refined_ate_rmse >= 0) refined.push_back(r);
    if (refined.empty()) return "-";
    return number(medianOf(refined, [](const BenchRun& r) { return r.refined_ate_rmse; }), 4);
  });
  out << "\n## Timing per frame (ms), medians over the mode's runs\n\n"
      << "Wall-clock per frame on one core: image decoding (the PNG files of image and mask), "
         "front-end, estimator; processing = front-end + estimator; total = all of it";
  if (setup.jobs > 1) out << ". Measured with " << setup.jobs << " runs in parallel";
  out << ".\n\n| mode | decoding median | front-end median | front-end p95 | optimization median "
         "| optimization p95 | processing median | processing p95 | total median | total p95 "
         "| real-time factor | peak memory (MB) |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& mode : setup.modes) {
    const auto pair = select(runs, mode, "");
    auto m = [&](double BenchRun::*field, int decimals) {
      return number(medianOf(pair, [&](const BenchRun& r) { return r.*field; }), decimals);
    };
    out << "| " << mode << " | " << m(&BenchRun::load_ms_median, 1) << " | "
        << m(&BenchRun::frontend_ms_median, 1) << " | " << m(&BenchRun::frontend_ms_p95, 1) << " | "
        << m(&BenchRun::optimization_ms_median, 1) << " | " << m(&BenchRun::optimization_ms_p95, 1)
        << " | " << m(&BenchRun::processing_ms_median, 1) << " | "
        << m(&BenchRun::processing_ms_p95, 1) << " | " << m(&BenchRun::total_ms_median, 1) << " | "
        << m(&BenchRun::total_ms_p95, 1) << " | " << m(&BenchRun::real_time_factor, 2) << " | "
        << m(&BenchRun::peak_memory_mb, 0) << " |\n";
  }
  std::vector<const BenchRun*> failed;
  for (const BenchRun& r : runs)
    if (!r.evaluated) failed.push_back(&r);
  if (!failed.empty()) {
    out << "\n## Runs without an evaluation\n\n";
    for (const BenchRun* r : failed)
      out << "- " << r->sequence << " " << r->mode << " run " << r->run << ": " << r->error << " (`"
          << r->dir << "`)\n";
  }
  out << "\nPlots: `plots/<sequence>.png` (every mode against the ground truth, top and side "
         "views).\n";
  return out.str();
}

std::string resultsJson(const BenchSetup& setup, const std::vector<BenchRun>& runs) {
  constexpr int kDigits = 10;
  JsonObject dynamic_fraction(kDigits);
  for (const std::string& sequence : setup.sequences) {
    const auto it = setup.dynamic_fraction.find(sequence);
    dynamic_fraction.number(sequence, it != setup.dynamic_fraction.end() ? it->second : NAN);
  }
  std::vector<JsonObject> run_objects;
  for (const BenchRun& r : runs)
    run_objects.push_back(JsonObject(kDigits)
                              .text("sequence", r.sequence)
                              .text("mode", r.mode)
                              .integer("run", r.run)
                              .text("dir", r.dir)
                              .integer("exit_code", r.exit_code)
                              .flag("evaluated", r.evaluated)
                              .flag("tracked", tracked(r, setup))
                              .text("error", r.error)
                              .number("ate_rmse", r.ate_rmse)
                              .number("ate_rotation_deg", r.ate_rotation_deg)
                              .number("coverage", r.coverage)
                              .number("refined_ate_rmse", r.refined_ate_rmse)
                              .stamp("initialized_at", r.initialized_at)
                              .integer("resets", r.resets)
                              .number("frontend_ms_median", r.frontend_ms_median)
                              .number("frontend_ms_p95", r.frontend_ms_p95)
                              .number("optimization_ms_median", r.optimization_ms_median)
                              .number("optimization_ms_p95", r.optimization_ms_p95)
                              .number("total_ms_median", r.total_ms_median)
                              .number("total_ms_p95", r.total_ms_p95)
                              .number("load_ms_median", r.load_ms_median)
                              .number("processing_ms_median", r.processing_ms_median)
                              .number("processing_ms_p95", r.processing_ms_p95)
                              .number("real_time_factor", r.real_time_factor)
                              .number("peak_memory_mb", r.peak_memory_mb)
                              .number("wall_s", r.wall_s));
  return JsonObject(kDigits)
      .text("suite", setup.suite_dir)
      .integer("runs_per_pair", setup.runs)
      .integer("jobs", setup.jobs)
      .number("wall_s", setup.wall_s)
      .number("min_coverage", setup.min_coverage)
      .object("dynamic_fraction_median", dynamic_fraction)
      .objects("runs", run_objects)
      .str();
}

}  // namespace rpvio::apps
