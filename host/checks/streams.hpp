// Streams keyed by identity (docs/design.md, "Samples"; issue 27): an
// integral's Philox stream is a hash of what the integral is (its check, its
// integrand's kind, terms by catalog id or model by name, and every parameter
// of its point), never its place in a plan. Adding a check, a term or a point
// therefore leaves every other integral's samples, and its record, unchanged.
#pragma once

#include "runtime/integrator.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

// The identity's text, the key hashed: "check=furnace kind=6 d=ggx g=smith_ggx
// f=none pd=0x1.99999ap-4 ...". Fields at their default (IntegralSpec{}) are
// left out, so a field added to the layout with a default moves no key; the
// sample counts (strata, points) and the stream itself are not part of it.
std::string integral_key(const std::string& check, const IntegralSpec& s);

// The 56-bit stream of a key (FNV-1a 64 of its text, finished by splitmix64's
// mixer, top 8 bits dropped): the low 32 bits go to IntegralSpec::stream, the
// rest to stream_hi (kernels/rng.cl: counter word 3 above the draw).
uint64_t stream_of_key(const std::string& key);

// Sets stream and stream_hi of every spec from its key. Two specs of one call
// with the same stream are an error (mfv::Error naming both keys): either the
// same integral twice (a builder's mistake) or a hash collision (chance about
// n^2 / 2^57, 1e-7 for the default run's 123,000 integrals), which no
// renumbering may resolve without making a stream depend on other integrals.
void assign_streams(const std::string& check, std::vector<IntegralSpec>& specs);

}  // namespace mfv
