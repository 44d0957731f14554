// csv/<reader>/<rows>: reading a dataset-shaped CSV table (14 kinematic columns and 6 wrench
// columns, numbers in round-trip form) with io::readCsvTable against the line-by-line reader it
// replaced (std::getline, a stringstream split and a row vector per line), in the same run.
// Issue 20: a 10-million-row dataset is read in seconds.

#include <benchmark/benchmark.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "io/csv_table.hpp"

namespace {

namespace fs = std::filesystem;

// A table of `rows` rows in the temporary folder, written once per size.
fs::path table(long rows) {
  const fs::path path =
      fs::temp_directory_path() / ("vcontact_csv_bench_" + std::to_string(rows) + ".csv");
  if (fs::exists(path)) return path;
  std::ofstream out(path);
  out.precision(std::numeric_limits<double>::max_digits10);
  out << "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz\n";
  for (long i = 0; i < rows; ++i) {
    const double t = 1e-4 * static_cast<double>(i);
    out << t;
    for (int c = 1; c < 20; ++c) out << ',' << std::sin(t * c + c) * (c == 4 ? 0.0 : 1e-3);
    out << '\n';
  }
  return path;
}

// The reader before issue 20, as it was in formats/dataset_file.cpp (errors left out).
std::vector<std::vector<double>> referenceRead(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::vector<double>> rows;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::string field;
    std::stringstream ss(line);
    while (std::getline(ss, field, ',')) fields.push_back(field);
    std::vector<double> row(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      std::from_chars(fields[c].data(), fields[c].data() + fields[c].size(), row[c]);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

void BM_ReferenceReader(benchmark::State& state) {
  const fs::path path = table(state.range(0));
  std::size_t rows = 0;
  for (auto _ : state) {
    const auto r = referenceRead(path.string());
    rows = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["rows"] = static_cast<double>(rows);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_CsvTable(benchmark::State& state) {
  const fs::path path = table(state.range(0));
  std::size_t rows = 0;
  for (auto _ : state) {
    const vcontact::io::CsvTable t = vcontact::io::readCsvTable(path.string());
    rows = t.rowCount();
    benchmark::DoNotOptimize(t.columns.data());
  }
  state.counters["rows"] = static_cast<double>(rows);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(BM_ReferenceReader)
    ->Name("csv/reference")
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CsvTable)
    ->Name("csv/csv_table")
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);

}  // namespace
