// mfv energy --layout glass (issue 33): the rough dielectric BSDF's E, E_R
// and E_T per (mu, roughness, eta), entering and leaving, from bsdf_furnace's
// integrand; its axes, its own table passing --compare, a planted error and a
// transposition flagged, bad glass tables refused, and cells against the
// independent facet-space quadrature (checks/transmission_truth.hpp).
#include "catalog/bsdfs.hpp"
#include "catalog/roughness.hpp"
#include "checks/energy.hpp"
#include "checks/energy_axes.hpp"
#include "checks/energy_compare.hpp"
#include "checks/energy_layouts.hpp"
#include "checks/transmission_truth.hpp"
#include "device_fixture.hpp"
#include "energy_criterion.hpp"
#include "run_mfv.hpp"
#include "stats/verdict.hpp"
#include "test_files.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>

using namespace mfv;
using mfv::test::Run;
using mfv::test::run_mfv;
using mfv::test::Scratch;
using mfv::test::slurp;

namespace {

// Fast settings for the glass tables the --compare tests write and check
// (a standard error per cell of 1e-5 to 1e-3 with bsdf_furnace's MIS
// estimator; the 1e-4 plant below takes the cap).
const std::string kGlass = " --layout glass:3 --replicates 16 --target 1e-3 --max-points 4096 ";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::string l;
  for (char c : text)
    if (c == '\n') out.push_back(l), l.clear();
    else l += c;
  return out;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out;
  std::string f;
  for (char c : line + ",")
    if (c == ',') out.push_back(f), f.clear();
    else f += c;
  return out;
}

std::string joined(const std::vector<std::string>& v, char sep) {
  std::string o;
  for (size_t i = 0; i < v.size(); ++i) o += (i ? std::string(1, sep) : "") + v[i];
  return o;
}

}  // namespace

TEST_CASE("the glass layout holds (eta, roughness) widths, eta and 1/eta ascending, in double", "[energy][axes]") {
  const std::vector<double> lg = parse_energy_axis("--eta", "log:1:100:3");
  REQUIRE(lg.size() == 3);
  CHECK(lg[0] == 1);
  CHECK(std::fabs(lg[1] - 10) < 1e-14);
  CHECK(lg[2] == 100);  // both ends exactly
  CHECK_THROWS_AS(parse_energy_axis("--eta", "log:0:1:3"), Error);
  CHECK_THROWS_AS(parse_energy_layout("glass:2"), Error);  // E_avg's midpoint rule needs 3 mu cells
  const LayoutChoice g = parse_energy_layout("glass:4");
  REQUIRE(g.layout != nullptr);
  const std::vector<double> eta = layout_eta_axis(*g.layout, 4);
  REQUIRE(eta.size() == 8);
  CHECK(eta[4] == 1.01);
  CHECK(eta[7] == 100);
  for (size_t k = 0; k < 4; ++k) CHECK(eta[3 - k] == 1.0 / eta[4 + k]);  // leaving: the inverses
  EnergyOptions o;
  apply_energy_layout(o, g);
  CHECK(o.fp64);
  CHECK(o.mu_axis == parse_energy_axis("--mu", "centers:4"));
  REQUIRE(o.alpha_axis.size() == 32);
  REQUIRE(o.eta.size() == 32);
  for (size_t w = 0; w < 32; ++w) {
    CHECK(o.eta[w] == eta[w / 4]);  // eta slowest
    CHECK(o.roughness[w] == (double(w % 4) + 0.5) / 4);
    CHECK(o.alpha_axis[w] == o.roughness[w] * o.roughness[w]);
  }
  CHECK(o.models == std::vector<std::string>{"walter_ggx_correlated"});
  validate_energy_options(o);
  // one side only: a renderer's entering table, and its leaving one, apart
  const std::vector<double> enter = layout_eta_axis(*parse_energy_layout("glass-enter:4").layout, 4);
  const std::vector<double> leave = layout_eta_axis(*parse_energy_layout("glass-leave:4").layout, 4);
  CHECK(enter == std::vector<double>(eta.begin() + 4, eta.end()));
  CHECK(leave == std::vector<double>(eta.begin(), eta.begin() + 4));
}

TEST_CASE("mfv energy --compare passes mfv's own glass table and flags a planted error and a transposition",
          "[device][energy][compare][glass]") {
  if (!test::device_runtime()) return;
  Scratch s;
  Run own = run_mfv("energy" + kGlass + "--out " + s / "own");
  INFO(own.out);
  REQUIRE(own.code == 0);
  const std::string csv = slurp(s / "own/layout/glass.csv");
  CHECK(csv.find("\nmu,roughness,eta,E,E_se,E_R,E_R_se,E_T,E_T_se\n") != std::string::npos);
  // its own table: the CSV (with its standard errors) at another seed, the C arrays at the same
  for (std::string f : {"glass.csv", "glass.h", "glass_E_avg.csv", "glass.exr"}) {
    Run r = run_mfv("energy" + kGlass + "--seed " + std::string(f == "glass.csv" ? "2" : "1") + " --compare " +
                    s / ("own/layout/" + f));
    CAPTURE(f, r.out);
    CHECK(r.code == 0);
    CHECK(r.out.find("PASS: 0 of") != std::string::npos);
  }
  // one side's table alone (a renderer's entering table): its own C arrays pass (27 x 3 + 9 E_avg)
  Run enter = run_mfv("energy --layout glass-enter:3 --replicates 16 --target 1e-3 --max-points 4096 --out " +
                      s / "enter");
  INFO(enter.out);
  REQUIRE(enter.code == 0);
  Run r1 = run_mfv("energy --layout glass-enter:3 --replicates 16 --target 1e-3 --max-points 4096 --compare " +
                   s / "enter/layout/glass_enter.h");
  CAPTURE(r1.out);
  CHECK(r1.code == 0);
  CHECK(r1.out.find("PASS: 0 of 90 cells") != std::string::npos);
  // a planted error in E_R of one entering cell (E_R is never one-sided), in
  // units of that cell's own standard error: 25 of them
  std::vector<std::string> rows = lines_of(csv);
  size_t at = 0;
  for (size_t i = 0; i < rows.size() && at == 0; ++i)
    if (rows[i].rfind("0.5,0.5,1.01,", 0) == 0) at = i;  // mu = 0.5, r = 0.5, eta = 1.01 (entering)
  REQUIRE(at > 0);
  std::vector<std::string> f = fields_of(rows[at]);
  const double plant = 25 * std::stod(f[6]);
  f[5] = fmt::format("{:.9g}", std::stod(f[5]) + plant);
  std::vector<std::string> planted = rows;
  planted[at] = joined(f, ',');
  Run r = run_mfv("energy" + kGlass + "--compare " + s.file("planted.csv", joined(planted, '\n') + "\n") +
                  " --out " + s / "cmp");
  CAPTURE(plant, r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("FAIL: 1 of 162 cells") != std::string::npos);
  CHECK(std::regex_search(r.out, std::regex(fmt::format("E_R +row {} .* FAIL", at + 1))));
  // compare.csv lists it first (worst first), with its eta; the heat maps where gnuplot is
  const std::vector<std::string> cmp = lines_of(slurp(s / "cmp/compare.csv"));
  REQUIRE(cmp.size() > 2);
  CHECK(cmp[1].find("quantity,where,width,eta,mu,") == 0);
  CHECK(cmp[2].find(fmt::format("E_R,\"row {}\",0.5,1.01,0.5,", at + 1)) == 0);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0)
    for (const char* q : {"E", "E_R", "E_T"}) CHECK(!slurp(s / fmt::format("cmp/plots/compare_heat_{}.png", q)).empty());
  // mu and roughness transposed within each eta slice of the C array of E_R
  const std::string h = slurp(s / "own/layout/glass.h");
  std::smatch m;
  REQUIRE(std::regex_search(h, m, std::regex("mfv_glass_E_R\\[54\\] = \\{([^}]*)\\}")));
  std::vector<std::string> items;
  for (auto& x : fields_of(m[1].str())) items.push_back(std::regex_replace(x, std::regex("[\\s]"), ""));
  REQUIRE(items.size() == 54);
  std::vector<std::string> tr = items;
  for (size_t k = 0; k < 6; ++k)
    for (size_t a = 0; a < 3; ++a)
      for (size_t j = 0; j < 3; ++j) tr[(k * 3 + a) * 3 + j] = items[(k * 3 + j) * 3 + a];
  std::string transposed = h;
  transposed.replace(size_t(m.position(1)), size_t(m.length(1)), joined(tr, ','));
  r = run_mfv("energy" + kGlass + "--compare " + s.file("transposed.h", transposed));
  CAPTURE(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("FAIL: ") != std::string::npos);
}

TEST_CASE("mfv energy --compare flags a 1e-4 error planted in one glass cell and names it, and passes the unplanted table",
          "[device][energy][compare][glass]") {
  if (!test::device_runtime()) return;
  Scratch s;
  // 27 entering cells at the cap (5 x 2^11 RQMC points a replicate): E_T's standard error is ~1e-5
  // (bsdf_furnace's MIS estimator, docs/performance.md "Glass tables"), a tenth of the plant
  const std::string glass = " --layout glass-enter:3 --target 1e-6 ";
  Run own = run_mfv("energy" + glass + "--out " + s / "own");
  INFO(own.out);
  REQUIRE(own.code == 0);
  // E_T alone, as a team's CSV without standard errors (its printed precision is 9 digits)
  const std::vector<std::string> rows = lines_of(slurp(s / "own/layout/glass_enter.csv"));
  REQUIRE(rows.size() == 29);  // a comment line, the header, 27 cells
  REQUIRE(rows[1] == "mu,roughness,eta,E,E_se,E_R,E_R_se,E_T,E_T_se");
  std::vector<std::string> theirs = {"mu,roughness,eta,E_T"};
  for (size_t i = 2; i < rows.size(); ++i) {
    const std::vector<std::string> f = fields_of(rows[i]);
    theirs.push_back(joined({f[0], f[1], f[2], f[7]}, ','));
  }
  Run ok = run_mfv("energy" + glass + "--compare " + s.file("theirs.csv", joined(theirs, '\n') + "\n"));
  CAPTURE(ok.out);
  CHECK(ok.code == 0);
  CHECK(ok.out.find("PASS: 0 of 27 cells") != std::string::npos);
  // +1e-4 in E_T of the file's row 6 (mu = 1/2, r = 1/2, eta = 1.01)
  std::vector<std::string> f = fields_of(theirs[5]);
  f[3] = fmt::format("{:.9g}", std::stod(f[3]) + 1e-4);
  std::vector<std::string> planted = theirs;
  planted[5] = joined(f, ',');
  Run r = run_mfv("energy" + glass + "--compare " + s.file("planted.csv", joined(planted, '\n') + "\n"));
  CAPTURE(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("FAIL: 1 of 27 cells") != std::string::npos);
  CHECK(std::regex_search(r.out, std::regex("E_T +row 6 .* FAIL")));
}

TEST_CASE("mfv energy --compare refuses bad glass tables with one line and exit 2", "[energy][compare][glass]") {
  Scratch s;
  const std::string head = "mu,roughness,eta,E\n";
  std::string ok;
  const std::vector<double> eta = layout_eta_axis(*parse_energy_layout("glass:3").layout, 3);
  for (double e : eta)
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 3; ++k) ok += fmt::format("{:.9g},{:.9g},{:.9g},0.9\n", (k + 0.5) / 3, (a + 0.5) / 3, e);
  std::string short_list = "0.5";
  for (int i = 1; i < 53; ++i) short_list += ", 0.5";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"no_eta.csv", "mu,roughness,E\n0.5,0.5,0.9\n"},                          // a glass layout needs eta
      {"missing.csv", head + ok.substr(0, ok.rfind('\n', ok.size() - 2) + 1)},  // one cell short
      {"off_axis.csv", head + std::regex_replace(ok, std::regex(fmt::format("^0.166666667,0.166666667,{:.9g},", eta[0])),
                                                 fmt::format("0.166666667,0.166666667,{:.9g},", 1.5 * eta[0]))},  // eta off its axis
      {"nan.csv", head + std::regex_replace(ok, std::regex(",0.9\n$"), ",nan\n")},
      {"short.h", "static const float e[53] = {" + short_list + "};"},  // 54 per quantity
  };
  for (auto& [name, text] : bad) {
    Run r = run_mfv("energy --layout glass:3 --compare " + s.file(name, text));
    CAPTURE(name, r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
  // an eta column on a layout without an eta axis
  Run r = run_mfv("energy --layout sheen:3 --compare " + s.file("eta.csv", "mu,roughness,eta,E\n0.5,0.5,1.5,0.9\n"));
  CHECK(r.code == 2);
  CHECK(r.out.find("no eta axis") != std::string::npos);
}

namespace {

// The deviations of the glass cells of `bsdf` (E_R, E_T, E at each cell),
// added to `tally`, in total uncertainties from the facet-space quadrature of the correct
// entry of its D (checks/transmission_truth.hpp, the truth of bsdf_furnace);
// where mfv's value is only a lower bound (glass_lower_bound_only) only an
// excess counts. Total: mfv's SE plus, linearly, the truth's error (a 12-node
// against an 8-node product rule) and mfv's rounding bound.
void glass_cell_deviations(Runtime& rt, const std::string& bsdf, uint64_t seed, test::DeviationTally& tally) {
  // three (eta, roughness) widths and two view cosines: entering glass,
  // leaving it (critical cosine 0.745: mu = 0.9 above, 0.3 beyond), a dense medium
  EnergyOptions o;
  o.models = {bsdf};
  o.catalog_models = false;
  o.fp64 = true;
  o.seed = seed;
  o.replicates = 32;
  o.target = 2e-3;
  o.max_points = 1 << 14;
  o.mu_axis = {0.3, 0.9};
  const std::vector<std::pair<double, double>> widths = {{1.5, 0.3}, {1 / 1.5, 0.5}, {3.0, 0.7}};
  for (auto [e, r] : widths) {
    o.eta.push_back(e);
    o.roughness.push_back(r);
    o.alpha_axis.push_back(r * r);
  }
  const EnergyReport rep = run_energy(rt, o);
  REQUIRE(rep.tables.size() == 1);
  const EnergyTable& t = rep.tables[0];
  const Bsdf& b = *try_find_bsdf("walter_ggx_correlated");  // the physics of the D (and of a planted entry)
  const ProductRule fine{12, 3, 8, 1e-10}, coarse{8, 2, 4, 1e-10};  // as suite_bsdf.cpp's truth
  for (const CellAt& c : rep.cells()) {
    const double e = o.eta[c.a], alpha = o.alpha_axis[c.a];
    // the truth at the point the kernel integrates (mu, eta and widths as float32: the integral ABI)
    const ref::BtdfSpec spec{b.d, b.g, b.form, b.variant, double(float(native_from_alpha(b.d->roughness, alpha))),
                             double(float(native_from_alpha(b.g->roughness, alpha))), double(float(e > 1 ? e : 1 / e))};
    const double mu = double(float(rep.mu[c.m]));
    const BsdfFlux q = bsdf_flux_truth(spec, mu, e < 1, fine), q2 = bsdf_flux_truth(spec, mu, e < 1, coarse);
    const double truth_error = std::max(std::fabs(q.reflected - q2.reflected), std::fabs(q.transmitted - q2.transmitted));
    for (const std::string quantity : {"E_R", "E_T", "E"}) {
      const Cell& v = table_quantity(t, quantity)[c.c];
      const double want = quantity == "E_R" ? q.reflected : quantity == "E_T" ? q.transmitted : q.reflected + q.transmitted;
      const double bias = (quantity == "E" ? 2 : 1) * truth_error + energy_rounding_bound(rep, t, c.a, v.mean);
      const double total = stats::total_uncertainty(v.se, bias);
      const bool lower_only = glass_lower_bound_only(rep, quantity, c.a, c.m);
      const double z = (v.mean - want) / total;
      CAPTURE(bsdf, quantity, e, alpha, rep.mu[c.m], v.mean, v.se, want, truth_error, lower_only, z);
      CHECK(v.se <= o.target * 3);
      tally.add(z, lower_only);  // a missed rare transmission lies below the truth
    }
  }
}

}  // namespace

TEST_CASE("glass cells lie within 3 total uncertainties of the facet-space quadrature, family-wise, entering and leaving",
          "[device][energy][fp64][glass]") {
  Runtime* rt = test::fp64_runtime("the glass layout's cells");
  if (!rt) return;
  // family-wise over the 54 values of the three seeds (tests/energy_criterion.hpp)
  test::DeviationTally correct(32), planted(32);
  for (uint64_t seed : {1, 2, 3}) glass_cell_deviations(*rt, "walter_ggx_correlated", seed, correct);
  correct.check();
  // a planted BSDF: F at n.i instead of i.h (catalog known-bad entry)
  glass_cell_deviations(*rt, "walter_ggx_f_at_n", 1, planted);
  CHECK(planted.fails());
}
