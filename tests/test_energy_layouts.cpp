// mfv energy's axes, points, engine layouts and --compare (issue 33): the
// axes exactly as given, a team's table passed, a planted error and a
// transposition flagged, bad tables refused, images read back (E at the
// Kulla-Conty points against quadrature: test_energy_kc_points.cpp).
#include "catalog/catalog.hpp"
#include "checks/energy_axes.hpp"
#include "checks/energy_compare.hpp"
#include "checks/energy_layouts.hpp"
#include "device_fixture.hpp"
#include "report/energy_layout_out.hpp"
#include "run_mfv.hpp"
#include "test_files.hpp"
#include "util/error.hpp"
#include "util/exr.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <regex>
#include <string>

using namespace mfv;
using Catch::Matchers::WithinAbs;
using mfv::test::Run;
using mfv::test::run_mfv;
using mfv::test::Scratch;
using mfv::test::slurp;

namespace {

// Every line of `text` but the one-line error: exit 2, "mfv: error: " first, one line.
void require_one_line_error(const Run& r) {
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.rfind("mfv: error: ", 0) == 0);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
}

// Fast settings for the tables the --compare tests write and check.
const std::string kFast = " --replicates 16 --target 5e-6 --max-points 262144 ";

// mfv's own table of `layout` in dir/layout/, written by one run.
void write_own_table(const Scratch& s, const std::string& layout) {
  Run r = run_mfv("energy --layout " + layout + kFast + "--out " + s / "own");
  INFO(r.out);
  REQUIRE(r.code == 0);
}

}  // namespace

TEST_CASE("energy axes are read exactly as given, in every range form", "[energy][axes]") {
  const std::vector<double> edges = parse_energy_axis("--mu", "edges:32");
  REQUIRE(edges.size() == 32);
  for (int y = 0; y < 32; ++y) CHECK(edges[size_t(y)] == double(y) / 31.0);
  CHECK(parse_energy_axis("--mu", "centers:4") == std::vector<double>{0.125, 0.375, 0.625, 0.875});
  CHECK(parse_energy_axis("--mu", "lin:0.2:1:5") == std::vector<double>{0.2, 0.4, 0.6000000000000001, 0.8, 1});
  CHECK(parse_energy_axis("--alpha", "0.5,0.1,1e-3") == std::vector<double>{0.5, 0.1, 1e-3});  // the given order
  CHECK(parse_energy_point("0.25,0.5") == std::pair<double, double>{0.25, 0.5});
  EnergyOptions o;
  set_energy_axes(o, {0.5}, {0.5, 1}, RoughnessAxis::R2, false);
  CHECK(o.alpha_axis == std::vector<double>{0.25, 1});
  CHECK(o.roughness == std::vector<double>{0.5, 1});
  const LayoutChoice kc = parse_energy_layout("kulla-conty:8");
  REQUIRE(kc.layout != nullptr);
  CHECK(kc.n == 8);
  apply_energy_layout(o, kc);
  CHECK(o.mu_axis == parse_energy_axis("--mu", "edges:8"));
  CHECK(o.alpha_axis[7] == 1.0);
  CHECK(o.alpha_axis[1] == (1.0 / 7) * (1.0 / 7));
}

TEST_CASE("energy axes refuse malformed lists, ranges, points and layouts", "[energy][axes]") {
  for (const char* bad : {"", "lin:0:1", "lin:0:1:0", "lin:a:1:3", "edges:1", "centers:0", "centers:-3", "edges:x",
                          "0.1,,0.2", "0.1,", "abc", "nan", "0.5,inf", "grid:3", "edges:2000"}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(parse_energy_axis("--mu", bad), Error);
  }
  for (const char* bad : {"0.5", "0.5,", "0.5,0.2,0.1", "x,0.2", ",0.3"}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(parse_energy_point(bad), Error);
  }
  for (const char* bad : {"kulla", "kulla-conty:", "kulla-conty:1", "split-sum:4:4", "sheen:x"}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(parse_energy_layout(bad), Error);
  }
  CHECK_THROWS_AS(parse_roughness_axis("r"), Error);
  EnergyOptions o;
  CHECK_THROWS_AS(set_energy_axes(o, {1.5}, {0.1}, RoughnessAxis::Alpha, false), Error);
  CHECK_THROWS_AS(set_energy_axes(o, {0.5}, {-0.1}, RoughnessAxis::Alpha, false), Error);
}

TEST_CASE("mfv energy rejects bad axes, points and layouts with one line and exit 2", "[energy][cli][axes]") {
  for (const char* args :
       {"--mu 0.5", "--alpha 0.5", "--mu 0.5 --alpha 0.5 --grid 4x4", "--at 0.5", "--at 0.5,0.1 --mu 0.5 --alpha 0.1",
        "--mu 2 --alpha 0.1", "--mu 0.5 --alpha lin:0:1", "--roughness r3 --at 0.5,0.1", "--roughness r2",
        "--layout nope", "--layout kulla-conty --roughness r2", "--compare x.csv", "--at 0.5,0.5,0.5"}) {
    CAPTURE(args);
    require_one_line_error(run_mfv(std::string("energy ") + args));
  }
}

TEST_CASE("mfv energy --mu/--alpha and --at write exactly the given values, in the given order", "[device][energy]") {
  if (!test::device_runtime()) return;
  Scratch s;
  Run r = run_mfv("energy --models ggx/smith_ggx_correlated --mu 0.9,0.1,0.5 --alpha 0.5,0.25 --roughness r2 "
                  "--replicates 4 --max-points 1024 --out " + s / "grid");
  INFO(r.out);
  REQUIRE(r.code == 0);
  nlohmann::json j = nlohmann::json::parse(slurp(s / "grid/energy.json"));
  CHECK(j["grid"]["mu"] == nlohmann::json({0.9, 0.1, 0.5}));
  CHECK(j["grid"]["alpha"] == nlohmann::json({0.25, 0.0625}));
  CHECK(j["grid"]["roughness"] == nlohmann::json({0.5, 0.25}));
  const auto& E = j["combinations"][0]["E"];
  REQUIRE(E.size() == 2);
  REQUIRE(E[0].size() == 3);
  CHECK(E[0][1].get<double>() < E[0][0].get<double>());  // grazing loses more than near-normal
  CHECK_FALSE(j["combinations"][0].contains("E_avg_quadrature"));  // not a midpoint grid
  r = run_mfv("energy --models ggx/smith_ggx_correlated --at 0.3,0.2 --at 0.7,0.05 --replicates 4 --max-points 1024 "
              "--out " + s / "at");
  INFO(r.out);
  REQUIRE(r.code == 0);
  j = nlohmann::json::parse(slurp(s / "at/energy.json"));
  CHECK(j["grid"]["mu"] == nlohmann::json({0.3, 0.7}));
  CHECK(j["grid"]["alpha"] == nlohmann::json({0.2, 0.05}));
  CHECK(j["grid"]["points"] == true);
  CHECK(j["combinations"][0]["E"].size() == 2);
  CHECK(slurp(s / "at/kulla_conty.h").find("MFV_A_ggx_smith_ggx_correlated[2]") != std::string::npos);
}

TEST_CASE("16-bit PNG tables read back to their quantization", "[energy][compare]") {
  Scratch s;
  const EnergyLayout& l = *parse_energy_layout("split-sum:3").layout;
  std::vector<double> v;
  for (int i = 0; i < 9 * 3; ++i) v.push_back(i % 3 == 2 ? 0.0 : std::fmod(0.123456789 * (i + 1), 1.0));
  const std::string path = s.file("t.png", png16(v, 3, 3, 3));
  const std::vector<double> axis = parse_energy_axis("--mu", "centers:3");
  const std::vector<TheirTable> t = read_their_table(path, l, axis, {0.1, 0.2, 0.3}, axis);
  REQUIRE(t.size() == 2);
  for (size_t q = 0; q < 2; ++q)
    for (size_t c = 0; c < 9; ++c) {
      CHECK(t[q].quantity == (q == 0 ? "A" : "B"));
      CHECK_THAT(t[q].value[c], WithinAbs(v[c * 3 + q], 0.5 / 65535 + 1e-12));
      CHECK(t[q].precision[c] == 0.5 / 65535);
    }
}

TEST_CASE("OpenEXR tables read back to their stored precision, float and half", "[energy][compare]") {
  Scratch s;
  const EnergyLayout& l = *parse_energy_layout("split-sum:3").layout;
  const std::vector<double> axis = parse_energy_axis("--mu", "centers:3");
  for (bool half : {false, true}) {
    ExrImage img;
    img.width = img.height = 3;
    std::vector<double> v[2];
    for (int q = 0; q < 2; ++q) {
      ExrChannel c;
      c.name = q == 0 ? "R" : "G";
      c.half = half;
      for (int i = 0; i < 9; ++i) {
        v[q].push_back(std::fmod(0.123456789 * (i + 1) * (q + 1), 1.0) * (i == 4 ? 1e-6 : 1.0));
        c.pixel.push_back(float(v[q].back()));
      }
      img.channels.push_back(c);
    }
    std::swap(img.channels[0], img.channels[1]);  // EXR's order: G, R
    const std::string path = s.file(half ? "half.exr" : "float.exr", exr_encode(img));
    const std::vector<TheirTable> t = read_their_table(path, l, axis, {0.1, 0.2, 0.3}, axis);
    REQUIRE(t.size() == 2);
    for (size_t q = 0; q < 2; ++q)
      for (size_t c = 0; c < 9; ++c) {
        CAPTURE(half, q, c, v[q][c], t[q].value[c], t[q].precision[c]);
        CHECK(t[q].quantity == (q == 0 ? "A" : "B"));
        CHECK(t[q].where[c] == fmt::format("pixel ({}, {}) channel {}", c % 3, c / 3, q == 0 ? "R" : "G"));
        CHECK(std::fabs(t[q].value[c] - v[q][c]) <= t[q].precision[c]);
        // the bound is half an ulp of the stored type, not looser
        CHECK(t[q].precision[c] <= (half ? std::max(v[q][c] * 0x1p-11, 0x1p-25) : v[q][c] * 0x1p-24) * (1 + 1e-3));
      }
  }
}

TEST_CASE("mfv energy --compare passes mfv's own table in each layout, as CSV, C array, PNG and EXR", "[device][energy][compare]") {
  if (!test::device_runtime()) return;
  for (std::string layout : {"split-sum:4", "kulla-conty:4", "sheen:4"}) {
    Scratch s;
    write_own_table(s, layout);
    std::string stem = layout.substr(0, layout.find(':'));
    std::replace(stem.begin(), stem.end(), '-', '_');
    // CSV (with its standard errors) against another seed; C array and PNG against the same seed
    for (std::string f : {stem + ".csv", stem + ".h", stem + ".png", stem + ".exr"}) {
      const std::string seed = f.find(".csv") != std::string::npos ? "2" : "1";
      Run r = run_mfv("energy --layout " + layout + kFast + "--seed " + seed + " --compare " + s / ("own/layout/" + f));
      CAPTURE(layout, f, r.out);
      CHECK(r.code == 0);
      CHECK(r.out.find("PASS: 0 of") != std::string::npos);
    }
  }
}

TEST_CASE("mfv energy --compare flags a planted 1e-4 error in one cell, naming it, and a transposition of the axes",
          "[device][energy][compare]") {
  if (!test::device_runtime()) return;
  Scratch s;
  write_own_table(s, "split-sum:4");
  const std::string h = slurp(s / "own/layout/split_sum.h");
  // the value of A at element 6 (roughness index 1, mu index 2) plus 1e-4
  std::smatch m;
  std::string planted = h;
  const std::regex a_list("mfv_split_sum_A\\[16\\] = \\{([^}]*)\\}");
  REQUIRE(std::regex_search(h, m, a_list));
  std::vector<std::string> items;
  {
    std::string body = m[1].str(), tok;
    for (char c : body + ",")
      if (c == ',') items.push_back(tok), tok.clear();
      else if (c != '\n' && c != ' ') tok += c;
  }
  REQUIRE(items.size() == 16);
  auto join = [](const std::vector<std::string>& v) {
    std::string o;
    for (size_t i = 0; i < v.size(); ++i) o += (i ? ", " : "") + v[i];
    return o;
  };
  std::vector<std::string> plant = items;
  plant[6] = fmt::format("{:.9g}f", std::stod(items[6]) + 1e-4);
  planted.replace(size_t(m.position(1)), size_t(m.length(1)), join(plant));
  Run r = run_mfv("energy --layout split-sum:4" + kFast + "--compare " + s.file("planted.h", planted));
  CAPTURE(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("FAIL: 1 of 32 cells") != std::string::npos);
  CHECK(std::regex_search(r.out, std::regex("A +mfv_split_sum_A element 6 .* FAIL")));
  // the axes transposed: element (a, m) holds the value of (m, a)
  std::vector<std::string> tr = items;
  for (size_t a = 0; a < 4; ++a)
    for (size_t k = 0; k < 4; ++k) tr[a * 4 + k] = items[k * 4 + a];
  std::string transposed = h;
  transposed.replace(size_t(m.position(1)), size_t(m.length(1)), join(tr));
  r = run_mfv("energy --layout split-sum:4" + kFast + "--compare " + s.file("transposed.h", transposed));
  CAPTURE(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("FAIL: ") != std::string::npos);
  // the same 1e-4 in B at pixel (3, 2) of the float EXR, and the EXR transposed
  ExrImage img = exr_decode(slurp(s / "own/layout/split_sum.exr"), "own");
  REQUIRE(img.channels.size() == 2);
  ExrImage plant_exr = img, tr_exr = img;
  REQUIRE(plant_exr.channels[0].name == "G");
  plant_exr.channels[0].pixel[2 * 4 + 3] += 1e-4f;
  r = run_mfv("energy --layout split-sum:4" + kFast + "--compare " + s.file("planted.exr", exr_encode(plant_exr)));
  CAPTURE(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("FAIL: 1 of 32 cells") != std::string::npos);
  CHECK(std::regex_search(r.out, std::regex("B +pixel \\(3, 2\\) channel G .* FAIL")));
  for (auto& c : tr_exr.channels)
    for (size_t a = 0; a < 4; ++a)
      for (size_t k = 0; k < 4; ++k) c.pixel[a * 4 + k] = img.find(c.name)->pixel[k * 4 + a];
  r = run_mfv("energy --layout split-sum:4" + kFast + "--compare " + s.file("transposed.exr", exr_encode(tr_exr)));
  CAPTURE(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("FAIL: ") != std::string::npos);
}

TEST_CASE("mfv energy --compare refuses a bad table with one line naming the file, row and field, exit 2", "[energy][compare]") {
  Scratch s;
  const std::string head = "mu,roughness,A,B\n";
  std::string good_rows;
  const std::vector<double> ax = parse_energy_axis("--mu", "centers:2");
  for (double r : ax)
    for (double m : ax) good_rows += fmt::format("{},{},0.5,0.1\n", m, r);
  struct Bad {
    std::string name, text, says;
  };
  const std::vector<Bad> bads = {
      {"short.csv", head + good_rows.substr(0, good_rows.rfind("0.75,0.75")), "wrong cell count"},
      {"nonnumeric.csv", head + std::regex_replace(good_rows, std::regex("0\\.5,0\\.1\\n$"), "0.5,abc\n"),
       "row 5 field 4 (B): 'abc' is not a number"},
      {"nan.csv", head + std::regex_replace(good_rows, std::regex("^0\\.25,0\\.25,0\\.5"), "0.25,0.25,nan"),
       "row 2 field 3 (A): 'nan' is not a finite number"},
      {"axis.csv", head + std::regex_replace(good_rows, std::regex("^0\\.25,0\\.25"), "0.3,0.25"),
       "row 2 field 1 (mu): mu = 0.3 is not on the layout's mu axis"},
      {"dup.csv", head + good_rows + "0.25,0.25,0.5,0.1\n", "row 6: the cell of A is also on row 2"},
      {"fields.csv", head + "0.25,0.25,0.5\n", "row 2: 3 fields"},
      {"nohead.csv", "# nothing\n", "no header"},
      {"eta.csv", "mu,roughness,eta,E\n", "eta column"},
      {"count.h", "static const float t[5] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f};\n", "has 5 elements"},
      {"word.h", "static const float t[4] = {0.1f, 0.2f, x, 0.4f};\nconst float u[4] = {1,1,1,1};\n",
       "element 2: 'x' is not a number"},
      {"nan.h", "static const double t[4] = {0.1, NAN, 0.3, 0.4};\n", "element 1: 'NAN' is not"},
      {"bad.png", "not a png", "not a readable PNG"},
      {"table.txt", "1,2\n", "want .csv"},
  };
  for (auto& b : bads) {
    Run r = run_mfv("energy --layout split-sum:2 --compare " + s.file(b.name, b.text));
    CAPTURE(b.name, b.says);
    require_one_line_error(r);
    CHECK(r.out.find(b.name) != std::string::npos);
    CHECK(r.out.find(b.says) != std::string::npos);
  }
  // the wrong size of image
  Run r = run_mfv("energy --layout split-sum:2 --compare " + s.file("small.png", png16({0.5, 0.5, 0.5}, 1, 1, 3)));
  require_one_line_error(r);
  CHECK(r.out.find("1 x 1 pixels") != std::string::npos);
  // EXR: not one, the wrong size, a NaN pixel, a missing channel
  auto exr = [](std::vector<std::pair<std::string, std::vector<float>>> ch, int w, int h) {
    ExrImage img;
    img.width = w, img.height = h;
    for (auto& [name, px] : ch) img.channels.push_back({name, px});
    return exr_encode(img);
  };
  const std::vector<float> ok(4, 0.5f);
  std::vector<float> nan = ok;
  nan[3] = std::nanf("");
  const std::vector<Bad> bad_exr = {
      {"bad.exr", "not an exr", "not a readable OpenEXR image"},
      {"small.exr", exr({{"G", {0.1f}}, {"R", {0.5f}}}, 1, 1), "1 x 1 pixels"},
      {"nan.exr", exr({{"G", ok}, {"R", nan}}, 2, 2), "pixel (1, 1) channel R: nan is not a finite number"},
      {"gray.exr", exr({{"Y", ok}}, 2, 2), "no channel R for A"},
  };
  for (auto& b : bad_exr) {
    r = run_mfv("energy --layout split-sum:2 --compare " + s.file(b.name, b.text));
    CAPTURE(b.name, b.says);
    require_one_line_error(r);
    CHECK(r.out.find(b.name) != std::string::npos);
    CHECK(r.out.find(b.says) != std::string::npos);
  }
}
