// What a run actually was, for every output file (DESIGN.md §7): the full
// command line, --kernel-dir, a SHA-256 of every kernel source the run built
// (embedded or read from --kernel-dir, and a user's file), the device and
// its driver. Process-wide: main records the command line, Runtime the
// device and each source it builds; report writers call provenance_json().
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace mfv {

struct DeviceInfo;

void record_command_line(int argc, const char* const* argv);
void record_runtime(const DeviceInfo& device, const std::string& kernel_dir);
void record_kernel_source(const std::string& name, const std::string& text);

// {"command", "version", "commit", "kernel_dir", "kernel_sources": {name: sha256},
//  "kernel_sha256" (over every name and digest), "device", "platform", "driver", "device_version"}
nlohmann::json provenance_json();

std::string sha256_hex(const std::string& data);

}  // namespace mfv
