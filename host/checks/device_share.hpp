// mfv run --device all (or a list, docs/scale.md "Every device at once"):
// one plan's integrals split across the devices of a machine with dynamic
// work sharing. Each device has its own Runtime and Integrator; the plan is
// cut into chunks that each device's thread takes, one after another, as it
// finishes the last, so a fast device takes more. Streams are keyed by the
// integral's identity (checks/streams.hpp) and an estimate depends on its
// integral alone, so where the devices round alike the records are those of
// a one-device run, whichever device took which chunk.
#pragma once

#include "runtime/integrator.hpp"

#include <cstdint>
#include <future>
#include <memory>
#include <string>
#include <vector>

namespace mfv {

// What one device did in a run: integrals integrated and seconds busy.
struct DeviceShare {
  std::string name, platform;
  int index = -1;  // in list_devices()
  uint64_t integrals = 0;
  double seconds = 0;
};

// The integrals of `specs` (one plan: one sample count), estimated as
// integrators[0]->run would, shared among `integrators` in chunks. A device
// whose sample layout for `samples` differs from the first's (another
// work-group size) sits the plan out, so every record keeps the first
// device's sample count. `shares` (one per integrator) accumulates.
std::vector<Estimate> run_shared(const std::vector<Integrator*>& integrators, const std::vector<IntegralSpec>& specs,
                                 uint64_t samples, uint64_t seed, std::vector<DeviceShare>& shares);

// One Integrator of `terms` per runtime of `more`, each built on its own
// thread (std::async), so that they build beside the caller's own build;
// the first build error is rethrown when the result is taken.
struct PendingIntegrators {
  std::vector<std::future<std::unique_ptr<Integrator>>> builds;
};
PendingIntegrators integrators_beside(const std::vector<Runtime*>& more, const TermSelection& terms);
// Waits for the builds; `shares` gets one row for `first` and one per other
// device (the first device's row first), and the others come back in order.
std::vector<std::unique_ptr<Integrator>> integrators_ready(PendingIntegrators& pending, const Runtime& first,
                                                           const std::vector<Runtime*>& more,
                                                           std::vector<DeviceShare>& shares);

// Chunk size: about 8 chunks per device, at least 16 integrals each (each
// launch has a fixed cost), and no more than the plan.
size_t share_chunk(size_t integrals, size_t devices);

}  // namespace mfv
