// The table of checks is the registry of check kinds now (checks/registry.hpp).
#pragma once
#include "checks/registry.hpp"
