#include "checks/bench.hpp"
#include "mfv_git_commit.h"

#include "catalog/catalog.hpp"
#include "catalog/roughness.hpp"
#include "checks/integrate.hpp"
#include "reference/estimators.hpp"
#include "runtime/provenance.hpp"
#include "util/error.hpp"
#include "util/files.hpp"
#include "util/parallel.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include <time.h>

namespace mfv {

double bench_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU time of every thread of this process: on a CPU device PoCL's workers
// are threads of it, so samples per CPU-second compare engines fairly on a
// machine other processes share (wall-clock ratios then depend on the load).
double bench_cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double bench_median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

const std::vector<std::string> kIntegrands = {"d_norm", "albedo", "reciprocity"};
const std::string kPeak = "peak";    // the FMA-bound row (kernels/peak.cl)
constexpr double kPeakFlops = 8192;  // per fma_peak work-item: 2 flops x 8 lanes x 8 chains x 64 steps
constexpr double kAlpha = 0.3;  // one representative width; the cost of these terms does not depend on it

// Wall and CPU seconds of each call of f.
struct Timings {
  std::vector<double> wall, cpu;
  template <class F>
  void time(F&& f) {
    const double c0 = bench_cpu_now(), t0 = bench_now();
    f();
    wall.push_back(bench_now() - t0);
    cpu.push_back(bench_cpu_now() - c0);
  }
};

// The representative integrands: D alone (GGX d_norm, stratified like the
// suite's), the full GGX + smith_ggx_correlated + Schlick (F0 = 0.04) albedo
// over views spread in cos θ_o, and reciprocity pairs of that BRDF.
std::vector<IntegralSpec> bench_specs(const std::string& integrand, uint32_t n) {
  const Term &d = find_term("ggx"), &g = find_term("smith_ggx_correlated"), &f = find_term("schlick");
  std::vector<IntegralSpec> specs(n);
  for (uint32_t j = 0; j < n; ++j) {
    IntegralSpec& s = specs[j];
    s.check = static_cast<int32_t>(integrand == "d_norm" ? IntegralKind::DNorm : IntegralKind::Albedo);
    s.d = term_index(d);
    s.g = term_index(g);
    s.f = term_index(f);
    s.pd = float(native_from_alpha(d.roughness, kAlpha));
    s.pg = float(native_from_alpha(g.roughness, kAlpha));
    s.f0 = 0.04f;
    s.width = float(kAlpha);
    s.cos_o = float((j + 0.5) / n);
    s.stream = j;
  }
  return specs;
}

BenchRow make_row(const std::string& integrand, const std::string& engine, uint64_t integrals, uint64_t samples,
                  const Timings& tm, double checksum) {
  BenchRow r;
  r.integrand = integrand;
  r.engine = engine;
  r.integrals = integrals;
  r.samples_per_integral = samples;
  r.median_seconds = bench_median(tm.wall);
  r.seconds = tm.wall;
  r.cpu_seconds = tm.cpu;
  r.samples_per_second = double(integrals) * double(samples) / r.median_seconds;
  r.samples_per_cpu_second = double(integrals) * double(samples) / bench_median(tm.cpu);
  r.integrals_per_second = double(integrals) / r.median_seconds;
  r.checksum = checksum;
  return r;
}

// The peak row: kernels/peak.cl's fma_peak on the same device, in the same
// run (its own program, built outside the timings). A "sample" is one
// work-item, kPeakFlops flops; 2^18 work-items per launch (~2.1 GFLOP).
BenchRow bench_peak(Runtime& rt, const DeviceInfo& dev, const BenchOptions& opt) {
  const double b0 = bench_now();
  cl::Program program = rt.build({"peak.cl"}, {});
  const double build = bench_now() - b0;
  cl::Kernel k(program, "fma_peak");
  const size_t items = size_t(1) << 18;
  cl::Buffer out(rt.context(), CL_MEM_WRITE_ONLY, items * sizeof(float));
  k.setArg(0, 0.999f);
  k.setArg(1, 1e-3f);
  k.setArg(2, out);
  std::vector<float> host(items);
  Timings tm;
  for (int rep_i = -1; rep_i < opt.repeats; ++rep_i) {  // repeat -1 warms up
    auto pass = [&] {
      rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(items));
      rt.queue().finish();
    };
    if (rep_i < 0)
      pass();
    else
      tm.time(pass);
  }
  rt.queue().enqueueReadBuffer(out, CL_TRUE, 0, items * sizeof(float), host.data());
  double checksum = 0;
  for (float v : host) checksum += v;
  BenchRow r = make_row(kPeak, dev.name, 1, items, tm, checksum / double(items));
  r.platform = dev.platform;
  r.driver = dev.driver;
  r.build_seconds = build;
  return r;
}

void bench_device(const DeviceInfo& dev, const std::string& kernel_dir, const BenchOptions& opt,
                  const std::vector<std::string>& integrands, BenchReport& rep) {
  Runtime rt(std::to_string(dev.index), kernel_dir);
  TermSelection sel;
  sel.d = {&find_term("ggx")};
  sel.g = {&find_term("smith_ggx_correlated")};
  sel.f = {&find_term("schlick")};
  Integrator in(rt, sel);
  in.set_microfacet_reciprocity_from(0);  // the integrand is the microfacet kernel's
  const double build = rt.build_stats().seconds;
  for (const auto& name : integrands) {
    const auto specs = bench_specs(name, opt.integrals);
    const bool recip = name == "reciprocity";
    // reciprocity: 64 work-items per integral, each over per_item pairs
    const uint32_t per_item = uint32_t(std::max<uint64_t>(1, opt.samples / 64));
    const uint64_t samples = recip ? uint64_t(per_item) * 64 : in.samples_used(opt.samples);
    double checksum = 0;
    Timings tm;
    for (int rep_i = -1; rep_i < opt.repeats; ++rep_i) {  // repeat -1 warms up (first launch, allocations)
      auto pass = [&] {
        double sum = 0;
        if (recip) {
          for (float w : in.reciprocity(specs, 64 * per_item, opt.seed + rep_i + 1).worst) sum += w;
        } else {
          for (const auto& e : in.run(specs, opt.samples, opt.seed + rep_i + 1)) sum += e.mean;
        }
        checksum = sum / specs.size();
      };
      if (rep_i < 0)
        pass();
      else
        tm.time(pass);
    }
    BenchRow r = make_row(name, dev.name, specs.size(), samples, tm, checksum);
    r.platform = dev.platform;
    r.driver = dev.driver;
    r.build_seconds = build;
    rep.rows.push_back(std::move(r));
  }
  rep.rows.push_back(bench_peak(rt, dev, opt));
}

// One integral in the reference: the mean of its first n samples.
double reference_integral(const std::string& name, const IntegralSpec& spec, uint64_t n, uint64_t seed) {
  ref::IntegralRef r = reference_of(spec);
  double sum = 0;
  if (name == "reciprocity") {
    double worst = 0;
    for (uint64_t k = 0; k < n; ++k) {
      glm::dvec3 a, b;
      ref::reciprocity_pair(seed, spec.stream, spec.stream_hi, uint32_t(k), a, b);
      const double f1 = ref::brdf(r.brdf, a, b), f2 = ref::brdf(r.brdf, b, a), m = std::max(f1, f2);
      const double asym = m > 0 ? std::fabs(f1 - f2) / m : 0.0;
      if (!(asym <= worst)) worst = asym;
    }
    return worst;
  }
  if (r.kind == ref::Integral::DNorm) r.strata = uint32_t(n);  // stratified as in the kernel
  for (uint64_t k = 0; k < n; ++k) sum += ref::sample_value(r, seed, k);
  return sum / double(n);
}

void bench_reference(const BenchOptions& opt, unsigned threads, const std::vector<std::string>& integrands,
                     BenchReport& rep) {
  for (const auto& name : integrands) {
    const auto specs = bench_specs(name, opt.integrals);
    std::vector<double> results(specs.size());
    Timings tm;
    for (int rep_i = 0; rep_i < opt.repeats; ++rep_i)
      tm.time([&] {
        parallel_for(specs.size(), threads, [&](size_t j) {
          results[j] = reference_integral(name, specs[j], opt.ref_samples, opt.seed + rep_i);
        });
      });
    double checksum = 0;
    for (double v : results) checksum += v / results.size();
    rep.rows.push_back(
        make_row(name, fmt::format("reference x{}", threads), specs.size(), opt.ref_samples, tm, checksum));
  }
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

}  // namespace

std::string bench_load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return in ? a + " " + b + " " + c : "unknown";
}

namespace {

const BenchRow* find_row(const BenchReport& r, const std::string& integrand, const std::string& engine) {
  for (auto& row : r.rows)
    if (row.integrand == integrand && row.engine == engine) return &row;
  return nullptr;
}

}  // namespace

// Counted from the compiled kernels: scripts/kernel-flops.py (the float
// operations per lane in the body of PoCL's vectorized loop over
// work-items, fma = 2; every instruction there runs for every work-item, the
// branches having become selects). The same counts on PoCL 3.1's haswell
// (AVX2) and skylake-avx512 targets; other drivers compile other code, so
// there the rate is an estimate. sincos_2pi is in-house polynomials, so it
// is in the flops; no library call is left. Not counted: the reductions
// (sum_pairs, sum_values: ~2 double additions per sample).
//   d_norm: d_norm_values 68 flops, 160 integer ops per work-item, which
//     takes two samples: 34 and 80 per sample (Philox's 32x32->64
//     multiplies in 64-bit lanes, xors, shifts, masks).
//   albedo: albedo_values 266 flops, 234 integer ops per work-item (two
//     samples): 133 and 117 per sample (mfv_philox_split since issue 31's
//     staged kernel: 268 and 224 before).
//   reciprocity: reciprocity_values_microfacet 764 flops, 521 integer ops per work-item, which
//     takes four pairs: 191 and 130 per pair (its Philox, mfv_philox_split, writes each product's
//     two words as separate expressions: 128 before, the same flops).
// The hand counts they replace (77, 172, 185 + 4 sin/cos) had counted
// sincos_2pi in d_norm's path, where the kernel has none.
FlopCount flops_per_sample(const std::string& integrand) {
  if (integrand == kPeak) return {kPeakFlops, 0, 0};
  if (integrand == "d_norm") return {34, 0, 80};
  if (integrand == "albedo") return {133, 0, 117};
  return {191, 0, 130};
}

void validate_bench_options(const BenchOptions& opt) {
  if (opt.integrals < 1 || opt.integrals > 65536)
    throw Error(fmt::format("--integrals {}: must be 1..65536", opt.integrals));
  if (opt.samples < 64 || opt.samples > (uint64_t(1) << 26))
    throw Error(fmt::format("--samples {}: must be 64..2^26", opt.samples));
  if (opt.ref_samples < 1 || opt.ref_samples > (uint64_t(1) << 26))
    throw Error(fmt::format("--ref-samples {}: must be 1..2^26", opt.ref_samples));
  if (opt.repeats < 1 || opt.repeats > 100) throw Error(fmt::format("--repeats {}: must be 1..100", opt.repeats));
  if (opt.threads > 1024) throw Error(fmt::format("--threads {}: at most 1024", opt.threads));
  for (auto& i : opt.integrands)
    if (std::find(kIntegrands.begin(), kIntegrands.end(), i) == kIntegrands.end())
      throw Error(fmt::format("unknown integrand '{}' (integrands: d_norm, albedo, reciprocity)", i));
}

BenchReport run_bench(const std::string& device_selector, const std::string& kernel_dir, const BenchOptions& opt) {
  validate_bench_options(opt);
  BenchReport rep;
  rep.opt = opt;
  rep.date = utc_timestamp();
  rep.cpu = cpu_model();
  rep.load_average = bench_load_average();
  rep.hardware_threads = std::max(1u, std::thread::hardware_concurrency());
  const auto integrands = opt.integrands.empty() ? kIntegrands : opt.integrands;
  std::vector<DeviceInfo> devices;
  if (device_selector.empty() || device_selector == "all")  // every device of every platform, one table
    devices = list_devices();
  else
    devices.push_back(select_device(device_selector));
  for (const auto& d : devices) bench_device(d, kernel_dir, opt, integrands, rep);
  const unsigned all = opt.threads ? opt.threads : rep.hardware_threads;
  bench_reference(opt, 1, integrands, rep);
  if (all > 1) bench_reference(opt, all, integrands, rep);
  return rep;
}

// GFLOP per CPU-second of a row (flops per sample as counted above).
double gflops_per_cpu_second(const BenchRow& row) {
  const FlopCount fc = flops_per_sample(row.integrand);
  return row.samples_per_cpu_second * (fc.flops + fc.transcend) * 1e-9;
}

// A device row's share of the same device's peak row, per CPU-second (both
// rows see the same load); < 0 where there is no peak row.
double fraction_of_peak(const BenchReport& r, const BenchRow& row) {
  const BenchRow* peak = row.platform.empty() ? nullptr : find_row(r, kPeak, row.engine);
  return peak ? gflops_per_cpu_second(row) / gflops_per_cpu_second(*peak) : -1.0;
}

std::string bench_table(const BenchReport& r) {
  std::string s = fmt::format(
      "| integrand | engine | integrals x samples | median s | samples/s | integrals/s | "
      "est. GFLOP/s | vs reference x1 | samples/CPU-s | per CPU-s vs reference x1 | GFLOP/CPU-s | of peak |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& row : r.rows) {
    const BenchRow* ref1 = find_row(r, row.integrand, "reference x1");
    const FlopCount fc = flops_per_sample(row.integrand);
    const double share = fraction_of_peak(r, row);
    s += fmt::format("| {} | {} | {} x {} | {:.4f} | {:.3e} | {:.3g} | {:.2f} | {} | {:.3e} | {} | {:.2f} | {} |\n",
                     row.integrand, row.engine, row.integrals, row.samples_per_integral, row.median_seconds,
                     row.samples_per_second, row.integrals_per_second,
                     row.samples_per_second * (fc.flops + fc.transcend) * 1e-9,
                     ref1 ? fmt::format("{:.1f}x", row.samples_per_second / ref1->samples_per_second) : "-",
                     row.samples_per_cpu_second,
                     ref1 ? fmt::format("{:.1f}x", row.samples_per_cpu_second / ref1->samples_per_cpu_second) : "-",
                     gflops_per_cpu_second(row), share >= 0 ? fmt::format("{:.1f} %", 100 * share) : "-");
  }
  s += "\nThe peak row: kernels/peak.cl, chains of float8 fma, 8192 flops per work-item (its samples); "
       "'of peak' is a device row's GFLOP per CPU-second over its device's peak row's.\n";
  s += "\nFlops per sample (counted in PoCL's compiled kernels by scripts/kernel-flops.py; see "
       "host/checks/bench.cpp): ";
  for (const auto& i : kIntegrands) {
    const FlopCount fc = flops_per_sample(i);
    s += fmt::format("{} {:g} (+{:g} integer ops); ", i, fc.flops, fc.int_ops);
  }
  s += "the reference rows run the same integrands in double.\n";
  return s;
}

std::string bench_json(const BenchReport& r) {
  using nlohmann::json;
  json j;
  j["schema"] = "mfv-bench/1";
  j["tool"] = {{"name", "mfv"}, {"version", MFV_VERSION}, {"commit", MFV_GIT_COMMIT}};
  j["provenance"] = provenance_json();  // command line, --kernel-dir, kernel hashes, device (runtime/provenance.hpp)
  j["date"] = r.date;
  j["host"] = {{"cpu", r.cpu}, {"hardware_threads", r.hardware_threads}, {"load_average", r.load_average}};
  j["options"] = {{"integrals", r.opt.integrals},
                  {"samples", r.opt.samples},
                  {"ref_samples", r.opt.ref_samples},
                  {"repeats", r.opt.repeats},
                  {"seed", r.opt.seed},
                  {"alpha", kAlpha},
                  {"brdf", "ggx / smith_ggx_correlated / schlick f0=0.04"}};
  j["rows"] = json::array();
  for (const auto& row : r.rows) {
    const FlopCount fc = flops_per_sample(row.integrand);
    const BenchRow* ref1 = find_row(r, row.integrand, "reference x1");
    json x{{"integrand", row.integrand},
           {"engine", row.engine},
           {"integrals", row.integrals},
           {"samples_per_integral", row.samples_per_integral},
           {"seconds", row.seconds},
           {"cpu_seconds", row.cpu_seconds},
           {"samples_per_cpu_second", row.samples_per_cpu_second},
           {"median_seconds", row.median_seconds},
           {"samples_per_second", row.samples_per_second},
           {"integrals_per_second", row.integrals_per_second},
           {"flops_per_sample", fc.flops},
           {"transcendentals_per_sample", fc.transcend},
           {"est_gflops", row.samples_per_second * (fc.flops + fc.transcend) * 1e-9},
           {"checksum", row.checksum}};
    x["gflops_per_cpu_second"] = gflops_per_cpu_second(row);
    if (const double share = fraction_of_peak(r, row); share >= 0) x["fraction_of_peak"] = share;
    if (ref1) {
      x["vs_reference_x1"] = row.samples_per_second / ref1->samples_per_second;
      x["per_cpu_second_vs_reference_x1"] = row.samples_per_cpu_second / ref1->samples_per_cpu_second;
    }
    if (!row.platform.empty()) {
      x["platform"] = row.platform;
      x["driver"] = row.driver;
      x["build_seconds"] = row.build_seconds;
    }
    j["rows"].push_back(x);
  }
  return j.dump(2) + "\n";
}

}  // namespace mfv
