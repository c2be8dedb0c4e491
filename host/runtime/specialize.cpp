#include "runtime/specialize.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

namespace mfv {

namespace {

// The kernels of kernels/integrate.cl defined by a MFV_*_VALUES macro (or
// MFV_ALBEDO_MIS_DF, MFV_ALBEDO_MIS_PAIR), what their specialization takes
// (the D id, the G id or both), whether they serve d_norm's (D, kNoG) pairs
// or the others, and whether only a program of one such pair gets them.
enum class By { D, G, Pair };
struct Specializable {
  const char* base;
  const char* macro;
  By by;
  bool d_norm;
  bool one_pair = false;
  bool rqmc = false;  // only for the pairs whose `rqmc` is set (fast_path_pairs)
};
constexpr Specializable kSpecializable[] = {
    {"d_norm_values", "MFV_D_NORM_VALUES", By::D, true},
    // masking and AlbedoMis in three kernels (kernels/integrate.cl): one per D and one per G, not per pair
    {"masking_d", "MFV_MASKING_D", By::D, false},
    {"masking_values", "MFV_MASKING_VALUES", By::G, false},
    {"albedo_mis_df", "MFV_ALBEDO_MIS_DF", By::D, false},
    {"albedo_mis_values", "MFV_ALBEDO_MIS_VALUES", By::G, false},
    {"albedo_rqmc_values", "MFV_ALBEDO_RQMC_VALUES", By::Pair, false, false, true},
    // AlbedoMis in one kernel, for a program of one pair only (bench --case, one model): one
    // launch instead of three; many pairs keep the three kernels' compiles (one per D, one per G)
    {"albedo_mis_pair", "MFV_ALBEDO_MIS_PAIR", By::Pair, false, true},
};

std::string name_of(const std::string& base, int d, int g, By by) {
  switch (by) {
    case By::D: return fmt::format("{}__d{}", base, d);
    case By::G: return fmt::format("{}__g{}", base, g);
    case By::Pair: return fmt::format("{}__d{}_g{}", base, d, g);
  }
  return base;
}

// The macro's arguments after the name: the ids it is specialized to.
std::string ids_of(int d, int g, By by) {
  switch (by) {
    case By::D: return fmt::format("{}", d);
    case By::G: return fmt::format("{}", g);
    case By::Pair: return fmt::format("{}, {}", d, g);
  }
  return "";
}

// kernels/model_values.cl, specialized per model
constexpr const char* kModelAlbedo = "model_albedo_values";
// kernels/reciprocity.cl, specialized per model
constexpr const char* kModelReciprocity = "model_reciprocity_values";

std::string model_kernel_name(int model, const char* base = kModelAlbedo) { return fmt::format("{}__m{}", base, model); }

const Specializable* find(const std::string& base) {
  for (const auto& k : kSpecializable)
    if (base == k.base) return &k;
  return nullptr;
}

}  // namespace

std::vector<TermPair> fast_path_pairs(const std::vector<IntegralSpec>& specs) {
  std::map<std::pair<int, int>, bool> pairs;  // (D, G) -> an RQMC integral among them
  // as Integrator's values_kernel and AlbedoMis: catalog terms (model 0),
  // isotropic (no second width, view in the xz-plane), one width
  for (const auto& s : specs)
    if (s.estimator == 0 && s.model == 0 && !(s.pd2 > 0) && !(s.width_y > 0) && s.phi_o == 0 && s.width > 0) {
      const bool rqmc = s.check == MFV_CHECK_ALBEDO_RQMC || s.check == MFV_CHECK_EAVG_RQMC;
      pairs[{s.d, s.check == MFV_CHECK_D_NORM ? kNoG : s.g}] |= rqmc;
    }
  std::vector<TermPair> out;
  for (const auto& [dg, rqmc] : pairs) out.push_back({dg.first, dg.second, rqmc});
  return out;
}

std::string generate_specializations(const std::vector<TermPair>& pairs) {
  std::string out;
  std::set<std::string> defined;  // a kernel by D or by G serves several pairs: defined once
  const auto others = std::count_if(pairs.begin(), pairs.end(), [](const TermPair& p) { return p.g != kNoG; });
  for (const auto& p : pairs)
    for (const auto& k : kSpecializable)
      if (k.d_norm == (p.g == kNoG) && (!k.one_pair || others == 1) && (p.rqmc || !k.rqmc)) {
        const std::string name = name_of(k.base, p.d, p.g, k.by);
        if (defined.insert(name).second) out += fmt::format("{}({}, {})\n", k.macro, name, ids_of(p.d, p.g, k.by));
      }
  return out;
}

std::string generate_model_specializations(const std::vector<const Model*>& models, bool reciprocity) {
  std::string out;
  for (const Model* m : models) {
    out += fmt::format("MFV_MODEL_ALBEDO_VALUES({}, {})\n", model_kernel_name(m->number()), m->number());
    if (reciprocity)
      out += fmt::format("MFV_MODEL_RECIPROCITY_VALUES({}, {})\n", model_kernel_name(m->number(), kModelReciprocity),
                         m->number());
  }
  return out;
}

bool model_reciprocity_per_model_pays(uint64_t pairs, size_t models) {
  return models > 0 && double(pairs) >= kModelReciprocityPairsPerKernel * double(models);
}

namespace {
// kernels/integrate.cl MFV_INTEGRATE_IID: `integrate` for the iid integrals of one check, by the
// check's case of sample_value
struct CheckKernel {
  int32_t check;
  const char* name;
  const char* fn;
};
constexpr CheckKernel kCheckKernels[] = {
    {MFV_CHECK_MASKING_T, "integrate_masking_t", "masking_t_value"},
    {MFV_CHECK_BSDF_AVG, "integrate_bsdf_avg", "bsdf_avg_value"},
};
}  // namespace

std::string generate_check_kernels() {
  std::string out;
  for (const auto& k : kCheckKernels) out += fmt::format("MFV_INTEGRATE_IID({}, {})\n", k.name, k.fn);
  return out;
}

std::vector<std::string> check_kernel_names() {
  std::vector<std::string> out;
  for (const auto& k : kCheckKernels) out.push_back(k.name);
  return out;
}

std::string check_kernel_name(const IntegralSpec& s) {
  if (s.estimator != 0 || s.strata != 0) return "";
  for (const auto& k : kCheckKernels)
    if (s.check == k.check) return k.name;
  return "";
}

std::string specialized_name(const std::string& base, const IntegralSpec& s) {
  if (base == kModelAlbedo || base == kModelReciprocity) return model_kernel_name(int(s.model), base.c_str());
  const Specializable* k = find(base);
  return k ? name_of(base, s.d, s.g, k->by) : base;
}

}  // namespace mfv
