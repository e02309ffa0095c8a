#pragma once
// Helpers shared by the mesh readers and the TetGen wrappers.
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

// det[b - a, c - a, d - a] / 6 of the tet `tet` (4 indices into xyz `vertices`).
double tet_signed_volume(const double* vertices, const int* tet);

// Throws unless the surface has triangles, finite coordinates and in-range indices.
void validate_surface(const SurfaceMesh& surface, const std::string& path);

// Merges bit-identical vertices, then drops triangles with a repeated vertex and unused vertices.
void weld_vertices(SurfaceMesh& surface);

// Throws if a region of `volume` meshed at `edge_length` would need an absurd number of tets.
void check_tet_budget(double volume, double edge_length, const std::string& path);

// Volume of a regular tet of edge λ: TetGen's maximum tet volume for target edge λ.
double regular_tet_volume(double edge_length);

}  // namespace fissure::mesh_detail
