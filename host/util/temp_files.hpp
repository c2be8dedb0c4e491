// Temporary files removed on SIGINT, SIGTERM and SIGHUP (issue 17): while a
// TempFile lives, its path sits in a fixed table that the signal handler
// walks with unlink(2), the only call it makes besides re-raising the signal
// with the default action (both async-signal-safe, POSIX.1-2017 2.4.3).
#pragma once

#include <string>

namespace mfv {

class TempFile {
 public:
  // Registers `path` (installs the handlers on first use); throws mfv::Error
  // when the table is full or the path too long to register.
  explicit TempFile(const std::string& path);
  ~TempFile();  // unregisters; does not remove the file (the caller renamed or removed it)
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  TempFile(TempFile&& o) noexcept : slot_(o.slot_) { o.slot_ = -1; }

 private:
  int slot_ = -1;
};

}  // namespace mfv
