#include "scene/study_config.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "core/error.hpp"
#include "scene/config_file.hpp"
#include "scene/yaml_reader.hpp"

namespace fissure {

namespace {

namespace fs = std::filesystem;

std::string relative_to(const std::string& study_file, const std::string& path) {
  if (fs::path(path).is_absolute()) return path;
  return (fs::path(study_file).parent_path() / path).lexically_normal().string();
}

// Adaptive runs (arkode without fixed_step) stop on every frame time by themselves; fixed-step
// ones get a dt that divides the compare interval.
bool adaptive(const YamlReader& r, const YAML::Node& integrator, const std::string& path) {
  const bool fixed_step =
      integrator["fixed_step"] && r.boolean(integrator["fixed_step"], join(path, "fixed_step"));
  return r.string(integrator["type"], join(path, "type")) == "arkode" && !fixed_step;
}

// The integrator block as a --set override of the whole `integrator` key (flow YAML).
std::string integrator_override(const YamlReader& r, const YAML::Node& node,
                                const std::string& path) {
  r.require_map(node, path);
  if (!node["type"]) r.fail(join(path, "type"), "missing: name the integrator type");
  YAML::Emitter out;
  out << YAML::Flow << node;
  return std::string("integrator=") + out.c_str();
}

// A dt or rtol list; with `allow_auto`, an entry `auto` (the scene's stable estimate) is 0.
std::vector<double> sweep_values(const YamlReader& r, const YAML::Node& node,
                                 const std::string& path, bool allow_auto) {
  if (!node.IsSequence() || node.size() == 0)
    r.fail(path, allow_auto ? "expected a non-empty list of positive numbers or auto"
                            : "expected a non-empty list of positive numbers");
  std::vector<double> values;
  for (std::size_t k = 0; k < node.size(); ++k) {
    if (allow_auto && node[k].IsScalar() && node[k].Scalar() == "auto")
      values.push_back(0);
    else
      values.push_back(r.positive(node[k], fmt::format("{}[{}]", path, k)));
  }
  return values;
}

}  // namespace

StudyConfig load_study(const std::string& path, const std::vector<std::string>& overrides) {
  const YamlReader r(path);
  YAML::Node root = load_yaml_with_base(path);
  for (const auto& assignment : overrides) apply_override(root, assignment, path);
  r.check_keys(root, "", {"scene", "set", "every", "reference", "runs", "output", "target"});
  StudyConfig c;
  c.file = path;
  if (!root["scene"]) r.fail("scene", "missing: the scene file to study");
  c.scene = relative_to(path, r.string(root["scene"], "scene"));
  if (const auto set = root["set"]) {
    if (!set.IsSequence()) r.fail("set", "expected a list of key.path=value strings");
    for (std::size_t k = 0; k < set.size(); ++k)
      c.scene_set.push_back(r.string(set[k], fmt::format("set[{}]", k)));
  }
  if (root["every"]) c.every = r.positive(root["every"], "every");
  const std::string stem = fs::path(path).stem().string();
  c.output_dir = "out/study_" + stem;
  if (const auto out = root["output"]) {
    r.check_keys(out, "output", {"dir"});
    if (out["dir"]) c.output_dir = r.string(out["dir"], "output.dir");
  }

  const YAML::Node reference = root["reference"];
  if (!reference)
    r.fail("reference", "missing: {integrator: {...}, dt: ...} or {probes: file.csv}");
  r.check_keys(reference, "reference", {"integrator", "dt", "probes"});
  if (reference["probes"]) {
    if (reference["integrator"])
      r.fail("reference", "give either an integrator run or a probes CSV, not both");
    c.reference_is_run = false;
    c.reference_probes = relative_to(path, r.string(reference["probes"], "reference.probes"));
  } else {
    if (!reference["integrator"]) r.fail("reference.integrator", "missing");
    c.reference_run.run = "reference";
    c.reference_run.overrides.push_back(
        integrator_override(r, reference["integrator"], "reference.integrator"));
    if (reference["dt"]) {
      c.reference_run.parameter = "dt";
      const YAML::Node dt = reference["dt"];
      c.reference_run.value =
          dt.IsScalar() && dt.Scalar() == "auto" ? 0 : r.positive(dt, "reference.dt");
    } else if (!adaptive(r, reference["integrator"], "reference.integrator")) {
      r.fail("reference.dt", "missing: a fixed-step reference needs its step");
    }
  }

  const YAML::Node runs = root["runs"];
  if (!runs || !runs.IsSequence() || runs.size() == 0)
    r.fail("runs", "expected a non-empty list of {name, integrator, dt or rtol}");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string p = fmt::format("runs[{}]", i);
    const YAML::Node run = runs[i];
    r.check_keys(run, p, {"name", "integrator", "dt", "rtol"});
    if (!run["name"]) r.fail(join(p, "name"), "missing");
    const std::string name = r.string(run["name"], join(p, "name"));
    if (name.empty() ||
        name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                               "0123456789_-") != std::string::npos)
      r.fail(join(p, "name"), "use letters, digits, '_' and '-' only (it names folders)");
    for (const auto& other : c.points)
      if (other.run == name) r.fail(join(p, "name"), "duplicate run name");
    if (!run["integrator"]) r.fail(join(p, "integrator"), "missing");
    const std::string integrator = integrator_override(r, run["integrator"], join(p, "integrator"));
    if (run["dt"] && run["rtol"]) r.fail(p, "sweep either dt or rtol, not both");
    if (!run["dt"] && !run["rtol"]) r.fail(p, "missing: a dt or rtol list to sweep");
    const std::string parameter = run["dt"] ? "dt" : "rtol";
    if (parameter == "rtol" && !adaptive(r, run["integrator"], join(p, "integrator")))
      r.fail(join(p, "rtol"),
             "an rtol sweep needs an adaptive integrator (arkode without "
             "fixed_step); sweep dt instead");
    for (double value : sweep_values(r, run[parameter], join(p, parameter), parameter == "dt")) {
      StudyPoint point{name, parameter, value, {integrator}};
      if (parameter == "rtol") {
        point.overrides.push_back(fmt::format("integrator.rtol={:.17g}", value));
        if (!run["integrator"]["atol"])
          point.overrides.push_back(fmt::format("integrator.atol={:.17g}", 1e-3 * value));
      }
      c.points.push_back(point);
    }
  }
  if (const auto target = root["target"]) {
    r.check_keys(target, "target", {"probe_error", "baseline"});
    if (!target["probe_error"])
      r.fail("target.probe_error", "missing: e.g. 0.01 (1% of the amplitude)");
    c.target_error = r.positive(target["probe_error"], "target.probe_error");
    if (!target["baseline"])
      r.fail("target.baseline", "missing: the name of the run to compare with");
    c.target_baseline = r.string(target["baseline"], "target.baseline");
    bool found = c.target_baseline == "reference" && c.reference_is_run;
    for (const auto& point : c.points) found = found || point.run == c.target_baseline;
    if (!found) r.fail("target.baseline", fmt::format("no run is named '{}'", c.target_baseline));
  }
  return c;
}

}  // namespace fissure
