#include "util/progress.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <unistd.h>

namespace mfv::progress {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

struct Task::Entry {
  std::string label;
  uint64_t total = 0;
  std::atomic<uint64_t> done{0};
  Clock::time_point start = Clock::now();
};

namespace {

using Entry = Task::Entry;

std::atomic<bool> g_quiet{false};
constexpr double kLogInterval = 2.0;  // seconds between lines off a terminal

std::string seconds_text(double s) {
  if (s < 90) return std::to_string(int(s + 0.5)) + " s";
  if (s < 5400) return std::to_string(int(s / 60 + 0.5)) + " min";
  return std::to_string(int(s / 3600 + 0.5)) + " h";
}

// One drawing thread per process, started by the first Task.
class Reporter {
 public:
  static Reporter& get() {
    static Reporter r;
    return r;
  }
  void push(Entry* e) {
    std::lock_guard<std::mutex> lock(m_);
    if (stack_.empty()) last_log_ = Clock::now();
    stack_.push_back(e);
    if (!thread_.joinable()) thread_ = std::thread([this] { loop(); });
  }
  void pop(Entry* e) {
    std::lock_guard<std::mutex> lock(m_);
    stack_.erase(std::remove(stack_.begin(), stack_.end(), e), stack_.end());
    if (stack_.empty() && drawn_) {
      std::fputs("\r\033[K", stderr);  // leave the terminal line empty for the results
      drawn_ = false;
    }
  }
  ~Reporter() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

 private:
  Reporter() : tty_(isatty(STDERR_FILENO) == 1) {}

  void loop() {
    std::unique_lock<std::mutex> lock(m_);
    while (!stop_) {
      cv_.wait_for(lock, std::chrono::milliseconds(tty_ ? 200 : 100));
      if (stop_ || stack_.empty()) continue;
      if (tty_) {
        std::fprintf(stderr, "\r\033[K%s", line(true).c_str());
        drawn_ = true;
      } else if (std::chrono::duration<double>(Clock::now() - last_log_).count() >= kLogInterval) {
        std::fprintf(stderr, "mfv: %s\n", line(false).c_str());
        last_log_ = Clock::now();
      }
      std::fflush(stderr);
    }
  }

  // "label: inner 45% [bar] 12 s, about 15 s left" for the innermost task
  // that knows its size; elapsed time only when none does.
  std::string line(bool bar) const {
    std::string label;
    for (auto* e : stack_) label += (label.empty() ? "" : ": ") + e->label;
    const Entry* sized = nullptr;
    for (auto* e : stack_)
      if (e->total > 0) sized = e;
    const double elapsed = std::chrono::duration<double>(Clock::now() - stack_.front()->start).count();
    if (!sized) return label + ", " + seconds_text(elapsed);
    const double f = std::min(1.0, double(sized->done.load()) / double(sized->total));
    const double own = std::chrono::duration<double>(Clock::now() - sized->start).count();
    std::string s = label;
    char pct[16];
    std::snprintf(pct, sizeof pct, " %3d%% ", int(f * 100));
    s += pct;
    if (bar) {
      const int width = 24, full = int(f * width);
      s += "[" + std::string(full, '#') + std::string(width - full, '.') + "] ";
    }
    s += seconds_text(elapsed);
    if (f > 0.01) s += ", about " + seconds_text(own * (1 - f) / f) + " left";
    return s;
  }

  std::mutex m_;
  std::condition_variable cv_;
  std::vector<Entry*> stack_;
  std::thread thread_;
  bool stop_ = false, drawn_ = false;
  const bool tty_;
  Clock::time_point last_log_ = Clock::now();
};

}  // namespace

void set_quiet(bool q) { g_quiet = q; }
bool quiet() { return g_quiet; }

Task::Task(std::string label, uint64_t total) {
  if (g_quiet) return;
  entry_ = std::make_unique<Entry>();
  entry_->label = std::move(label);
  entry_->total = total;
  Reporter::get().push(entry_.get());
}

Task::~Task() {
  if (entry_) Reporter::get().pop(entry_.get());
}

void Task::advance(uint64_t done) {
  if (entry_) entry_->done += done;
}

}  // namespace mfv::progress
