#include "study/study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "app/simulation.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/external_program.hpp"
#include "model/model.hpp"
#include "scene/config.hpp"
#include "scene/scene.hpp"
#include "scene/study_config.hpp"
#include "study/plot_script.hpp"
#include "study/study_errors.hpp"

namespace fissure {

namespace {

namespace fs = std::filesystem;

struct StudyRow {
  StudyPoint point;
  std::string status = "ok";  // ok | refused (bad input, e.g. dt above the limit) | failed
  std::string message;
  double dt = 0;
  RunSummary summary;
  StudyError error;
};

double statistic(const RunSummary& s, const char* name) {
  for (const auto& [key, value] : s.integrator_statistics)
    if (key == name) return value;
  return std::numeric_limits<double>::quiet_NaN();
}

std::string cell(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : ""; }

std::string folder_name(const StudyPoint& p) {
  return p.parameter.empty() ? p.run : fmt::format("{}_{}_{:.3g}", p.run, p.parameter, p.value);
}

// A step that divides the compare interval (so fixed-step frames land on the compare times),
// as close to dt from below as that allows.
double dividing_step(double dt, double interval) {
  return interval / double(steps_to(interval, dt));
}

const char* kColumns =
    "run,parameter,value,dt,status,wall_seconds,step_seconds,steps,force_evaluations,"
    "newton_iterations,linear_solves,factorizations,error_max,error_rms,probe_error,message,"
    "probe_error_amplitude,krylov_iterations,back_solves";

std::vector<std::string> fields(const StudyRow& r) {
  const RunSummary& s = r.summary;
  const bool ran = r.status == "ok";
  return {r.point.run,
          r.point.parameter,
          cell(r.point.value),
          cell(r.dt),
          r.status,
          ran ? cell(s.wall_seconds) : "",
          ran ? cell(s.seconds_per_step * s.steps) : "",
          ran ? std::to_string(s.steps) : "",
          ran ? std::to_string(s.force_evaluations) : "",
          ran ? cell(statistic(s, "newton_iterations")) : "",
          ran ? cell(statistic(s, "linear_solves")) : "",
          ran ? cell(statistic(s, "factorizations")) : "",
          cell(r.error.max),
          cell(r.error.rms),
          cell(r.error.probe),
          r.message,
          cell(r.error.probe_amplitude),
          ran ? cell(statistic(s, "krylov_iterations")) : "",
          ran ? cell(statistic(s, "back_solves")) : ""};
}

std::string csv_quoted(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

void write_results(const std::string& folder, const std::vector<StudyRow>& rows,
                   const std::string& target) {
  write_atomically(folder + "/results.csv", [&](std::ostream& out) {
    out << kColumns << "\n";
    for (const auto& r : rows) {
      const auto f = fields(r);
      for (std::size_t k = 0; k < f.size(); ++k) out << (k ? "," : "") << csv_quoted(f[k]);
      out << "\n";
    }
  });
  write_atomically(folder + "/results.md", [&](std::ostream& out) {
    out << "| run | parameter | value | dt | status | wall s | stepping s | steps | force evals | "
           "Newton its | linear solves | factorizations | max err/d | RMS err/d | probe err/d | "
           "probe err/amplitude | Krylov its | back-solves |\n"
        << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
      auto f = fields(r);
      f.erase(f.begin() + 15);  // the message goes below the table
      out << "|";
      for (const auto& v : f) out << " " << v << " |";
      out << "\n";
    }
    out << target;
    for (const auto& r : rows)
      if (!r.message.empty())
        out << fmt::format("\n- {} {} = {}: {}\n", r.point.run, r.point.parameter,
                           cell(r.point.value), r.message);
  });
}

// The scene with the study's overrides, this point's, and the output the errors need.
Config point_config(const StudyConfig& study, const StudyPoint& point, double interval,
                    const std::string& dir, double dt) {
  std::vector<std::string> overrides = study.scene_set;
  overrides.insert(overrides.end(), point.overrides.begin(), point.overrides.end());
  overrides.push_back(fmt::format("output.every={:.17g}", interval));
  overrides.push_back(fmt::format("output.probe_every={:.17g}", interval));
  overrides.push_back("output.surface=false");
  overrides.push_back("output.tets=false");
  if (dt > 0) overrides.push_back(fmt::format("time.dt={:.17g}", dt));
  Config c = load_config(study.scene, overrides);
  c.output.dir = dir;
  return c;
}

// dt: auto of a run: the scene's safety × the stable estimate, rounded down to divide the
// compare interval.
double auto_step(const StudyConfig& study, const StudyPoint& point, double interval) {
  std::vector<std::string> overrides = study.scene_set;
  overrides.insert(overrides.end(), point.overrides.begin(), point.overrides.end());
  const Config c = load_config(study.scene, overrides);
  const Scene scene = build_scene(c);
  const double stable = make_model(scene)->stable_time_step();
  return dividing_step(c.time.safety * stable, interval);
}

// For each run, its fastest point within the target, side by side with the baseline's first
// point: what the target accuracy costs in stepping time.
std::string target_summary(const StudyConfig& study, const std::vector<StudyRow>& rows) {
  auto seconds = [](const StudyRow& r) { return r.summary.seconds_per_step * r.summary.steps; };
  const StudyRow* baseline = nullptr;
  for (const auto& r : rows)
    if (r.point.run == study.target_baseline && r.status == "ok") {
      baseline = &r;
      break;
    }
  std::string text = fmt::format(
      "\nFastest point of each run whose probe error stays within {:g} of the amplitude, against "
      "{}:\n\n| run | dt | probe err/amplitude | stepping s | steps | speed-up over {} |\n"
      "|---|---|---|---|---|---|\n",
      study.target_error, study.target_baseline, study.target_baseline);
  std::vector<std::string> names;
  for (const auto& r : rows)
    if (std::find(names.begin(), names.end(), r.point.run) == names.end())
      names.push_back(r.point.run);
  for (const auto& name : names) {
    const StudyRow* best = nullptr;
    for (const auto& r : rows)
      if (r.point.run == name && r.status == "ok" &&
          r.error.probe_amplitude <= study.target_error && (!best || seconds(r) < seconds(*best)))
        best = &r;
    if (name == study.target_baseline && baseline) best = baseline;
    if (!best) {
      text += fmt::format("| {} | none within the target | | | | |\n", name);
      continue;
    }
    text += fmt::format("| {} | {:.4g} | {:.3g} | {:.3g} | {} | {} |\n", name, best->dt,
                        best->error.probe_amplitude, seconds(*best), best->summary.steps,
                        baseline ? fmt::format("{:.2f}", seconds(*baseline) / seconds(*best)) : "");
  }
  return text;
}

bool make_plot(const std::string& folder) {
  // Debian's interpreter, where python3-matplotlib installs, before whatever python3 comes
  // first on PATH (e.g. a pyenv shim without matplotlib).
  const std::string python =
      fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : find_program("python3");
  if (python.empty()) {
    fmt::print(stderr,
               "warning: python3 not found: no work-precision plot (scripts/setup "
               "installs python3-matplotlib)\n");
    return false;
  }
  write_atomically(folder + "/plot_study.py", [](std::ostream& out) { out << kPlotScript; });
  const int status = run_program({python, "plot_study.py", "results.csv", "work_precision"}, folder,
                                 folder + "/plot.log");
  if (status != 0)
    fmt::print(stderr,
               "warning: the plot script failed (exit {}), see {}/plot.log; is "
               "python3-matplotlib installed?\n",
               status, folder);
  return status == 0;
}

}  // namespace

StudyOutcome run_study(const StudyConfig& study, bool progress) {
  const Config scene = load_config(study.scene, study.scene_set);
  const double end = scene.time.end;
  const double interval = study.every > 0 ? study.every : end;
  const long compares = std::lround(end / interval);
  if (std::abs(compares * interval - end) > 1e-9 * end)
    throw InputError(study.file, "every",
                     fmt::format("must divide the scene's time.end = {:.6g} s", end));
  std::vector<double> times;
  for (long k = 1; k <= compares; ++k) times.push_back(k * interval);

  StudyOutcome outcome;
  outcome.folder = study.output_dir;
  fs::create_directories(study.output_dir);
  const std::string runs_dir = study.output_dir + "/runs";

  std::string reference_dir;
  StudyRow reference_row;  // the reference run, a baseline for target: {baseline: reference}
  ProbePositions reference_probes;
  double diagonal = 0;
  if (study.reference_is_run) {
    reference_dir = study.output_dir + "/reference";
    const StudyPoint& ref = study.reference_run;
    double dt = ref.parameter == "dt" ? dividing_step(ref.value, interval) : 0;
    if (ref.parameter == "dt" && ref.value == 0) dt = auto_step(study, ref, interval);
    if (progress) fmt::print(stderr, "study: reference run into {}\n", reference_dir);
    const Config c = point_config(study, ref, interval, reference_dir, dt);
    RunOptions options;
    options.progress = progress;
    reference_row.point = ref;
    reference_row.summary = run_simulation(c, options);
    reference_row.dt = reference_row.summary.dt;
    reference_row.error.probe_amplitude = 0;
    reference_probes = read_probe_positions(reference_dir + "/probes.csv");
    diagonal = frame_diagonal(reference_dir);
  } else {
    reference_probes = read_probe_positions(study.reference_probes);
  }

  std::vector<StudyRow> rows;
  for (const StudyPoint& point : study.points) {
    StudyRow row;
    row.point = point;
    const std::string dir = runs_dir + "/" + folder_name(point);
    row.dt = point.parameter == "dt" ? dividing_step(point.value, interval) : 0;
    if (point.parameter == "dt" && point.value == 0) row.dt = auto_step(study, point, interval);
    if (progress)
      fmt::print(stderr, "study: {} {} = {:.3g}\n", point.run, point.parameter, point.value);
    try {
      const Config c = point_config(study, point, interval, dir, row.dt);
      RunOptions options;
      options.progress = progress;
      row.summary = run_simulation(c, options);
      row.dt = row.summary.dt;
      if (diagonal == 0) diagonal = frame_diagonal(dir);
      row.error = study_error(dir, reference_dir, reference_probes, times, diagonal);
    } catch (const InputError& e) {
      row.status = "refused";
      row.message = e.what();
    } catch (const RunError& e) {
      row.status = "failed";
      row.message = e.what();
    }
    if (row.status != "ok") ++outcome.failed;
    ++outcome.runs;
    fmt::print("{} {}={:.3g}: {}{}\n", point.run, point.parameter, point.value, row.status,
               row.status == "ok"
                   ? fmt::format(", max error/d {:.3g}, {:.3g} s stepping", row.error.max,
                                 row.summary.seconds_per_step * row.summary.steps)
                   : ": " + row.message);
    std::fflush(stdout);
    rows.push_back(row);
    write_results(study.output_dir, rows, "");
  }
  if (study.target_error > 0) {
    std::vector<StudyRow> candidates = rows;
    if (study.target_baseline == "reference") candidates.insert(candidates.begin(), reference_row);
    const std::string verdict = target_summary(study, candidates);
    fmt::print("{}", verdict);
    write_results(study.output_dir, rows, verdict);
  }
  outcome.plotted = make_plot(study.output_dir);
  return outcome;
}

}  // namespace fissure
