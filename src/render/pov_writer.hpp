#pragma once
// One frame as a POV-Ray 3.7 scene: particles as spheres coloured by a field, or a triangle
// surface, under a fixed camera, on a floor. Coordinates are the run's (right-handed, z up).
#include <string>
#include <vector>

#include "render/view.hpp"

namespace fissure {

struct PovScene {
  Camera camera;
  int width = 800, height = 600;
  double floor_z = 0;     // height of the floor plane
  double scene_size = 1;  // size of the scene, places the lights
  // Particles: positions and a colour parameter t in [0, 1] each (see cool_warm).
  const std::vector<double>* points = nullptr;
  std::vector<double> color_t;
  double radius = 0;
  // Surface, drawn instead of the particles when it has triangles.
  std::vector<double> surface_vertices;
  std::vector<long> surface_triangles;
};

void write_pov(const std::string& path, const PovScene& scene);

}  // namespace fissure
