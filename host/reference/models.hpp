// Reference twins of the whole models (kernels/models.cl), in double, written
// plainly from the seeds and papers. f(l, v) with l = light, v = view, n = +z;
// unit directions, taken as given; below either horizon f = 0.
// Parameters p[0..5] as declared in host/catalog/models.cpp.
#pragma once

#include <glm/vec3.hpp>

namespace mfv::ref {

// A whole model's f(l, v): l = light, v = view, unit, n = +z; p its parameters.
using ModelFn = double(const glm::dvec3& l, const glm::dvec3& v, const double* p);

ModelFn model_lambert;
ModelFn model_oren_nayar;
ModelFn model_eon;
ModelFn model_toon_diffuse;
ModelFn model_toon_specular;
ModelFn model_phong;
ModelFn model_phong_normalized;
ModelFn model_blinn;
ModelFn model_ward;
ModelFn model_ward_dur;
ModelFn model_cook_torrance_kmix;
ModelFn model_torrance_sparrow;
ModelFn model_radiance_002;
ModelFn model_radiance_002_fixed;

// Exact directional albedos E(l) = ∫ f(l, v) (n·v) dv, NaN where no closed form.
double albedo_lambert(double cos_l, const double* p);
double albedo_oren_nayar(double cos_l, const double* p);        // at normal incidence only: kd A
double albedo_eon(double cos_l, const double* p);               // everywhere (Portsmouth et al. 2025)
double albedo_toon_diffuse(double cos_l, const double* p);      // everywhere: kd q(cos_l) / cos_l
double albedo_toon_specular(double cos_l, const double* p);     // at normal incidence, t >= cos 45°
double albedo_phong(double cos_l, const double* p);             // at normal incidence: ks 2π/(n+2)
double albedo_phong_normalized(double cos_l, const double* p);  // at normal incidence: ks
// FON's directional albedo at rho = 1 (Portsmouth, Kutz, Hill 2025, Listing 1).
double E_fon(double mu, double sigma);

}  // namespace mfv::ref
