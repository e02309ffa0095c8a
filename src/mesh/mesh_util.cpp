#include "mesh/mesh_util.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/error.hpp"

namespace fissure::mesh_detail {

namespace fs = std::filesystem;

namespace {

// Meshes beyond this many tets are taken as a mistake in the edge length.
constexpr double kMaxTets = 5e7;

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

}  // namespace

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "", "file not found");
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "", "not a regular file");
  const auto size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) throw InputError(path, "", "cannot open file for reading");
  std::string data(size, '\0');
  if (!in.read(data.data(), static_cast<std::streamsize>(size))) {
    throw InputError(path, "", "read error");
  }
  return data;
}

std::string lowercase_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::vector<std::string_view> split_tokens(std::string_view text) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && is_space(text[i])) ++i;
    const size_t start = i;
    while (i < text.size() && !is_space(text[i])) ++i;
    if (i > start) tokens.push_back(text.substr(start, i - start));
  }
  return tokens;
}

std::vector<Line> tokenized_lines(std::string_view text, bool hash_comments) {
  std::vector<Line> lines;
  int number = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    if (hash_comments) line = line.substr(0, line.find('#'));
    auto tokens = split_tokens(line);
    if (!tokens.empty()) lines.push_back({number, std::move(tokens)});
  }
  return lines;
}

bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && !token.empty();
}

bool parse_int(std::string_view token, long long& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && !token.empty();
}

void fail_at_line(const std::string& path, int line, const std::string& reason) {
  throw InputError(path, "", fmt::format("line {}: {}", line, reason));
}

double tet_signed_volume(const double* vertices, const int* tet) {
  const double* a = vertices + 3 * tet[0];
  const double* b = vertices + 3 * tet[1];
  const double* c = vertices + 3 * tet[2];
  const double* d = vertices + 3 * tet[3];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

void validate_surface(const SurfaceMesh& surface, const std::string& path) {
  if (surface.triangles.empty()) throw InputError(path, "", "no triangles");
  const size_t vertex_count = surface.vertices.size() / 3;
  for (size_t i = 0; i < surface.vertices.size(); ++i) {
    if (!std::isfinite(surface.vertices[i])) {
      throw InputError(path, "",
                       fmt::format("vertex {} (0-based) has a non-finite coordinate", i / 3));
    }
  }
  for (size_t i = 0; i < surface.triangles.size(); ++i) {
    const int v = surface.triangles[i];
    if (v < 0 || static_cast<size_t>(v) >= vertex_count) {
      throw InputError(path, "",
                       fmt::format("triangle {} (0-based) uses vertex index {}, out of range for "
                                   "{} vertices",
                                   i / 3, v, vertex_count));
    }
  }
}

void weld_vertices(SurfaceMesh& surface) {
  std::map<std::array<double, 3>, int> unique;
  std::vector<int> merged(surface.vertices.size() / 3);
  for (size_t i = 0; i < merged.size(); ++i) {
    const double* p = &surface.vertices[3 * i];
    merged[i] =
        unique.emplace(std::array<double, 3>{p[0], p[1], p[2]}, int(unique.size())).first->second;
  }
  std::vector<int> triangles;
  for (size_t t = 0; t < surface.triangles.size(); t += 3) {
    const int a = merged[surface.triangles[t]];
    const int b = merged[surface.triangles[t + 1]];
    const int c = merged[surface.triangles[t + 2]];
    if (a != b && b != c && a != c) triangles.insert(triangles.end(), {a, b, c});
  }
  std::vector<std::array<double, 3>> coords(unique.size());
  for (const auto& [p, index] : unique) coords[index] = p;
  std::vector<int> renumber(unique.size(), -1);
  std::vector<double> vertices;
  for (int& v : triangles) {
    if (renumber[v] < 0) {
      renumber[v] = static_cast<int>(vertices.size() / 3);
      vertices.insert(vertices.end(), coords[v].begin(), coords[v].end());
    }
    v = renumber[v];
  }
  surface.vertices = std::move(vertices);
  surface.triangles = std::move(triangles);
}

void check_tet_budget(double volume, double area, double edge_length, const std::string& path) {
  const double estimate = (volume + area * edge_length) / regular_tet_volume(edge_length);
  if (!(estimate <= kMaxTets)) {
    throw InputError(path, "",
                     fmt::format("edge length {} would need about {:.3g} tets (limit {:.0g}); "
                                 "use a larger edge length",
                                 edge_length, estimate, kMaxTets));
  }
}

double regular_tet_volume(double edge_length) {
  return edge_length * edge_length * edge_length / (6.0 * std::sqrt(2.0));
}

void append_vertex(const Line& line, const std::string& path, std::vector<double>& vertices) {
  if (line.tokens.size() < 4) fail_at_line(path, line.number, "vertex needs x y z");
  for (int k = 1; k <= 3; ++k) {
    double x;
    if (!parse_double(line.tokens[k], x))
      fail_at_line(path, line.number, fmt::format("invalid number '{}'", line.tokens[k]));
    vertices.push_back(x);
  }
}

}  // namespace fissure::mesh_detail
