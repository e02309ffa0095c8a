#pragma once
// The checkpoint file format: a magic string, a format version, named sections of bytes, and an
// FNV-1a checksum of everything before it. Written atomically (temporary file, then rename), so a
// run killed while writing leaves the previous checkpoint whole.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/named_arrays.hpp"

namespace fissure {

inline constexpr std::uint32_t kCheckpointVersion = 1;

class CheckpointWriter {
 public:
  void add_bytes(const std::string& name, const void* data, std::size_t bytes);
  void add(const std::string& name, const std::vector<double>& values) {
    add_bytes(name, values.data(), values.size() * sizeof(double));
  }
  void add(const std::string& name, const std::vector<std::uint8_t>& values) {
    add_bytes(name, values.data(), values.size());
  }
  void add(const std::string& name, const std::string& text) {
    add_bytes(name, text.data(), text.size());
  }
  void write(const std::string& path) const;

 private:
  std::vector<std::pair<std::string, std::string>> sections_;
};

class CheckpointReader {
 public:
  // Reads and checks the whole file; throws InputError naming it when it is missing, not a
  // checkpoint, of another format version, truncated or corrupted (checksum).
  explicit CheckpointReader(const std::string& path);
  bool has(const std::string& name) const { return sections_.count(name) > 0; }
  const std::string& path() const { return path_; }
  // The names of every section, in order.
  std::vector<std::string> names() const {
    std::vector<std::string> names;
    for (const auto& [name, bytes] : sections_) names.push_back(name);
    return names;
  }
  // Every section whose name starts with `prefix`, as numbers.
  NamedArrays arrays(const std::string& prefix) const;
  // Throw InputError naming the file and section when it is missing or has the wrong size.
  std::vector<double> doubles(const std::string& name) const;
  double number(const std::string& name) const;
  std::vector<std::uint8_t> bytes(const std::string& name) const;
  std::string text(const std::string& name) const;

 private:
  const std::string& section(const std::string& name) const;

  std::string path_;
  std::map<std::string, std::string> sections_;
};

}  // namespace fissure
