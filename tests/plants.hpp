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
    "  if (NoH <= R(0.0)) return R(0.0);\n  real c = min(NoH, R(1.0));\n  // divide by α² first",
    "  real c = min(fabs(NoH), R(1.0));\n  // divide by α² first"};

inline PlantedKernelDir planted(const Plant& p) { return PlantedKernelDir(p.file, p.from, p.to); }

}  // namespace mfv::test
