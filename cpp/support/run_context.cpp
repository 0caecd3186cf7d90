// What every command shares beyond its options: the command line for the "# command:" header,
// the program version, and the progress line of long runs.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/version.hpp"

namespace coatcontact::cli {
namespace {

std::string g_command_line;

std::string shell_quote(const std::string& arg) {
  bool plain = !arg.empty();
  for (char c : arg) {
    const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      std::string("_./:=,+@%^-").find(c) != std::string::npos;
    if (!safe) plain = false;
  }
  if (plain) return arg;
  std::string out = "'";
  for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// ---- progress line ----

using Clock = std::chrono::steady_clock;
constexpr double kShowAfterSeconds = 2.0;

std::string seconds_text(double s) {
  char buffer[32];
  if (s < 90) {
    std::snprintf(buffer, sizeof buffer, "%.0f s", s);
  } else if (s < 5400) {
    std::snprintf(buffer, sizeof buffer, "%.0f min", s / 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.1f h", s / 3600);
  }
  return buffer;
}

class Reporter {
 public:
  explicit Reporter(std::string command) : command_(std::move(command)), start_(Clock::now()) {
    if (isatty(STDERR_FILENO) == 1) thread_ = std::thread([this] { loop(); });
  }
  ~Reporter() { pause(); }
  Reporter(const Reporter&) = delete;
  Reporter& operator=(const Reporter&) = delete;

  void set_estimate(double seconds) {
    std::lock_guard<std::mutex> lock(mutex_);
    estimate_ = seconds;
  }
  void step(std::size_t done, std::size_t total) {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = done;
    total_ = total;
  }
  void pause() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    bool shown = false;
    while (!wake_.wait_for(lock, std::chrono::milliseconds(250), [this] { return stop_; })) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
      if (elapsed < kShowAfterSeconds) continue;
      std::string line = "\rcoatcontact " + command_ + ": working, " + seconds_text(elapsed);
      if (total_ > 0) line += ", step " + std::to_string(done_) + "/" + std::to_string(total_);
      if (total_ > 0 && done_ > 0) {
        line += ", ETA " + seconds_text(elapsed * static_cast<double>(total_ - done_) / static_cast<double>(done_));
      } else if (estimate_ > elapsed) {
        line += ", ETA ~" + seconds_text(estimate_ - elapsed) + " (estimate)";
      } else {
        line += ", ETA unknown";
      }
      line += "\x1b[K";
      shown = write(STDERR_FILENO, line.data(), line.size()) > 0 || shown;
    }
    if (shown) {
      const char clear[] = "\r\x1b[K";
      (void)!write(STDERR_FILENO, clear, sizeof clear - 1);
    }
  }

  std::string command_;
  Clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
  bool stop_ = false;
  double estimate_ = 0.0;
  std::size_t done_ = 0, total_ = 0;
};

Reporter* g_reporter = nullptr;

}  // namespace

void set_command_line(int argc, const char* const* argv) {
  std::string program = argc > 0 && argv[0] != nullptr ? argv[0] : "coatcontact";
  const std::size_t slash = program.rfind('/');
  if (slash != std::string::npos) program.erase(0, slash + 1);
  g_command_line = shell_quote(program);
  for (int i = 1; i < argc; ++i) g_command_line += " " + shell_quote(argv[i]);
}

const std::string& command_line() { return g_command_line; }

std::string version_string() {
  std::string text = COATCONTACT_VERSION;
  const std::string git = COATCONTACT_GIT_DESCRIBE;
  if (!git.empty()) text += " (git " + git + ")";
  return text;
}

ProgressScope::ProgressScope(const std::string& command) {
  if (g_reporter == nullptr) {
    g_reporter = new Reporter(command);
    owner_ = true;
  }
}

ProgressScope::~ProgressScope() {
  if (!owner_) return;
  delete g_reporter;
  g_reporter = nullptr;
}

void progress_set_estimate(double seconds) {
  if (g_reporter != nullptr) g_reporter->set_estimate(seconds);
}
void progress_step(std::size_t done, std::size_t total) {
  if (g_reporter != nullptr) g_reporter->step(done, total);
}
void progress_pause() {
  if (g_reporter != nullptr) g_reporter->pause();
}

}  // namespace coatcontact::cli
