// mfv samplers: every sampling routine the suite uses, verified (docs/design.md
// §3): its pdf integrates to 1 (deterministic quadrature) and a histogram of
// its draws matches the pdf (chi-square, Šidák-corrected over all tests).
// Draws come from the device (kernels/samplers.cl, which calls the very
// routines of kernels/estimators.cl) and from the double reference twin
// (host/reference/estimators.cpp); expected cell masses always come from the
// reference pdf, by quadrature.
#pragma once

#include "runtime/opencl.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace mfv {

// Ids shared with kernels/samplers.cl (SAMPLER_*).
// Flux: bsdf_furnace's proposal of o over the whole sphere (kernels/transmission.cl,
// flux_mis_direction / flux_mis_pdf), light from i at cos_o, relative index eta.
enum class Sampler : int { Mixture = 0, Slopes = 1, Cosine = 2, Vis = 3, Flux = 4 };

struct SamplerCase {
  Sampler sampler;
  double width;      // proposal width w
  double cos_o;      // view (Vis), light (Flux)
  double eta = 1.0;  // relative index seen from the light (Flux only)
};

std::string sampler_name(Sampler s);
std::vector<SamplerCase> default_sampler_cases();

// The reference pdf of a case's draws, per solid angle at unit direction d
// (for Vis: over light directions on the whole sphere).
double sampler_pdf(const SamplerCase& c, const glm::dvec3& d);
// ∫ pdf dω by tensor Gauss-Legendre refined geometrically towards the lobe's
// peak (for Vis, over half vectors with the reflection Jacobian 4 o·h; for
// Flux over the sphere of o, split where the density is not smooth).
double sampler_pdf_total(const SamplerCase& c);
// The chance that a draw gives no direction (0 but for Flux, a sub-probability:
// a facet facing away, total internal reflection, o on the wrong side), by
// quadrature over the normals the shares draw: ∫pdf + lost = 1.
double sampler_lost_mass(const SamplerCase& c);
// Flux's ∫pdf dω with the density `pdf` (sampler_pdf_total: its own; tests plant a wrong one).
double flux_pdf_total(const SamplerCase& c, const std::function<double(const glm::dvec3&)>& pdf);
// n draws of the reference twin, on the Philox uniforms the kernel uses.
std::vector<glm::dvec3> reference_draws(const SamplerCase& c, uint64_t n, uint64_t seed);

struct SamplersOptions {
  uint64_t samples = 1u << 20;  // draws per case and implementation
  uint64_t seed = 7;
  double significance = 0.01;  // family-wise, Šidák-corrected over every test of the run
  int cos_bins = 64, phi_bins = 128;
  bool reference = true;  // also test the reference twin's draws
};

struct SamplerResult {
  SamplerCase c;
  std::string impl;  // "device" or "reference"
  double pdf_total = 0, lost_mass = 0;  // ∫pdf dω and the chance of no direction: they sum to 1
  double chi2 = 0, p_value = 0, level = 0;
  int dof = 0;
  uint64_t lost = 0;       // draws outside the binned domain or not finite
  std::string impossible;  // samples where the pdf is zero
  bool pdf_ok = false, fit_ok = false;
  bool pass() const { return pdf_ok && fit_ok; }
  // the histogram: cos_bins x phi_bins cells, cos θ-major, for the
  // observed/expected/difference image (report/sampler_plots.hpp)
  int cos_bins = 0, phi_bins = 0;
  double cos_low = 0;  // the cells span cos θ in [cos_low, 1]
  std::vector<double> observed, expected;
  std::string plot;  // the image's file name, where one was written
};

// Histogram of directions in (cos θ, φ) cells against the case's pdf.
SamplerResult test_draws(const SamplerCase& c, const std::vector<glm::dvec3>& draws, const SamplersOptions& opt,
                         double level);

std::vector<SamplerResult> run_samplers(Runtime& rt, const SamplersOptions& opt);
void print_samplers(const std::vector<SamplerResult>& r);
std::string samplers_json(const std::vector<SamplerResult>& r, const Runtime& rt, const SamplersOptions& opt);

}  // namespace mfv
