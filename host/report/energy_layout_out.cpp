#include "report/energy_layout_out.hpp"

#include "report/energy_plots.hpp"
#include "report/energy_report.hpp"
#include "util/error.hpp"
#include "util/exr.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <png.h>

#include <algorithm>
#include <cmath>

namespace mfv {

namespace {

std::string stem(const EnergyLayout& l) {
  std::string s = l.name;
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

// A float OpenEXR of t's quantities `qs` (w x h values each): channel Y for
// one, R and G for two (docs/energy-layouts.md).
std::string exr_table(const EnergyTable& t, const std::vector<std::string>& qs, size_t w, size_t h) {
  ExrImage img;
  img.width = int(w);
  img.height = int(h);
  for (size_t k = 0; k < qs.size(); ++k) {
    ExrChannel c;
    c.name = qs.size() == 1 ? "Y" : std::string(1, "RGB"[k]);
    for (const Cell& v : table_quantity(t, qs[k])) c.pixel.push_back(float(v.mean));
    img.channels.push_back(c);
  }
  std::sort(img.channels.begin(), img.channels.end(),
            [](const ExrChannel& a, const ExrChannel& b) { return a.name < b.name; });  // EXR's channel order
  return exr_encode(img);
}

void png_write_bytes(png_structp p, png_bytep data, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<const char*>(data), n);
}

}  // namespace

std::string png16(const std::vector<double>& v, size_t w, size_t h, size_t channels) {
  std::string out;
  png_structp p = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = p ? png_create_info_struct(p) : nullptr;
  if (!p || !info) throw Error("libpng: out of memory");
  std::vector<png_byte> row(w * channels * 2);
  if (setjmp(png_jmpbuf(p))) {
    png_destroy_write_struct(&p, &info);
    throw Error("libpng: could not encode the PNG");
  }
  png_set_write_fn(p, &out, png_write_bytes, nullptr);
  png_set_IHDR(p, info, png_uint_32(w), png_uint_32(h), 16, channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(p, info);
  for (size_t y = 0; y < h; ++y) {
    for (size_t i = 0; i < w * channels; ++i) {
      const double x = std::clamp(v[y * w * channels + i], 0.0, 1.0);
      const unsigned q = unsigned(std::lround(x * 65535.0));
      row[2 * i] = png_byte(q >> 8);  // PNG samples are big-endian
      row[2 * i + 1] = png_byte(q & 0xff);
    }
    png_write_row(p, row.data());
  }
  png_write_end(p, nullptr);
  png_destroy_write_struct(&p, &info);
  return out;
}

std::vector<std::pair<std::string, std::string>> energy_layout_files(const EnergyReport& rep, const EnergyLayout& l,
                                                                     const std::string& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  const size_t nm = rep.mu.size(), na = rep.alpha.size();
  const bool r2 = !rep.opt.roughness.empty();
  const std::vector<double>& w = r2 ? rep.opt.roughness : rep.alpha;
  const std::string wname = r2 ? "roughness" : "alpha";
  std::vector<std::string> per_cell, per_width;
  for (auto& q : l.quantities) (layout_quantity_per_cell(q) ? per_cell : per_width).push_back(q);
  for (auto& t : rep.tables) {
    const std::string base = dir + "/layout/" + stem(l) + (rep.tables.size() > 1 ? "_" + energy_file_stem(t) : "");
    const std::string head = fmt::format("# mfv energy --layout {}: {}{}, F = none; {}; seed {}\n", rep.opt.layout,
                                         t.bsdf ? "BSDF = " + t.bsdf->id + ", " : "", "D = " + t.d->id + ", G = " + t.g->id,
                                         l.source, rep.opt.seed);
    // CSV: one row per cell, mu fastest; the layout's parametrization names the width column
    // a glass layout adds the eta column (its widths are (eta, roughness) pairs, eta slowest)
    const bool glass = !rep.opt.eta.empty();
    auto eta_at = [&](size_t a) { return glass ? fmt::format(",{:.9g}", rep.opt.eta[a]) : std::string(); };
    std::string csv = head + "mu," + wname + (glass ? ",eta" : "");
    for (auto& q : per_cell) csv += "," + q + "," + q + "_se";
    csv += "\n";
    for (const CellAt& c : rep.cells()) {
      csv += fmt::format("{:.9g},{:.9g}", rep.mu[c.m], w[c.a]) + eta_at(c.a);
      for (auto& q : per_cell) csv += fmt::format(",{:.9g},{:.3e}", table_quantity(t, q)[c.c].mean, table_quantity(t, q)[c.c].se);
      csv += "\n";
    }
    files.push_back({base + ".csv", csv});
    // C/C++: one flat float array per quantity, [width][mu] order (mu fastest)
    const size_t n_r = glass ? size_t(std::count(rep.opt.eta.begin(), rep.opt.eta.end(), rep.opt.eta[0])) : na;
    std::string h = "/* " + head.substr(2, head.size() - 3) + ".\n * " + rep.opt.layout +
                    (glass ? fmt::format(": {} eta x {} {} x {} mu, index [(eta index * {} + {} index) * {} + mu "
                                         "index], eta ascending (leaving, 1/eta, first). */\n",
                                         na / n_r, n_r, wname, nm, n_r, wname, nm)
                           : fmt::format(": {} widths x {} mu, index [{} index * {} + mu index]. */\n", na, nm, wname, nm));
    for (auto& q : l.quantities) {
      const auto& v = table_quantity(t, q);
      h += fmt::format("static const float mfv_{}_{}[{}] = {{", stem(l), q, v.size());
      for (size_t i = 0; i < v.size(); ++i) h += fmt::format("{}{}{:.9g}f", i ? "," : "", i % 8 ? " " : "\n  ", v[i].mean);
      h += "\n};\n";
    }
    files.push_back({base + ".h", h});
    // PNG, 16-bit: mu across (x), width down (y, row 0 = the first width); per-cell quantities as channels
    std::vector<double> px;
    const size_t ch = per_cell.size() == 1 ? 1 : 3;
    for (size_t c = 0; c < nm * na; ++c)
      for (size_t k = 0; k < ch; ++k) px.push_back(k < per_cell.size() ? table_quantity(t, per_cell[k])[c].mean : 0.0);
    files.push_back({base + ".png", png16(px, nm, na, ch)});
    // OpenEXR, 32-bit float: the same pixels; Y for one quantity, R and G for two (A, B)
    files.push_back({base + ".exr", exr_table(t, per_cell, nm, na)});
    for (auto& q : per_width) {
      std::string e = head + wname + (glass ? ",eta," : ",") + q + "," + q + "_se\n";
      std::vector<double> row;
      for (size_t a = 0; a < na; ++a) {
        e += fmt::format("{:.9g}{},{:.9g},{:.3e}\n", w[a], eta_at(a), t.eavg[a].mean, t.eavg[a].se);
        row.push_back(t.eavg[a].mean);
      }
      files.push_back({base + "_" + q + ".csv", e});
      files.push_back({base + "_" + q + ".png", png16(row, na, 1, 1)});
      files.push_back({base + "_" + q + ".exr", exr_table(t, {q}, na, 1)});
    }
  }
  return files;
}

void print_compare_console(const CompareResult& r) {
  fmt::print("compare {} (layout {}) with mfv's {}: {} cells; total uncertainty = mfv SE + mfv rounding + the table's "
             "precision; Holm over every cell, family-wise {:g}\n",
             r.file, r.layout, r.table, r.cells.size(), r.alpha_fw);
  fmt::print("  {:<8} {:<34} {:>14} {:>14} {:>10} {:>10} {:>9} {}\n", "quantity", "cell", "theirs", "mfv", "total u",
             "their prec", "z", "verdict");
  const std::vector<size_t> worst = r.worst_first();
  for (size_t i = 0; i < worst.size() && i < 10; ++i) {
    const CompareCell& c = r.cells[worst[i]];
    fmt::print("  {:<8} {:<34} {:>14.9f} {:>14.9f} {:>10.2e} {:>10.2e} {:>9.2f} {}\n", c.quantity, c.where, c.theirs,
               c.ours, c.total, c.precision, c.z, c.fails ? "FAIL" : "ok");
  }
  fmt::print("{}: {} of {} cells deviate beyond their total uncertainty\n", r.pass() ? "PASS" : "FAIL", r.failed,
             r.cells.size());
}

std::vector<std::pair<std::string, std::string>> compare_files(const CompareResult& r, const EnergyReport& rep,
                                                               const std::string& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  const std::vector<double>& w = rep.opt.roughness.empty() ? rep.alpha : rep.opt.roughness;
  std::string csv = fmt::format("# mfv energy --compare {} --layout {}: mfv's {}; Holm, family-wise {:g}\n", r.file,
                                r.layout, r.table, r.alpha_fw);
  csv += "quantity,where,width,eta,mu,theirs,mfv,mfv_se,mfv_rounding,their_precision,total_uncertainty,z,p,"
         "one_sided,fails\n";
  nlohmann::json cells = nlohmann::json::array();
  for (size_t i : r.worst_first()) {
    const CompareCell& c = r.cells[i];
    const bool per_cell = layout_quantity_per_cell(c.quantity);
    const std::string eta = rep.opt.eta.empty() ? "" : fmt::format("{:.9g}", rep.opt.eta[c.a]);
    csv += fmt::format("{},\"{}\",{:.9g},{},{},{:.9g},{:.9g},{:.3e},{:.3e},{:.3e},{:.3e},{:.4g},{:.3e},{},{}\n",
                       c.quantity, c.where, w[c.a], eta, per_cell ? fmt::format("{:.9g}", rep.mu[c.m]) : "",
                       c.theirs, c.ours, c.se, c.rounding, c.precision, c.total, c.z, c.p, c.one_sided ? 1 : 0,
                       c.fails ? 1 : 0);
    cells.push_back({{"quantity", c.quantity}, {"where", c.where}, {"width", w[c.a]},
                     {"eta", rep.opt.eta.empty() ? nlohmann::json(nullptr) : nlohmann::json(rep.opt.eta[c.a])},
                     {"one_sided", c.one_sided},
                     {"mu", per_cell ? nlohmann::json(rep.mu[c.m]) : nlohmann::json(nullptr)},
                     {"theirs", c.theirs}, {"mfv", c.ours}, {"total_uncertainty", c.total}, {"z", c.z},
                     {"p", c.p}, {"fails", c.fails}});
  }
  files.push_back({dir + "/compare.csv", csv});
  nlohmann::json j{{"schema", "mfv-energy-compare/1"}, {"file", r.file},        {"layout", r.layout},
                   {"table", r.table},                  {"alpha_fw", r.alpha_fw}, {"cells_failed", r.failed},
                   {"pass", r.pass()},                  {"cells_worst_first", cells}};
  files.push_back({dir + "/compare.json", j.dump(1)});
  // heat maps of z over (mu, width), one per per-cell quantity
  NamedBytes data;
  std::vector<std::string> names;
  std::string gp = "set encoding utf8\nset view map\nset palette defined (-5 '#2166ac', 0 '#f7f7f7', 5 '#b2182b')\n";
  std::vector<std::string> seen;
  for (auto& c : r.cells)
    if (layout_quantity_per_cell(c.quantity) && std::find(seen.begin(), seen.end(), c.quantity) == seen.end())
      seen.push_back(c.quantity);
  for (auto& q : seen) {
    std::string d;
    size_t last_a = SIZE_MAX;
    for (auto& c : r.cells)
      if (c.quantity == q) {
        if (last_a != SIZE_MAX && c.a != last_a) d += "\n";
        last_a = c.a;
        d += fmt::format("{:.9g} {:.9g} {:.6g}\n", rep.mu[c.m], w[c.a], std::isfinite(c.z) ? c.z : 1e3);
      }
    data.push_back({"z_" + q + ".dat", d});
    const std::string png = "compare_heat_" + q + ".png";
    names.push_back(png);
    gp += fmt::format(
        "set terminal pngcairo size 640,520 font ',9'\nset output '{}'\nset title '{}: (theirs − mfv) / total "
        "uncertainty, {}'\nset xlabel 'μ'\nset ylabel '{}'\nset cbrange [-5:5]\nset autoscale xfix\nset autoscale "
        "yfix\nplot 'z_{}.dat' using 1:2:3 with image notitle\n",
        png, q, gnuplot_literal(r.layout), rep.opt.roughness.empty() ? "α" : "r (α = r^2)", q);
  }
  if (!names.empty())
    for (auto& [n, bytes] : render_gnuplot(data, gp, names)) files.push_back({dir + "/plots/" + n, bytes});
  return files;
}

}  // namespace mfv
