#pragma once
// CSV files the runs write (probes.csv, results.csv): a header line of column names, then one
// line per row, cells separated by commas.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fissure::test {

// The cells of one line.
inline std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

// A file's column names and the cells of each line after the header.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

inline Csv read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  Csv csv;
  std::string line;
  std::getline(in, line);
  csv.header = csv_cells(line);
  while (std::getline(in, line)) csv.rows.push_back(csv_cells(line));
  return csv;
}

// Each row as column name → cell (cells beyond the header are dropped).
inline std::vector<std::map<std::string, std::string>> read_records(
    const std::filesystem::path& path) {
  const Csv csv = read_csv(path);
  std::vector<std::map<std::string, std::string>> records;
  for (const auto& row : csv.rows) {
    std::map<std::string, std::string> record;
    for (std::size_t k = 0; k < csv.header.size() && k < row.size(); ++k)
      record[csv.header[k]] = row[k];
    records.push_back(record);
  }
  return records;
}

// A run's probes.csv as numbers: column name → its values, row by row.
inline std::map<std::string, std::vector<double>> read_probes(const std::filesystem::path& path) {
  const Csv csv = read_csv(path);
  std::map<std::string, std::vector<double>> columns;
  for (const auto& row : csv.rows)
    for (std::size_t k = 0; k < csv.header.size() && k < row.size(); ++k)
      columns[csv.header[k]].push_back(std::stod(row[k]));
  return columns;
}

}  // namespace fissure::test
