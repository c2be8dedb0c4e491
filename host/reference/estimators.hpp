// The conformance estimators in double (twin of kernels/integrate.cl):
// the same Philox uniforms, the same proposal, written from the formulas.
#pragma once

#include "abi/integral.h"
#include "reference/brdf.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace mfv::ref {

// AlbedoRqmc and EavgRqmc (mfv energy) are Albedo on randomized-QMC uniforms;
// EavgRqmc also draws the view cosine per sample with density 2μ.
// AlbedoMis (mfv run's albedo): visible normals of the GGX shape, Cauchy
// slopes and the cosine lobe by multi-sample MIS, strata = points per
// randomized-QMC replicate (twin of albedo_mis_microfacet in kernels/albedo.cl).
enum class Integral {
  DNorm = MFV_CHECK_D_NORM,
  Masking = MFV_CHECK_MASKING,
  Albedo = MFV_CHECK_ALBEDO,
  AlbedoRqmc = MFV_CHECK_ALBEDO_RQMC,
  EavgRqmc = MFV_CHECK_EAVG_RQMC,
  AlbedoMis = MFV_CHECK_ALBEDO_MIS,
  BsdfFlux = MFV_CHECK_BSDF_FLUX,  // the rough dielectric BSDF's E_R or E_T (host/reference/transmission.cpp)
  MaskingT = MFV_CHECK_MASKING_T,  // the weak white furnace for o below the surface (the same file)
  BsdfAvg = MFV_CHECK_BSDF_AVG     // T_avg(1/eta) - T_avg(eta)/eta^2 (the same file)
};

struct IntegralRef {
  Integral kind = Integral::DNorm;
  BrdfSpec brdf;           // D, G, F and their native parameters, kd
  double width = 0.1;      // proposal width (equivalent alpha)
  double cos_o = 1.0;      // view for masking and albedo, at azimuth phi_o about n
  double phi_o = 0.0;      // (0: in the xz-plane); twin of IntegralSpec::phi_o
  double width_y = 0;      // > 0: the proposal stretched to (width, width_y) (twin of IntegralSpec::width_y)
  uint32_t stream = 0;     // Philox stream, low and high words (twin of IntegralSpec::stream, stream_hi)
  uint32_t stream_hi = 0;
  uint32_t strata = 0;     // d_norm, E_avg: stratified over this many samples (0 = iid)
  uint32_t points = 0;     // AlbedoMis: points per replicate
  uint32_t estimator = 0;  // mfv convergence: 0 = the check's own, else Estimator below
  // The interface (twins of IntegralSpec::eta, side, bsdf, lobe): the
  // rough dielectric BSDF of brdf.d and brdf.g with MFV_BTDF_CODE bsdf.
  double eta = 1.0;
  int side = MFV_SIDE_ABOVE;
  int bsdf = -1;
  uint32_t lobe = MFV_LOBE_ALL;
};

// mfv convergence's estimators (MFV_EST_* in kernels/abi/integral.h).
enum class Estimator : uint32_t {
  Own = MFV_EST_OWN,
  Uniform = MFV_EST_UNIFORM,
  Cosine = MFV_EST_COSINE,
  DSampleGgx = MFV_EST_DSAMPLE_GGX,
  DSampleBeckmann = MFV_EST_DSAMPLE_BECKMANN,
  Vndf = MFV_EST_VNDF,
  Rqmc = MFV_EST_RQMC
};

// The index-th sample of the estimator: its mean over samples is the integral.
double sample_value(const IntegralRef& s, uint64_t seed, uint64_t index);
// BsdfFlux's, MaskingT's and BsdfAvg's samples (host/reference/transmission.cpp).
double bsdf_flux(const IntegralRef& s, uint64_t seed, uint64_t index);
double masking_t(const IntegralRef& s, uint64_t seed, uint64_t index);
double bsdf_avg(const IntegralRef& s, uint64_t seed, uint64_t index);
// bsdf_furnace's proposal alone (twins of flux_mis_direction and flux_mis_pdf
// in kernels/transmission.cl), for mfv samplers: light from i above, eta the
// relative index seen from i, lobe MFV_LOBE_*. The direction one share (vis,
// cosine, else Cauchy slopes) draws from its uniforms, false where it gives
// none (the proposal is a sub-probability); the shares' mixture density of o
// over the sphere, c = (15/16, 1/32, 1/32); a share's chance of reflecting.
bool flux_mis_direction(bool vis, bool cosine, double u_phi, double u_r, double u_c, const glm::dvec3& i, double w,
                        double eta, uint32_t lobe, glm::dvec3& o);
double flux_mis_pdf(const glm::dvec3& i, const glm::dvec3& o, double w, double eta, uint32_t lobe);
double flux_reflect_chance(uint32_t lobe, bool visible, double cm, double eta);

// The proposals on their own (twins of kernels/integrate.cl), for mfv
// samplers' quadrature and chi-square tests. Densities are over solid angle.
double pdf_slope(double c, double s2, double w);  // 2D Cauchy slopes of width w, at cos c, sin² s2
double pdf_m(double c, double s2, double w);      // the conformance mixture: cosine lobe + Cauchy slopes
glm::dvec3 sample_m(double u_pick, double u_phi, double u_r, double w, double& c, double& s2);
double vis_pdf_i(const glm::dvec3& h, const glm::dvec3& o, double w);  // light direction reflect(o, h)
double vis_pdf_i(const glm::dvec3& h, const glm::dvec3& o, double wx, double wy);  // stretched to (wx, wy)
// The anisotropic proposal (brdf.aniso(): Cauchy slopes stretched by (wx, wy)).
double pdf_slope_aniso(const glm::dvec3& m, double wx, double wy);  // the stretched slopes alone
double pdf_m_aniso(const glm::dvec3& m, double wx, double wy);
glm::dvec3 sample_m_aniso(double u_pick, double u_phi, double u_r, double wx, double wy);
glm::dvec3 sample_vis(const glm::dvec3& o, double u_phi, double u_r, double w);
glm::dvec3 sample_vis(const glm::dvec3& o, double u_phi, double u_r, double wx, double wy);
// Point k of the Owen-scrambled 2D Sobol sequence with scramble seeds s0, s1 (AlbedoMis's points).
void owen_sobol_2d(uint32_t k, uint32_t s0, uint32_t s1, double& u0, double& u1);
// Point k of Sobol's third dimension, Owen-scrambled with seed s (bsdf_furnace's side of the whole sphere).
double owen_sobol_dim3(uint32_t k, uint32_t s);
// Point index = r n + k of an AlbedoMis or BsdfFlux integral (n = s.points): replicate r's
// scramble seeds (Philox draw 3 at counter r), the share of point k (the first 4n/5 visible
// normals, the next n/10 Cauchy slopes, the last n/10 the cosine lobe) and its coordinates.
struct MisPoint {
  bool vis = false, cosine = false;
  double u_phi = 0, u_r = 0, u_c = 0;
};
MisPoint mis_point(const IntegralRef& s, uint64_t seed, uint64_t index);

// Reciprocity pair `index` of integral `stream` (twin of the `reciprocity` kernel).
void reciprocity_pair(uint64_t seed, uint32_t stream, uint32_t stream_hi, uint32_t index, glm::dvec3& a,
                      glm::dvec3& b);

// Counter word 3 of integral s's Philox draw `draw` (< 256): the draw with the
// stream's high bits above it (twin of spec_draw in kernels/estimators.cl).
inline uint32_t draw_word(const IntegralRef& s, uint32_t draw) { return draw | s.stream_hi << 8; }

}  // namespace mfv::ref
