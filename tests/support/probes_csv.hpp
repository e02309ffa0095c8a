#pragma once
// A run's probes.csv as numbers, by column name.
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fissure::test {

// Column name → its values, row by row.
inline std::map<std::string, std::vector<double>> read_probes(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::istringstream names(line);
  for (std::string cell; std::getline(names, cell, ',');) header.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::string cell;
    for (std::size_t k = 0; k < header.size() && std::getline(cells, cell, ','); ++k)
      columns[header[k]].push_back(std::stod(cell));
  }
  return columns;
}

}  // namespace fissure::test
