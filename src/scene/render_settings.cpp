#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "scene/config.hpp"
#include "scene/render_settings_reader.hpp"

namespace fissure {

namespace {

std::string one_of(const YamlReader& r, const YAML::Node& node, const std::string& path,
                   const std::vector<std::string>& valid) {
  const std::string value = r.string(node, path);
  if (std::find(valid.begin(), valid.end(), value) == valid.end())
    r.fail(path, fmt::format("unknown value '{}' (valid: {})", value, fmt::join(valid, ", ")));
  return value;
}

int positive_int(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  const double v = r.positive(node, path);
  if (v != std::floor(v) || v > 1e5)
    r.fail(path, fmt::format("expected a whole number, got {}", v));
  return static_cast<int>(v);
}

}  // namespace

RenderSettings read_render_settings(const YamlReader& r, const YAML::Node& node) {
  r.check_keys(node, "render",
               {"field", "camera", "width", "height", "range", "radius", "every", "animation",
                "fps", "show"});
  RenderSettings s;
  if (node["field"])
    s.field = one_of(r, node["field"], "render.field",
                     {"damage", "velocity", "displacement", "dilatation"});
  if (const auto camera = node["camera"]) {
    r.check_keys(camera, "render.camera", {"position", "look_at", "angle"});
    if (camera["position"] || camera["look_at"]) {
      if (!camera["position"] || !camera["look_at"])
        r.fail("render.camera", "give both position and look_at");
      s.camera_given = true;
      s.camera_position = r.vec3(camera["position"], "render.camera.position");
      s.look_at = r.vec3(camera["look_at"], "render.camera.look_at");
      if (s.camera_position == s.look_at)
        r.fail("render.camera.look_at", "must differ from the camera position");
    }
    if (camera["angle"]) {
      s.view_angle = r.positive(camera["angle"], "render.camera.angle");
      if (s.view_angle >= 180) r.fail("render.camera.angle", "must be below 180 degrees");
    }
  }
  if (node["width"]) s.width = positive_int(r, node["width"], "render.width");
  if (node["height"]) s.height = positive_int(r, node["height"], "render.height");
  if (const auto range = node["range"]) {
    if (!range.IsSequence() || range.size() != 2) r.fail("render.range", "expected [min, max]");
    s.range_given = true;
    s.range_min = r.number(range[0], "render.range[0]");
    s.range_max = r.number(range[1], "render.range[1]");
    if (s.range_max <= s.range_min) r.fail("render.range", "max must exceed min");
  }
  if (node["radius"]) s.particle_radius = r.positive(node["radius"], "render.radius");
  if (node["every"]) s.every = positive_int(r, node["every"], "render.every");
  if (node["animation"])
    s.animation = one_of(r, node["animation"], "render.animation", {"gif", "mp4", "none"});
  if (node["fps"]) s.fps = r.positive(node["fps"], "render.fps");
  if (node["show"])
    s.show = one_of(r, node["show"], "render.show", {"auto", "particles", "surface"});
  return s;
}

RenderSettings load_render_settings(const std::string& config_path,
                                    const std::vector<std::string>& overrides) {
  if (!config_path.empty()) return load_config(config_path, overrides).render;
  const std::string source = "command line";
  YAML::Node root(YAML::NodeType::Map);
  for (const auto& assignment : overrides) apply_override(root, assignment, source);
  const YamlReader r(source);
  r.check_keys(root, "", {"render"});
  return root["render"] ? read_render_settings(r, root["render"]) : RenderSettings{};
}

}  // namespace fissure
