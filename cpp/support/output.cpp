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

// A file-size limit (ulimit -f) raises SIGXFSZ, whose default action kills the process and
// leaves the temporary file; ignored, the write fails with EFBIG instead, which an output
// reports (exit 2, naming the file) after removing its temporary file. Set when the CLI
// support library is loaded; a program that handles or ignores the signal itself is left alone.
[[maybe_unused]] const bool g_file_size_signal_ignored = [] {
  struct sigaction previous {};
  if (sigaction(SIGXFSZ, nullptr, &previous) != 0) return false;
  if (previous.sa_handler != SIG_DFL || (previous.sa_flags & SA_SIGINFO) != 0) return false;
  signal(SIGXFSZ, SIG_IGN);
  return true;
}();

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

// Where an output goes: stdout ("-", /dev/stdout), another descriptor already open in this
// process (/dev/stderr, /dev/fd/N, /proc/self/fd/N: written to that descriptor, so a shell's
// ">>" keeps appending), a device written in place (/dev/null), or a regular file replaced
// atomically.
enum class Target { kStdout, kDescriptor, kDirect, kFile };

// The descriptor a path names, or -1 for a path that is not a descriptor name: 1 for "", "-"
// and /dev/stdout, 2 for /dev/stderr, N for /dev/fd/N and /proc/self/fd/N.
int descriptor_of(const std::string& path) {
  if (path.empty() || path == "-" || path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    const std::string p(prefix);
    if (path.size() > p.size() && path.size() <= p.size() + 6 && path.compare(0, p.size(), p) == 0) {
      int n = 0;
      for (std::size_t i = p.size(); i < path.size(); ++i) {
        if (path[i] < '0' || path[i] > '9') return -1;
        n = n * 10 + (path[i] - '0');
      }
      return n;
    }
  }
  return -1;
}

// "standard output", "standard error" or "descriptor N", for messages.
std::string descriptor_name(int fd) {
  if (fd == 1) return "standard output";
  if (fd == 2) return "standard error";
  return "descriptor " + std::to_string(fd);
}

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
    "standard output, /dev/stderr or /dev/fd/N of a descriptor open for writing, /dev/null";

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

// Test hook: COATCONTACT_TEST_RENAME_FAILURE=<path as given> makes that output's final rename
// fail with EPERM (an immutable file, another user's file in a sticky folder), so tests can
// check the roll-back of the outputs already published without root.
bool injected_rename_failure(const std::string& path) {
  const char* value = std::getenv("COATCONTACT_TEST_RENAME_FAILURE");
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
  int stream_fd = -1;      // kStdout, kDescriptor: the descriptor written at publish
  FileId id;
  std::string backup_path; // a hard link to the file being replaced, until all are published
  int backup_slot = -1;    // its signal-cleanup slot
  bool replaced = false;   // renamed into place (undone by roll_back)
  int fd = -1;
  int slot = -1;
  bool complete = false;   // every byte is in the temporary file (or memory)
  bool committed = false;  // published
  std::unique_ptr<FdBuffer> buffer;
  std::unique_ptr<std::ostream> file_stream;
  std::ostringstream memory;  // stdout and in-place devices: published at commit

  [[noreturn]] void fail(const std::string& what, int error_number) const {
    throw InputError(option + ": output file " + quoted(path) + ": " + what +
                     (error_number != 0 ? std::string(": ") + std::strerror(error_number) : ""));
  }
  void publish_memory();
  void keep_backup();
  void rename_into_place();
  void roll_back();
  void drop_backup();
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
  if (target == Target::kDescriptor) {
    if (stream_fd == 2) std::cerr.flush();
    FdBuffer writer(stream_fd);
    std::ostream stream(&writer);
    stream << text;
    stream.flush();
    const int error_number = writer.flush_all() ? 0 : writer.error();
    if (error_number != 0 || injected_write_failure(path)) {
      throw InputError(option + ": cannot write to " + descriptor_name(stream_fd) + " (" + quoted(path) + ")" +
                       ": " + std::strerror(error_number != 0 ? error_number : ENOSPC));
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

// Before any output of the command is replaced, each existing target gets a hard link
// "<path>.old.XXXXXX" beside it: making it proves the file can be replaced (an immutable file,
// or another user's file in a sticky folder, refuses the link as it would refuse the rename),
// and it is what roll_back() restores if a later output cannot be published.
void Output::Impl::keep_backup() {
  struct stat info {};
  if (lstat(write_path.c_str(), &info) != 0) return;  // a new file: nothing to keep
  install_handlers_once();
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string name = write_path + ".old.XXXXXX";
    // A unique name from mkstemp, then replaced by the link (link() never overwrites).
    const int probe = mkstemp(name.data());
    if (probe < 0) fail("cannot create a file beside it to keep the old contents", errno);
    close(probe);
    unlink(name.c_str());
    SignalBlock block;  // linked and registered as one step, so a signal never leaves it behind
    if (link(write_path.c_str(), name.c_str()) == 0) {
      backup_path = name;
      backup_slot = register_pending(name);
      return;
    }
    if (errno != EEXIST) fail("cannot be replaced (no other output of this command was written)", errno);
  }
  fail("cannot be replaced: no free name for keeping the old contents", EEXIST);
}

void Output::Impl::roll_back() {
  if (!replaced) return;
  if (!backup_path.empty()) {
    rename(backup_path.c_str(), write_path.c_str());
    backup_path.clear();
    unregister_pending(backup_slot);
    backup_slot = -1;
  } else {
    unlink(write_path.c_str());  // the file was new
  }
  replaced = false;
}

void Output::Impl::drop_backup() {
  if (!backup_path.empty()) unlink(backup_path.c_str());
  backup_path.clear();
  unregister_pending(backup_slot);
  backup_slot = -1;
}

void Output::Impl::rename_into_place() {
  if (injected_rename_failure(path)) fail("cannot rename the temporary file into place", EPERM);
  if (rename(temp_path.c_str(), write_path.c_str()) != 0) {
    fail("cannot rename the temporary file into place", errno);
  }
  replaced = true;
  unregister_pending(slot);
  slot = -1;
  // Make the rename itself durable (best effort: some file systems refuse fsync on folders).
  const int folder_fd = open(folder_of(write_path).c_str(), O_RDONLY | O_DIRECTORY);
  if (folder_fd >= 0) {
    fsync(folder_fd);
    close(folder_fd);
  }
}

namespace {

// The descriptor `fd` must be open for writing to be an output.
void check_descriptor(const Output::Impl& probe, int fd) {
  const int flags = fcntl(fd, F_GETFL);
  if (flags < 0) {
    probe.fail("names " + descriptor_name(fd) + ", which is not open in this process; " + kAllowedTargets, 0);
  }
  if ((flags & O_ACCMODE) == O_RDONLY) {
    probe.fail("names " + descriptor_name(fd) + ", which is open for reading only; " + kAllowedTargets, 0);
  }
}

// Two outputs of one command on one stream would interleave: refused.
void check_stream_unique(const Output::Impl& probe, int fd) {
  for (const Output::Impl* other : live_outputs()) {
    // A committed output has written its stream; one still pending would interleave.
    if ((other->target == Target::kStdout || other->target == Target::kDescriptor) && other->stream_fd == fd &&
        !other->committed) {
      probe.fail("is " + descriptor_name(fd) + ", also the target of " + other->option + " (" + quoted(other->path) +
                     "); two outputs of a command cannot share one stream", 0);
    }
  }
}

}  // namespace

void check_output_path(const std::string& path, const std::string& option) {
  Output::Impl probe;
  probe.option = option;
  probe.path = path;
  if (const int fd = descriptor_of(path); fd >= 0) {
    if (fd != 1) check_descriptor(probe, fd);
    check_stream_unique(probe, fd);
    return;
  }
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
      if (errno == ENOENT || errno == ENOTDIR) probe.fail("folder " + quoted(folder) + " does not exist", 0);
      probe.fail("cannot access folder " + quoted(folder), errno);
    }
    if (!S_ISDIR(info.st_mode)) probe.fail(quoted(folder) + " is not a folder", 0);
  }
  const FileId id = file_id(path);
  // Standard input redirected from a file ("< data.tsv") is that file: never replaced.
  struct stat in_info {};
  if (id.exists && fstat(0, &in_info) == 0 && S_ISREG(in_info.st_mode) && in_info.st_dev == id.device &&
      in_info.st_ino == id.inode) {
    probe.fail("is the file standard input is read from (the same file); an output never replaces an input, "
               "choose another name", 0);
  }
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

bool output_is_regular_file(const std::string& path) {
  if (path.empty() || descriptor_of(path) >= 0) return false;
  struct stat info {};
  if (stat(path.c_str(), &info) != 0) return true;  // a new file
  return S_ISREG(info.st_mode);
}

void check_output_paths(const std::vector<std::pair<std::string, std::string>>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    check_output_path(outputs[i].second, outputs[i].first);
    // An empty path is an option not given; "-" and descriptor names are streams.
    const int fd = outputs[i].second.empty() ? -1 : descriptor_of(outputs[i].second);
    if (fd >= 0) {
      for (std::size_t j = 0; j < i; ++j) {
        if (!outputs[j].second.empty() && descriptor_of(outputs[j].second) == fd) {
          throw InputError(outputs[i].first + ": output " + quoted(outputs[i].second) + " is " + descriptor_name(fd) +
                           ", also the target of " + outputs[j].first + " (" + quoted(outputs[j].second) +
                           "); two outputs of a command cannot share one stream");
        }
      }
      continue;
    }
    if (outputs[i].second.empty() || outputs[i].second == "/dev/null") continue;
    for (std::size_t j = 0; j < i; ++j) {
      if (outputs[j].second.empty()) continue;
      if (file_id(outputs[j].second) == file_id(outputs[i].second)) {
        throw InputError(outputs[i].first + ": output file " + quoted(outputs[i].second) + " is also the file of " +
                         outputs[j].first + " (" + quoted(outputs[j].second) +
                         "); each output of a command needs its own file");
      }
    }
  }
}

Output::Output(const std::string& path, const std::string& option) : impl_(std::make_unique<Impl>()) {
  impl_->option = option;
  impl_->path = path;
  check_output_path(path, option);  // before creating anything, so a bad path leaves no trace
  struct stat info {};
  if (const int fd = descriptor_of(path); fd >= 0) {
    impl_->target = fd == 1 ? Target::kStdout : Target::kDescriptor;
    impl_->stream_fd = fd;
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
    if (impl_->fd < 0) impl_->fail("cannot create a file in folder " + quoted(folder), errno);
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

void write_table_and_picture(const std::string& output_path, const std::string& table,
                             const std::optional<std::string>& plot_path, const std::string& picture) {
  Output output(output_path);
  output.stream() << table;
  std::unique_ptr<Output> plot_output;
  if (plot_path) {
    plot_output = std::make_unique<Output>(*plot_path, "--plot");
    plot_output->stream().write(picture.data(), static_cast<std::streamsize>(picture.size()));
    plot_output->commit();
  }
  output.commit();
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
  std::size_t files = 0;
  for (const Output::Impl* other : live) files += other->target == Target::kFile ? 1 : 0;
  // Several files: check that every one can be replaced before replacing any.
  const auto drop_backups = [&] {
    for (Output::Impl* other : live) other->drop_backup();
  };
  if (files > 1) {
    try {
      for (Output::Impl* other : live) {
        if (other->target == Target::kFile) other->keep_backup();
      }
    } catch (...) {
      drop_backups();
      throw;
    }
  }
  // Streams first (they can fail and cannot be undone), then the cheap renames; a failed
  // rename puts back every file already replaced.
  try {
    for (Output::Impl* other : live) {
      if (other->target != Target::kFile) other->publish_memory();
    }
    for (Output::Impl* other : live) {
      if (other->target == Target::kFile) other->rename_into_place();
    }
  } catch (...) {
    for (Output::Impl* other : live) other->roll_back();
    drop_backups();
    throw;
  }
  drop_backups();
  for (Output::Impl* other : live) other->committed = true;
}

}  // namespace coatcontact::cli
