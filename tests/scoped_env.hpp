// One environment variable set for the scope of a test.
#pragma once

#include <cstdlib>
#include <string>

namespace mfv::test {

// Sets `name` to `value` (unsets it where `value` is null) and unsets it at
// the end of the scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (value)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv() { ::unsetenv(name_.c_str()); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_;
};

}  // namespace mfv::test
