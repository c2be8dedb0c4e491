#include "report/sheen_table.hpp"

#include <fmt/format.h>

namespace mfv {

std::string sheen_table_block(const EnergyReport& rep) {
  for (auto& t : rep.tables) {
    if (!t.d->own_lobe) continue;
    const size_t nm = rep.mu.size(), na = rep.alpha.size();
    if (nm != na) return "";  // the kernel's table is square (SHEEN_E_N per side)
    std::string s = fmt::format(
        "// E_sheen(mu, alpha) = ∫ D_charlie V_charlie (n·l) dl (white sheen), rows\n"
        "// alpha = 10^(-3 + 3 j/{}), columns mu = (m + 0.5)/{}: the E table of\n"
        "// `mfv energy --models {}/{} --grid {}x{}` (its sheen_e.cl; seed {}, max standard error {:.1e}).\n"
        "#define SHEEN_E_N {}\n__constant float SHEEN_E[SHEEN_E_N * SHEEN_E_N] = {{\n",
        na - 1, nm, t.d->id, t.g->id, nm, na, rep.opt.seed, rep.max_se, nm);
    for (size_t a = 0; a < na; ++a) {
      s += "   ";
      for (size_t m = 0; m < nm; ++m) s += fmt::format(" {:.6f}f,", t.E[a * nm + m].mean);
      s += "\n";
    }
    return s + "};\n";
  }
  return "";
}

}  // namespace mfv
