#pragma once
// Google Benchmark programs run by the report, their JSON read back.

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

namespace patchwork::performance {

/// Runs `program` (with `arguments`, shell-quoted by the caller) writing its results to
/// `json_file`; nullopt if it is missing or fails.
inline std::optional<nlohmann::json> run_benchmark(const std::filesystem::path& program,
                                                   const std::filesystem::path& json_file,
                                                   const std::string& arguments = "") {
  if (!std::filesystem::exists(program)) return std::nullopt;
  // A stream, not operator+ on literals and strings: GCC 12 warns falsely there (-Wrestrict).
  std::ostringstream command;
  command << "'" << program.string() << "' " << arguments << " --benchmark_out='" << json_file.string()
          << "' --benchmark_out_format=json > '" << json_file.string() << ".log' 2>&1";
  if (std::system(command.str().c_str()) != 0) return std::nullopt;
  std::ifstream in(json_file);
  return nlohmann::json::parse(in);
}

/// A benchmark's registered name: Google Benchmark appends "/iterations:3", "/real_time".
inline std::string registered_name(std::string name) {
  for (const std::string suffix : {"/real_time", "/manual_time"}) {
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      name.resize(name.size() - suffix.size());
    }
  }
  if (const auto k = name.find("/iterations:"); k != std::string::npos) name.resize(k);
  return name;
}

/// Each benchmark's seconds per iteration, by registered name: `field` is "cpu_time" or
/// "real_time" (the wall clock, for benchmarks that run threads of their own).
inline std::map<std::string, double> benchmark_seconds(const nlohmann::json& results, const std::string& field) {
  std::map<std::string, double> seconds;
  for (const nlohmann::json& b : results.at("benchmarks")) {
    const std::string unit = b.at("time_unit").get<std::string>();
    const double scale = unit == "ns" ? 1e-9 : unit == "us" ? 1e-6 : unit == "ms" ? 1e-3 : 1.0;
    seconds[registered_name(b.at("name").get<std::string>())] = b.at(field).get<double>() * scale;
  }
  return seconds;
}

/// Each benchmark's CPU seconds per iteration, by registered name.
inline std::map<std::string, double> cpu_seconds(const nlohmann::json& results) {
  return benchmark_seconds(results, "cpu_time");
}

}  // namespace patchwork::performance
