// Atomic output files: write to "<path>.tmp.XXXXXX" in the same folder, fsync, rename.
// The only global state of the support library lives here: the registry of pending
// temporary files that the SIGINT/SIGTERM handler removes.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <ostream>
#include <streambuf>
#include <vector>

#include "coatcontact/cli_support.hpp"

namespace coatcontact::cli {
namespace {

// ---- signal-cleanup registry (async-signal-safe: fixed arrays, lock-free atomics) ----

constexpr int kMaxPending = 64;
constexpr std::size_t kMaxPathBytes = 4096;
enum SlotState : int { kFree = 0, kWriting = 1, kActive = 2 };

char g_pending_paths[kMaxPending][kMaxPathBytes];
std::atomic<int> g_pending_state[kMaxPending];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

extern "C" void cleanup_and_reraise(int signal_number) {
  const int saved_errno = errno;
  for (int i = 0; i < kMaxPending; ++i) {
    if (g_pending_state[i].load() == kActive) unlink(g_pending_paths[i]);
  }
  errno = saved_errno;
  // Default action (terminate) once this handler returns and the signal is unblocked.
  signal(signal_number, SIG_DFL);
  raise(signal_number);
}

void install_handlers_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int signal_number : {SIGINT, SIGTERM}) {
      struct sigaction previous {};
      if (sigaction(signal_number, nullptr, &previous) != 0) continue;
      // Respect a program (or nohup) that ignores or handles the signal itself.
      if (previous.sa_handler != SIG_DFL || (previous.sa_flags & SA_SIGINFO) != 0) continue;
      struct sigaction action {};
      action.sa_handler = cleanup_and_reraise;
      sigemptyset(&action.sa_mask);
      sigaddset(&action.sa_mask, SIGINT);
      sigaddset(&action.sa_mask, SIGTERM);
      action.sa_flags = 0;
      sigaction(signal_number, &action, nullptr);
    }
  });
}

// Returns the slot index, or -1 if the path is too long or all slots are in use.
int register_pending(const std::string& path) {
  if (path.size() + 1 > kMaxPathBytes) return -1;
  for (int i = 0; i < kMaxPending; ++i) {
    int expected = kFree;
    if (g_pending_state[i].compare_exchange_strong(expected, kWriting)) {
      std::memcpy(g_pending_paths[i], path.c_str(), path.size() + 1);
      g_pending_state[i].store(kActive);
      return i;
    }
  }
  return -1;
}

void unregister_pending(int slot) {
  if (slot >= 0) g_pending_state[slot].store(kFree);
}

// Blocks SIGINT/SIGTERM in this thread for a scope (so a temp file is never created
// without being registered).
class SignalBlock {
 public:
  SignalBlock() {
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &block, &previous_);
  }
  ~SignalBlock() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  sigset_t previous_;
};

// ---- a streambuf writing to a file descriptor, remembering the first error ----

class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd), buffer_(1 << 16) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  int error() const { return error_; }
  bool flush_all() { return drain(); }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const char* data = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0 && error_ == 0) {
      const ssize_t written = write(fd_, data, left);
      if (written < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        break;
      }
      data += written;
      left -= static_cast<std::size_t>(written);
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return error_ == 0;
  }

  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

// The process umask without changing it (umask() can only be read by setting it).
mode_t current_umask() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("Umask:", 0) == 0) {
      try {
        return static_cast<mode_t>(std::stoul(line.substr(6), nullptr, 8));
      } catch (const std::exception&) {
        break;
      }
    }
  }
  return 022;
}

std::string folder_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

}  // namespace

struct Output::Impl {
  std::string path;      // empty: stdout
  std::string temp_path;
  int fd = -1;
  int slot = -1;
  bool committed = false;
  std::unique_ptr<FdBuffer> buffer;
  std::unique_ptr<std::ostream> file_stream;

  [[noreturn]] void fail(const std::string& what, int error_number) const {
    throw InputError("output file '" + path + "': " + what +
                     (error_number != 0 ? std::string(": ") + std::strerror(error_number) : ""));
  }
};

Output::Output(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path == "-" ? std::string() : path;
  if (impl_->path.empty()) return;

  // Check the folder before creating anything, so a bad path leaves no trace.
  if (path.back() == '/') impl_->fail("is a folder name, expected a file name", 0);
  const std::string folder = folder_of(path);
  struct stat info {};
  if (stat(folder.c_str(), &info) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) impl_->fail("folder '" + folder + "' does not exist", 0);
    impl_->fail("cannot access folder '" + folder + "'", errno);
  }
  if (!S_ISDIR(info.st_mode)) impl_->fail("'" + folder + "' is not a folder", 0);
  if (stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) impl_->fail("is a folder", 0);

  install_handlers_once();
  std::string temp = path + ".tmp.XXXXXX";
  {
    SignalBlock block;  // created and registered as one step, as far as signals can tell
    impl_->fd = mkstemp(temp.data());
    if (impl_->fd < 0) impl_->fail("cannot create a file in folder '" + folder + "'", errno);
    impl_->temp_path = temp;
    impl_->slot = register_pending(temp);
  }
  try {
    // mkstemp makes 0600; give the result the permissions of an ordinary new file.
    fchmod(impl_->fd, static_cast<mode_t>(0666) & ~current_umask());
    impl_->buffer = std::make_unique<FdBuffer>(impl_->fd);
    impl_->file_stream = std::make_unique<std::ostream>(impl_->buffer.get());
  } catch (...) {  // no destructor runs for a half-built object: clean up here
    close(impl_->fd);
    unlink(impl_->temp_path.c_str());
    unregister_pending(impl_->slot);
    throw;
  }
}

Output::~Output() {
  if (!impl_ || impl_->path.empty() || impl_->committed) return;
  impl_->file_stream.reset();
  if (impl_->fd >= 0) close(impl_->fd);
  if (!impl_->temp_path.empty()) unlink(impl_->temp_path.c_str());
  unregister_pending(impl_->slot);
}

std::ostream& Output::stream() {
  if (impl_->path.empty()) return std::cout;
  return *impl_->file_stream;
}

void Output::commit() {
  if (impl_->committed) return;
  if (impl_->path.empty()) {
    std::cout.flush();
    if (!std::cout) throw InputError("cannot write to standard output");
    impl_->committed = true;
    return;
  }
  impl_->file_stream->flush();
  if (!impl_->buffer->flush_all() || !*impl_->file_stream) {
    impl_->fail("write failed", impl_->buffer->error());
  }
  if (fsync(impl_->fd) != 0 && errno != EINVAL) impl_->fail("fsync failed", errno);
  const int fd = impl_->fd;
  impl_->fd = -1;
  if (close(fd) != 0) impl_->fail("close failed", errno);
  if (rename(impl_->temp_path.c_str(), impl_->path.c_str()) != 0) {
    impl_->fail("cannot rename the temporary file into place", errno);
  }
  impl_->committed = true;
  unregister_pending(impl_->slot);
  // Make the rename itself durable (best effort: some file systems refuse fsync on folders).
  const int folder_fd = open(folder_of(impl_->path).c_str(), O_RDONLY | O_DIRECTORY);
  if (folder_fd >= 0) {
    fsync(folder_fd);
    close(folder_fd);
  }
}

}  // namespace coatcontact::cli
