#include "scene/config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "scene/config_file.hpp"
#include "scene/option_reader.hpp"
#include "scene/render_settings_reader.hpp"
#include "scene/yaml_reader.hpp"

namespace fissure {

bool Config::fracture_enabled() const {
  for (const Body& b : bodies)
    if (b.material.fracture.enabled) return true;
  return !initial_cracks.empty();
}

bool Config::plasticity_enabled() const {
  for (const Body& b : bodies)
    if (b.material.plasticity.enabled) return true;
  return false;
}

bool Config::anisotropy_enabled() const {
  for (const Body& b : bodies)
    if (b.material.anisotropy.enabled) return true;
  return false;
}

bool Region::contains(const double* p) const {
  if (kind == Kind::box)
    return p[0] >= min[0] && p[0] <= max[0] && p[1] >= min[1] && p[1] <= max[1] && p[2] >= min[2] &&
           p[2] <= max[2];
  const double dx = p[0] - center[0], dy = p[1] - center[1], dz = p[2] - center[2];
  return dx * dx + dy * dy + dz * dz <= radius * radius;
}

namespace {

std::string indexed(const std::string& path, std::size_t i) {
  return fmt::format("{}[{}]", path, i);
}

void check_box(const YamlReader& r, const Vec3& min, const Vec3& max, const std::string& path) {
  for (int k = 0; k < 3; ++k)
    if (max[k] <= min[k]) r.fail(join(path, "max"), "each component of max must exceed min");
}

Region read_region(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  r.check_keys(node, path, {"box", "sphere"});
  if (node.size() != 1) r.fail(path, "give exactly one of box, sphere");
  Region region;
  if (node["box"]) {
    const std::string p = join(path, "box");
    r.check_keys(node["box"], p, {"min", "max"});
    region.kind = Region::Kind::box;
    region.min = r.vec3(node["box"]["min"], join(p, "min"));
    region.max = r.vec3(node["box"]["max"], join(p, "max"));
    check_box(r, region.min, region.max, p);
  } else {
    const std::string p = join(path, "sphere");
    r.check_keys(node["sphere"], p, {"center", "radius"});
    region.kind = Region::Kind::sphere;
    region.center = r.vec3(node["sphere"]["center"], join(p, "center"));
    region.radius = r.positive(node["sphere"]["radius"], join(p, "radius"));
  }
  return region;
}

std::string resolve(const std::string& config_file, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute() || config_file.empty()) return path;
  return (std::filesystem::path(config_file).parent_path() / p).lexically_normal().string();
}

Geometry read_geometry(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  const std::vector<std::string> kinds = {"box", "sphere", "cylinder", "mesh", "points"};
  r.check_keys(node, path, kinds);
  if (node.size() != 1) r.fail(path, "give exactly one of box, sphere, cylinder, mesh, points");
  Geometry g;
  if (const auto n = node["box"]) {
    const std::string p = join(path, "box");
    r.check_keys(n, p, {"min", "max"});
    g.kind = Geometry::Kind::box;
    g.min = r.vec3(n["min"], join(p, "min"));
    g.max = r.vec3(n["max"], join(p, "max"));
    check_box(r, g.min, g.max, p);
  } else if (const auto n = node["sphere"]) {
    const std::string p = join(path, "sphere");
    r.check_keys(n, p, {"center", "radius"});
    g.kind = Geometry::Kind::sphere;
    g.center = r.vec3(n["center"], join(p, "center"));
    g.radius = r.positive(n["radius"], join(p, "radius"));
  } else if (const auto n = node["cylinder"]) {
    const std::string p = join(path, "cylinder");
    r.check_keys(n, p, {"p0", "p1", "radius"});
    g.kind = Geometry::Kind::cylinder;
    g.p0 = r.vec3(n["p0"], join(p, "p0"));
    g.p1 = r.vec3(n["p1"], join(p, "p1"));
    g.radius = r.positive(n["radius"], join(p, "radius"));
    if (g.p0 == g.p1) r.fail(join(p, "p1"), "the axis end points p0 and p1 coincide");
  } else {
    const bool mesh = static_cast<bool>(node["mesh"]);
    const std::string p = join(path, mesh ? "mesh" : "points");
    const YAML::Node entry = node[mesh ? "mesh" : "points"];
    r.check_keys(entry, p, {"file", "scale", "translate"});
    g.kind = mesh ? Geometry::Kind::mesh : Geometry::Kind::points;
    g.file = resolve(r.file(), r.string(entry["file"], join(p, "file")));
    if (entry["scale"]) g.scale = r.positive(entry["scale"], join(p, "scale"));
    if (entry["translate"]) g.translate = r.vec3(entry["translate"], join(p, "translate"));
  }
  return g;
}

FractureSettings read_fracture(const YamlReader& r, const YAML::Node& node,
                               const std::string& path) {
  r.check_keys(node, path, {"critical_stretch", "alpha"});
  FractureSettings f;
  f.enabled = true;
  f.critical_stretch = r.positive(node["critical_stretch"], join(path, "critical_stretch"));
  if (node["alpha"]) f.alpha = r.non_negative(node["alpha"], join(path, "alpha"));
  return f;
}

Crack read_crack(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  r.check_keys(node, path, {"plane", "box"});
  if (node.size() != 1) r.fail(path, "give exactly one of plane, box");
  Crack crack;
  if (const auto plane = node["plane"]) {
    const std::string p = join(path, "plane");
    r.check_keys(plane, p, {"point", "normal", "region"});
    crack.kind = Crack::Kind::plane;
    crack.point = r.vec3(plane["point"], join(p, "point"));
    crack.normal = r.vec3(plane["normal"], join(p, "normal"));
    if (crack.normal == Vec3{0, 0, 0}) r.fail(join(p, "normal"), "must not be zero");
    if (plane["region"]) {
      crack.bounded = true;
      crack.region = read_region(r, plane["region"], join(p, "region"));
    }
  } else {
    crack.kind = Crack::Kind::box;
    YAML::Node wrapped;
    wrapped["box"] = node["box"];
    crack.region = read_region(r, wrapped, path);
  }
  return crack;
}

PlasticitySettings read_plasticity(const YamlReader& r, const YAML::Node& node,
                                   const std::string& path) {
  r.check_keys(node, path, {"yield", "yield_stress", "max_plastic_stretch"});
  PlasticitySettings p;
  p.enabled = true;
  if (static_cast<bool>(node["yield"]) == static_cast<bool>(node["yield_stress"]))
    r.fail(path, "give either yield (Ψ0 of the paper's Eq 13) or yield_stress (Pa)");
  if (node["yield"]) p.yield = r.positive(node["yield"], join(path, "yield"));
  if (node["yield_stress"])
    p.yield_stress = r.positive(node["yield_stress"], join(path, "yield_stress"));
  if (node["max_plastic_stretch"])
    p.max_plastic_stretch =
        r.positive(node["max_plastic_stretch"], join(path, "max_plastic_stretch"));
  return p;
}

AnisotropySettings read_anisotropy(const YamlReader& r, const YAML::Node& node,
                                   const std::string& path) {
  r.check_keys(node, path, {"G", "direction", "ratio"});
  AnisotropySettings a;
  a.enabled = true;
  if (const auto g = node["G"]) {
    if (node["direction"] || node["ratio"]) r.fail(path, "give either G or direction and ratio");
    const std::string p = join(path, "G");
    if (!g.IsSequence() || g.size() != 3) r.fail(p, "expected a 3×3 matrix [[..], [..], [..]]");
    for (std::size_t row = 0; row < 3; ++row) {
      const auto values = r.vec3(g[row], fmt::format("{}[{}]", p, row));
      for (std::size_t col = 0; col < 3; ++col) a.G[3 * row + col] = values[col];
    }
  } else {
    // G = I + (r − 1) d dᵀ: bonds along d weigh 1/r as much (Eq 17).
    const Vec3 d = r.vec3(node["direction"], join(path, "direction"));
    const double ratio = r.positive(node["ratio"], join(path, "ratio"));
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (length == 0) r.fail(join(path, "direction"), "must not be zero");
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col)
        a.G[3 * row + col] = (row == col) + (ratio - 1) * d[row] * d[col] / (length * length);
  }
  const auto& G = a.G;
  const double det = G[0] * (G[4] * G[8] - G[5] * G[7]) - G[1] * (G[3] * G[8] - G[5] * G[6]) +
                     G[2] * (G[3] * G[7] - G[4] * G[6]);
  if (!(std::abs(det) > 1e-12)) r.fail(path, "G must be invertible");
  return a;
}

// A colliders entry: exactly one shape key, which the shape's registered parser reads
// (contact/collider_registry.hpp), and the keys every shape shares, as far as the shape allows.
Collider read_collider(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  const auto& shapes = collider_option_parsers();
  std::vector<std::string> allowed;
  for (const auto& shape : shapes) allowed.push_back(shape.name);
  std::vector<std::string> names = allowed;
  allowed.insert(allowed.end(), {"velocity", "mass"});
  r.check_keys(node, path, allowed);
  const ColliderOptionParser* parser = nullptr;
  int given = 0;
  for (const auto& shape : shapes)
    if (node[shape.name]) ++given, parser = &shape;
  if (given != 1) r.fail(path, fmt::format("give exactly one of {}", fmt::join(names, ", ")));
  Collider c;
  c.shape = parser->name;
  const std::string p = join(path, parser->name);
  const YAML::Node own = node[parser->name];
  r.check_keys(own, p, parser->keys);
  c.options = parser->parse ? parser->parse(OptionReader(r, own, p))
                            : std::make_shared<const ColliderOptions>();
  if (node["velocity"]) {
    if (!c.options->moves()) r.fail(join(path, "velocity"), "a " + c.shape + " does not move");
    c.velocity = r.vec3(node["velocity"], join(path, "velocity"));
  }
  if (const auto m = node["mass"]) {
    if (!c.options->can_be_dynamic()) r.fail(join(path, "mass"), "only a sphere can be dynamic");
    if (!(m.IsScalar() && m.Scalar() == "kinematic")) {
      c.kinematic = false;
      c.mass = r.positive(m, join(path, "mass"));
    }
  }
  return c;
}

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t k = 0; k < names.size(); ++k)
    text += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  return text;
}

template <class Options>
const OptionParser<Options>* find_parser(const std::vector<OptionParser<Options>>& parsers,
                                         const std::string& type) {
  for (const auto& p : parsers)
    if (p.name == type) return &p;
  return nullptr;
}

// The keys of the map at `path` for a part of type `type` (scene/option_parsers.hpp): a key of
// other registered types fails naming them (a key of one type before a key several share),
// then any key neither in `shared` nor the type's own.
template <class Options>
void check_part_keys(const YamlReader& r, const YAML::Node& node, const std::string& path,
                     const std::string& type, std::vector<std::string> shared,
                     const std::vector<OptionParser<Options>>& parsers) {
  std::vector<std::pair<std::string, std::vector<std::string>>> owners;
  for (const auto& p : parsers)
    for (const auto& key : p.keys) {
      auto it = std::find_if(owners.begin(), owners.end(), [&](auto& o) { return o.first == key; });
      if (it == owners.end()) it = owners.insert(owners.end(), {key, {}});
      it->second.push_back(p.name);
    }
  std::stable_partition(owners.begin(), owners.end(), [](auto& o) { return o.second.size() == 1; });
  for (const auto& [key, names] : owners)
    if (node[key] && std::find(names.begin(), names.end(), type) == names.end())
      r.fail(join(path, key), fmt::format("is an option of {}, not of '{}'", listed(names), type));
  if (const auto* parser = find_parser(parsers, type))
    shared.insert(shared.end(), parser->keys.begin(), parser->keys.end());
  r.check_keys(node, path, shared);
}

// The options of type `type` read by its registered parser, or null (none, or not registered).
template <class Options>
std::shared_ptr<const Options> read_part_options(
    const YamlReader& r, const YAML::Node& node, const std::string& path, const std::string& type,
    const std::vector<OptionParser<Options>>& parsers) {
  const auto* parser = find_parser(parsers, type);
  if (!parser || !parser->parse) return nullptr;
  return parser->parse(OptionReader(r, node, path));
}

Material read_material(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  r.require_map(node, path);
  Material m;
  if (node["model"]) m.model = r.string(node["model"], join(path, "model"));
  check_part_keys(r, node, path, m.model,
                  {"model", "density", "bulk_modulus", "shear_modulus", "surface_correction",
                   "fracture", "plasticity", "anisotropy"},
                  model_option_parsers());
  if (!find_parser(model_option_parsers(), m.model)) {
    std::vector<std::string> names;
    for (const auto& p : model_option_parsers()) names.push_back(p.name);
    r.fail(join(path, "model"),
           fmt::format("unknown model '{}' (valid: {})", m.model, fmt::join(names, ", ")));
  }
  m.density = r.positive(node["density"], join(path, "density"));
  m.bulk_modulus = r.positive(node["bulk_modulus"], join(path, "bulk_modulus"));
  m.shear_modulus = r.positive(node["shear_modulus"], join(path, "shear_modulus"));
  // none | dilatation | full; a YAML boolean, the key's form before `full`, means dilatation or
  // none as it did
  bool corrected = false;
  if (node["surface_correction"] &&
      YAML::convert<bool>::decode(node["surface_correction"], corrected))
    m.surface_correction = corrected ? SurfaceCorrection::dilatation : SurfaceCorrection::none;
  else
    m.surface_correction = OptionReader(r, node, path)
                               .choice("surface_correction", m.surface_correction,
                                       {{"none", SurfaceCorrection::none},
                                        {"dilatation", SurfaceCorrection::dilatation},
                                        {"full", SurfaceCorrection::full},
                                        {"fictitious", SurfaceCorrection::fictitious}});
  if (node["fracture"]) m.fracture = read_fracture(r, node["fracture"], join(path, "fracture"));
  if (node["anisotropy"])
    m.anisotropy = read_anisotropy(r, node["anisotropy"], join(path, "anisotropy"));
  if (node["plasticity"])
    m.plasticity = read_plasticity(r, node["plasticity"], join(path, "plasticity"));
  m.options = read_part_options(r, node, path, m.model, model_option_parsers());
  return m;
}

Body read_body(const YamlReader& r, const YAML::Node& node, const std::string& path,
               std::size_t index) {
  r.check_keys(node, path, {"name", "geometry", "resolution", "horizon", "material", "velocity"});
  Body b;
  b.name = node["name"] ? r.string(node["name"], join(path, "name")) : fmt::format("body{}", index);
  b.geometry = read_geometry(r, node["geometry"], join(path, "geometry"));
  b.resolution = r.positive(node["resolution"], join(path, "resolution"));
  if (node["horizon"]) b.horizon = r.positive(node["horizon"], join(path, "horizon"));
  b.material = read_material(r, node["material"], join(path, "material"));
  if (node["velocity"]) b.velocity = r.vec3(node["velocity"], join(path, "velocity"));
  return b;
}

// A clamped face: {clamp: {point: [x, y, z], normal: [nx, ny, nz]}}, the normal pointing out of
// the body, made a unit vector.
Constraint read_clamp(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  r.check_keys(node, path, {"clamp"});
  const std::string p = join(path, "clamp");
  r.check_keys(node["clamp"], p, {"point", "normal"});
  Constraint c;
  c.clamp = true;
  c.clamp_point = r.vec3(node["clamp"]["point"], join(p, "point"));
  c.clamp_normal = r.vec3(node["clamp"]["normal"], join(p, "normal"));
  const double length =
      std::sqrt(c.clamp_normal[0] * c.clamp_normal[0] + c.clamp_normal[1] * c.clamp_normal[1] +
                c.clamp_normal[2] * c.clamp_normal[2]);
  if (!(length > 0)) r.fail(join(p, "normal"), "must not be zero");
  for (double& n : c.clamp_normal) n /= length;
  return c;
}

Constraint read_constraint(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  if (node.IsMap() && node["clamp"]) return read_clamp(r, node, path);
  r.check_keys(node, path,
               {"region", "fix", "velocity", "angular_velocity", "center", "release_at"});
  Constraint c;
  c.region = read_region(r, node["region"], join(path, "region"));
  if (node["fix"]) c.fix = r.boolean(node["fix"], join(path, "fix"));
  const bool moves = node["velocity"] || node["angular_velocity"];
  if (c.fix == moves)
    r.fail(path, "give either fix: true or velocity: [vx, vy, vz] and/or angular_velocity");
  if (node["velocity"]) c.velocity = r.vec3(node["velocity"], join(path, "velocity"));
  if (node["angular_velocity"]) {
    c.angular_velocity = r.vec3(node["angular_velocity"], join(path, "angular_velocity"));
    if (!node["center"])
      r.fail(join(path, "center"), "missing: a point on the rotation axis, [x, y, z]");
    c.center = r.vec3(node["center"], join(path, "center"));
  } else if (node["center"]) {
    r.fail(join(path, "center"), "only used with angular_velocity");
  }
  if (node["release_at"])
    c.release_at = r.non_negative(node["release_at"], join(path, "release_at"));
  return c;
}

TimeSettings read_time(const YamlReader& r, const YAML::Node& node) {
  r.check_keys(node, "time", {"end", "dt", "safety"});
  TimeSettings t;
  t.end = r.positive(node["end"], "time.end");
  const YAML::Node dt = node["dt"];
  if (!dt || (dt.IsScalar() && dt.Scalar() == "auto")) {
    t.dt_auto = true;
  } else {
    t.dt_auto = false;
    t.dt = r.positive(dt, "time.dt");
  }
  if (node["safety"]) t.safety = r.positive(node["safety"], "time.safety");
  if (t.safety > 1) r.fail("time.safety", fmt::format("must be in (0, 1], got {}", t.safety));
  return t;
}

// The keys every integrator shares; the type's own are its parser's (integrators/registry.hpp).
IntegratorSettings read_integrator(const YamlReader& r, const YAML::Node& node) {
  r.require_map(node, "integrator");
  IntegratorSettings s;
  if (node["type"]) s.type = r.string(node["type"], "integrator.type");
  check_part_keys(r, node, "integrator", s.type,
                  {"type", "allow_unstable_dt", "energy_growth_limit"},
                  integrator_option_parsers());
  if (node["allow_unstable_dt"])
    s.allow_unstable_dt = r.boolean(node["allow_unstable_dt"], "integrator.allow_unstable_dt");
  if (node["energy_growth_limit"])
    s.energy_growth_limit =
        r.non_negative(node["energy_growth_limit"], "integrator.energy_growth_limit");
  s.options = read_part_options(r, node, "integrator", s.type, integrator_option_parsers());
  return s;
}

// A static solve ramps the loads over integrator.steps increments of time.dt: a time.dt that
// reaches time.end in fewer increments would end the run part-way up the ramp.
void check_load_ramp(const YamlReader& r, const TimeSettings& t, const IntegratorSettings& s) {
  const int ramp = s.options ? s.options->load_increments() : 0;
  if (ramp == 0 || t.dt_auto) return;
  // Compared as a ratio first: a time.dt tiny against time.end (more steps than a long holds)
  // passes here and is refused by the run's step limit (app/time_step.cpp).
  if (t.end / t.dt >= ramp) return;
  const long increments = steps_to(t.end, t.dt);
  if (increments >= ramp) return;
  r.fail("time.dt",
         fmt::format("{:.6g} s reaches time.end = {:.6g} s in {} load increment(s), but "
                     "integrator.steps = {} ramps the loads over {} increments: the run would "
                     "end at {:.3g} of the load. Use time.dt: auto (time.end / integrator.steps), "
                     "a time.dt of at most {:.6g} s, or integrator.steps: {}",
                     t.dt, t.end, increments, ramp, ramp, double(increments) / ramp, t.end / ramp,
                     increments));
}

// What surface_correction: fictitious (model/second_order_model.hpp) does not model yet, and the
// clamped faces that only it models, refused with the key that asks for them.
void check_fictitious_particles(const YamlReader& r, const Config& c) {
  const Material& m = c.bodies.front().material;
  const bool fictitious = m.surface_correction == SurfaceCorrection::fictitious;
  for (std::size_t i = 0; i < c.constraints.size(); ++i)
    if (c.constraints[i].clamp && !fictitious)
      r.fail(indexed("constraints", i) + ".clamp",
             "a clamped face needs bodies' material.surface_correction: fictitious (the other "
             "corrections hold particles: use region with fix: true)");
  if (!fictitious) return;
  for (std::size_t i = 0; i < c.bodies.size(); ++i) {
    const std::string path = indexed("bodies", i);
    const Material& b = c.bodies[i].material;
    if (b.model != "lps")
      r.fail(path + ".material.surface_correction", "fictitious needs model: lps");
    if (c.bodies[i].geometry.kind == Geometry::Kind::points)
      r.fail(path + ".geometry",
             "surface_correction: fictitious needs a tet-sampled body (its boundary and cells), "
             "not points");
    if (b.fracture.enabled)
      r.fail(path + ".material.fracture",
             "surface_correction: fictitious has no fracture yet (docs/model.md, deviation 8)");
    if (b.plasticity.enabled)
      r.fail(path + ".material.plasticity",
             "surface_correction: fictitious has no plasticity yet (docs/model.md, deviation 8)");
    if (b.anisotropy.enabled)
      r.fail(path + ".material.anisotropy",
             "surface_correction: fictitious is isotropic only (docs/model.md, deviation 8)");
  }
  if (!c.initial_cracks.empty())
    r.fail("initial_cracks",
           "surface_correction: fictitious has no fracture yet (docs/model.md, deviation 8)");
}

Config read_config(const YamlReader& r, const YAML::Node& root) {
  r.check_keys(root, "",
               {"name", "time", "integrator", "gravity", "bodies", "constraints", "initial_cracks",
                "colliders", "contact", "damping", "probes", "output", "render"});
  Config c;
  c.file = r.file();
  c.source = YAML::Dump(root);
  c.name = root["name"] ? r.string(root["name"], "name")
                        : std::filesystem::path(r.file()).stem().string();
  c.time = read_time(r, root["time"]);
  if (const auto n = root["integrator"]) c.integrator = read_integrator(r, n);
  check_load_ramp(r, c.time, c.integrator);
  if (root["gravity"]) c.gravity = r.vec3(root["gravity"], "gravity");
  const YAML::Node bodies = root["bodies"];
  if (!bodies || !bodies.IsSequence() || bodies.size() == 0)
    r.fail("bodies", "expected a non-empty list of bodies");
  for (std::size_t i = 0; i < bodies.size(); ++i)
    c.bodies.push_back(read_body(r, bodies[i], indexed("bodies", i), i));
  for (std::size_t i = 1; i < c.bodies.size(); ++i)
    if (c.bodies[i].material.model != c.bodies[0].material.model)
      r.fail(indexed("bodies", i) + ".material.model", "all bodies must use the same model");
  for (std::size_t i = 1; i < c.bodies.size(); ++i)
    if (c.bodies[i].material.surface_correction != c.bodies[0].material.surface_correction)
      r.fail(indexed("bodies", i) + ".material.surface_correction",
             "all bodies must use the same surface_correction");
  if (const auto n = root["constraints"]) {
    if (!n.IsSequence()) r.fail("constraints", "expected a list");
    for (std::size_t i = 0; i < n.size(); ++i)
      c.constraints.push_back(read_constraint(r, n[i], indexed("constraints", i)));
  }
  if (const auto n = root["initial_cracks"]) {
    if (!n.IsSequence()) r.fail("initial_cracks", "expected a list");
    for (std::size_t i = 0; i < n.size(); ++i)
      c.initial_cracks.push_back(read_crack(r, n[i], indexed("initial_cracks", i)));
  }
  if (const auto n = root["colliders"]) {
    if (!n.IsSequence()) r.fail("colliders", "expected a list");
    for (std::size_t i = 0; i < n.size(); ++i)
      c.colliders.push_back(read_collider(r, n[i], indexed("colliders", i)));
  }
  if (const auto n = root["contact"]) {
    r.check_keys(n, "contact", {"stiffness", "friction", "self"});
    if (n["self"]) c.contact.self = r.boolean(n["self"], "contact.self");
    if (n["stiffness"]) c.contact.stiffness = r.positive(n["stiffness"], "contact.stiffness");
    if (n["friction"]) c.contact.friction = r.non_negative(n["friction"], "contact.friction");
  }
  if (root["damping"]) c.damping = r.non_negative(root["damping"], "damping");
  if (const auto n = root["probes"]) {
    if (!n.IsSequence()) r.fail("probes", "expected a list");
    for (std::size_t i = 0; i < n.size(); ++i) {
      const std::string p = indexed("probes", i);
      r.check_keys(n[i], p, {"name", "region"});
      Probe probe{r.string(n[i]["name"], join(p, "name")),
                  read_region(r, n[i]["region"], join(p, "region"))};
      if (probe.name.empty() ||
          probe.name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                       "0123456789_-") != std::string::npos)
        r.fail(join(p, "name"), "use letters, digits, '_' and '-' only (it names CSV columns)");
      for (const auto& other : c.probes)
        if (other.name == probe.name) r.fail(join(p, "name"), "duplicate probe name");
      c.probes.push_back(probe);
    }
  }
  const YAML::Node out = root["output"];
  std::vector<std::string> output_keys = {"dir",     "every", "probe_every",   "checkpoint_every",
                                          "surface", "tets",  "surface_motion"};
  for (const auto& parser : output_option_parsers())
    output_keys.insert(output_keys.end(), parser.keys.begin(), parser.keys.end());
  if (out) r.check_keys(out, "output", output_keys);
  c.output.dir = out && out["dir"] ? r.string(out["dir"], "output.dir") : "out/" + c.name;
  if (c.output.dir.empty()) r.fail("output.dir", "must not be empty");
  c.output.every =
      out && out["every"] ? r.positive(out["every"], "output.every") : c.time.end / 100;
  c.output.probe_every = out && out["probe_every"]
                             ? r.positive(out["probe_every"], "output.probe_every")
                             : c.output.every;
  if (out && out["checkpoint_every"])
    c.output.checkpoint_every = r.positive(out["checkpoint_every"], "output.checkpoint_every");
  if (out && out["surface"]) c.output.surface = r.boolean(out["surface"], "output.surface");
  if (out && out["tets"]) c.output.tets = r.boolean(out["tets"], "output.tets");
  if (out && out["surface_motion"]) {
    const std::string motion = r.string(out["surface_motion"], "output.surface_motion");
    if (motion == "velocity")
      c.output.surface_motion = OutputSettings::SurfaceMotion::velocity;
    else if (motion != "position")
      r.fail("output.surface_motion", "expected `position` or `velocity`, got '" + motion + "'");
  }
  const YAML::Node own = out ? out : YAML::Node(YAML::NodeType::Map);
  for (const auto& parser : output_option_parsers())
    if (parser.parse)
      c.output.options.emplace_back(parser.name, parser.parse(OptionReader(r, own, "output")));
  if (root["render"]) c.render = read_render_settings(r, root["render"]);
  check_fictitious_particles(r, c);
  return c;
}

}  // namespace

Config parse_config(const std::string& yaml_text, const std::string& file,
                    const std::vector<std::string>& overrides) {
  YAML::Node root = parse_yaml(yaml_text, file);
  for (const auto& assignment : overrides) apply_override(root, assignment, file);
  return read_config(YamlReader(file), root);
}

Config load_config(const std::string& path, const std::vector<std::string>& overrides) {
  YAML::Node root = load_yaml_with_base(path);
  for (const auto& assignment : overrides) apply_override(root, assignment, path);
  return read_config(YamlReader(path), root);
}

}  // namespace fissure
