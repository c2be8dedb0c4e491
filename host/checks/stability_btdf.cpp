// mfv stability's cases of the rough dielectric BTDFs (catalog/bsdfs.hpp):
// near the critical angle, η = 1 ± 1e-6, grazing, α down to 1e-7 and the
// degenerate h_t where η_i i + η_o o ≈ 0, on both sides of the interface.
#include "abi/bsdf.h"
#include "catalog/bsdfs.hpp"
#include "catalog/roughness.hpp"
#include "checks/pointwise_inputs.hpp"
#include "checks/stability_cases.hpp"
#include "reference/btdf.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <cmath>

namespace mfv::stability_detail {

CaseDef btdf_case(const Bsdf& b, bool fp64, const std::vector<std::array<double, 2>>& scene_points) {
  CaseDef c;
  c.info.group = "bsdf";
  c.info.family = "BTDF";
  c.info.name = "BTDF " + b.id;
  c.info.formula = b.formula;
  // known-bad entries plant physics bugs (the same-side one divides by a grazing i.n
  // it no longer rejects): reported, not gated
  c.info.stable = b.d->stable && b.g->stable && b.known_bad.empty();
  c.mode = PW_BTDF;
  c.d = b.d;
  c.g = b.g;
  c.f_code = b.code();
  const Bsdf* pb = &b;
  c.ref = [pb](const In& r) {
    const ref::BtdfSpec s{pb->d, pb->g, pb->form, pb->variant, r[PW_PD], r[PW_PG], r[PW_F0]};
    return ref::btdf(s, wi_of(r), wo_of(r));
  };
  c.describe = [](const In& r) {
    return fmt::format("wi=({}, {}, {}) wo=({}, {}, {}) pD={} pG={} eta={}", hx(r[PW_WI_X]), hx(r[PW_WI_Y]),
                       hx(r[PW_WI_Z]), hx(r[PW_WO_X]), hx(r[PW_WO_Y]), hx(r[PW_WO_Z]), hx(r[PW_PD]), hx(r[PW_PG]),
                       hx(r[PW_F0]));
  };
  // α converted to each term's parameter, skipped outside a term's range.
  std::vector<std::array<double, 2>> widths;
  for (double a : {1e-7, 1e-4, 1e-2, 0.3, 1.0}) {
    const double nd = native_from_alpha(b.d->roughness, a), ng = native_from_alpha(b.g->roughness, a);
    if (nd < b.d->params[0].lo || nd > b.d->params[0].hi || ng < b.g->params[0].lo || ng > b.g->params[0].hi) continue;
    widths.push_back({nd, ng});
  }
  auto add = [&](int region, const glm::dvec3& i, const glm::dvec3& o, double eta) {
    for (auto& w : widths) {
      Point pt;
      pt.region = region;
      pt.in = record(i, o, {w[0], w[1], eta});
      c.points.push_back(pt);
      pt.in = record(-i, -o, {w[0], w[1], eta});  // the other side: light from below
      c.points.push_back(pt);
    }
  };
  // o = i refracted through the facet m from index 1 into eta (none: straight through).
  auto refracted = [](const glm::dvec3& i, const glm::dvec3& m, double eta) {
    glm::dvec3 t;
    return ref::refract(i, m, 1.0 / eta, t) ? t : -i;
  };
  // the declared range's ends (catalog/bsdfs.hpp) with the common indices
  const double etas[] = {1.5, 1 / 1.5, 3.0, 0.1, 10.0, b.eta.lo, b.eta.hi};
  const double az = 0.4;
  {
    int r = c.add_region({"refracted",
                          fmt::format("o = i refracted through facets near n (the lobe's peak and flank); eta in "
                                      "{{1.5, 1/1.5, 3, 0.1, 10, {:g}, {:g}}}; alpha in {{1e-7, 1e-4, 1e-2, 0.3, 1}} "
                                      "within range",
                                      b.eta.lo, b.eta.hi),
                          true, ""});
    for (double eta : etas)
      for (double ci : {0.99, 0.7, 0.3})
        for (double tm : {0.0, 1e-4, 0.05, 0.5}) add(r, dir(ci, az), refracted(dir(ci, az), dir(std::cos(tm), 1.0), eta), eta);
  }
  if (!scene_points.empty()) {
    // mfv stability --scene: each refracting material at its own alpha and eta
    // (= ior): refracted pairs as above, and leaving it around its critical angle
    std::string pts;
    for (auto& [a, eta] : scene_points) pts += fmt::format(" (alpha {:.4g}, eta {:.4g})", a, eta);
    int r = c.add_region({"scene",
                          "the scene's refracting materials:" + pts +
                              "; o refracted through facets near n, and n.i at cos(theta_c) of 1/eta (1 +- {1e-7, "
                              "1e-4, 1e-2})",
                          true, ""});
    for (auto& [a, eta] : scene_points) {
      const double nd = native_from_alpha(b.d->roughness, a), ng = native_from_alpha(b.g->roughness, a);
      auto put = [&](const glm::dvec3& i, const glm::dvec3& o, double e) {
        Point pt;
        pt.region = r;
        pt.in = record(i, o, {nd, ng, e});
        c.points.push_back(pt);
        pt.in = record(-i, -o, {nd, ng, e});  // the other side: light from below
        c.points.push_back(pt);
      };
      for (double ci : {0.99, 0.7, 0.3, 0.05})
        for (double tm : {0.0, 1e-4, 0.05, 0.5}) put(dir(ci, az), refracted(dir(ci, az), dir(std::cos(tm), 1.0), eta), eta);
      const double inv = 1.0 / eta, cc = std::sqrt((1 - inv) * (1 + inv));  // leaving: relative index 1/eta
      if (inv < 1.0)
        for (double k : {-1e-2, -1e-4, -1e-7, 0.0, 1e-7, 1e-4, 1e-2}) {
          const glm::dvec3 i = dir(std::min(1.0, cc * (1 + k)), az);
          put(i, refracted(i, glm::dvec3(0, 0, 1), inv), inv);
        }
    }
  }
  {
    // leaving a dense medium (eta < 1) at cosines around the critical one, cos θc = sqrt(1 - eta²)
    int r = c.add_region({"near_critical",
                          fmt::format("eta in {{1/1.5, 0.1, {:g}}}, n.i at cos(theta_c) (1 +- {{1e-7, 1e-4, 1e-2}}), o "
                                      "refracted through n or straight through",
                                      b.eta.lo),
                          true, ""});
    for (double eta : {1 / 1.5, 0.1, b.eta.lo}) {
      const double cc = std::sqrt((1 - eta) * (1 + eta));
      for (double k : {-1e-2, -1e-4, -1e-7, 0.0, 1e-7, 1e-4, 1e-2}) {
        const glm::dvec3 i = dir(std::min(1.0, cc * (1 + k)), az);
        add(r, i, refracted(i, glm::dvec3(0, 0, 1), eta), eta);
        add(r, i, dir(0.05, az + M_PI), eta);
      }
    }
  }
  {
    int r = c.add_region({"eta_near_1", "eta in {1 - 1e-6, 1 + 1e-6}: h_t's lobe a sliver about o = -i, and o = -i "
                                        "(h_t = 0/0 at eta = 1 exactly)",
                          true, ""});
    for (double eta : {1 - 1e-6, 1 + 1e-6, 1.0})
      for (double ci : {0.9, 0.3, 1e-3}) {
        const glm::dvec3 i = dir(ci, az);
        add(r, i, -i, eta);
        add(r, i, refracted(i, dir(std::cos(0.01), 1.0), eta), eta);
        add(r, i, glm::normalize(-i + glm::dvec3(1e-6, 0, 0)), eta);
      }
  }
  {
    int r = c.add_region({"grazing", "n.i or n.o in {2^-149, 1e-30, 1e-20, 1e-7, 1e-3}, the other at 0.5; eta in "
                                     "{1.5, 1/1.5}",
                          true, ""});
    for (double eta : {1.5, 1 / 1.5})
      for (double g : {kTinyCos[0], kTinyCos[1], kTinyCos[2], 1e-7, 1e-3}) {
        add(r, dir(g, az), -dir(0.5, az + M_PI), eta);
        add(r, dir(0.5, az), -dir(g, az + M_PI), eta);
        add(r, dir(g, az), -dir(g, az + M_PI), eta);
      }
  }
  {
    int r = c.add_region({"same_side", "i and o on one side of the surface, or o in it: no transmission", true, "0"});
    for (double eta : {1.5, 1 / 1.5}) {
      add(r, dir(0.5, az), dir(0.7, az + 2), eta);
      add(r, dir(0.5, az), mirror(dir(0.5, az)), eta);
      add(r, dir(0.5, az), glm::dvec3(1, 0, 0), eta);
    }
  }
  (void)fp64;
  return c;
}

}  // namespace mfv::stability_detail
