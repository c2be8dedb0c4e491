// mfv energy's plan (checks/energy_plan.hpp): its integrals come from the
// check table's energy rows in record order, each on streams of its own.
#include "checks/check_table.hpp"
#include "checks/energy_plan.hpp"
#include "checks/integrate.hpp"

#include <catch2/catch.hpp>

using namespace mfv;

TEST_CASE("mfv energy's units: per width, E(mu) at every mu then E_avg, R streams each", "[energy][plan]") {
  EnergyReport rep;
  rep.opt.models = {"ggx/smith_ggx_correlated"};  // one table
  rep.opt.catalog_models = false;
  rep.opt.n_mu = 3;
  rep.opt.n_alpha = 2;
  rep.opt.replicates = 4;
  rep.mu = energy_mu_grid(rep.opt.n_mu);
  rep.alpha = energy_alpha_grid(rep.opt.n_alpha);
  const TermSelection sel = add_energy_subjects(rep);
  REQUIRE(rep.tables.size() == 1);
  CHECK(sel.f.size() == 1);
  uint32_t next = 0;
  const std::vector<EnergyUnit> units = energy_units(rep, next);
  REQUIRE(units.size() == 2 * (3 + 1));
  CHECK(next == units.size() * 4);
  for (size_t a = 0; a < 2; ++a)
    for (size_t m = 0; m < 4; ++m) {
      const EnergyUnit& u = units[a * 4 + m];
      const bool avg = m == 3;
      CHECK(u.first_stream == (a * 4 + m) * 4);
      CHECK(u.eavg == avg);
      CHECK(u.index == (avg ? a : a * 3 + m));
      CHECK(u.base.check == static_cast<int32_t>(avg ? IntegralKind::EavgRqmc : IntegralKind::AlbedoRqmc));
      CHECK(u.base.cos_o == float(avg ? 1.0 : rep.mu[m]));
      CHECK(u.base.pd == float(rep.alpha[a]));
      CHECK(u.base.width == float(proposal_width(*rep.tables[0].d, rep.alpha[a])));
    }
  CHECK(check_row("energy_mu").kind == IntegralKind::AlbedoRqmc);
  CHECK(check_row("energy_avg").kind == IntegralKind::EavgRqmc);
  const std::vector<IntegralSpec> r = specs_of(units[1], 4);
  REQUIRE(r.size() == 4);
  CHECK(r[3].stream == units[1].first_stream + 3);
}

TEST_CASE("mfv energy's plan refuses an empty selection", "[energy][plan]") {
  EnergyReport rep;
  rep.opt.tables = false;
  rep.opt.catalog_models = false;
  rep.mu = energy_mu_grid(2);
  rep.alpha = energy_alpha_grid(2);
  CHECK_THROWS_WITH(add_energy_subjects(rep), Catch::Contains("no D/G combination or whole model selected"));
}
