#include "checks/samplers.hpp"
#include "mfv_git_commit.h"

#include "abi/integral.h"
#include "checks/chi_square.hpp"
#include "numeric/quadrature.hpp"
#include "reference/estimators.hpp"
#include "rng/philox.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/integrator.hpp"
#include "runtime/provenance.hpp"
#include "util/error.hpp"
#include "util/files.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <cmath>

namespace mfv {
namespace {

glm::dvec3 view_of(double cos_o) { return {std::sqrt((1.0 - cos_o) * (1.0 + cos_o)), 0.0, cos_o}; }

glm::dvec3 direction(double z, double phi) {
  const double s = std::sqrt(std::max(0.0, (1.0 - z) * (1.0 + z)));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// Lowest cos θ a case's draws can have: light directions reflected about a
// visible normal may lie below the horizon.
double z_low(const SamplerCase& c) { return c.sampler == Sampler::Vis || c.sampler == Sampler::Flux ? -1.0 : 0.0; }

// ∫ f(d) dω over directions d with polar angle θ in [0, theta_hi], by
// Gauss-Legendre (8 nodes) in φ (512 panels) and, per φ node, in θ between
// the places where the density is not smooth: the sign changes of
// `events(d, out)` (its values at d), found on a scan of 256 steps and
// bisected, and π/2; panels at most 0.02 wide between them. Measured
// (the default Flux cases): |∫pdf + lost - 1| <= 7e-8, against 8e-6 with
// 64 φ panels (the inner integral has kinks in φ where a cut appears).
template <class F, class E>
double sphere_integral(F&& f, E&& events, double theta_hi) {
  const GaussRule g = gauss_legendre(8);
  const int n_phi = 512, n_scan = 256;
  const double max_panel = 0.02;
  double total = 0;
  std::vector<double> prev, cur, mid;
  for (int b = 0; b < n_phi; ++b)
    for (size_t j = 0; j < g.x.size(); ++j) {
      const double phi = 2 * M_PI / n_phi * (b + 0.5 * (g.x[j] + 1.0)), cp = std::cos(phi), sp = std::sin(phi);
      auto at = [&](double t) { return glm::dvec3(std::sin(t) * cp, std::sin(t) * sp, std::cos(t)); };
      std::vector<double> cuts = {0.0, theta_hi};
      if (theta_hi > M_PI / 2) cuts.push_back(M_PI / 2);
      events(at(0.0), prev);
      for (int k = 1; k <= n_scan; ++k) {
        const double t1 = theta_hi * k / n_scan, t0 = theta_hi * (k - 1) / n_scan;
        events(at(t1), cur);
        for (size_t e = 0; e < cur.size(); ++e)
          if ((prev[e] > 0) != (cur[e] > 0)) {
            double lo = t0, hi = t1;
            const bool lo_pos = prev[e] > 0;
            for (int it = 0; it < 60; ++it) {
              const double m = 0.5 * (lo + hi);
              events(at(m), mid);
              ((mid[e] > 0) == lo_pos ? lo : hi) = m;
            }
            cuts.push_back(0.5 * (lo + hi));
          }
        prev.swap(cur);
      }
      std::sort(cuts.begin(), cuts.end());
      double inner = 0;
      for (size_t a = 0; a + 1 < cuts.size(); ++a) {
        const double len = cuts[a + 1] - cuts[a];
        if (!(len > 0)) continue;
        const int panels = int(std::ceil(len / max_panel));
        const double h = len / panels;
        for (int q = 0; q < panels; ++q)
          for (size_t i = 0; i < g.x.size(); ++i) {
            // θ = smoothstep in u over the piece: the density's square-root
            // edges (1 - F at the critical angle) become smooth in u
            const double u = (q + 0.5 * (g.x[i] + 1.0)) / panels, t = cuts[a] + len * u * u * (3.0 - 2.0 * u);
            inner += g.w[i] * 0.5 * h * 6.0 * u * (1.0 - u) * f(at(t)) * std::sin(t);
          }
      }
      total += g.w[j] * (M_PI / n_phi) * inner;
    }
  return total;
}

// Flux: the light i above, eta seen from it, the critical facet cosine (0 where none).
glm::dvec3 light_of(const SamplerCase& c) { return view_of(c.cos_o); }
double critical_cos(double eta) { return eta < 1.0 ? std::sqrt((1.0 - eta) * (1.0 + eta)) : 0.0; }

// o refracted through m from i (eq. 40 with η_i/η_o = 1/eta); false under total internal reflection.
bool refracted(const glm::dvec3& i, const glm::dvec3& m, double eta, glm::dvec3& o) {
  const double im = glm::dot(i, m), k = 1.0 / eta, t2 = 1.0 - k * k * (1.0 - im * im);
  if (t2 <= 0.0) return false;
  o = (k * im - std::sqrt(t2)) * m - k * i;
  return true;
}

// ∫∫ f(z, φ) dz dφ over [z0, z1] x [p0, p1] by an nz x np Gauss-Legendre product.
template <class F>
double cell_integral(const GaussRule& gz, const GaussRule& gp, double z0, double z1, double p0, double p1, F&& f) {
  double sum = 0;
  const double hz = 0.5 * (z1 - z0), hp = 0.5 * (p1 - p0);
  for (size_t i = 0; i < gz.x.size(); ++i) {
    const double z = z0 + hz * (gz.x[i] + 1.0);
    for (size_t j = 0; j < gp.x.size(); ++j) sum += gz.w[i] * gp.w[j] * f(z, p0 + hp * (gp.x[j] + 1.0));
  }
  return sum * hz * hp;
}

}  // namespace

std::string sampler_name(Sampler s) {
  switch (s) {
    case Sampler::Mixture: return "mixture";  // sample_m / pdf_m
    case Sampler::Slopes: return "cauchy_slopes";
    case Sampler::Cosine: return "cosine";
    case Sampler::Vis: return "visible_normals";
    case Sampler::Flux: return "bsdf_flux_sphere";  // bsdf_furnace's proposal of o
  }
  return "?";
}

std::vector<SamplerCase> default_sampler_cases() {
  // widths where a (cos θ, φ) histogram of 64 x 128 cells resolves the lobe;
  // the visible normals at normal, oblique and grazing view (cos_o = 0.15);
  // bsdf_furnace's sphere proposal entering and leaving (eta = 1.5 and 1/1.5,
  // as pbrt-v4's rough dielectric chi-square) at two widths and light cosines
  return {{Sampler::Mixture, 0.2, 1},        {Sampler::Mixture, 0.8, 1},          {Sampler::Slopes, 0.3, 1},
          {Sampler::Cosine, 1, 1},           {Sampler::Vis, 0.3, 0.9},            {Sampler::Vis, 0.3, 0.15},
          {Sampler::Vis, 1.0, 0.5},          {Sampler::Flux, 0.3, 0.7, 1.5},      {Sampler::Flux, 0.3, 0.7, 1 / 1.5},
          {Sampler::Flux, 0.8, 0.3, 1.5},    {Sampler::Flux, 0.8, 0.3, 1 / 1.5}};
}

double sampler_pdf(const SamplerCase& c, const glm::dvec3& d) {
  if (c.sampler == Sampler::Flux) return ref::flux_mis_pdf(light_of(c), d, c.width, c.eta, MFV_LOBE_ALL);
  if (c.sampler == Sampler::Vis) {
    // i = reflect(o, h) for a visible normal h: the density of i at d is that
    // of h = (d + o)/|d + o| times the Jacobian, zero where h is no visible normal
    const glm::dvec3 o = view_of(c.cos_o), sum = d + o;
    const double len = glm::length(sum);
    if (!(len > 0.0)) return 0.0;
    const glm::dvec3 h = sum / len;
    return h.z > 0.0 ? ref::vis_pdf_i(h, o, c.width) : 0.0;
  }
  if (!(d.z > 0.0)) return 0.0;
  const double s2 = d.x * d.x + d.y * d.y;
  if (c.sampler == Sampler::Cosine) return d.z / M_PI;
  if (c.sampler == Sampler::Slopes) return ref::pdf_slope(d.z, s2, c.width);
  return ref::pdf_m(d.z, s2, c.width);
}

double flux_pdf_total(const SamplerCase& c, const std::function<double(const glm::dvec3&)>& pdf) {
  {
    // over the sphere of o: the density is not smooth where o crosses the
    // surface, where the refraction's half vector turns over (i_z + eta o_z = 0),
    // where its facet faces away from i or o (i·o = -1/eta, -eta), where the
    // facet of either lobe reaches the critical cosine, and at o_z = -i_z
    const glm::dvec3 i = light_of(c);
    const double eta = c.eta, cc = critical_cos(eta);
    auto events = [&](const glm::dvec3& o, std::vector<double>& e) {
      const glm::dvec3 hr = glm::normalize(i + o), ht = glm::normalize(i + eta * o);
      const double io = glm::dot(i, o);
      e = {i.z + eta * o.z, io + 1.0 / eta, io + eta, o.z + i.z, std::fabs(glm::dot(i, hr)) - cc,
           std::fabs(glm::dot(i, ht)) - cc};
    };
    return sphere_integral(pdf, events, M_PI);
  }
}

double sampler_pdf_total(const SamplerCase& c) {
  if (c.sampler == Sampler::Flux) return flux_pdf_total(c, [&](const glm::dvec3& o) { return sampler_pdf(c, o); });
  // Over m (for Vis: over h, with dω_i = 4 (o·h) dω_h) in t = 1 - cos θ,
  // panels geometric towards the normal, where every lobe here peaks; in φ
  // 16 panels x 8 nodes. For Vis the domain o·h > 0 ends at cos θ = z_c(φ)
  // (a kink no panel edge would follow), so the t range is cut there per φ:
  // o·h = 0 at z_c = |sin_o cos φ| / sqrt(cos_o² + sin_o² cos² φ) where cos φ < 0.
  const GaussRule gz = gauss_legendre(10), gp = gauss_legendre(8);
  const std::vector<double> t = geometric_panels(1e-12, 4);
  const glm::dvec3 o = view_of(c.cos_o);
  double total = 0;
  for (int b = 0; b < 16; ++b)  // edges at multiples of π/8 include π/2 and 3π/2, where z_c has kinks
    for (size_t j = 0; j < gp.x.size(); ++j) {
      const double phi = M_PI / 8 * (b + 0.5 * (gp.x[j] + 1.0));
      const double cp = std::cos(phi) * o.x;
      const double zc = c.sampler == Sampler::Vis && cp < 0 ? -cp / std::sqrt(o.z * o.z + cp * cp) : 0.0;
      double inner = 0;
      for (size_t a = 0; a + 1 < t.size(); ++a) {
        const double t0 = t[a] * (1.0 - zc), t1 = t[a + 1] * (1.0 - zc), ht = 0.5 * (t1 - t0);
        for (size_t i = 0; i < gz.x.size(); ++i) {
          const glm::dvec3 m = direction(1.0 - (t0 + ht * (gz.x[i] + 1.0)), phi);
          double f;
          if (c.sampler != Sampler::Vis) {
            f = sampler_pdf(c, m);
          } else {
            const double om = glm::dot(o, m);
            f = om > 0.0 ? sampler_pdf(c, 2.0 * om * m - o) * 4.0 * om : 0.0;
          }
          inner += gz.w[i] * ht * f;
        }
      }
      total += gp.w[j] * (M_PI / 16) * inner;
    }
  return total;
}

double sampler_lost_mass(const SamplerCase& c) {
  if (c.sampler != Sampler::Flux) return 0.0;
  // over the normals m the shares draw (above the surface), written from the
  // sampler's steps, not from its density of o: the visible normals (density
  // vis_pdf_i 4 i·m) reflect with the estimator's Fresnel and lose o below
  // the surface, refract otherwise and lose o above; the Cauchy slopes lose
  // facets facing away, and reflect or refract with 1/2 each, losing as the
  // visible normals do and under total internal reflection; the cosine lobe
  // loses nothing. Split where i·m, i·m - cos θc, o_r.z or o_t.z change sign.
  const glm::dvec3 i = light_of(c);
  const double eta = c.eta, cc = critical_cos(eta), w = c.width;
  auto lost_t = [&](const glm::dvec3& m) {  // refracted: no direction or on the wrong side
    glm::dvec3 o;
    return !refracted(i, m, eta, o) || !(o.z < 0.0);
  };
  auto lost = [&](const glm::dvec3& m) {
    const double im = glm::dot(i, m);
    const double slopes = ref::pdf_slope(m.z, m.x * m.x + m.y * m.y, w);
    if (!(im > 0.0)) return slopes / 32.0;
    const bool lost_r = !((2.0 * im * m - i).z > 0.0);
    const double f = ref::flux_reflect_chance(MFV_LOBE_ALL, true, im, eta);
    const double vis = ref::vis_pdf_i(m, i, w) * 4.0 * im;
    return 15.0 / 16.0 * vis * (f * lost_r + (1.0 - f) * lost_t(m)) +
           1.0 / 32.0 * slopes * (0.5 * lost_r + 0.5 * lost_t(m));
  };
  auto events = [&](const glm::dvec3& m, std::vector<double>& e) {
    const double im = glm::dot(i, m);
    glm::dvec3 o;
    const double ot = refracted(i, m, eta, o) ? o.z : 1.0;
    e = {im, im - cc, (2.0 * im * m - i).z, ot};
  };
  return sphere_integral(lost, events, M_PI / 2);
}

std::vector<glm::dvec3> reference_draws(const SamplerCase& c, uint64_t n, uint64_t seed) {
  std::vector<glm::dvec3> out(n);
  const glm::dvec3 o = view_of(c.cos_o);
  for (uint64_t k = 0; k < n; ++k) {
    const auto r = philox(seed, uint32_t(c.sampler), 3, k);  // as kernels/samplers.cl
    double u_pick = u01_open(r[0]);
    const double u_phi = u01_open(r[1]), u_r = u01_open(r[2]);
    if (c.sampler == Sampler::Flux) {  // as draw_samples: the share by u_pick, the side by word 3
      const bool vis = u_pick < 15.0 / 16.0, cosine = !(u_pick < 31.0 / 32.0);
      if (!ref::flux_mis_direction(vis, cosine, u_phi, u_r, u01_open(r[3]), o, c.width, c.eta, MFV_LOBE_ALL, out[k]))
        out[k] = glm::dvec3(0.0);
      continue;
    }
    if (c.sampler == Sampler::Vis) {
      const glm::dvec3 m = ref::sample_vis(o, u_phi, u_r, c.width);
      out[k] = m.z > 0.0 ? 2.0 * glm::dot(o, m) * m - o : glm::dvec3(0.0);
      continue;
    }
    if (c.sampler == Sampler::Slopes) u_pick = 1.0;
    if (c.sampler == Sampler::Cosine) u_pick = 0.0;
    double cz, s2;
    out[k] = ref::sample_m(u_pick, u_phi, u_r, c.width, cz, s2);
  }
  return out;
}

SamplerResult test_draws(const SamplerCase& c, const std::vector<glm::dvec3>& draws, const SamplersOptions& opt,
                         double level) {
  SamplerResult r;
  r.c = c;
  r.level = level;
  const int nz = opt.cos_bins, np = opt.phi_bins;
  const double zlo = z_low(c);
  std::vector<double> observed(size_t(nz) * np + 1, 0.0), expected(observed.size(), 0.0);
  for (const auto& d0 : draws) {
    const double len = glm::length(d0);
    if (!(len > 0.5) || !std::isfinite(len)) {
      ++r.lost;
      observed.back() += 1;  // the last cell: draws that are no direction (expected count 0)
      continue;
    }
    const glm::dvec3 d = d0 / len;
    double phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2 * M_PI;
    const int iz = std::clamp(int((d.z - zlo) / (1.0 - zlo) * nz), 0, nz - 1);
    const int ip = std::clamp(int(phi / (2 * M_PI) * np), 0, np - 1);
    if (d.z < zlo) ++r.lost;
    observed[size_t(iz) * np + ip] += 1;
  }
  // expected counts: the reference pdf over each cell, 2 x 8 nodes in cos θ
  // and 6 in φ per cell (a composite rule: lobes are at most a few cells wide)
  const GaussRule gz = gauss_legendre(8), gp = gauss_legendre(6);
  const double n = double(draws.size()), dz = (1.0 - zlo) / nz, dp = 2 * M_PI / np;
  for (int iz = 0; iz < nz; ++iz)
    for (int ip = 0; ip < np; ++ip) {
      double m = 0;
      for (int half = 0; half < 2; ++half) {
        const double z0 = zlo + dz * (iz + 0.5 * half);
        m += cell_integral(gz, gp, z0, z0 + 0.5 * dz, dp * ip, dp * (ip + 1),
                           [&](double z, double phi) { return sampler_pdf(c, direction(z, phi)); });
      }
      expected[size_t(iz) * np + ip] = m * n;
    }
  // expected.back(): a draw that is no direction is impossible, not merely
  // unlikely, but for the sub-probability of Flux (its lost mass)
  expected.back() = n * sampler_lost_mass(c);
  const ChiSquare t = chi_square_test(observed, expected);
  r.cos_bins = nz;
  r.phi_bins = np;
  r.cos_low = zlo;
  r.observed.assign(observed.begin(), observed.end() - 1);  // without the no-direction cell
  r.expected.assign(expected.begin(), expected.end() - 1);
  r.chi2 = t.statistic;
  r.dof = t.dof;
  r.p_value = t.p_value;
  r.impossible = t.impossible;
  r.fit_ok = t.impossible.empty() && r.p_value >= level;
  return r;
}

std::vector<SamplerResult> run_samplers(Runtime& rt, const SamplersOptions& opt) {
  if (opt.samples < 1000 || opt.samples > (uint64_t(1) << 26))
    throw Error(fmt::format("--samples {}: must be between 1000 and 2^26", opt.samples));
  if (!(opt.significance > 0 && opt.significance < 1))
    throw Error(fmt::format("--significance {}: must lie in (0, 1)", opt.significance));
  if (opt.cos_bins < 2 || opt.phi_bins < 1 || opt.cos_bins * opt.phi_bins > (1 << 20))
    throw Error("--bins: need at least 2 x 1 cells and at most 2^20");
  const auto cases = default_sampler_cases();
  const int tests = int(cases.size()) * (opt.reference ? 2 : 1);
  const double level = sidak_level(opt.significance, tests);
  // estimators.cl holds the routines; it needs some D, G and F to compile
  TermSelection sel;
  sel.d = {&find_term("ggx")};
  sel.g = {&find_term("smith_ggx")};
  sel.f = {&find_term("none")};
  std::vector<std::string> files = integration_files();  // the proposals' routines
  files.push_back("samplers.cl");
  cl::Program prog =
      rt.build(catalog_sources(files),
               rt.device().fp64 ? std::vector<std::string>{"MFV_ACC_DOUBLE"} : std::vector<std::string>{},
               generate_dispatch(sel), kDispatchBefore);
  cl::Kernel k(prog, "draw_samples");
  cl::Buffer buf(rt.context(), CL_MEM_WRITE_ONLY, opt.samples * 3 * sizeof(float));
  std::vector<float> host(opt.samples * 3);
  std::vector<SamplerResult> out;
  progress::Task task("samplers: cases", cases.size());
  for (const auto& c : cases) {
    const double total = sampler_pdf_total(c), lost = sampler_lost_mass(c);
    k.setArg(0, static_cast<cl_int>(c.sampler));
    k.setArg(1, static_cast<cl_float>(c.width));
    k.setArg(2, static_cast<cl_float>(c.cos_o));
    k.setArg(3, static_cast<cl_float>(c.eta));
    k.setArg(4, static_cast<cl_ulong>(opt.seed));
    k.setArg(5, buf);
    rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(opt.samples));
    rt.queue().enqueueReadBuffer(buf, CL_TRUE, 0, host.size() * sizeof(float), host.data());
    std::vector<glm::dvec3> draws(opt.samples);
    for (uint64_t i = 0; i < opt.samples; ++i) draws[i] = {host[3 * i], host[3 * i + 1], host[3 * i + 2]};
    std::vector<std::pair<std::string, std::vector<glm::dvec3>>> sets;
    sets.emplace_back("device", std::move(draws));
    if (opt.reference) sets.emplace_back("reference", reference_draws(c, opt.samples, opt.seed));
    for (auto& [impl, d] : sets) {
      SamplerResult r = test_draws(c, d, opt, level);
      r.impl = impl;
      r.pdf_total = total;
      r.lost_mass = lost;
      r.pdf_ok = std::fabs(total + lost - 1.0) < 1e-6;  // the quadrature resolves the lobe to ~1e-10
      out.push_back(r);
    }
    task.advance(1);
  }
  return out;
}

void print_samplers(const std::vector<SamplerResult>& rs) {
  fmt::print("{:<16} {:>5} {:>6} {:>6} {:<9} {:>12} {:>10} {:>6} {:>10} {:>10} {:>6}  {}\n", "sampler", "w", "cos_o",
             "eta", "draws", "∫pdf+lost-1", "chi2", "dof", "p", "level", "lost", "verdict");
  for (auto& r : rs)
    fmt::print("{:<16} {:>5g} {:>6g} {:>6} {:<9} {:>12.2e} {:>10.1f} {:>6} {:>10.3g} {:>10.3g} {:>6}  {}{}\n",
               sampler_name(r.c.sampler), r.c.width, r.c.cos_o,
               r.c.sampler == Sampler::Flux ? fmt::format("{:.4g}", r.c.eta) : "-", r.impl,
               r.pdf_total + r.lost_mass - 1.0, r.chi2, r.dof, r.p_value, r.level, r.lost,
               r.pass() ? "pass" : "FAIL", r.impossible.empty() ? "" : " (" + r.impossible + ")");
}

std::string samplers_json(const std::vector<SamplerResult>& rs, const Runtime& rt, const SamplersOptions& opt) {
  using nlohmann::json;
  json j;
  j["schema"] = "mfv-samplers/1";
  j["tool"] = {{"name", "mfv"}, {"version", MFV_VERSION}, {"commit", MFV_GIT_COMMIT}};
  j["provenance"] = provenance_json();  // command line, --kernel-dir, kernel hashes, device (runtime/provenance.hpp)
  j["device"] = {{"name", rt.device().name}, {"platform", rt.device().platform}, {"driver", rt.device().driver}};
  j["date"] = utc_timestamp();
  j["options"] = {{"samples", opt.samples},
                  {"seed", opt.seed},
                  {"significance", opt.significance},
                  {"cells", {opt.cos_bins, opt.phi_bins}},
                  {"correction", "Sidak over every test of the run"}};
  j["tests"] = json::array();
  for (auto& r : rs)
    j["tests"].push_back({{"sampler", sampler_name(r.c.sampler)},
                          {"width", r.c.width},
                          {"cos_o", r.c.cos_o},
                          {"draws", r.impl},
                          {"eta", r.c.sampler == Sampler::Flux ? json(r.c.eta) : json()},
                          {"pdf_integral", r.pdf_total},
                          {"lost_mass", r.lost_mass},
                          {"chi2", r.chi2},
                          {"dof", r.dof},
                          {"p_value", r.p_value},
                          {"level", r.level},
                          {"lost", r.lost},
                          {"impossible", r.impossible},
                          {"pass", r.pass()}});
  for (size_t i = 0; i < rs.size(); ++i)
    if (!rs[i].plot.empty()) j["tests"][i]["plot"] = "plots/" + rs[i].plot;
  return j.dump(2) + "\n";
}

}  // namespace mfv
