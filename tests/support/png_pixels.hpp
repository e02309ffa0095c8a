#pragma once
// Decodes an 8-bit RGB or RGBA PNG (non-interlaced, as POV-Ray writes) into its pixels, so tests
// can look at a picture. Returns an empty image for anything else.
#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fissure::test {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint32_t> rgb;  // 0xRRGGBB per pixel, row by row
};

inline std::uint32_t big_endian(const unsigned char* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
         p[3];
}

inline Image read_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> file((std::istreambuf_iterator<char>(in)), {});
  Image image;
  if (file.size() < 8 || file[1] != 'P' || file[2] != 'N' || file[3] != 'G') return image;
  int channels = 0;
  std::vector<unsigned char> compressed;
  for (std::size_t at = 8; at + 12 <= file.size();) {
    const std::uint32_t length = big_endian(&file[at]);
    const std::string type(file.begin() + at + 4, file.begin() + at + 8);
    const unsigned char* data = &file[at + 8];
    if (at + 12 + length > file.size()) return {};
    if (type == "IHDR") {
      image.width = static_cast<int>(big_endian(data));
      image.height = static_cast<int>(big_endian(data + 4));
      channels = data[9] == 2 ? 3 : data[9] == 6 ? 4 : 0;
      if (data[8] != 8 || channels == 0 || data[12] != 0) return {};
    } else if (type == "IDAT") {
      compressed.insert(compressed.end(), data, data + length);
    }
    at += 12 + length;
  }
  const std::size_t stride = static_cast<std::size_t>(image.width) * channels;
  std::vector<unsigned char> raw((stride + 1) * image.height);
  uLongf raw_size = raw.size();
  if (channels == 0 ||
      uncompress(raw.data(), &raw_size, compressed.data(), compressed.size()) != Z_OK ||
      raw_size != raw.size())
    return {};
  std::vector<unsigned char> previous(stride, 0), row(stride);
  for (int y = 0; y < image.height; ++y) {
    const unsigned char filter = raw[y * (stride + 1)];
    const unsigned char* line = &raw[y * (stride + 1) + 1];
    for (std::size_t x = 0; x < stride; ++x) {
      const int a = x >= std::size_t(channels) ? row[x - channels] : 0;
      const int b = previous[x];
      const int c = x >= std::size_t(channels) ? previous[x - channels] : 0;
      int predictor = 0;
      if (filter == 1) predictor = a;
      if (filter == 2) predictor = b;
      if (filter == 3) predictor = (a + b) / 2;
      if (filter == 4) {
        const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
        predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      row[x] = static_cast<unsigned char>(line[x] + predictor);
    }
    for (int x = 0; x < image.width; ++x)
      image.rgb.push_back((std::uint32_t(row[x * channels]) << 16) |
                          (std::uint32_t(row[x * channels + 1]) << 8) | row[x * channels + 2]);
    previous = row;
  }
  return image;
}

}  // namespace fissure::test
