// Every registered check kind is complete (docs/adding-a-check.md): its
// integrand in the kernel's closed dispatch (kernels/integrate.cl
// sample_value), its reference twin (ref::sample_value), an expectation for
// the points its sources give, and its report line. A kind registered with a
// piece missing fails here with a message naming the piece; the companion
// test plants one kind per missing piece and shows each message firing.
#include "abi/bsdf.h"
#include "albedo_spec.hpp"
#include "checks/integrate.hpp"
#include "checks/registry.hpp"
#include "device_fixture.hpp"
#include "reference/estimators.hpp"
#include "util/error.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace mfv;

namespace {

constexpr uint32_t kProbeSamples = 64;
constexpr uint64_t kSeed = 3;

// Kinds with an integrand of their own (Runner::Integral and Table): the
// reciprocity pairs run their own kernel (Integrator::reciprocity), the
// pointwise kinds mfv agree's and stability's.
bool integrates(const CheckKind& k) { return k.runner == Runner::Integral || k.runner == Runner::Table; }

// One integral of the kind at an ordinary point: GGX with its Smith G1, F = 1.
IntegralSpec probe_spec(const CheckKind& k) {
  IntegralSpec s = test::albedo_spec("ggx", "smith_ggx_correlated", "none", 0.3, 0.7, 0.0, 0.0, 1, k.kind);
  if (k.kind == IntegralKind::DNorm || k.kind == IntegralKind::EavgRqmc) s.strata = kProbeSamples;
  if (k.kind == IntegralKind::AlbedoMis || k.kind == IntegralKind::BsdfFlux) s.points = kProbeSamples / 4;
  if (k.domain == Domain::Sphere) {  // a rough dielectric BSDF's: glass, entered, the transmitted flux
    s.bsdf = MFV_BTDF_CODE(MFV_BTDF_CORRELATED, MFV_BTDF_OK);
    s.eta = 1.5f;
    s.lobe = MFV_LOBE_TRANSMIT;
  }
  return s;
}

// The kernel's first kProbeSamples values of each spec (a device run).
using KernelValues = std::function<std::vector<float>(const std::vector<IntegralSpec>&)>;

// What the kinds lack, one message a gap; `kernel` empty: the kernel's
// dispatch is not probed (no device).
std::vector<std::string> gaps(const std::vector<CheckKind>& kinds, const KernelValues& kernel) {
  std::vector<std::string> out;
  std::vector<IntegralSpec> probes;
  std::vector<const CheckKind*> probed;
  for (const CheckKind& k : kinds) {
    if (std::string(k.summary).empty())
      out.push_back(fmt::format("check kind {}: no report line (CheckKind::summary)", k.check));
    if (std::string(k.verdict).empty())
      out.push_back(fmt::format("check kind {}: no account of its expected verdicts (CheckKind::verdict)", k.check));
    if (k.sources == 0) out.push_back(fmt::format("check kind {}: no point source takes it (CheckKind::sources)", k.check));
    // a kind that gives verdicts on D x G x F points needs the catalog's prediction for them
    const bool dgf_points = (k.sources & ~unsigned(kSourceModels)) != 0;
    if (k.runner == Runner::Integral && dgf_points && !k.expect)
      out.push_back(fmt::format("check kind {}: no expectation for its points (CheckKind::expect)", k.check));
    if (!integrates(k)) continue;
    const IntegralSpec s = probe_spec(k);
    try {
      const ref::IntegralRef r = reference_of(s);
      double sum = 0;
      for (uint32_t i = 0; i < kProbeSamples; ++i) sum += ref::sample_value(r, kSeed, i);
      if (!std::isfinite(sum)) throw Error("its samples are not finite");
    } catch (const Error& e) {
      out.push_back(fmt::format("check kind {}: no reference twin for check id {} ({})", k.check, s.check, e.what()));
    }
    probes.push_back(s);
    probed.push_back(&k);
  }
  if (kernel && !probes.empty()) {
    const std::vector<float> v = kernel(probes);
    for (size_t j = 0; j < probes.size(); ++j) {
      double sum = 0;
      for (uint32_t i = 0; i < kProbeSamples; ++i) sum += v[j * kProbeSamples + i];
      if (!std::isfinite(sum))
        out.push_back(fmt::format("check kind {}: no integrand in the kernel for check id {} "
                                  "(kernels/integrate.cl sample_value gave NaN)",
                                  probed[j]->check, probes[j].check));
    }
  }
  return out;
}

KernelValues device_kernel(Runtime& rt) {
  return [&rt](const std::vector<IntegralSpec>& specs) {
    TermSelection sel;
    sel.d = {&find_term("ggx")};
    sel.g = {&find_term("smith_ggx_correlated")};
    sel.f = {&find_term("none")};
    static cl::Program prog = build_integrate_program(rt, sel);
    return program_sample_values<float>(rt, prog, specs, kProbeSamples, kSeed);
  };
}

bool has(const std::vector<std::string>& gaps, const std::string& piece) {
  for (auto& g : gaps)
    if (g.find(piece) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("Every registered check kind has its report line, expectation and reference twin", "[checks][registry]") {
  for (auto& gap : gaps(check_kinds(), {})) FAIL_CHECK(gap);
}

TEST_CASE("Every registered check kind has its integrand in the kernel's dispatch", "[device][checks][registry]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  for (auto& gap : gaps(check_kinds(), device_kernel(*rt))) FAIL_CHECK(gap);
}

TEST_CASE("The completeness test names each missing piece of a planted check kind", "[checks][registry]") {
  const CheckKind base = check_kind("furnace");
  REQUIRE(gaps({base}, {}).empty());
  auto planted = [&](auto plant) {
    CheckKind k = base;
    k.check = "planted";
    plant(k);
    return gaps({k}, {});
  };
  const auto no_line = planted([](CheckKind& k) { k.summary = ""; });
  CHECK(no_line.size() == 1);
  CHECK(has(no_line, "check kind planted: no report line"));
  const auto no_expect = planted([](CheckKind& k) { k.expect = nullptr; });
  CHECK(no_expect.size() == 1);
  CHECK(has(no_expect, "check kind planted: no expectation for its points"));
  const auto no_verdict = planted([](CheckKind& k) { k.verdict = ""; });
  CHECK(has(no_verdict, "check kind planted: no account of its expected verdicts"));
  // a check id with no case in the reference's closed dispatch: it throws, named
  const auto no_twin = planted([](CheckKind& k) { k.kind = static_cast<IntegralKind>(99); });
  CHECK(no_twin.size() == 1);
  CHECK(has(no_twin, "check kind planted: no reference twin for check id 99 (reference: check id 99 has no integrand"));
}

TEST_CASE("A planted check id with no integrand gives NaN in the kernel and a named failure", "[device][checks][registry]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  CheckKind k = check_kind("masking");
  k.check = "planted";
  k.kind = static_cast<IntegralKind>(99);
  const auto g = gaps({k}, device_kernel(*rt));
  CHECK(has(g, "check kind planted: no integrand in the kernel for check id 99 (kernels/integrate.cl sample_value gave NaN)"));
  CHECK(has(g, "check kind planted: no reference twin for check id 99"));
  // and the real kind beside it has none of these gaps
  CHECK(gaps({check_kind("masking")}, device_kernel(*rt)).empty());
}
