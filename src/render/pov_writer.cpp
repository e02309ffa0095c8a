#include "render/pov_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ostream>

#include "io/output_file.hpp"
#include "render/field_colors.hpp"

namespace fissure {

namespace {

constexpr int kColours = 64;

std::string vec(const Point3& p) { return fmt::format("<{:.6g},{:.6g},{:.6g}>", p[0], p[1], p[2]); }

void write_particles(std::ostream& out, const PovScene& s) {
  out << "#declare T = array[" << kColours << "] {\n";
  for (int c = 0; c < kColours; ++c) {
    const auto rgb = cool_warm(c / double(kColours - 1));
    out << fmt::format(
        "  texture {{ pigment {{ srgb <{:.4f},{:.4f},{:.4f}> }} finish {{ F }} }}{}\n", rgb[0],
        rgb[1], rgb[2], c + 1 < kColours ? "," : "");
  }
  out << "}\n#macro P(X, Y, Z, C) sphere { <X, Y, Z>, " << fmt::format("{:.6g}", s.radius)
      << " texture { T[C] } } #end\n";
  const std::vector<double>& x = *s.points;
  for (std::size_t i = 0; i < s.color_t.size(); ++i) {
    const int c =
        std::clamp(static_cast<int>(std::lround(s.color_t[i] * (kColours - 1))), 0, kColours - 1);
    out << fmt::format("P({:.6g},{:.6g},{:.6g},{})\n", x[3 * i], x[3 * i + 1], x[3 * i + 2], c);
  }
}

void write_surface(std::ostream& out, const PovScene& s) {
  const std::size_t vertices = s.surface_vertices.size() / 3;
  out << "mesh2 {\n  vertex_vectors { " << vertices;
  for (std::size_t v = 0; v < vertices; ++v)
    out << fmt::format(",\n    <{:.6g},{:.6g},{:.6g}>", s.surface_vertices[3 * v],
                       s.surface_vertices[3 * v + 1], s.surface_vertices[3 * v + 2]);
  const std::size_t faces = s.surface_triangles.size() / 3;
  out << "\n  }\n  face_indices { " << faces;
  for (std::size_t f = 0; f < faces; ++f)
    out << fmt::format(",\n    <{},{},{}>", s.surface_triangles[3 * f],
                       s.surface_triangles[3 * f + 1], s.surface_triangles[3 * f + 2]);
  out << "\n  }\n  texture { pigment { srgb <0.80,0.78,0.72> } finish { F } }\n}\n";
}

}  // namespace

void write_pov(const std::string& path, const PovScene& s) {
  OutputFile file(path, OutputFile::Mode::truncate);  // OutputError naming the file and why
  std::ostream& out = file.stream();
  const double aspect = static_cast<double>(s.width) / s.height;
  Point3 key = s.camera.look_at;
  const Point3 key_direction{-0.4, -1.0, 1.5};
  for (int k = 0; k < 3; ++k) key[k] += 4 * s.scene_size * key_direction[k];
  // right = −x·aspect makes POV-Ray's left-handed frame right-handed; sky and up are z.
  out << "#version 3.7;\n"
      << "global_settings { assumed_gamma 1.0 }\n"
      << "background { rgb <1, 1, 1> }\n"
      << fmt::format(
             "camera {{ perspective location {} sky <0,0,1> up <0,0,1> right <{:.6g},0,0> "
             "angle {:.6g} look_at {} }}\n",
             vec(s.camera.position), -aspect, s.camera.angle, vec(s.camera.look_at))
      << fmt::format("light_source {{ {} rgb 0.85 }}\n", vec(key))
      << fmt::format("light_source {{ {} rgb 0.45 shadowless }}\n", vec(s.camera.position))
      << "#declare F = finish { ambient 0.12 diffuse 0.8 specular 0.15 roughness 0.05 }\n"
      << fmt::format(
             "plane {{ z, {:.6g} pigment {{ srgb <0.93,0.93,0.92> }} finish {{ ambient 0.35 "
             "diffuse 0.6 }} }}\n",
             s.floor_z);
  if (!s.surface_triangles.empty())
    write_surface(out, s);
  else
    write_particles(out, s);
  file.close();
}

}  // namespace fissure
