// Stanford .ply, ascii or binary_little_endian: vertex x y z and face vertex_indices lists;
// other elements and properties are read and skipped.
#include <fmt/format.h>

#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

#include "core/error.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/surface_formats.hpp"

namespace fissure::mesh_detail {

namespace {

static_assert(std::endian::native == std::endian::little, "binary readers assume little endian");

enum class Type { i8, u8, i16, u16, i32, u32, f32, f64 };

std::optional<Type> parse_type(std::string_view name) {
  if (name == "char" || name == "int8") return Type::i8;
  if (name == "uchar" || name == "uint8") return Type::u8;
  if (name == "short" || name == "int16") return Type::i16;
  if (name == "ushort" || name == "uint16") return Type::u16;
  if (name == "int" || name == "int32") return Type::i32;
  if (name == "uint" || name == "uint32") return Type::u32;
  if (name == "float" || name == "float32") return Type::f32;
  if (name == "double" || name == "float64") return Type::f64;
  return std::nullopt;
}

size_t type_size(Type t) {
  switch (t) {
    case Type::i8:
    case Type::u8:
      return 1;
    case Type::i16:
    case Type::u16:
      return 2;
    case Type::i32:
    case Type::u32:
    case Type::f32:
      return 4;
    case Type::f64:
      return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  Type type;
  std::optional<Type> list_count;  // set for list properties
};

struct Element {
  std::string name;
  unsigned long long count;
  std::vector<Property> properties;
};

struct Header {
  bool binary = false;
  std::vector<Element> elements;
  size_t body = 0;  // offset of the first byte after end_header
};

Header parse_header(std::string_view data, const std::string& path) {
  Header h;
  bool has_format = false;
  size_t pos = 0;
  for (int number = 1;; ++number) {
    const size_t end = data.find('\n', pos);
    if (end == std::string_view::npos) throw InputError(path, "", "PLY header has no end_header");
    const auto tokens = split_tokens(data.substr(pos, end - pos));
    pos = end + 1;
    if (number == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply") throw InputError(path, "", "missing ply magic");
      continue;
    }
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "end_header") break;
    if (tokens[0] == "format" && tokens.size() >= 2) {
      if (tokens[1] != "ascii" && tokens[1] != "binary_little_endian") {
        fail_at_line(path, number, fmt::format("unsupported PLY format '{}'", tokens[1]));
      }
      h.binary = tokens[1] == "binary_little_endian";
      has_format = true;
    } else if (tokens[0] == "element" && tokens.size() == 3) {
      long long count;
      if (!parse_int(tokens[2], count) || count < 0) {
        fail_at_line(path, number, fmt::format("invalid element count '{}'", tokens[2]));
      }
      h.elements.push_back({std::string(tokens[1]), static_cast<unsigned long long>(count), {}});
    } else if (tokens[0] == "property" && !h.elements.empty()) {
      Property p;
      const bool list = tokens.size() == 5 && tokens[1] == "list";
      if (!list && tokens.size() != 3) {
        fail_at_line(path, number, "property needs a type and a name (or list, two types, a name)");
      }
      const std::optional<Type> type = parse_type(tokens[list ? 3 : 1]);
      if (!type) {
        fail_at_line(path, number, fmt::format("unknown property type '{}'", tokens[list ? 3 : 1]));
      }
      p.type = *type;
      p.name = tokens.back();
      if (list) {
        p.list_count = parse_type(tokens[2]);
        if (!p.list_count || *p.list_count == Type::f32 || *p.list_count == Type::f64) {
          fail_at_line(path, number, "invalid list count type");
        }
      }
      h.elements.back().properties.push_back(std::move(p));
    } else {
      fail_at_line(path, number, "unrecognised PLY header line");
    }
  }
  if (!has_format) throw InputError(path, "", "PLY header has no format line");
  h.body = pos;
  return h;
}

// Reads values from the body, as whitespace-separated text or packed little-endian binary.
class BodyReader {
 public:
  BodyReader(std::string_view body, bool binary, const std::string& path)
      : body_(body), binary_(binary), path_(path) {
    if (!binary_) tokens_ = split_tokens(body_);
  }

  double read(Type t) {
    if (!binary_) {
      if (next_ >= tokens_.size()) throw InputError(path_, "", "unexpected end of PLY data");
      double value;
      if (!parse_double(tokens_[next_], value)) {
        throw InputError(path_, "", fmt::format("invalid number '{}' in PLY data", tokens_[next_]));
      }
      ++next_;
      return value;
    }
    if (type_size(t) > body_.size() - next_) {
      throw InputError(path_, "", "unexpected end of PLY data");
    }
    const char* p = body_.data() + next_;
    next_ += type_size(t);
    switch (t) {
      case Type::i8:
        return load<int8_t>(p);
      case Type::u8:
        return load<uint8_t>(p);
      case Type::i16:
        return load<int16_t>(p);
      case Type::u16:
        return load<uint16_t>(p);
      case Type::i32:
        return load<int32_t>(p);
      case Type::u32:
        return load<uint32_t>(p);
      case Type::f32:
        return load<float>(p);
      case Type::f64:
        return load<double>(p);
    }
    return 0.0;
  }

  // Values (tokens or bytes) left to read.
  size_t remaining() const { return (binary_ ? body_.size() : tokens_.size()) - next_; }

 private:
  template <class T>
  static double load(const char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);
    return static_cast<double>(value);
  }

  std::string_view body_;
  bool binary_;
  const std::string& path_;
  std::vector<std::string_view> tokens_;
  size_t next_ = 0;
};

int as_index(double value, const std::string& path, const char* what) {
  if (!(value >= 0.0 && value <= INT_MAX) || value != std::floor(value)) {
    throw InputError(path, "", fmt::format("invalid {} {} in PLY data", what, value));
  }
  return static_cast<int>(value);
}

int find_property(const Element& e, std::string_view name) {
  for (size_t i = 0; i < e.properties.size(); ++i) {
    if (e.properties[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

SurfaceMesh parse_ply(std::string_view data, const std::string& path) {
  const Header header = parse_header(data, path);
  BodyReader reader(data.substr(header.body), header.binary, path);
  SurfaceMesh s;
  std::vector<double> values;
  std::vector<int> polygon;
  for (const Element& e : header.elements) {
    if (e.properties.empty()) continue;
    size_t min_size = 0;  // bytes (binary) or tokens (ascii) per element, with empty lists
    for (const Property& p : e.properties) {
      min_size += header.binary ? type_size(p.list_count.value_or(p.type)) : 1;
    }
    if (e.count > reader.remaining() / min_size) {
      throw InputError(
          path, "",
          fmt::format("header claims {} '{}' elements but the data can hold at most {}", e.count,
                      e.name, reader.remaining() / min_size));
    }
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    const int xyz[3] = {find_property(e, "x"), find_property(e, "y"), find_property(e, "z")};
    if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)) {
      throw InputError(path, "", "PLY vertex element lacks x, y or z");
    }
    int indices = find_property(e, "vertex_indices");
    if (indices < 0) indices = find_property(e, "vertex_index");
    if (is_face && (indices < 0 || !e.properties[indices].list_count)) {
      throw InputError(path, "", "PLY face element lacks a vertex_indices list");
    }
    values.resize(e.properties.size());
    for (unsigned long long i = 0; i < e.count; ++i) {
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (!p.list_count) {
          values[k] = reader.read(p.type);
          continue;
        }
        const int length = as_index(reader.read(*p.list_count), path, "list length");
        const bool keep = is_face && static_cast<int>(k) == indices;
        if (keep) polygon.clear();
        for (int j = 0; j < length; ++j) {
          const double value = reader.read(p.type);
          if (keep) polygon.push_back(as_index(value, path, "vertex index"));
        }
        if (keep) {
          if (polygon.size() < 3) {
            throw InputError(path, "", fmt::format("face {} has fewer than 3 vertices", i));
          }
          for (size_t j = 1; j + 1 < polygon.size(); ++j) {
            s.triangles.insert(s.triangles.end(), {polygon[0], polygon[j], polygon[j + 1]});
          }
        }
      }
      if (is_vertex) {
        for (int c : xyz) s.vertices.push_back(values[c]);
      }
    }
  }
  return s;
}

}  // namespace fissure::mesh_detail
