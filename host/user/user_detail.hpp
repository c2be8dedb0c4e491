// mfv check's internals shared by host/user/user_check.cpp (the integrals,
// reciprocity and the run) and host/user/user_pointwise.cpp (the census and
// the agreement, on the pointwise records of kernels/abi/pointwise.h).
#pragma once

#include "checks/suite.hpp"
#include "user/claim.hpp"
#include "user/user_brdf.hpp"
#include "user/user_check.hpp"

#include <chrono>
#include <map>
#include <string>
#include <vector>

namespace mfv::user_detail {

using Values = std::vector<double>;  // one value per user parameter
using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The roughness values whose widths are `alphas` and lie in the declared
// range (evenly thinned to at most `most`); the defaults alone without a
// roughness or with a fixed one.
std::vector<Values> roughness_grid(const UserBrdf& u, const std::vector<double>& alphas, size_t most);
// Every other parameter at each end of its range (a product of corners).
std::vector<Values> corners(const UserBrdf& u, const Values& base);
std::map<std::string, double> named(const UserBrdf& u, const Values& v);
std::string named_text(const UserBrdf& u, const Values& v);
IntegralSpec user_spec(const UserBrdf& u, IntegralKind kind, const Values& v, double cos_o, int channel);
PointResult point_of(const UserBrdf& u, const std::string& check, const Values& v);

// The NaN/Inf census over the stability sweep's extremes (check 'finite').
void run_census(Runtime& rt, const cl::Program& prog, const UserBrdf& u, const UserCheckOptions& opt, SuiteReport& rep);
// The worst reciprocity pair of each point (params worst_pair, stream and
// channel; values at settings[k] for pts[k]): both directions and both
// values in its detail, the kernel's pair rounded to float.
void describe_reciprocity(Runtime& rt, const cl::Program& prog, uint64_t seed, const std::vector<Values>& settings,
                          std::vector<PointResult*> pts);
// Pointwise agreement with a claimed catalog model (check 'agree'). With the
// double twin (user/user_twin.hpp) the verdict is the twin's (formula error),
// and the float code's own deviation is named float conditioning.
// agree's measure at one input: the error of v (the twin's or the float
// code's value, as the float record holds it) against the reference rv
// beyond what rounding explains, relative to rv: max(0, |v - rv| - 2 dev -
// rounding) / max(|rv|, FLT_MIN). dev: what the model itself moves when a
// direction moves by one float rounding; rounding: the value's own
// rounding at this input (rounding_at). Infinite where v is not finite.
double agree_error(double v, double rv, double dev, double rounding);
// The absolute rounding of a value at one input: half an ulp of `v` in
// float (the record's own rounding: 2^-24 |v|, 2^-150 below FLT_MIN), plus,
// where the float code's value `kf` is finite, |kf - v|: with the double
// twin's v, the float code's own rounding at this very input (kf - kd).
double rounding_at(double v, double kf);
void run_agreement(Runtime& rt, const cl::Program& prog, const cl::Program* twin, const UserBrdf& u, const Claim& claim,
                   const UserCheckOptions& opt, SuiteReport& rep);

// The transmission kinds of a btdf or bsdf (user/user_transmission.cpp):
// add_transmission builds the points of one of the registry's kinds
// (bsdf_furnace: E_R and E_T of each view as two integrals side by side;
// bsdf_avg_reciprocity; transmission_masking) at the user's widths and
// indices; merge_flux_points makes each such pair of rep.points[first..]
// one point E_R + E_T <= 1, with E_R and E_T in its params and detail;
// run_bsdf_reciprocity evaluates the generalized reciprocity of the radiance
// form, f(i,o)/eta_o^2 = f(o,i)/eta_i^2, on pairs (a bounded maximum).
void add_transmission(Plan& p, const CheckKind& k, const UserBrdf& u, const UserCheckOptions& opt);
void merge_flux_points(SuiteReport& rep, size_t first);
void run_bsdf_reciprocity(Runtime& rt, const cl::Program& prog, const UserBrdf& u, const UserCheckOptions& opt,
                          SuiteReport& rep);

}  // namespace mfv::user_detail
