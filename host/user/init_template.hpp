// mfv check --init glsl|hlsl: a commented adapter to start from.
#pragma once

#include <string>

namespace mfv {

// The template's text; throws mfv::Error for a dialect other than glsl or hlsl.
std::string init_template(const std::string& dialect);

}  // namespace mfv
