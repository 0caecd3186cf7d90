// Atomic output files: write to "<path>.tmp.XXXXXX" in the same folder, fsync, rename.
// The only global state of the support library lives here: the registry of pending
// temporary files that the SIGINT/SIGTERM handler removes.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <ostream>
#include <sstream>
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

std::string base_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// Where an output goes: stdout ("-", /dev/stdout), a device written in place (/dev/null), or
// a regular file replaced atomically.
enum class Target { kStdout, kDirect, kFile };

// Identity of a path for same-file checks: device and inode when it exists, else the
// resolved folder plus the name (two spellings of one new file compare equal).
struct FileId {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::string resolved;
  bool operator==(const FileId& other) const {
    if (exists && other.exists) return device == other.device && inode == other.inode;
    return !exists && !other.exists && resolved == other.resolved;
  }
};

FileId file_id(const std::string& path) {
  FileId id;
  struct stat info {};
  if (stat(path.c_str(), &info) == 0) {
    id.exists = true;
    id.device = info.st_dev;
    id.inode = info.st_ino;
    return id;
  }
  char* folder = realpath(folder_of(path).c_str(), nullptr);
  id.resolved = (folder != nullptr ? std::string(folder) : folder_of(path)) + "/" + base_of(path);
  std::free(folder);
  return id;
}

struct InputRecord {
  std::string what;
  std::string path;
  FileId id;
};
std::vector<InputRecord>& inputs() {
  static std::vector<InputRecord> list;
  return list;
}

const char* kAllowedTargets =
    "allowed: a regular file (new or existing, replaced atomically), '-' or /dev/stdout for "
    "standard output, /dev/null";

std::string file_type(mode_t mode) {
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISDIR(mode)) return "a folder";
  return "not a regular file";
}

// Test hook: COATCONTACT_TEST_WRITE_FAILURE=<path as given, or '-'> makes that output's write
// fail with ENOSPC, so tests can check a full disk without filling one.
bool injected_write_failure(const std::string& path) {
  const char* value = std::getenv("COATCONTACT_TEST_WRITE_FAILURE");
  return value != nullptr && path == value;
}

}  // namespace

void register_input(const std::string& path, const std::string& what) {
  inputs().push_back({what, path, file_id(path)});
}

struct Output::Impl {
  std::string option;
  std::string path;       // as given ("-" for stdout)
  std::string write_path; // where the file is renamed to (a symlink's target)
  std::string temp_path;
  Target target = Target::kFile;
  FileId id;
  int fd = -1;
  int slot = -1;
  bool complete = false;   // every byte is in the temporary file (or memory)
  bool committed = false;  // published
  std::unique_ptr<FdBuffer> buffer;
  std::unique_ptr<std::ostream> file_stream;
  std::ostringstream memory;  // stdout and in-place devices: published at commit

  [[noreturn]] void fail(const std::string& what, int error_number) const {
    throw InputError(option + ": output file '" + path + "': " + what +
                     (error_number != 0 ? std::string(": ") + std::strerror(error_number) : ""));
  }
  void publish_memory();
  void rename_into_place();
};

namespace {

// Outputs of this process not yet published: committed together (all or none).
std::vector<Output::Impl*>& live_outputs() {
  static std::vector<Output::Impl*> list;
  return list;
}
bool g_output_set_aborted = false;

}  // namespace

void Output::Impl::publish_memory() {
  const std::string text = memory.str();
  if (target == Target::kStdout) {
    std::fflush(stdout);
    const bool ok = !injected_write_failure(path.empty() ? "-" : path) &&
                    std::fwrite(text.data(), 1, text.size(), stdout) == text.size() &&
                    std::fflush(stdout) == 0 && !std::ferror(stdout);
    if (!ok) {
      const int error_number = injected_write_failure(path.empty() ? "-" : path) ? ENOSPC : errno;
      throw InputError(option + ": cannot write to standard output" +
                       (error_number != 0 ? std::string(": ") + std::strerror(error_number) : ""));
    }
    return;
  }
  // In place (no O_CREAT, no O_TRUNC): a device is never replaced.
  const int direct = open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (direct < 0) fail("cannot open", errno);
  FdBuffer writer(direct);
  std::ostream stream(&writer);
  stream << text;
  stream.flush();
  const int error_number = writer.flush_all() ? 0 : writer.error();
  close(direct);
  if (error_number != 0 || injected_write_failure(path)) fail("write failed", error_number != 0 ? error_number : ENOSPC);
}

void Output::Impl::rename_into_place() {
  if (rename(temp_path.c_str(), write_path.c_str()) != 0) {
    fail("cannot rename the temporary file into place", errno);
  }
  unregister_pending(slot);
  slot = -1;
  // Make the rename itself durable (best effort: some file systems refuse fsync on folders).
  const int folder_fd = open(folder_of(write_path).c_str(), O_RDONLY | O_DIRECTORY);
  if (folder_fd >= 0) {
    fsync(folder_fd);
    close(folder_fd);
  }
}

void check_output_path(const std::string& path, const std::string& option) {
  Output::Impl probe;
  probe.option = option;
  probe.path = path;
  if (path.empty() || path == "-" || path == "/dev/stdout") return;
  struct stat info {};
  if (path == "/dev/null" && stat(path.c_str(), &info) == 0 && S_ISCHR(info.st_mode)) return;
  if (path.back() == '/') probe.fail("is a folder name, expected a file name", 0);
  if (lstat(path.c_str(), &info) == 0) {
    if (S_ISLNK(info.st_mode)) {
      struct stat target {};
      if (stat(path.c_str(), &target) != 0) {
        probe.fail(std::string("is a symbolic link to a missing or unreachable file; ") + kAllowedTargets, 0);
      }
      info = target;
    }
    if (S_ISDIR(info.st_mode)) probe.fail("is a folder", 0);
    if (!S_ISREG(info.st_mode)) {
      probe.fail("is " + file_type(info.st_mode) + ", not a regular file; " + kAllowedTargets, 0);
    }
  } else {
    const std::string folder = folder_of(path);
    if (stat(folder.c_str(), &info) != 0) {
      if (errno == ENOENT || errno == ENOTDIR) probe.fail("folder '" + folder + "' does not exist", 0);
      probe.fail("cannot access folder '" + folder + "'", errno);
    }
    if (!S_ISDIR(info.st_mode)) probe.fail("'" + folder + "' is not a folder", 0);
  }
  const FileId id = file_id(path);
  for (const auto& input : inputs()) {
    if (input.id == id) {
      probe.fail("is the " + input.what + " '" + input.path +
                     "' (the same file); an output never replaces an input, choose another name", 0);
    }
  }
  for (const Output::Impl* other : live_outputs()) {
    if (other->target == Target::kFile && other->id == id) {
      probe.fail("is also the file of " + other->option + " ('" + other->path +
                     "'); each output of a command needs its own file", 0);
    }
  }
}

void check_output_paths(const std::vector<std::pair<std::string, std::string>>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    check_output_path(outputs[i].second, outputs[i].first);
    if (outputs[i].second.empty() || outputs[i].second == "-" || outputs[i].second == "/dev/stdout" ||
        outputs[i].second == "/dev/null") {
      continue;
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (outputs[j].second.empty()) continue;
      if (file_id(outputs[j].second) == file_id(outputs[i].second)) {
        throw InputError(outputs[i].first + ": output file '" + outputs[i].second + "' is also the file of " +
                         outputs[j].first + " ('" + outputs[j].second +
                         "'); each output of a command needs its own file");
      }
    }
  }
}

Output::Output(const std::string& path, const std::string& option) : impl_(std::make_unique<Impl>()) {
  impl_->option = option;
  impl_->path = path;
  check_output_path(path, option);  // before creating anything, so a bad path leaves no trace
  struct stat info {};
  if (path.empty() || path == "-" || path == "/dev/stdout") {
    impl_->target = Target::kStdout;
  } else if (path == "/dev/null" && stat(path.c_str(), &info) == 0 && S_ISCHR(info.st_mode)) {
    impl_->target = Target::kDirect;
  }
  if (impl_->target != Target::kFile) {
    live_outputs().push_back(impl_.get());
    return;
  }
  impl_->id = file_id(path);
  // A symlink to a regular file: replace the file it points to, keep the link.
  impl_->write_path = path;
  if (lstat(path.c_str(), &info) == 0 && S_ISLNK(info.st_mode)) {
    char* resolved = realpath(path.c_str(), nullptr);
    if (resolved == nullptr) impl_->fail("cannot resolve the symbolic link", errno);
    impl_->write_path = resolved;
    std::free(resolved);
  }
  const std::string folder = folder_of(impl_->write_path);

  install_handlers_once();
  std::string temp = impl_->write_path + ".tmp.XXXXXX";
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
    live_outputs().push_back(impl_.get());
  } catch (...) {  // no destructor runs for a half-built object: clean up here
    close(impl_->fd);
    unlink(impl_->temp_path.c_str());
    unregister_pending(impl_->slot);
    throw;
  }
}

Output::~Output() {
  if (!impl_) return;
  auto& live = live_outputs();
  const auto it = std::find(live.begin(), live.end(), impl_.get());
  if (it != live.end()) {
    live.erase(it);
    // Destroyed before publishing: the other outputs of this command must not appear either.
    if (!impl_->committed) g_output_set_aborted = true;
  }
  if (live.empty()) g_output_set_aborted = false;
  if (impl_->target != Target::kFile || impl_->committed) return;
  impl_->file_stream.reset();
  if (impl_->fd >= 0) close(impl_->fd);
  if (!impl_->temp_path.empty()) unlink(impl_->temp_path.c_str());
  unregister_pending(impl_->slot);
}

std::ostream& Output::stream() {
  if (impl_->target != Target::kFile) return impl_->memory;
  return *impl_->file_stream;
}

void Output::commit() {
  if (impl_->committed || impl_->complete) return;
  if (g_output_set_aborted) throw InputError(impl_->option + ": not written (another output of this command failed)");
  if (impl_->target == Target::kFile) {
    impl_->file_stream->flush();
    if (injected_write_failure(impl_->path)) impl_->fail("write failed", ENOSPC);
    if (!impl_->buffer->flush_all() || !*impl_->file_stream) {
      impl_->fail("write failed", impl_->buffer->error());
    }
    if (fsync(impl_->fd) != 0 && errno != EINVAL) impl_->fail("fsync failed", errno);
    const int fd = impl_->fd;
    impl_->fd = -1;
    if (close(fd) != 0) impl_->fail("close failed", errno);
  }
  impl_->complete = true;
  // All or none: publish only when every output of the command is complete.
  auto& live = live_outputs();
  for (const Output::Impl* other : live) {
    if (!other->complete) return;
  }
  progress_pause();
  // Streams first (they can fail and cannot be undone), then the cheap renames.
  for (Output::Impl* other : live) {
    if (other->target != Target::kFile) other->publish_memory();
  }
  for (Output::Impl* other : live) {
    if (other->target == Target::kFile) other->rename_into_place();
    other->committed = true;
  }
}

}  // namespace coatcontact::cli
