#include "io/checkpoint_file.hpp"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fissure {

namespace {

constexpr char kMagic[8] = {'F', 'I', 'S', 'S', 'C', 'K', 'P', 'T'};

// FNV-1a, 64 bit.
std::uint64_t checksum(const char* data, std::size_t size) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t k = 0; k < size; ++k) {
    hash ^= static_cast<unsigned char>(data[k]);
    hash *= 1099511628211ull;
  }
  return hash;
}

template <class T>
void append(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

}  // namespace

void CheckpointWriter::add_bytes(const std::string& name, const void* data, std::size_t bytes) {
  sections_.emplace_back(name, std::string(static_cast<const char*>(data), bytes));
}

void CheckpointWriter::write(const std::string& path) const {
  std::string body(kMagic, sizeof(kMagic));
  append(body, kCheckpointVersion);
  append(body, static_cast<std::uint64_t>(sections_.size()));
  for (const auto& [name, bytes] : sections_) {
    append(body, static_cast<std::uint32_t>(name.size()));
    body += name;
    append(body, static_cast<std::uint64_t>(bytes.size()));
    body += bytes;
  }
  append(body, checksum(body.data(), body.size()));
  write_atomically(path, [&](std::ostream& out) { out.write(body.data(), body.size()); });
}

CheckpointReader::CheckpointReader(const std::string& path) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "no checkpoint here (cannot open the file)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string data = buffer.str();
  const std::size_t header = sizeof(kMagic) + sizeof(std::uint32_t) + sizeof(std::uint64_t);
  if (data.size() < sizeof(kMagic) || std::memcmp(data.data(), kMagic, sizeof(kMagic)) != 0)
    throw InputError(path, "", "not a Fissure checkpoint (wrong magic bytes)");
  if (data.size() < header + sizeof(std::uint64_t))
    throw InputError(path, "", fmt::format("truncated: {} bytes", data.size()));
  std::uint32_t version;
  std::memcpy(&version, data.data() + sizeof(kMagic), sizeof(version));
  if (version != kCheckpointVersion)
    throw InputError(path, "",
                     fmt::format("format version {}, but this fissure reads version {}", version,
                                 kCheckpointVersion));
  std::size_t at = header;
  std::uint64_t count;
  std::memcpy(&count, data.data() + sizeof(kMagic) + sizeof(version), sizeof(count));
  auto need = [&](std::uint64_t bytes) {
    if (bytes > data.size() || data.size() - at < bytes + sizeof(std::uint64_t))
      throw InputError(path, "",
                       fmt::format("truncated or corrupted: a section runs past the end of the "
                                   "{}-byte file",
                                   data.size()));
  };
  for (std::uint64_t s = 0; s < count; ++s) {
    std::uint32_t name_size;
    need(sizeof(name_size));
    std::memcpy(&name_size, data.data() + at, sizeof(name_size));
    at += sizeof(name_size);
    need(name_size);
    std::string name = data.substr(at, name_size);
    at += name_size;
    std::uint64_t size;
    need(sizeof(size));
    std::memcpy(&size, data.data() + at, sizeof(size));
    at += sizeof(size);
    need(size);
    sections_[name] = data.substr(at, size);
    at += size;
  }
  if (at + sizeof(std::uint64_t) != data.size())
    throw InputError(
        path, "",
        fmt::format("corrupted: {} bytes after the last section, expected 8", data.size() - at));
  std::uint64_t stored;
  std::memcpy(&stored, data.data() + at, sizeof(stored));
  if (stored != checksum(data.data(), at))
    throw InputError(path, "", "corrupted: the checksum does not match the contents");
}

const std::string& CheckpointReader::section(const std::string& name) const {
  const auto it = sections_.find(name);
  if (it == sections_.end())
    throw InputError(path_, name, "missing from the checkpoint (written by another scene?)");
  return it->second;
}

std::vector<double> CheckpointReader::doubles(const std::string& name) const {
  const std::string& bytes = section(name);
  if (bytes.size() % sizeof(double) != 0)
    throw InputError(path_, name,
                     fmt::format("{} bytes is not a whole number of doubles", bytes.size()));
  std::vector<double> values(bytes.size() / sizeof(double));
  std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

double CheckpointReader::number(const std::string& name) const {
  const std::vector<double> values = doubles(name);
  if (values.size() != 1)
    throw InputError(path_, name, fmt::format("{} numbers where one was expected", values.size()));
  return values[0];
}

std::vector<std::uint8_t> CheckpointReader::bytes(const std::string& name) const {
  const std::string& bytes = section(name);
  return {bytes.begin(), bytes.end()};
}

NamedArrays CheckpointReader::arrays(const std::string& prefix) const {
  NamedArrays arrays;
  for (const auto& [name, bytes] : sections_)
    if (name.rfind(prefix, 0) == 0) arrays.emplace_back(name, doubles(name));
  return arrays;
}

std::string CheckpointReader::text(const std::string& name) const { return section(name); }

}  // namespace fissure
