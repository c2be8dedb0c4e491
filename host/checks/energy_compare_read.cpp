// mfv energy --compare's readers (checks/energy_compare.hpp): CSV, C/C++
// array literals, PNG and OpenEXR images into the layout's cells, strictly: any cell
// missing, repeated, off the axes, non-numeric or NaN is an error naming the
// file, row and field.
#include "checks/energy_compare.hpp"

#include "util/error.hpp"
#include "util/exr.hpp"
#include "util/files.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <memory>

namespace mfv {

namespace {

std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r\"'"), b = s.find_last_not_of(" \t\r\"'");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Half a unit of the last digit `text` prints: "0.9876" -> 5e-5, "9.8e-01" -> 5e-3.
double printed_half_unit(const std::string& text) {
  const size_t e = text.find_first_of("eE");
  const std::string mant = text.substr(0, e);
  const size_t dot = mant.find('.');
  int frac = 0;
  if (dot != std::string::npos)
    for (size_t i = dot + 1; i < mant.size() && std::isdigit(static_cast<unsigned char>(mant[i])); ++i) ++frac;
  const int exp10 = e == std::string::npos ? 0 : std::atoi(text.c_str() + e + 1);
  return 0.5 * std::pow(10.0, double(exp10 - frac));
}

// A finite number, or an error naming where it stands.
double cell_number(const std::string& where, const std::string& text) {
  const std::string t = trim(text);
  double v;
  try {
    v = parse_number(where, t);
  } catch (const Error&) {
    throw Error(fmt::format("{}: '{}' is not a number", where, t));
  }
  if (!std::isfinite(v)) throw Error(fmt::format("{}: '{}' is not a finite number", where, t));
  return v;
}

// The index of `v` on `axis` within `tol`, or an error.
size_t axis_index(const std::string& where, const std::string& name, double v, double tol,
                  const std::vector<double>& axis) {
  size_t best = 0;
  double spacing = INFINITY;  // the axis' smallest step: a printed value may round, but not to another cell
  for (size_t i = 1; i < axis.size(); ++i) {
    if (std::fabs(axis[i] - v) < std::fabs(axis[best] - v)) best = i;
    spacing = std::min(spacing, std::fabs(axis[i] - axis[i - 1]));
  }
  tol = std::min(tol * 1.001, 0.05 * spacing);
  if (std::fabs(axis[best] - v) > tol + 1e-12 * std::max(1.0, std::fabs(v)))
    throw Error(fmt::format("{}: {} = {} is not on the layout's {} axis (nearest {:.9g})", where, name, v, name,
                            axis[best]));
  return best;
}

TheirTable empty_quantity(const std::string& file, const std::string& q, size_t n) {
  TheirTable t;
  t.file = file;
  t.quantity = q;
  t.value.assign(n, std::nan(""));
  t.precision.assign(n, 0);
  t.se.assign(n, 0);
  t.where.assign(n, "");
  return t;
}

// Every cell written once: else the first missing one is named.
void require_complete(const TheirTable& t, const std::vector<double>& mu, const std::vector<double>& width,
                      const std::vector<double>& eta, bool per_cell) {
  for (size_t c = 0; c < t.value.size(); ++c)
    if (t.where[c].empty()) {
      const size_t nm = mu.size(), w = per_cell ? c / nm : c;
      const std::string at = fmt::format("width = {:.9g}{}", width[w], eta.empty() ? "" : fmt::format(", eta = {:.9g}", eta[w]));
      throw Error(per_cell ? fmt::format("{}: wrong cell count: no {} at mu = {:.9g}, {} ({} cells)", t.file,
                                         t.quantity, mu[c % nm], at, t.value.size())
                           : fmt::format("{}: wrong cell count: no {} at {} ({} widths)", t.file, t.quantity, at,
                                         t.value.size()));
    }
}

// A glass layout's widths are (eta, roughness) pairs, eta slowest: the
// roughness axis (the widths of the first eta) and the eta axis.
size_t widths_per_eta(const std::vector<double>& eta) {
  size_t n = 0;
  while (n < eta.size() && eta[n] == eta[0]) ++n;
  return std::max<size_t>(1, n);
}

std::vector<TheirTable> read_csv(const std::string& path, const EnergyLayout& layout, const std::vector<double>& mu,
                                 const std::vector<double>& alpha, const std::vector<double>& roughness,
                                 const std::vector<double>& eta) {
  const std::string text = read_text_file(path, "--compare");
  const std::vector<std::string> lines = split(text, '\n');
  size_t row = 0;
  std::vector<std::string> head;
  size_t head_line = 0;
  for (; row < lines.size(); ++row) {
    const std::string l = trim(lines[row]);
    if (l.empty() || l[0] == '#') continue;
    for (auto& h : split(lines[row], ',')) head.push_back(trim(h));
    head_line = row++;
    break;
  }
  if (head.empty()) throw Error(fmt::format("{}: no header line", path));
  int col_mu = -1, col_r = -1, col_alpha = -1, col_eta = -1;
  std::map<std::string, int> qcol, secol;  // a quantity's column and its standard error's, where the file has one
  for (size_t i = 0; i < head.size(); ++i) {
    const std::string h = lower(head[i]);
    if (h == "mu" || h == "nov" || h == "cos_theta") col_mu = int(i);
    if (h == "roughness" || h == "r" || h == "perceptual_r") col_r = int(i);
    if (h == "alpha") col_alpha = int(i);
    if (h == "eta" || h == "ior") col_eta = int(i);
    for (auto& q : layout.quantities) {
      if (head[i] == q) qcol[q] = int(i);
      if (head[i] == q + "_se") secol[q] = int(i);
    }
  }
  // the width column: the layout's parametrization where the file has both
  const bool use_r = col_r >= 0 && (col_alpha < 0 || layout.param == RoughnessAxis::R2);
  const int col_w = use_r ? col_r : col_alpha;
  if (col_w < 0) throw Error(fmt::format("{}: header has no width column (roughness, r or alpha)", path));
  if (use_r && roughness.empty())
    throw Error(fmt::format("{}: a roughness column, but layout {} reads widths as alpha", path, layout.name));
  const std::vector<double>& waxis = use_r ? roughness : alpha;
  const std::string wname = use_r ? "roughness" : "alpha";
  if ((col_eta >= 0) != !eta.empty())
    throw Error(col_eta >= 0 ? fmt::format("{}: an eta column (a glass table), but layout {} has no eta axis", path,
                                           layout.name)
                             : fmt::format("{}: layout {} has an eta axis; the header has no eta column", path,
                                           layout.name));
  // a glass layout: the width index of (eta, roughness) is k * n_r + a
  const size_t n_r = widths_per_eta(eta);
  const std::vector<double> r_axis(waxis.begin(), waxis.begin() + long(eta.empty() ? waxis.size() : n_r));
  std::vector<double> eta_axis;
  for (size_t w = 0; w < eta.size(); w += n_r) eta_axis.push_back(eta[w]);
  // per-cell quantities with a mu column, or E_avg per width without one
  std::vector<std::string> qs;
  for (auto& [q, c] : qcol)
    if (layout_quantity_per_cell(q) == (col_mu >= 0)) qs.push_back(q);
  if (qs.empty())
    throw Error(fmt::format("{}: header names none of layout {}'s quantities{}", path, layout.name,
                            col_mu >= 0 ? " per cell (E, A, B)" : " per width (E_avg)"));
  const size_t n = col_mu >= 0 ? mu.size() * waxis.size() : waxis.size();
  std::vector<TheirTable> out;
  for (auto& q : qs) out.push_back(empty_quantity(path, q, n));
  for (; row < lines.size(); ++row) {
    const std::string l = trim(lines[row]);
    if (l.empty() || l[0] == '#') continue;
    const std::vector<std::string> f = split(lines[row], ',');
    const std::string where = fmt::format("{} row {}", path, row + 1);
    if (f.size() != head.size())
      throw Error(fmt::format("{}: {} fields, the header (line {}) has {}", where, f.size(), head_line + 1,
                              head.size()));
    auto field = [&](int c) { return fmt::format("{} field {} ({})", where, c + 1, head[size_t(c)]); };
    const double w = cell_number(field(col_w), f[size_t(col_w)]);
    size_t a = axis_index(field(col_w), wname, w, printed_half_unit(trim(f[size_t(col_w)])), r_axis);
    if (col_eta >= 0) {
      const double e = cell_number(field(col_eta), f[size_t(col_eta)]);
      a += n_r * axis_index(field(col_eta), "eta", e, printed_half_unit(trim(f[size_t(col_eta)])), eta_axis);
    }
    size_t c = a;
    if (col_mu >= 0) {
      const double m = cell_number(field(col_mu), f[size_t(col_mu)]);
      c = a * mu.size() + axis_index(field(col_mu), "mu", m, printed_half_unit(trim(f[size_t(col_mu)])), mu);
    }
    for (auto& t : out) {
      const int qc = qcol[t.quantity];
      if (!t.where[c].empty())
        throw Error(fmt::format("{}: the cell of {} is also on {}", where, t.quantity, t.where[c]));
      t.value[c] = cell_number(field(qc), f[size_t(qc)]);
      t.precision[c] = printed_half_unit(trim(f[size_t(qc)]));
      t.where[c] = fmt::format("row {}", row + 1);
      if (secol.count(t.quantity)) {
        t.se[c] = cell_number(field(secol[t.quantity]), f[size_t(secol[t.quantity])]);
        if (t.se[c] < 0) throw Error(fmt::format("{}: a negative standard error", field(secol[t.quantity])));
      }
    }
  }
  for (auto& t : out) require_complete(t, mu, waxis, eta, col_mu >= 0);
  return out;
}

// The array literals of a C/C++ file: each `= { ... }` initializer's numbers,
// nested braces flattened, comments removed; `is_float`: declared float or with an f suffix.
struct ArrayLiteral {
  std::string name;
  std::vector<std::string> items;
  bool is_float = false;
  size_t line = 0;
};

std::vector<ArrayLiteral> array_literals(const std::string& path) {
  std::string s = read_text_file(path, "--compare");
  for (size_t i = 0; i + 1 < s.size(); ++i) {  // comments to spaces, newlines kept (line numbers)
    if (s[i] == '/' && s[i + 1] == '/')
      for (; i < s.size() && s[i] != '\n'; ++i) s[i] = ' ';
    else if (s[i] == '/' && s[i + 1] == '*')
      for (size_t j = i + 2, prev = 0; j < s.size(); ++j) {
        const bool end = prev == '*' && s[j] == '/';
        prev = size_t(s[j]);
        if (s[j] != '\n') s[j] = ' ';
        s[i] = s[i + 1] = ' ';
        if (end) break;
      }
  }
  std::vector<ArrayLiteral> out;
  for (size_t eq = s.find('='); eq != std::string::npos; eq = s.find('=', eq + 1)) {
    size_t b = s.find_first_not_of(" \t\r\n", eq + 1);
    if (b == std::string::npos || s[b] != '{') continue;
    ArrayLiteral a;
    const size_t decl = s.rfind(';', eq) == std::string::npos ? 0 : s.rfind(';', eq) + 1;
    std::string d = s.substr(decl, eq - decl);
    a.is_float = d.find("float") != std::string::npos && d.find("double") == std::string::npos;
    const size_t br = d.find('[');
    a.name = trim(d.substr(0, br));
    a.name = a.name.substr(a.name.find_last_of(" \t\n") == std::string::npos ? 0 : a.name.find_last_of(" \t\n") + 1);
    a.line = size_t(std::count(s.begin(), s.begin() + long(b), '\n')) + 1;
    int depth = 0;
    std::string tok;
    size_t i = b;
    for (; i < s.size(); ++i) {
      const char ch = s[i];
      if (ch == '{') {
        ++depth;
      } else if (ch == '}' || ch == ',') {
        if (!trim(tok).empty()) a.items.push_back(trim(tok));
        tok.clear();
        if (ch == '}' && --depth == 0) break;
      } else if (ch != '\n') {
        tok += ch;
      }
    }
    if (depth != 0) throw Error(fmt::format("{} line {}: unterminated array literal", path, a.line));
    out.push_back(a);
    eq = i;
  }
  return out;
}

std::vector<TheirTable> read_c_arrays(const std::string& path, const EnergyLayout& layout,
                                      const std::vector<double>& mu, const std::vector<double>& alpha) {
  std::vector<std::string> per_cell, per_width;
  for (auto& q : layout.quantities) (layout_quantity_per_cell(q) ? per_cell : per_width).push_back(q);
  const size_t nm = mu.size(), na = alpha.size(), cells = nm * na, k = per_cell.size();
  std::vector<TheirTable> out;
  size_t next_cell = 0, next_width = 0;
  const std::vector<ArrayLiteral> arrays = array_literals(path);
  if (arrays.empty()) throw Error(fmt::format("{}: no array literal (= {{ ... }})", path));
  for (auto& arr : arrays) {
    const size_t n = arr.items.size();
    std::vector<std::string> qs;  // the quantities this array holds, interleaved
    if (n == cells * k && k > 1 && next_cell == 0) {
      qs = per_cell, next_cell = k;
    } else if (n == cells && next_cell < k) {
      qs = {per_cell[next_cell++]};
    } else if (n == na && next_width < per_width.size()) {
      qs = {per_width[next_width++]};
    } else {
      throw Error(fmt::format("{} line {}: array {} has {} elements; layout {} wants {} per quantity ({} x {}){}", path,
                              arr.line, arr.name, n, layout.name, cells, na, nm,
                              per_width.empty() ? "" : fmt::format(" or {} (E_avg)", na)));
    }
    const size_t per = qs.size();
    for (size_t j = 0; j < per; ++j) {
      TheirTable t = empty_quantity(path, qs[j], n / per);
      for (size_t c = 0; c < n / per; ++c) {
        std::string item = arr.items[c * per + j];
        const std::string where = fmt::format("{} line {}: {} element {}", path, arr.line, arr.name, c * per + j);
        bool fsuffix = false;
        while (!item.empty() && std::string("fFlL").find(item.back()) != std::string::npos) {
          fsuffix = fsuffix || item.back() == 'f' || item.back() == 'F';
          item.pop_back();
        }
        t.value[c] = cell_number(where, item);
        // the printed digits, then a float's storage: half an ulp, 2^-24 relative
        t.precision[c] = printed_half_unit(item) + ((arr.is_float || fsuffix) ? std::fabs(t.value[c]) * 0x1p-24 : 0.0);
        t.where[c] = fmt::format("{} element {}", arr.name, c * per + j);
      }
      out.push_back(t);
    }
  }
  return out;
}

// The quantities a w x h image of the layout holds: its per-cell ones (nm x
// na pixels, mu across, width down) or its per-width ones (na x 1).
std::vector<std::string> image_quantities(const std::string& path, const EnergyLayout& layout, size_t nm, size_t na,
                                          size_t w, size_t h) {
  std::vector<std::string> per_cell, per_width;
  for (auto& q : layout.quantities) (layout_quantity_per_cell(q) ? per_cell : per_width).push_back(q);
  if (w == nm && h == na) return per_cell;
  if (w == na && h == 1 && !per_width.empty()) return per_width;
  throw Error(fmt::format("{}: {} x {} pixels; layout {} wants {} x {} (mu across, width down){}", path, w, h,
                          layout.name, nm, na, per_width.empty() ? "" : fmt::format(" or {} x 1 (E_avg)", na)));
}

std::vector<TheirTable> read_png(const std::string& path, const EnergyLayout& layout, const std::vector<double>& mu,
                                 const std::vector<double>& alpha) {
  int w = 0, h = 0, ch = 0;
  const bool sixteen = stbi_is_16_bit(path.c_str());
  std::unique_ptr<void, void (*)(void*)> px(sixteen ? static_cast<void*>(stbi_load_16(path.c_str(), &w, &h, &ch, 0))
                                                    : static_cast<void*>(stbi_load(path.c_str(), &w, &h, &ch, 0)),
                                            stbi_image_free);
  if (!px) throw Error(fmt::format("{}: not a readable PNG ({})", path, stbi_failure_reason()));
  const std::vector<std::string> qs = image_quantities(path, layout, mu.size(), alpha.size(), size_t(w), size_t(h));
  if (size_t(ch) < qs.size() || (qs.size() == 1 && ch != 1 && ch != 2))
    throw Error(fmt::format("{}: {} channels; layout {} stores {} ({})", path, ch, layout.name, layout.image_channels,
                            qs.size()));
  const double full = sixteen ? 65535.0 : 255.0;
  std::vector<TheirTable> out;
  for (size_t j = 0; j < qs.size(); ++j) {
    TheirTable t = empty_quantity(path, qs[j], size_t(w) * size_t(h));
    for (size_t c = 0; c < t.value.size(); ++c) {
      const size_t at = c * size_t(ch) + j;
      const double v = sixteen ? static_cast<const uint16_t*>(px.get())[at] : static_cast<const uint8_t*>(px.get())[at];
      t.value[c] = v / full;
      t.precision[c] = 0.5 / full;
      t.where[c] = fmt::format("pixel ({}, {}) channel {}", c % size_t(w), c / size_t(w), "RGBA"[j]);
    }
    out.push_back(t);
  }
  return out;
}

// An OpenEXR table: the layout's image as the PNG's (N x N, or N x 1 for
// E_avg), one quantity in Y (or the only channel, or R), two in R and G;
// float channels read to half a float ulp, half ones to half a half ulp.
std::vector<TheirTable> read_exr(const std::string& path, const EnergyLayout& layout, const std::vector<double>& mu,
                                 const std::vector<double>& alpha) {
  const ExrImage img = exr_decode(read_text_file(path, "--compare"), path);
  const size_t w = size_t(img.width), h = size_t(img.height);
  const std::vector<std::string> qs = image_quantities(path, layout, mu.size(), alpha.size(), w, h);
  std::vector<TheirTable> out;
  for (size_t j = 0; j < qs.size(); ++j) {
    const ExrChannel* ch = qs.size() == 1 ? img.find("Y") : img.find(std::string(1, "RGB"[j]));
    if (!ch && qs.size() == 1) ch = img.channels.size() == 1 ? &img.channels[0] : img.find("R");
    if (!ch)
      throw Error(fmt::format("{}: no channel {} for {} (layout {}: {})", path,
                              qs.size() == 1 ? "Y" : std::string(1, "RGB"[j]), qs[j], layout.name,
                              qs.size() == 1 ? "Y, R or a single channel" : layout.image_channels));
    TheirTable t = empty_quantity(path, qs[j], w * h);
    for (size_t c = 0; c < t.value.size(); ++c) {
      t.value[c] = double(ch->pixel[c]);
      t.where[c] = fmt::format("pixel ({}, {}) channel {}", c % w, c / w, ch->name);
      if (!std::isfinite(t.value[c]))
        throw Error(fmt::format("{}: {}: {} is not a finite number", path, t.where[c], t.value[c]));
      // half an ulp of the stored type (half: 11 significant bits, subnormal spacing 2^-24)
      t.precision[c] = ch->half ? std::max(std::fabs(t.value[c]) * 0x1p-11, 0x1p-25) : std::fabs(t.value[c]) * 0x1p-24;
    }
    out.push_back(t);
  }
  return out;
}

}  // namespace

std::vector<TheirTable> read_their_table(const std::string& path, const EnergyLayout& layout,
                                         const std::vector<double>& mu, const std::vector<double>& alpha,
                                         const std::vector<double>& roughness, const std::vector<double>& eta) {
  const std::string ext = lower(path.substr(path.find_last_of('.') == std::string::npos ? path.size()
                                                                                         : path.find_last_of('.')));
  if (ext == ".csv") return read_csv(path, layout, mu, alpha, roughness, eta);
  if (ext == ".h" || ext == ".hpp" || ext == ".c" || ext == ".cpp" || ext == ".inl" || ext == ".hlsl" ||
      ext == ".glsl")
    return read_c_arrays(path, layout, mu, alpha);
  if (ext == ".png") return read_png(path, layout, mu, alpha);
  if (ext == ".exr") return read_exr(path, layout, mu, alpha);
  throw Error(fmt::format("--compare {}: want .csv, a C/C++ file (.h, .hpp, .c, .cpp, .inl), .png or .exr", path));
}

}  // namespace mfv
