// mfv bench: throughput of the suite's integrands on every OpenCL device (or
// the selected one) and in the scalar double reference with one thread and
// with all threads, in one run; medians over repeats, ratios, flops/sample,
// and a peak row (FMA-bound kernel) per device with each integrand's share.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

struct BenchOptions {
  uint32_t integrals = 64;          // integrals per device launch (and per reference pass)
  uint64_t samples = 1u << 16;      // samples per integral on a device
  uint64_t ref_samples = 1u << 12;  // samples per integral in the reference (it is ~10-100x slower)
  int repeats = 5;                  // timed repetitions; medians are reported
  unsigned threads = 0;             // reference threads for the "all threads" row (0: hardware)
  uint64_t seed = 1;
  std::vector<std::string> integrands;  // empty: all (d_norm, albedo, reciprocity)
};

// Float operations per sample of each integrand, counted in the compiled
// kernel (bench.cpp, scripts/kernel-flops.py), for achieved GFLOP/s; the
// peak row's per work-item.
struct FlopCount {
  double flops;      // + - * / sqrt min max, fma = 2
  double transcend;  // library sin, cos, exp... (none left in the bench kernels)
  double int_ops;    // Philox4x32-10 and uniform conversion
};

struct BenchRow {
  std::string integrand, engine;  // engine: device name, "reference x1", "reference xN"
  std::string platform, driver;   // devices only
  double build_seconds = 0;       // devices: program build, kept out of the timings
  uint64_t integrals = 0, samples_per_integral = 0;
  std::vector<double> seconds;      // each repeat, wall clock
  std::vector<double> cpu_seconds;  // each repeat, CPU time of the whole process (PoCL's worker threads included)
  double median_seconds = 0, samples_per_second = 0, integrals_per_second = 0;
  double samples_per_cpu_second = 0;  // robust where other processes share the cores
  double checksum = 0;                // mean of the integrals (keeps the work observable)
};

struct BenchReport {
  BenchOptions opt;
  std::vector<BenchRow> rows;
  std::string date, cpu;
  std::string load_average;  // /proc/loadavg at the start: other processes on the cores skew wall-clock ratios
  unsigned hardware_threads = 0;
};

// device_selector "" benchmarks every OpenCL device; otherwise the one it picks.
BenchReport run_bench(const std::string& device_selector, const std::string& kernel_dir, const BenchOptions& opt);
FlopCount flops_per_sample(const std::string& integrand);
std::string bench_table(const BenchReport& r);  // console and Markdown
std::string bench_json(const BenchReport& r);
void validate_bench_options(const BenchOptions& opt);
std::string bench_load_average();  // /proc/loadavg's first three fields
double bench_now();                // steady clock, seconds
double bench_cpu_now();            // CPU seconds of every thread of this process
double bench_median(std::vector<double> v);

}  // namespace mfv
