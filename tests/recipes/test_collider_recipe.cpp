// The recipe for adding a collider shape (docs/architecture.md), shown by a test-only one: a
// horizontal floor at colliders[i].floor.height, registered from this file alone and named by a
// scene. A particle of radius r at height z presses into it by p = r − (z − h) and feels k p
// upwards (k its penalty stiffness, contact/contact_particles.hpp); a height that did not reach
// the shape, or a shape the colliders ignored, gives other forces. Bad values fail with the key
// path, and what the shape does not allow (a velocity) is refused by name.
#include <gtest/gtest.h>

#include <stdexcept>

#include "contact/collider_registry.hpp"
#include "contact/colliders.hpp"
#include "contact/contact_particles.hpp"
#include "support/error_message.hpp"

namespace fissure {
namespace {

struct FloorOptions final : ColliderOptions {
  double height = 0;
  bool moves() const override { return false; }
};

class Floor final : public ShapeContact<Floor> {
 public:
  explicit Floor(double height) : height_(height) {}
  Point origin() const override { return {0, 0, height_}; }
  double penetration(const double* x, const double* y, double radius, double* n) const {
    n[0] = n[1] = 0;
    n[2] = 1;
    return radius - (y[2] - x[2]);
  }

 private:
  double height_;
};

const bool registered = [] {
  register_collider({"floor",
                     {"height"},
                     [](const OptionReader& r) {
                       auto o = std::make_shared<FloorOptions>();
                       o->height = r.number("height", 0.0);
                       return o;
                     },
                     [](const ColliderOptions& o) {
                       return std::make_unique<Floor>(shape_options<FloorOptions>(o).height);
                     }});
  return true;
}();

std::string scene_with(const std::string& collider) {
  return "time: {end: 0.1}\n"
         "bodies:\n  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}\n"
         "    resolution: 0.025\n"
         "    material: {density: 1000, bulk_modulus: 1.0e6, shear_modulus: 1.0e6}\n"
         "colliders:\n  - " +
         collider + "\n";
}

TEST(ColliderRecipe, FloorPushesEveryParticleBelowItsHeightByItsPenaltyLaw) {
  ASSERT_TRUE(registered);
  // the floor below the block at load (a body may not start inside a collider), the block then
  // lowered by 8 cm into it
  const double h = -0.05;
  const Scene scene = build_scene(parse_config(scene_with("{floor: {height: -0.05}}"), "f.yaml"));
  ASSERT_EQ(scene.config.colliders.size(), 1u);
  EXPECT_EQ(scene.config.colliders[0].shape, "floor");
  Colliders colliders(scene);
  std::vector<double> y = scene.particles.reference;
  for (std::size_t i = 0; i < y.size() / 3; ++i) y[3 * i + 2] -= 0.08;
  const std::vector<double> v(y.size(), 0.0);
  std::vector<double> f(y.size(), 0.0);
  colliders.add_forces(y.data(), v.data(), f.data());
  const ContactParticles c = contact_particles(scene);
  int pressed = 0, free = 0;
  for (int i = 0; i < scene.particles.count(); ++i) {
    const double depth = c.radius[i] - (y[3 * i + 2] - h);
    EXPECT_EQ(f[3 * i], 0.0);
    EXPECT_EQ(f[3 * i + 1], 0.0);
    if (depth > 0) {
      ++pressed;
      EXPECT_EQ(f[3 * i + 2], c.stiffness[i] * depth) << "particle " << i;  // same operations
    } else {
      ++free;
      EXPECT_EQ(f[3 * i + 2], 0.0) << "particle " << i;
    }
  }
  EXPECT_GT(pressed, 0);  // the floor cuts the block, so both kinds of particle are checked
  EXPECT_GT(free, 0);
}

TEST(ColliderRecipe, BadValuesFailWithTheKeyPath) {
  ASSERT_TRUE(registered);
  auto parse = [](const std::string& collider) {
    return test::input_error_message([&] { parse_config(scene_with(collider), "f.yaml"); });
  };
  std::string e = parse("{floor: {height: low}}");
  EXPECT_NE(e.find("f.yaml: colliders[0].floor.height: expected a number"), std::string::npos) << e;
  e = parse("{floor: {hieght: 0.1}}");
  EXPECT_NE(e.find("colliders[0].floor.hieght"), std::string::npos) << e;
  e = parse("{floor: {height: 0.1}, velocity: [0, 0, 1]}");
  EXPECT_NE(e.find("colliders[0].velocity: a floor does not move"), std::string::npos) << e;
  e = parse("{floor: {height: 0.1}, plane: {point: [0, 0, 0], normal: [0, 0, 1]}}");
  EXPECT_NE(e.find("colliders[0]: give exactly one of sphere, plane, box, floor"),
            std::string::npos)
      << e;
}

// A name is registered once: a second shape called sphere would make "sphere" ambiguous.
TEST(ColliderRecipe, ANameIsRegisteredOnce) {
  ASSERT_TRUE(registered);
  EXPECT_THROW(register_collider(sphere_collider_kind()), std::logic_error);
  EXPECT_THROW(register_collider(plane_collider_kind()), std::logic_error);
}

}  // namespace
}  // namespace fissure
