// mfv samplers: for a chi-square test, an image of the histogram it judged:
// observed counts, expected counts and the standardized difference
// (observed - expected) / sqrt(expected) over (phi, cos theta), as pbrt-v4's
// and Mitsuba 3's chi-square tests write. PNG and SVG (report/gnuplot.hpp).
#pragma once

#include "checks/samplers.hpp"
#include "report/gnuplot.hpp"

#include <vector>

namespace mfv {

// Images of the tests that failed, or of every test with `all`; sets each
// drawn result's `plot` (the PNG's name). Nothing where gnuplot is missing.
NamedBytes sampler_plots(std::vector<SamplerResult>& results, bool all);

}  // namespace mfv
