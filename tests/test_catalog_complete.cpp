// Every catalog term is complete (docs/adding-a-term.md): its kernel function
// in kernels/terms_*.cl, its reference twin, and expected verdicts in the
// checks mfv run makes of it. A term declared with a piece missing fails here
// with a message naming the piece, before any device run.
#include "catalog/catalog.hpp"
#include "checks/suite.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

using namespace mfv;

namespace {

std::string kernel_text(Kind k) {
  const char* file = k == Kind::D ? "terms_d.cl" : k == Kind::G ? "terms_g.cl" : "terms_f.cl";
  std::ifstream in(std::string(MFV_KERNEL_SOURCE_DIR) + "/" + file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string file_of(Kind k) {
  return std::string("kernels/terms_") + (k == Kind::D ? "d" : k == Kind::G ? "g" : "f") + ".cl";
}

bool defines(const std::string& text, const std::string& fn) {
  return std::regex_search(text, std::regex("static inline real " + fn + "\\("));
}

// The reference twin of the term's kind, evaluated at its default parameter: finite.
bool reference_ok(const Term& t) {
  const double p = t.params.empty() ? 0.0 : t.params[0].fallback;
  const double p1 = t.params.size() > 1 ? t.params[1].fallback : 0.0;
  switch (t.kind) {
    case Kind::D: return t.ref_d && std::isfinite(t.ref_d(0.8, p)) && (!t.aniso || t.ref_d_aniso);
    case Kind::G:
      return t.ref_g && std::isfinite(t.ref_g(0.7, 0.6, 0.9, 0.8, p)) && (t.g1_kernel_fn.empty() || t.ref_g1) &&
             (!t.aniso || t.ref_g1_aniso);
    case Kind::F: return t.ref_f && std::isfinite(t.ref_f(0.5, p, p1));
  }
  return false;
}

// What the terms lack, one message a gap. `plans` are mfv run's integral
// checks; a term is expected somewhere when a point of them names it, and
// every expected failure there gives its reason.
std::vector<std::string> gaps(const std::vector<const Term*>& terms, const std::vector<Plan>& plans) {
  std::vector<std::string> out;
  std::set<const Term*> in_plans;
  for (auto& p : plans)
    for (auto& pt : p.points) {
      for (const Term* t : {pt.d, pt.g, pt.f}) in_plans.insert(t);
      if (pt.expect != Expect::Hold && pt.reason.empty() && pt.d)
        out.push_back(fmt::format("{} of {}: an expected failure without its reason", p.check, pt.d->id));
    }
  for (auto* t : terms) {
    const std::string text = kernel_text(t->kind), name = fmt::format("{} '{}'", kind_name(t->kind), t->id);
    if (!defines(text, t->kernel_fn))
      out.push_back(fmt::format("{}: kernel function {} is not defined in {}", name, t->kernel_fn, file_of(t->kind)));
    if (!t->g1_kernel_fn.empty() && !defines(text, t->g1_kernel_fn))
      out.push_back(
          fmt::format("{}: G1 kernel function {} is not defined in {}", name, t->g1_kernel_fn, file_of(t->kind)));
    if (!reference_ok(*t))
      out.push_back(
          fmt::format("{}: no reference twin (host/reference/terms_*.cpp) in its catalog entry, or it is not "
                      "finite at the default parameter",
                      name));
    if (!in_plans.count(t))
      out.push_back(
          fmt::format("{}: no expected verdicts (mfv run checks it nowhere: a D x G grid, "
                      "host/checks/suite_aniso.cpp or suite_sheen.cpp)",
                      name));
  }
  return out;
}

std::vector<Plan> run_plans() {
  static const std::vector<Plan> plans = make_plans(SuiteOptions{});
  return plans;
}

}  // namespace

TEST_CASE("Every catalog term has its kernel function, its reference twin and expected verdicts",
          "[catalog][complete]") {
  std::vector<const Term*> terms;
  for (auto& t : catalog()) terms.push_back(&t);
  for (auto& gap : gaps(terms, run_plans())) FAIL_CHECK(gap);
}

TEST_CASE("The completeness check names each missing piece of a term", "[catalog][complete][planted]") {
  Term t = find_term("charlie");  // a copy, then a piece removed at a time
  SECTION("kernel function") {
    t.kernel_fn = "D_charlie_missing";
    auto g = gaps({&t}, {});
    REQUIRE(g.size() == 2);  // and no plan names this copy
    CHECK_THAT(g[0], Catch::Contains("kernel function D_charlie_missing is not defined in kernels/terms_d.cl"));
  }
  SECTION("reference") {
    t.ref_d = nullptr;
    auto g = gaps({&t}, {});
    REQUIRE(g.size() == 2);
    CHECK_THAT(g[0], Catch::Contains("D 'charlie': no reference twin"));
  }
  SECTION("expected verdicts") {
    auto g = gaps({&t}, run_plans());
    REQUIRE(g.size() == 1);
    CHECK_THAT(g[0], Catch::Contains("D 'charlie': no expected verdicts"));
  }
}
