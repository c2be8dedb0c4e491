// Mathematical constants, defined once for every layer.
#pragma once

namespace mfv {

// π to the precision of a double (the literal carries more digits than a
// double holds; the compiler rounds it once, correctly).
inline constexpr double kPi = 3.14159265358979323846264338327950288;

}  // namespace mfv
