#pragma once
// Reading the `render:` map of a scene file (config.cpp). It exposes YAML, so only the config
// layer includes it; the rest of the code sees the plain RenderSettings.
#include "scene/render_settings.hpp"
#include "scene/yaml_reader.hpp"

namespace fissure {

RenderSettings read_render_settings(const YamlReader& r, const YAML::Node& node);

}  // namespace fissure
