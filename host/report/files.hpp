// Transitional: the atomic file writes now live in util/files.hpp so that
// checks/ can write files without including report/ (a layer above it).
// Kept so that branches in flight still build; replace the include with
// "util/files.hpp" and delete.
#pragma once
#include "util/files.hpp"
