#pragma once
// Internals shared by the files of the mesh module: parsing helpers, surface checks and the
// TetGen wrapper. Not for use outside src/mesh.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace fissure::mesh_detail {

// Whole file as bytes; throws InputError if it is missing or unreadable.
std::string read_file(const std::string& path);

// Extension with its dot, lowercased; "" if none.
std::string lowercase_extension(const std::string& path);

// A non-empty line split at whitespace, with its 1-based line number.
struct Line {
  int number;
  std::vector<std::string_view> tokens;
};

std::vector<std::string_view> split_tokens(std::string_view text);

// Non-empty lines of `text`; with `hash_comments`, text after '#' is dropped.
std::vector<Line> tokenized_lines(std::string_view text, bool hash_comments);

// Whole-token parses; false on any malformed input.
bool parse_double(std::string_view token, double& value);
bool parse_int(std::string_view token, long long& value);

// InputError(path, "", "line N: reason").
[[noreturn]] void fail_at_line(const std::string& path, int line, const std::string& reason);

// Appends the coordinates in tokens 1–3 of a vertex line ("v x y z", "vertex x y z").
void append_vertex(const Line& line, const std::string& path, std::vector<double>& vertices);

// det[b - a, c - a, d - a] / 6 of the tet `tet` (4 indices into xyz `vertices`).
double tet_signed_volume(const double* vertices, const int* tet);

// Throws unless the surface has triangles, finite coordinates and in-range indices.
void validate_surface(const SurfaceMesh& surface, const std::string& path);

// Merges bit-identical vertices, then drops triangles with a repeated vertex and unused vertices.
void weld_vertices(SurfaceMesh& surface);

// Splits edges longer than `max_edge` at their midpoints until none is left. The new points lie
// on the input triangles, so the enclosed volume is unchanged.
void refine_surface(SurfaceMesh& surface, double max_edge);

// TetGen quality mesh (radius-edge ratio 1.414, tets up to `max_volume`) of a closed, welded
// surface, kept as is; tets positively oriented. Failures become InputError(file, ...).
// TetGen's self-intersection check can cost as much as the meshing itself.
TetMesh tetgen_quality_mesh(const SurfaceMesh& surface, double max_volume, const std::string& file,
                            bool check_intersections);

// tetrahedralize_surface for surfaces valid by construction: no self-intersection check. The
// surface is given at the origin (a box's lowest corner, a sphere's centre, a cylinder's first
// end) and the mesh moved by `origin` after meshing, so that the mesh of a primitive does not
// depend on where it lies (TetGen's choices among a box's regular, cospherical points follow the
// last bits of the coordinates: 857 particles at the origin, 846 a kilometre away).
TetMesh tetrahedralize_primitive(const SurfaceMesh& surface, double edge_length,
                                 const std::array<double, 3>& origin);

// Throws if a body of `volume` and surface `area` meshed at `edge_length` would need an absurd
// number of tets (thin bodies still need a layer of λ-sized tets over their surface).
void check_tet_budget(double volume, double area, double edge_length, const std::string& path);

// Volume of a regular tet of edge λ: TetGen's maximum tet volume for target edge λ.
double regular_tet_volume(double edge_length);

}  // namespace fissure::mesh_detail
