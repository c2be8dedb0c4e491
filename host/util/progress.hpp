// Progress on stderr for long runs. On a terminal: one line redrawn in place,
// a bar with the percentage and the time left. Otherwise (a CI log, a pipe):
// one plain line every 2 seconds, so a log shows a run is alive long before
// it ends. stdout keeps the results; progress never goes there.
//
// A Task is a piece of work with a known total (samples, records, cases).
// Tasks nest: the innermost open one is shown, prefixed by its parent's label
// ("masking: 45%"). A background thread draws, so a single long launch that
// advances nothing still shows its elapsed time.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace mfv::progress {

// --quiet: no progress output at all. Call before the first Task.
void set_quiet(bool quiet);
bool quiet();

class Task {
 public:
  // total == 0: the size is unknown (only the elapsed time is shown).
  Task(std::string label, uint64_t total);
  ~Task();
  Task(const Task&) = delete;
  Task& operator=(const Task&) = delete;
  void advance(uint64_t done);  // adds `done` units

  struct Entry;

 private:
  std::unique_ptr<Entry> entry_;  // null while quiet
};

}  // namespace mfv::progress
