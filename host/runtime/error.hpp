// Transitional: mfv::Error now lives in the lowest layer (util/error.hpp) so
// that catalog and util need nothing above them. Kept so that branches in
// flight still build; replace the include with "util/error.hpp" and delete.
#pragma once
#include "util/error.hpp"
