// Named plants: one defect per bug, planted in a copy of kernels/
// (test::PlantedKernelDir) by replacing `from` with `to` in `file`, and
// reused by every test that shows a check catching it.
#pragma once

#include "kernel_dir.hpp"

#include <string>

namespace mfv::test {

struct Plant {
  const char* name;
  const char* file;
  const char* from;
  const char* to;
};

// GGX's D without its horizon test: n.h <= 0 gives a value, not 0 (issue 27:
// the integrals never sample such h, so only mfv run's pointwise kinds,
// agree and stability, see it).
inline const Plant kGgxNoHorizon = {
    "D_ggx without its horizon test", "terms_d.cl",
    "  real d = R(1.0) / (MFV_PI * a2 * k * k);\n  return NoH <= R(0.0) ? R(0.0) : d;",
    "  real d = R(1.0) / (MFV_PI * a2 * k * k);\n  return d;"};

inline PlantedKernelDir planted(const Plant& p) { return PlantedKernelDir(p.file, p.from, p.to); }

}  // namespace mfv::test
