// Temporary files are removed on SIGINT, SIGTERM and SIGHUP, and earlier
// results survive (util/temp_files.hpp, util/files.hpp; issue 17).
#include "util/error.hpp"
#include "util/files.hpp"
#include "util/temp_files.hpp"

#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("mfv_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("A signal removes the registered temporary file and still ends the process", "[files][signals]") {
  int sig = GENERATE(SIGINT, SIGTERM, SIGHUP);
  CAPTURE(sig);
  fs::path dir = scratch("signal");
  const fs::path tmp = dir / "results.json.tmp-mfv";
  pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    mfv::TempFile t(tmp.string());
    std::ofstream(tmp) << "partial";
    ::raise(sig);
    ::_exit(0);  // not reached: the handler re-raises with the default action
  }
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == sig);
  CHECK_FALSE(fs::exists(tmp));
  fs::remove_all(dir);
}

TEST_CASE("Without a signal the registry removes nothing: an unregistered file stays", "[files][signals]") {
  // planted bug check for the test above: a file the table does not hold survives the signal
  fs::path dir = scratch("unregistered");
  const fs::path kept = dir / "other.tmp-mfv", tmp = dir / "results.json.tmp-mfv";
  pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    { mfv::TempFile released(kept.string()); }  // registered, then released before the signal
    mfv::TempFile t(tmp.string());
    std::ofstream(kept) << "x";
    std::ofstream(tmp) << "x";
    ::raise(SIGTERM);
    ::_exit(0);
  }
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  CHECK(WIFSIGNALED(status));
  CHECK(fs::exists(kept));
  CHECK_FALSE(fs::exists(tmp));
  fs::remove_all(dir);
}

TEST_CASE("write_files_atomically leaves no temporary file and keeps earlier results when it fails", "[files]") {
  fs::path dir = scratch("atomic");
  const std::string a = (dir / "results.json").string(), b = (dir / "blocked" / "report.md").string();
  mfv::write_files_atomically({{a, "first"}});
  CHECK(read(a) == "first");
  std::ofstream(dir / "blocked") << "a file where a folder is needed";
  CHECK_THROWS_AS(mfv::write_files_atomically({{a, "second"}, {b, "x"}}), mfv::Error);
  CHECK(read(a) == "first");
  for (auto& e : fs::recursive_directory_iterator(dir)) {
    CAPTURE(e.path());
    CHECK(e.path().string().find(".tmp-mfv") == std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("prepare_output_dir rejects an empty name and a folder it cannot write, before any work", "[files][out]") {
  CHECK_THROWS_WITH(mfv::prepare_output_dir(""), Catch::Contains("empty"));
  fs::path dir = scratch("readonly");
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  // root writes a read-only folder anyway; /proc/self is a folder nobody can create files in
  const std::string unwritable = ::access(dir.c_str(), W_OK) == 0 ? "/proc/self" : dir.string();
  CAPTURE(unwritable);
  CHECK_THROWS_WITH(mfv::prepare_output_dir(unwritable), Catch::Contains("cannot write"));
  fs::permissions(dir, fs::perms::owner_all);
  CHECK_NOTHROW(mfv::prepare_output_dir(dir.string()));
  CHECK(fs::is_empty(dir));  // the probe file is gone
  std::ofstream(dir / "file") << "x";
  CHECK_THROWS_WITH(mfv::prepare_output_dir((dir / "file").string()), Catch::Contains("not a folder"));
  fs::remove_all(dir);
}
