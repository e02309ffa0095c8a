#pragma once
// The scene as plain, validated structs: the rest of the code never sees YAML.
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/option_parsers.hpp"
#include "scene/render_settings.hpp"

namespace fissure {

using Vec3 = std::array<double, 3>;

struct Region {
  enum class Kind { box, sphere } kind = Kind::box;
  Vec3 min{}, max{};  // box
  Vec3 center{};      // sphere
  double radius = 0;  // sphere
  bool contains(const double* p) const;
};

struct Geometry {
  enum class Kind { box, sphere, cylinder, mesh, points } kind = Kind::box;
  Vec3 min{}, max{};   // box
  Vec3 center{};       // sphere
  Vec3 p0{}, p1{};     // cylinder axis end points
  double radius = 0;   // sphere, cylinder
  std::string file;    // mesh, points (resolved against the config's folder)
  double scale = 1.0;  // mesh, points
  Vec3 translate{};    // mesh, points
};

// Bond breaking (paper §5.1, Eqs 18–19); absent means the body never breaks.
struct FractureSettings {
  bool enabled = false;
  double critical_stretch = 0;  // s_c, Table 1's s^ω column
  double alpha = 0;             // α: the criterion grows as (1 + α φ) with damage φ
};

// Plastic flow (paper §4.2, Eqs 11–16); absent means purely elastic.
struct PlasticitySettings {
  bool enabled = false;
  double yield = std::numeric_limits<double>::quiet_NaN();               // Ψ0 of Eq 13
  double yield_stress = std::numeric_limits<double>::quiet_NaN();        // σ_y [Pa], maps to Ψ0
  double max_plastic_stretch = std::numeric_limits<double>::infinity();  // γ/|ξ|, Table 1
};

// Anisotropy (paper §4.3): ω_ij = δ / |G ξ| (Eq 17) with G the same for every particle of a body.
struct AnisotropySettings {
  bool enabled = false;
  std::array<double, 9> G{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row major
};

// lps only (docs/model.md, deviations 4 and 8): none, the dilatation weights calibrated so that
// θ = tr ε near surfaces, or those and the deviatoric weights calibrated so that every small
// homogeneous strain gives the continuum's energy on every particle, or the second-order model
// with fictitious particles (model/second_order_model.hpp), exact for every quadratic field.
enum class SurfaceCorrection { none, dilatation, full, fictitious };

struct Material {
  std::string model = "lps";  // a registered model (model/model_registry.hpp)
  double density = 0;
  double bulk_modulus = 0;
  double shear_modulus = 0;
  SurfaceCorrection surface_correction = SurfaceCorrection::dilatation;
  FractureSettings fracture;
  PlasticitySettings plasticity;
  AnisotropySettings anisotropy;
  std::shared_ptr<const ModelOptions> options;  // the model's own, from its parser; null: none
};

struct Body {
  std::string name;
  Geometry geometry;
  double resolution = 0;  // target tet edge length λ [m]
  double horizon = 1.45;  // δ in units of λ
  Material material;
  Vec3 velocity{};
};

struct Constraint {
  // A clamped face instead of a region (surface_correction: fictitious only): the body's
  // displacement held at zero on the plane through clamp_point, clamp_normal pointing out of the
  // body; it holds no particle, the model continues the field through the plane.
  bool clamp = false;
  Vec3 clamp_point{}, clamp_normal{};
  Region region;
  bool fix = false;  // velocity zero
  Vec3 velocity{};   // prescribed velocity when not fixed
  // Rigid rotation at angular_velocity [rad/s] about the axis through `center` (which moves with
  // `velocity`): a held particle moves at velocity + ω × (its rotated offset from the centre).
  Vec3 angular_velocity{};
  Vec3 center{};
  bool rotates() const { return angular_velocity != Vec3{}; }
  double release_at = std::numeric_limits<double>::infinity();
};

// A pre-crack: removes every bond that crosses it before the run starts.
struct Crack {
  enum class Kind { plane, box } kind = Kind::plane;
  Vec3 point{}, normal{};  // plane
  bool bounded = false;    // plane: only where the crossing point lies in `region`
  Region region;           // plane bound, or the box itself
};

// A rigid obstacle the particles collide with (penalty contact with friction).
struct Collider {
  std::string shape;  // its key: sphere, plane, box or a registered one
  std::shared_ptr<const ColliderOptions> options;  // the shape's own, as its parser read them
  Vec3 velocity{};  // constant (kinematic) or initial (dynamic) velocity, where the shape moves
  bool kinematic = true;
  double mass = 0;  // dynamic
};

struct ContactSettings {
  double stiffness = 1.0;  // penalty factor: k_i = stiffness × κ_i × V_i^(1/3)
  double friction = 0.0;   // Coulomb coefficient
  bool self = false;       // repulsion between particles that are not bonded
};

struct Probe {
  std::string name;
  Region region;
};

struct TimeSettings {
  double end = 0;
  bool dt_auto = true;
  double dt = 0;        // used when !dt_auto
  double safety = 0.9;  // factor on the stable estimate when dt is auto
};

// Steps of dt that reach `end`, the last one shortened; a ratio within 1e-9 of a whole number
// counts as that number (round-off in end / dt does not add a sliver of a step).
inline long steps_to(double end, double dt) {
  return static_cast<long>(std::ceil(end / dt - 1e-9));
}

// The time integrator (docs/integrators.md): the keys every type shares, and the type's own
// options as its registered parser read them (scene/option_parsers.hpp); only the keys of the
// chosen type may be given.
struct IntegratorSettings {
  std::string type = "symplectic_euler";
  bool allow_unstable_dt = false;  // explicit: run even when time.dt exceeds the stable estimate
  // The run stops as unstable once energy that no load put in exceeds this fraction of the
  // run's energy scale (the ledger's balance with Π ≥ 0, checked every step); 0 turns it off.
  double energy_growth_limit = 1.0;
  std::shared_ptr<const IntegratorOptions> options;  // null: the type's defaults
};

struct OutputSettings {
  std::string dir;
  double every = 0;             // seconds of simulated time between VTU frames
  double probe_every = 0;       // seconds between probes.csv rows (default: every)
  double checkpoint_every = 0;  // seconds between checkpoints (0: none)
  bool surface = false;         // crack surfaces of the embedded tet mesh per frame (§5.2)
  bool tets = false;            // the whole embedded tet mesh per frame
  // How mesh vertices follow the particles: `position` (mass-weighted displacement) or
  // `velocity` (Eqs 20–22, integrated every step).
  enum class SurfaceMotion { position, velocity } surface_motion = SurfaceMotion::position;
  // The registered outputs' own settings, by output name, as their parsers read them
  // (app/output_registry.hpp); the keys above are the built-in outputs', which other layers
  // read too.
  std::vector<std::pair<std::string, std::shared_ptr<const OutputOptions>>> options;
  bool embedded_mesh() const { return surface || tets; }
};

struct Config {
  std::string file;    // the YAML file it came from
  std::string source;  // the YAML it was read from, base and overrides merged (for checkpoints)
  std::string name;
  TimeSettings time;
  IntegratorSettings integrator;
  Vec3 gravity{};
  std::vector<Body> bodies;
  std::vector<Constraint> constraints;
  std::vector<Crack> initial_cracks;
  std::vector<Collider> colliders;
  ContactSettings contact;
  double damping = 0;  // mass-proportional damping coefficient [1/s]
  std::vector<Probe> probes;
  OutputSettings output;
  RenderSettings render;  // only `fissure render` reads it

  bool fracture_enabled() const;
  bool plasticity_enabled() const;
  bool anisotropy_enabled() const;
};

// Loads and validates a scene, starting from its `base:` file if it names one
// (config_file.hpp). `overrides` are "key.path=value" strings (CLI --set) applied to the YAML
// tree before validation. Throws InputError naming file, key path and reason.
Config load_config(const std::string& path, const std::vector<std::string>& overrides = {});

// The same, from YAML text (without `base:`); `file` names it in error messages and resolves
// relative paths.
Config parse_config(const std::string& yaml_text, const std::string& file,
                    const std::vector<std::string>& overrides = {});

}  // namespace fissure
