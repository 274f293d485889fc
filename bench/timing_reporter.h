#pragma once
// Google Benchmark's console output, plus the seconds per iteration (wall and CPU) of every
// benchmark by name, so a bench can print ratios between methods after the run. With
// --benchmark_repetitions the median of the repetitions is kept.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

namespace patchwork::bench {

class TimingReporter : public benchmark::ConsoleReporter {
 public:
  struct Seconds {
    double wall;
    double cpu;
  };

  // Colours only on a terminal (a custom reporter does not see --benchmark_color).
  TimingReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_Defaults : OO_Tabular) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if ((run.run_type == Run::RT_Iteration || median) && !run.error_occurred && run.iterations > 0) {
        const auto iterations = static_cast<double>(run.iterations);
        seconds_[run.run_name.function_name] = {run.real_accumulated_time / iterations,
                                                run.cpu_accumulated_time / iterations};
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  /// Seconds per iteration of the benchmark `name`, or null if it did not run.
  const Seconds* find(const std::string& name) const {
    const auto it = seconds_.find(name);
    return it == seconds_.end() ? nullptr : &it->second;
  }

  /// Whether any benchmark ran.
  bool empty() const { return seconds_.empty(); }

 private:
  std::map<std::string, Seconds> seconds_;
};

/// The main() of a bench that prints ratios: runs the benchmarks named on the command line, then
/// print(reporter) for the ratios.
template <class Print>
int run_benchmarks(int argc, char** argv, const Print& print) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  TimingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  print(reporter);
  benchmark::Shutdown();
  return 0;
}

}  // namespace patchwork::bench
