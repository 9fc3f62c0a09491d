// Output files and standard descriptors: the rules of output_file.hpp, and why.
//
// The temporary file. It lives in the target's directory, because rename(2) is atomic only within
// one file system, and an attacker may share that directory (/tmp). A name derived from the pid
// could be guessed and a symbolic link planted there in advance: opening it with O_CREAT|O_TRUNC
// would truncate and overwrite whatever the link points to, and a file planted by another user
// would become the output, owned by that user. So the name carries random characters (from the
// kernel's generator), and the file is created with O_CREAT|O_EXCL|O_NOFOLLOW: if anything exists
// under that name, the creation fails and another name is drawn. It is created with mode 0600 (no
// one else reads a half-written file) and gets the mode a new file would get, 0666 minus the umask,
// when complete. Its name is `.<target name>.tmp.<pid>.<random>`, the target's name shortened if
// needed (at a character boundary) so that the whole stays within the directory's NAME_MAX: any
// target name that is valid can be written. The pid lets the next run writing the same target
// remove the temporary file of a process that no longer exists (killed by SIGKILL, which cannot be
// caught).
//
// Targets that are not regular files. Replacing /dev/null by a regular file (what a rename does,
// and root may) is never what the user meant, nor replacing a FIFO that a reader waits on: character
// devices and FIFOs are opened and written in place, without creating or truncating. A FIFO is
// opened without blocking: with no reader that fails at once (ENXIO) and the option is refused,
// instead of hanging. /dev/stdout and /dev/stderr are symbolic links to /proc/self/fd/N; when the
// target is the very file open on descriptor 1 or 2 (same device and inode), that descriptor is
// duplicated, so that the data go where the shell sent the standard output, at its current offset.
// Any other symbolic link is refused rather than followed or replaced: following it lets whoever
// planted it choose which file is overwritten, replacing it silently destroys a link the user made.
// Directories, sockets and block devices are refused. After an in-place open the descriptor is
// checked to be the object that was examined (a swap between the check and the open is refused).
//
// The same file twice. Two outputs of one run that name the same file (the same path, ./path,
// dir/../path, a hard link, a path through a linked directory) would silently lose one of them.
// Each open output records the identity of its target: device and inode of an existing file, or
// of the directory plus the name for a new one; a second output with the same identity is refused,
// naming both options. Character devices are exempt (writing twice to /dev/null is harmless).
//
// Interrupted runs. A process ended by a signal runs no destructor. For every signal whose default
// action ends the process and that can be caught (SIGHUP, SIGINT, SIGQUIT, SIGILL, SIGTRAP, SIGABRT,
// SIGBUS, SIGFPE, SIGUSR1, SIGSEGV, SIGUSR2, SIGPIPE, SIGALRM, SIGTERM, SIGSTKFLT, SIGXCPU, SIGXFSZ,
// SIGVTALRM, SIGPROF, SIGIO, SIGPWR, SIGSYS and the real-time signals), a handler removes the
// temporary files not yet committed, restores the default action and raises the signal again, so
// that the process ends exactly as it would have. The handler is async-signal-safe: it reads a
// fixed table of paths prepared in advance (a slot holds a heap copy of a path, published and
// withdrawn by atomic exchange), calls unlink(2) and raise(3). It is installed, when the first
// output is opened, only for the signals whose action is still the default: a program (or a
// sanitizer) that handles or ignores a signal keeps its choice.
#include "output_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <iterator>
#include <random>
#include <sstream>
#include <system_error>

#include <fcntl.h>
#include <signal.h>
#include <sys/random.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include "options.hpp"

namespace mrm::cli {

TEST_SUITE_BEGIN("output files");

namespace {

// A refusal of an output path: a UsageError naming the option, or, for a path that does not come
// from an option, a plain runtime error.
[[noreturn]] void refuse(std::string_view option, const std::string& path, const std::string& reason) {
  const std::string message = "cannot write " + json_string(path) + ": " + reason;
  if (option.empty()) {
    throw std::runtime_error(message);
  }
  throw UsageError(std::string(option) + ": " + message);
}
[[noreturn]] void refuse_errno(std::string_view option, const std::string& path, int error_number) {
  refuse(option, path, std::strerror(error_number));
}

// ---- Interrupted runs ----------------------------------------------------------------------------

constexpr std::size_t max_pending = 64;
std::atomic<char*> pending_paths[max_pending];

extern "C" void remove_pending_and_reraise(int signal_number) {
  const int saved_errno = errno;
  for (std::atomic<char*>& slot : pending_paths) {
    if (const char* path = slot.load()) {
      ::unlink(path);
    }
  }
  ::signal(signal_number, SIG_DFL);  // already reset by SA_RESETHAND; stated for clarity
  ::raise(signal_number);            // delivered when the handler returns
  errno = saved_errno;
}

// The catchable signals whose default action ends the process.
std::vector<int> terminating_signals() {
  std::vector<int> signals{SIGHUP,  SIGINT,  SIGQUIT, SIGILL,  SIGTRAP, SIGABRT, SIGBUS,    SIGFPE,  SIGUSR1, SIGSEGV,
                           SIGUSR2, SIGPIPE, SIGALRM, SIGTERM, SIGXCPU, SIGXFSZ, SIGVTALRM, SIGPROF, SIGIO,   SIGSYS};
#ifdef SIGSTKFLT
  signals.push_back(SIGSTKFLT);
#endif
#ifdef SIGPWR
  signals.push_back(SIGPWR);
#endif
  for (int signal_number = SIGRTMIN; signal_number <= SIGRTMAX; ++signal_number) {
    signals.push_back(signal_number);
  }
  return signals;
}

// Installed again by every new output for the signals whose action is (still, or again) the
// default: a program that handles or ignores a signal keeps its choice.
void install_cleanup_handlers() {
  for (const int signal_number : terminating_signals()) {
    struct sigaction current {};
    if (::sigaction(signal_number, nullptr, &current) != 0 || (current.sa_flags & SA_SIGINFO) != 0 ||
        current.sa_handler != SIG_DFL) {
      continue;
    }
    struct sigaction action {};
    action.sa_handler = remove_pending_and_reraise;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    ::sigaction(signal_number, &action, nullptr);
  }
}

// Registers a path with the handler; returns its slot, or max_pending when the table is full (the
// file is then removed by destructors only).
std::size_t register_pending(const std::string& path) {
  install_cleanup_handlers();
  char* copy = ::strdup(path.c_str());
  if (copy == nullptr) {
    return max_pending;
  }
  for (std::size_t slot = 0; slot < max_pending; ++slot) {
    char* expected = nullptr;
    if (pending_paths[slot].compare_exchange_strong(expected, copy)) {
      return slot;
    }
  }
  std::free(copy);
  return max_pending;
}

void withdraw_pending(std::size_t slot) noexcept {
  if (slot < max_pending) {
    std::free(pending_paths[slot].exchange(nullptr));
  }
}

// ---- Names --------------------------------------------------------------------------------------

// Random characters from the kernel's generator (getrandom; std::random_device if it fails).
std::string random_characters(std::size_t count) {
  static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  std::vector<unsigned char> bytes(count);
  if (::getrandom(bytes.data(), bytes.size(), 0) != static_cast<ssize_t>(bytes.size())) {
    std::random_device device;
    for (unsigned char& byte : bytes) {
      byte = static_cast<unsigned char>(device());
    }
  }
  std::string result;
  for (const unsigned char byte : bytes) {
    result += alphabet[byte % (sizeof alphabet - 1)];
  }
  return result;
}

// The first `limit` bytes of a name, not cutting a UTF-8 character in two.
std::string shortened(const std::string& name, std::size_t limit) {
  if (name.size() <= limit) {
    return name;
  }
  std::size_t end = limit;
  while (end > 0 && (static_cast<unsigned char>(name[end]) & 0xC0) == 0x80) {
    --end;
  }
  return name.substr(0, end);
}

constexpr std::size_t random_length = 10;
// The room a temporary name needs beyond the shortened target name: '.', ".tmp.", a pid of at most
// 7 digits (pid_max is at most 2^22), '.', the random characters, and ".old" for the link that keeps
// a previous target during a commit of several outputs (commit_all).
constexpr std::size_t name_overhead = 1 + 5 + 7 + 1 + random_length + 4;

std::string temporary_prefix(const std::filesystem::path& directory, const std::string& name) {
  long name_max = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  if (name_max <= 0) {
    name_max = 255;
  }
  const std::size_t room =
      static_cast<std::size_t>(name_max) > name_overhead + 1 ? static_cast<std::size_t>(name_max) - name_overhead : 1;
  return "." + shortened(name, room) + ".tmp.";
}

// Temporary files of the same target left by processes that no longer exist are removed when the
// target is written again; those of a live process (another run writing the same target now) are
// left alone.
void remove_stale_temporaries(const std::filesystem::path& directory, const std::string& prefix) noexcept {
  try {
    namespace fs = std::filesystem;
    std::error_code error;
    std::vector<fs::path> stale;
    for (fs::directory_iterator entry(directory, error), end; !error && entry != end; entry.increment(error)) {
      const std::string name = entry->path().filename().string();
      if (name.compare(0, prefix.size(), prefix) != 0) {
        continue;
      }
      const std::string_view rest = std::string_view(name).substr(prefix.size());
      long pid = 0;
      const auto [end_of_pid, status] = std::from_chars(rest.data(), rest.data() + rest.size(), pid);
      if (status != std::errc() || end_of_pid == rest.data() || end_of_pid == rest.data() + rest.size() ||
          *end_of_pid != '.' || pid <= 0 || pid == ::getpid()) {
        continue;
      }
      if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
        stale.push_back(entry->path());
      }
    }
    for (const fs::path& path : stale) {
      fs::remove(path, error);
    }
  } catch (...) {
  }
}

// ---- Identities of the open outputs -------------------------------------------------------------

struct Identity {
  dev_t device = 0;
  ino_t inode = 0;
  std::string name;  // empty for an existing file; the file name for a new one (then the directory's ids)
  std::string option;
  bool used = false;
};
std::mutex identities_mutex;
std::vector<Identity> identities;

constexpr std::size_t no_identity = static_cast<std::size_t>(-1);

// Records the identity; refuses it if another open output has it.
std::size_t claim_identity(Identity identity, std::string_view option, const std::string& path) {
  std::lock_guard<std::mutex> lock(identities_mutex);
  for (const Identity& other : identities) {
    if (other.used && other.device == identity.device && other.inode == identity.inode && other.name == identity.name) {
      const std::string other_option = other.option.empty() ? "another output" : other.option;
      refuse(option, path, "the same file as " + other_option + " (allowed: a different file)");
    }
  }
  identity.option = std::string(option);
  identity.used = true;
  for (std::size_t slot = 0; slot < identities.size(); ++slot) {
    if (!identities[slot].used) {
      identities[slot] = identity;
      return slot;
    }
  }
  identities.push_back(identity);
  return identities.size() - 1;
}

void release_identity(std::size_t slot) noexcept {
  if (slot == no_identity) {
    return;
  }
  std::lock_guard<std::mutex> lock(identities_mutex);
  if (slot < identities.size()) {
    identities[slot].used = false;
  }
}

bool same_object(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

// The standard descriptor (1 or 2) whose file is `object`, or -1.
int standard_descriptor_of(const struct stat& object) {
  for (const int descriptor : {1, 2}) {
    struct stat open_file {};
    if (::fstat(descriptor, &open_file) == 0 && same_object(open_file, object)) {
      return descriptor;
    }
  }
  return -1;
}

mode_t current_umask() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return mask;
}

bool standard_output_closed = false;

}  // namespace

// ---- The stream buffer ----------------------------------------------------------------------------

DescriptorBuffer::DescriptorBuffer(int descriptor) : descriptor_(descriptor), buffer_(1 << 16) {
  setp(buffer_.data(), buffer_.data() + buffer_.size());
}

void DescriptorBuffer::reset(int descriptor) {
  descriptor_ = descriptor;
  error_ = 0;
  setp(buffer_.data(), buffer_.data() + buffer_.size());
}

bool DescriptorBuffer::drain() {
  const char* data = pbase();
  std::size_t size = static_cast<std::size_t>(pptr() - pbase());
  while (size > 0 && error_ == 0) {
    const ssize_t written = ::write(descriptor_, data, size);
    if (written < 0) {
      if (errno == EINTR) {
        continue;
      }
      error_ = errno;
    } else if (written == 0) {
      error_ = EIO;
    } else {
      data += written;
      size -= static_cast<std::size_t>(written);
    }
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  return error_ == 0;
}

DescriptorBuffer::int_type DescriptorBuffer::overflow(int_type character) {
  if (!drain()) {
    return traits_type::eof();
  }
  if (!traits_type::eq_int_type(character, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(character);
    pbump(1);
  }
  return traits_type::not_eof(character);
}

int DescriptorBuffer::sync() { return drain() ? 0 : -1; }

// ---- Opening ---------------------------------------------------------------------------------------

AtomicFile::AtomicFile(std::string path, std::string_view option)
    : path_(std::move(path)),
      option_(option),
      stream_(&buffer_),
      pending_slot_(max_pending),
      identity_slot_(no_identity) {
  namespace fs = std::filesystem;
  if (path_.empty()) {
    refuse_errno(option, path_, ENOENT);
  }
  const fs::path target(path_);
  if (!target.has_filename()) {
    refuse_errno(option, path_, EISDIR);
  }
  const std::string allowed =
      " (allowed: a regular file, a new file, a character device, a FIFO, or the standard output)";
  struct stat link {};
  if (::lstat(path_.c_str(), &link) != 0) {
    if (errno != ENOENT) {
      refuse_errno(option, path_, errno);
    }
    open_temporary(option);
    return;
  }
  struct stat object = link;
  if (S_ISLNK(link.st_mode)) {
    if (::stat(path_.c_str(), &object) != 0) {
      refuse(option, path_, "a symbolic link to a missing file" + allowed);
    }
    const int standard = standard_descriptor_of(object);
    if (standard >= 0) {
      const int descriptor = ::fcntl(standard, F_DUPFD_CLOEXEC, 3);
      if (descriptor < 0) {
        refuse_errno(option, path_, errno);
      }
      open_in_place(descriptor);
      return;
    }
    if (!S_ISCHR(object.st_mode) && !S_ISFIFO(object.st_mode)) {
      refuse(option, path_, "a symbolic link (it is never followed nor replaced)" + allowed);
    }
  }
  if (S_ISDIR(object.st_mode)) {
    refuse_errno(option, path_, EISDIR);
  }
  if (S_ISSOCK(object.st_mode)) {
    refuse(option, path_, "a socket" + allowed);
  }
  if (S_ISBLK(object.st_mode)) {
    refuse(option, path_, "a block device" + allowed);
  }
  if (S_ISREG(object.st_mode)) {
    if (const int standard = standard_descriptor_of(object); standard >= 0) {
      refuse(option, path_,
             std::string("the file open on the standard ") + (standard == 1 ? "output" : "error") +
                 " (allowed: a different file)");
    }
    open_temporary(option);
    return;
  }
  // A character device or a FIFO: opened in place, never created nor truncated; a FIFO without
  // blocking (no reader: ENXIO), then switched back to blocking writes.
  const bool fifo = S_ISFIFO(object.st_mode);
  const int descriptor = ::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | (fifo ? O_NONBLOCK : 0));
  if (descriptor < 0) {
    if (fifo && errno == ENXIO) {
      refuse(option, path_, "a FIFO that no process reads (start its reader first)");
    }
    refuse_errno(option, path_, errno);
  }
  struct stat opened {};
  if (::fstat(descriptor, &opened) != 0 || !same_object(opened, object)) {
    ::close(descriptor);
    refuse(option, path_, "it changed while it was being opened");
  }
  if (fifo) {
    ::fcntl(descriptor, F_SETFL, ::fcntl(descriptor, F_GETFL) & ~O_NONBLOCK);
    try {
      identity_slot_ = claim_identity({opened.st_dev, opened.st_ino, "", "", false}, option, path_);
    } catch (...) {
      ::close(descriptor);
      throw;
    }
  }
  open_in_place(descriptor);
}

void AtomicFile::open_in_place(int descriptor) {
  descriptor_ = descriptor;
  buffer_.reset(descriptor);
}

void AtomicFile::open_temporary(std::string_view option) {
  namespace fs = std::filesystem;
  const fs::path target(path_);
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string name = target.filename().string();
  // The identity: an existing file's own, or the directory's and the name for a new one.
  struct stat existing {};
  if (::stat(path_.c_str(), &existing) == 0) {
    identity_slot_ = claim_identity({existing.st_dev, existing.st_ino, "", "", false}, option, path_);
  } else {
    struct stat folder {};
    if (::stat(directory.c_str(), &folder) != 0) {
      refuse_errno(option, path_, errno);
    }
    if (!S_ISDIR(folder.st_mode)) {
      refuse_errno(option, path_, ENOTDIR);
    }
    identity_slot_ = claim_identity({folder.st_dev, folder.st_ino, name, "", false}, option, path_);
  }
  const std::string prefix = temporary_prefix(directory, name);
  for (int attempt = 0; attempt < 100 && descriptor_ < 0; ++attempt) {
    const std::string candidate =
        (directory / (prefix + std::to_string(::getpid()) + "." + random_characters(random_length))).string();
    const int descriptor = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (descriptor >= 0) {
      temporary_path_ = candidate;
      descriptor_ = descriptor;
    } else if (errno != EEXIST) {
      const int error_number = errno;
      release_identity(identity_slot_);
      identity_slot_ = no_identity;
      refuse_errno(option, path_, error_number);
    }
  }
  if (descriptor_ < 0) {
    release_identity(identity_slot_);
    identity_slot_ = no_identity;
    refuse(option, path_, "no free temporary name in its directory");
  }
  pending_slot_ = register_pending(temporary_path_);
  remove_stale_temporaries(directory, prefix);
  buffer_.reset(descriptor_);
}

// ---- Committing ------------------------------------------------------------------------------------

// Finishing: everything buffered is written out and checked, a temporary file gets the mode of a
// new file and is closed (close can report a delayed write error, as on NFS). Throws on failure,
// leaving the cleaning to discard().
void AtomicFile::finish_writing() {
  if (finished_) {
    throw std::logic_error("AtomicFile: " + json_string(path_) + " is already committed");
  }
  stream_.flush();
  const bool written = buffer_.drain() && !stream_.fail();
  if (!written) {
    throw std::runtime_error(
        "cannot write " + json_string(path_) + ": " +
        (buffer_.error() != 0 ? std::strerror(buffer_.error()) : "writing the data failed (is the disk full?)"));
  }
  if (!in_place()) {
    ::fchmod(descriptor_, 0666 & ~current_umask());
  }
  const int descriptor = descriptor_;
  descriptor_ = -1;
  if (::close(descriptor) != 0 && errno != EINTR) {
    throw std::runtime_error("cannot write " + json_string(path_) + ": " + std::strerror(errno));
  }
}

void AtomicFile::discard() noexcept {
  finished_ = true;
  if (descriptor_ >= 0) {
    ::close(descriptor_);
    descriptor_ = -1;
  }
  if (!temporary_path_.empty()) {
    ::unlink(temporary_path_.c_str());
  }
  withdraw_pending(pending_slot_);
  pending_slot_ = max_pending;
  release_identity(identity_slot_);
  identity_slot_ = no_identity;
}

AtomicFile::~AtomicFile() {
  if (!finished_) {
    discard();
  }
}

void AtomicFile::commit() { commit_all({this}); }

void commit_all(const std::vector<AtomicFile*>& given) {
  std::vector<AtomicFile*> files;
  std::copy_if(given.begin(), given.end(), std::back_inserter(files), [](AtomicFile* file) { return file; });
  const auto discard_all = [&] {
    for (AtomicFile* file : files) {
      if (!file->finished_) {
        file->discard();
      }
    }
  };
  for (AtomicFile* file : files) {
    if (file->finished_) {
      throw std::logic_error("AtomicFile: " + json_string(file->path_) + " is already committed");
    }
  }
  // 1. The standard streams: what the program printed is part of what it delivers.
  std::cout.flush();
  if (!std::cout) {
    discard_all();
    throw std::runtime_error(standard_output_closed ? "writing the standard output failed: it is closed"
                                                    : "writing the standard output failed");
  }
  if (!std::cerr) {
    discard_all();
    throw std::runtime_error("writing the standard error failed");
  }
  // 2. Every file written out, in place ones first (they cannot be taken back, so a failing
  // device stops the commit before any rename).
  std::vector<AtomicFile*> order(files);
  std::stable_partition(order.begin(), order.end(), [](AtomicFile* file) { return file->in_place(); });
  try {
    for (AtomicFile* file : order) {
      file->finish_writing();
    }
  } catch (...) {
    discard_all();
    throw;
  }
  // 3. The renames, each previous target kept under a hard link until all are done.
  struct Renamed {
    AtomicFile* file;
    std::string backup;
    bool had_target;
  };
  std::vector<Renamed> renamed;
  std::vector<std::size_t> backup_slots;
  const std::size_t renames = static_cast<std::size_t>(
      std::count_if(order.begin(), order.end(), [](AtomicFile* file) { return !file->in_place(); }));
  for (AtomicFile* file : order) {
    if (file->in_place()) {
      continue;
    }
    struct stat target {};
    const bool had_target = ::lstat(file->path_.c_str(), &target) == 0;
    std::string backup;
    if (renames > 1 && had_target && S_ISREG(target.st_mode)) {
      const std::string candidate = file->temporary_path_ + ".old";
      if (::link(file->path_.c_str(), candidate.c_str()) == 0) {
        backup = candidate;
        backup_slots.push_back(register_pending(backup));
      }
    }
    if (::rename(file->temporary_path_.c_str(), file->path_.c_str()) != 0) {
      const int error_number = errno;
      if (!backup.empty()) {
        ::unlink(backup.c_str());
      }
      // Put the earlier targets back, newest first.
      for (auto done = renamed.rbegin(); done != renamed.rend(); ++done) {
        if (!done->backup.empty()) {
          ::rename(done->backup.c_str(), done->file->path_.c_str());
        } else if (!done->had_target) {
          ::unlink(done->file->path_.c_str());
        }
      }
      for (const std::size_t slot : backup_slots) {
        withdraw_pending(slot);
      }
      discard_all();
      throw std::runtime_error("cannot write " + json_string(file->path_) + ": renaming " +
                               json_string(file->temporary_path_) + " failed: " + std::strerror(error_number));
    }
    renamed.push_back({file, backup, had_target});
    withdraw_pending(file->pending_slot_);
    file->pending_slot_ = max_pending;
  }
  for (const Renamed& done : renamed) {
    if (!done.backup.empty()) {
      ::unlink(done.backup.c_str());
    }
  }
  for (const std::size_t slot : backup_slots) {
    withdraw_pending(slot);
  }
  for (AtomicFile* file : files) {
    file->finished_ = true;
    release_identity(file->identity_slot_);
    file->identity_slot_ = no_identity;
  }
}

// ---- Standard descriptors ----------------------------------------------------------------------------

bool prepare_standard_descriptors() noexcept {
  for (int descriptor = 0; descriptor <= 2; ++descriptor) {
    if (::fcntl(descriptor, F_GETFD) != -1 || errno != EBADF) {
      continue;
    }
    // The lowest free descriptor is this one: the lower ones are open by now.
    int opened = ::open("/dev/null", (descriptor == 2 ? O_WRONLY : O_RDONLY) | O_NOCTTY);
    if (opened < 0) {
      opened = ::open("/", O_RDONLY | O_DIRECTORY);
    }
    if (opened >= 0 && opened != descriptor) {
      ::dup2(opened, descriptor);
      ::close(opened);
    }
    if (descriptor == 1) {
      standard_output_closed = true;
    }
  }
  return standard_output_closed;
}

// ---- Memory -----------------------------------------------------------------------------------------

double available_memory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  double available = pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size) : 1e300;
  // The room left under the limits: the limit minus what the process already uses (its virtual
  // size for RLIMIT_AS; the same, a safe overestimate of the data segment, for RLIMIT_DATA).
  double used = 0;
  {
    std::ifstream statm("/proc/self/statm");
    double size_pages = 0;
    if (statm >> size_pages && page_size > 0) {
      used = size_pages * static_cast<double>(page_size);
    }
  }
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit limit {};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
      available = std::min(available, static_cast<double>(limit.rlim_cur) - used);
    }
  }
  return std::max(available, 0.0);
}

namespace {
std::string bytes_text(double bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  std::size_t unit = 0;
  while (bytes >= 1000 && unit + 1 < std::size(units)) {
    bytes /= 1000;
    ++unit;
  }
  char text[64];
  std::snprintf(text, sizeof text, "%.3g %s", bytes, units[unit]);
  return text;
}
}  // namespace

void require_memory(std::string_view option, std::string_view what, double bytes) {
  const double available = available_memory();
  if (!(bytes <= available)) {
    throw UsageError(std::string(option) + ": " + std::string(what) + " need about " + bytes_text(bytes) +
                     " of memory, more than the " + bytes_text(available) +
                     " this process may use (allowed: runs that fit in memory)");
  }
}

// ---- Doctests ------------------------------------------------------------------------------------------

namespace {

class Scratch {
 public:
  Scratch()
      : path_(std::filesystem::temp_directory_path() /
              ("mrm_output_test." + std::to_string(::getpid()) + "." + random_characters(6))) {
    std::filesystem::create_directory(path_);
  }
  ~Scratch() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  std::string file(std::string_view name) const { return (path_ / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }
  static std::string content(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
  }
  static void write(const std::string& path, std::string_view text) { std::ofstream(path, std::ios::binary) << text; }

 private:
  std::filesystem::path path_;
};

}  // namespace

TEST_CASE("a committed AtomicFile replaces the target with the complete content and the umask's mode") {
  Scratch directory;
  const std::string target = directory.file("results.dat");
  SUBCASE("new target") {}
  SUBCASE("existing target") { Scratch::write(target, "old content\n"); }
  AtomicFile file(target, "--output");
  CHECK(std::filesystem::path(file.temporary_path()).parent_path() == std::filesystem::path(target).parent_path());
  const std::string name = std::filesystem::path(file.temporary_path()).filename().string();
  const std::string prefix = ".results.dat.tmp." + std::to_string(::getpid()) + ".";
  CHECK(name.rfind(prefix, 0) == 0);
  CHECK(name.size() == prefix.size() + random_length);
  struct stat written {};
  REQUIRE(::stat(file.temporary_path().c_str(), &written) == 0);
  CHECK((written.st_mode & 0777) == 0600);
  file.stream() << "# elements = 4\n1 2\n";
  file.commit();
  CHECK(Scratch::content(target) == "# elements = 4\n1 2\n");
  CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
  struct stat committed {};
  REQUIRE(::stat(target.c_str(), &committed) == 0);
  CHECK((committed.st_mode & 0777) == (0666 & ~current_umask()));
  CHECK_THROWS_AS(file.commit(), std::logic_error);
}

TEST_CASE("two temporary names for the same target differ in their random part") {
  Scratch directory;
  AtomicFile first(directory.file("a.dat"), "--output"), second(directory.file("b.dat"), "--tex");
  const std::string a = std::filesystem::path(first.temporary_path()).filename().string();
  const std::string b = std::filesystem::path(second.temporary_path()).filename().string();
  CHECK(a.substr(a.size() - random_length) != b.substr(b.size() - random_length));
}

TEST_CASE("an AtomicFile destroyed without commit leaves no file and the old target intact") {
  Scratch directory;
  const std::string target = directory.file("results.dat");
  Scratch::write(target, "old content\n");
  {
    AtomicFile file(target);
    file.stream() << "half of the data";
  }
  CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
  CHECK(Scratch::content(target) == "old content\n");
}

TEST_CASE("a planted link or file at a temporary name is never used") {
  // Names of the old scheme (pid and counter) and a link under every name of a guessed shape: the
  // creation is exclusive and does not follow links, so none of them is written.
  Scratch directory;
  const std::string victim = directory.file("victim");
  Scratch::write(victim, "victim\n");
  const std::string pid = std::to_string(::getpid());
  for (int n = 0; n < 4; ++n) {
    std::filesystem::create_symlink(victim, directory.file(".out.dat.tmp." + pid + "." + std::to_string(n)));
  }
  AtomicFile file(directory.file("out.dat"), "--output");
  file.stream() << "data\n";
  file.commit();
  CHECK(Scratch::content(victim) == "victim\n");
  CHECK(Scratch::content(directory.file("out.dat")) == "data\n");
  CHECK(std::filesystem::is_symlink(directory.file("out.dat")) == false);
  CHECK(directory.entries().size() == 6);
}

TEST_CASE("a name of NAME_MAX characters gets a temporary name that fits") {
  Scratch directory;
  for (const std::size_t length : {244u, 250u, 255u}) {
    CAPTURE(length);
    const std::string name(length, 'x');
    AtomicFile file(directory.file(name), "--output");
    CHECK(std::filesystem::path(file.temporary_path()).filename().string().size() <= 255);
    file.stream() << "data\n";
    file.commit();
    CHECK(Scratch::content(directory.file(name)) == "data\n");
  }
  // A name cut inside a UTF-8 character is cut before it.
  const std::string accented = std::string(240, 'a') + "\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9";
  CHECK(shortened(accented, 241) == std::string(240, 'a'));
  CHECK(shortened(accented, 242) == std::string(240, 'a') + "\xc3\xa9");
  CHECK_THROWS_WITH_AS(AtomicFile(directory.file(std::string(256, 'x')), "--output"),
                       doctest::Contains("File name too long"), UsageError);
}

TEST_CASE("targets that are not regular files: devices and FIFOs in place, the rest refused") {
  Scratch directory;
  SUBCASE("/dev/null is written in place and stays the device") {
    AtomicFile file("/dev/null", "--output");
    CHECK(file.in_place());
    file.stream() << "discarded\n";
    file.commit();
    struct stat null_device {};
    REQUIRE(::stat("/dev/null", &null_device) == 0);
    CHECK(S_ISCHR(null_device.st_mode));
  }
  SUBCASE("/dev/full fails at the commit, naming the device") {
    AtomicFile file("/dev/full", "--output");
    file.stream() << "data\n";
    CHECK_THROWS_WITH_AS(file.commit(), "cannot write \"/dev/full\": No space left on device", std::runtime_error);
  }
  SUBCASE("a FIFO without a reader is refused at once") {
    const std::string fifo = directory.file("fifo");
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    CHECK_THROWS_WITH_AS(AtomicFile(fifo, "--output"), doctest::Contains("a FIFO that no process reads"), UsageError);
  }
  SUBCASE("a FIFO with a reader gets the data") {
    const std::string fifo = directory.file("fifo");
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    REQUIRE(reader >= 0);
    {
      AtomicFile file(fifo, "--output");
      file.stream() << "through the FIFO\n";
      file.commit();
    }
    char received[64] = {};
    CHECK(::read(reader, received, sizeof received - 1) == 17);
    CHECK(std::string(received) == "through the FIFO\n");
    ::close(reader);
    CHECK(directory.entries() == std::vector<std::string>{"fifo"});
  }
  SUBCASE("a directory, a socket, a symbolic link to a regular or missing file are refused") {
    std::filesystem::create_directory(directory.file("sub"));
    CHECK_THROWS_WITH_AS(AtomicFile(directory.file("sub"), "--output"), doctest::Contains("Is a directory"),
                         UsageError);
    const std::string socket_path = directory.file("sock");
    const int socket_descriptor = ::socket(AF_UNIX, SOCK_STREAM, 0);
    REQUIRE(socket_descriptor >= 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::snprintf(address.sun_path, sizeof address.sun_path, "%s", socket_path.c_str());
    REQUIRE(::bind(socket_descriptor, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
    CHECK_THROWS_WITH_AS(AtomicFile(socket_path, "--output"), doctest::Contains("a socket"), UsageError);
    ::close(socket_descriptor);
    Scratch::write(directory.file("real.dat"), "old\n");
    std::filesystem::create_symlink("real.dat", directory.file("link.dat"));
    CHECK_THROWS_WITH_AS(AtomicFile(directory.file("link.dat"), "--output"),
                         doctest::Contains("a symbolic link (it is never followed nor replaced)"), UsageError);
    std::filesystem::create_symlink("missing.dat", directory.file("dangling.dat"));
    CHECK_THROWS_WITH_AS(AtomicFile(directory.file("dangling.dat"), "--output"),
                         doctest::Contains("a symbolic link to a missing file"), UsageError);
    CHECK(Scratch::content(directory.file("real.dat")) == "old\n");
    CHECK(std::filesystem::is_symlink(directory.file("link.dat")));
  }
}

TEST_CASE("two outputs naming the same file are refused, naming both options") {
  Scratch directory;
  std::filesystem::create_directory(directory.file("sub"));
  const std::string target = directory.file("out.dat");
  SUBCASE("a new file under two spellings") {
    AtomicFile first(target, "--output");
    const std::string second = directory.file("sub/../out.dat");
    CHECK_THROWS_WITH_AS(
        AtomicFile(second, "--tex"),
        ("--tex: cannot write " + json_string(second) + ": the same file as --output (allowed: a different file)")
            .c_str(),
        UsageError);
  }
  SUBCASE("an existing file and its hard link") {
    Scratch::write(target, "old\n");
    std::filesystem::create_hard_link(target, directory.file("other.dat"));
    AtomicFile first(target, "--output");
    CHECK_THROWS_WITH_AS(AtomicFile(directory.file("other.dat"), "--tex"),
                         doctest::Contains("the same file as --output"), UsageError);
  }
  SUBCASE("once the first is committed, the name is free again") {
    {
      AtomicFile first(target, "--output");
      first.commit();
    }
    CHECK_NOTHROW(AtomicFile(target, "--tex"));
  }
  SUBCASE("a character device twice is allowed") {
    AtomicFile first("/dev/null", "--output");
    CHECK_NOTHROW(AtomicFile("/dev/null", "--tex"));
  }
}

TEST_CASE("commit_all replaces every target or none") {
  Scratch directory;
  const std::string a = directory.file("a.dat"), b = directory.file("b.dat");
  Scratch::write(a, "old a\n");
  Scratch::write(b, "old b\n");
  SUBCASE("both") {
    AtomicFile first(a, "--output"), second(b, "--tex");
    first.stream() << "new a\n";
    second.stream() << "new b\n";
    commit_all({&first, &second});
    CHECK(Scratch::content(a) == "new a\n");
    CHECK(Scratch::content(b) == "new b\n");
    CHECK(directory.entries() == std::vector<std::string>{"a.dat", "b.dat"});
  }
  SUBCASE("the second fails to write: the first keeps its old content") {
    AtomicFile first(a, "--output"), second(b, "--tex");
    first.stream() << "new a\n";
    second.stream() << "new b\n";
    second.stream().setstate(std::ios::badbit);
    CHECK_THROWS_AS(commit_all({&first, &second}), std::runtime_error);
    CHECK(Scratch::content(a) == "old a\n");
    CHECK(Scratch::content(b) == "old b\n");
    CHECK(directory.entries() == std::vector<std::string>{"a.dat", "b.dat"});
  }
  SUBCASE("a device that fails: nothing renamed") {
    AtomicFile first(a, "--output"), second("/dev/full", "--tex");
    first.stream() << "new a\n";
    second.stream() << "new b\n";
    CHECK_THROWS_WITH_AS(commit_all({&first, &second}), doctest::Contains("/dev/full"), std::runtime_error);
    CHECK(Scratch::content(a) == "old a\n");
    CHECK(directory.entries() == std::vector<std::string>{"a.dat", "b.dat"});
  }
  SUBCASE("the second rename fails: the first is put back") {
    AtomicFile first(a, "--output"), second(b, "--tex");
    first.stream() << "new a\n";
    second.stream() << "new b\n";
    // b.dat becomes a non-empty directory meanwhile: its rename fails.
    std::filesystem::remove(b);
    std::filesystem::create_directory(b);
    Scratch::write(b + "/inside", "x");
    CHECK_THROWS_WITH_AS(commit_all({&first, &second}), doctest::Contains("renaming"), std::runtime_error);
    CHECK(Scratch::content(a) == "old a\n");
    CHECK(directory.entries() == std::vector<std::string>{"a.dat", "b.dat"});
  }
  SUBCASE("standard output failed: nothing committed") {
    AtomicFile first(a, "--output");
    first.stream() << "new a\n";
    const std::ios::iostate state = std::cout.rdstate();
    std::cout.setstate(std::ios::badbit);
    CHECK_THROWS_WITH_AS(first.commit(), doctest::Contains("standard output"), std::runtime_error);
    std::cout.clear(state);
    CHECK(Scratch::content(a) == "old a\n");
    CHECK(directory.entries() == std::vector<std::string>{"a.dat", "b.dat"});
  }
}

TEST_CASE("closed standard descriptors are reopened so that no output takes their place") {
  // In a child: close 0, 1 and 2, prepare, open an output: it must not get descriptor 0, 1 or 2,
  // and writing to the standard output must fail.
  std::cout.flush();
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::close(0);
    ::close(1);
    ::close(2);
    const bool closed = prepare_standard_descriptors();
    const int probe = ::open("/dev/null", O_RDONLY);
    const bool above = probe > 2;
    const bool write_fails = ::write(1, "x", 1) < 0;
    const bool error_works = ::write(2, "x", 1) == 1;
    ::_exit(closed && above && write_fails && error_works ? 0 : 1);
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
}

TEST_CASE("the memory a run needs is compared with what the process may use") {
  CHECK(available_memory() > 1e6);
  CHECK_NOTHROW(require_memory("--elements", "10 elements", 1e3));
  CHECK_THROWS_WITH_AS(require_memory("--elements", "1e20 elements", 1e30),
                       doctest::Contains("--elements: 1e20 elements need about 1e+12 EB of memory"), UsageError);
}

TEST_CASE("a failed write makes the commit throw and leaves the old target intact") {
  Scratch directory;
  const std::string target = directory.file("results.dat");
  Scratch::write(target, "old content\n");
  AtomicFile file(target, "--output");
  file.stream() << "new content\n";
  file.stream().setstate(std::ios::badbit);
  CHECK_THROWS_WITH_AS(
      file.commit(), ("cannot write " + json_string(target) + ": writing the data failed (is the disk full?)").c_str(),
      std::runtime_error);
  CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
  CHECK(Scratch::content(target) == "old content\n");
}

TEST_CASE("an unwritable output path is refused at once with the option's name and the reason") {
  Scratch directory;
  SUBCASE("missing directory") {
    const std::string path = directory.file("missing/x.dat");
    CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                         ("--output: cannot write " + json_string(path) + ": No such file or directory").c_str(),
                         UsageError);
  }
  SUBCASE("path is a directory") {
    const std::string path = directory.file("");
    CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                         ("--output: cannot write " + json_string(path) + ": Is a directory").c_str(), UsageError);
    const std::string without_slash = directory.file(".");
    CHECK_THROWS_WITH_AS(AtomicFile(without_slash, "--output"), doctest::Contains(": Is a directory"), UsageError);
  }
  SUBCASE("parent is a file") {
    Scratch::write(directory.file("plain"), "");
    const std::string path = directory.file("plain/x.dat");
    CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                         ("--output: cannot write " + json_string(path) + ": Not a directory").c_str(), UsageError);
  }
  SUBCASE("empty path") {
    CHECK_THROWS_WITH_AS(AtomicFile("", "--output"), "--output: cannot write \"\": No such file or directory",
                         UsageError);
  }
  SUBCASE("directory without write permission") {
    std::filesystem::permissions(directory.file(""),
                                 std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    if (::geteuid() == 0) {
      MESSAGE("skipped: permissions do not apply to root");
    } else {
      const std::string path = directory.file("x.dat");
      CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                           ("--output: cannot write " + json_string(path) + ": Permission denied").c_str(), UsageError);
    }
    std::filesystem::permissions(directory.file(""), std::filesystem::perms::owner_all);
  }
  SUBCASE("a path not given by an option") {
    const std::string path = directory.file("missing/x.dat");
    CHECK_THROWS_WITH_AS(AtomicFile{path},
                         ("cannot write " + json_string(path) + ": No such file or directory").c_str(),
                         std::runtime_error);
    bool usage_error = false;
    try {
      AtomicFile file(path);
    } catch (const UsageError&) {
      usage_error = true;
    } catch (const std::runtime_error&) {
    }
    CHECK_FALSE(usage_error);
  }
  for (const std::string& name : directory.entries()) {
    CAPTURE(name);
    CHECK(name.rfind(".", 0) != 0);
  }
}

// The signal handler is checked in a child process, which creates an AtomicFile over an existing
// target, writes part of its data and is then stopped by the signal, as a run interrupted by the
// user or the system would be. The parent checks how the child ended and what is left on disk.
TEST_CASE("a run ended by any terminating signal leaves the old target intact and no temporary file") {
  for (const int signal_number : {SIGTERM, SIGINT, SIGHUP, SIGPIPE, SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGVTALRM,
                                  SIGPROF, SIGSYS, SIGRTMIN + 3, SIGRTMAX}) {
    CAPTURE(signal_number);
    Scratch directory;
    const std::string target = directory.file("results.dat");
    Scratch::write(target, "old content\n");
    std::cout.flush();
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      // The child inherits the test runner's handlers; the test is about a program that
      // left the default action.
      ::signal(signal_number, SIG_DFL);
      {
        AtomicFile file(target, "--output");
        file.stream() << "half of the new data" << std::flush;
        ::raise(signal_number);
      }
      ::_exit(0);  // not reached if the handler ended the process
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == signal_number);
    CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
    CHECK(Scratch::content(target) == "old content\n");
  }
}

TEST_CASE("a temporary file left by a process that no longer exists is removed on the next write") {
  Scratch directory;
  const std::string target = directory.file("results.dat");
  Scratch::write(target, "old content\n");
  // A pid that no longer exists: a child that has ended and has been waited for.
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::_exit(0);
  }
  REQUIRE(::waitpid(child, nullptr, 0) == child);
  const std::string stale = ".results.dat.tmp." + std::to_string(child) + ".0";
  const std::string live = ".results.dat.tmp." + std::to_string(::getppid()) + ".0";
  const std::string other = ".other.dat.tmp." + std::to_string(child) + ".0";
  for (const std::string& name : {stale, live, other}) {
    Scratch::write(directory.file(name), "left over");
  }
  AtomicFile file(target, "--output");
  file.stream() << "new content\n";
  file.commit();
  std::vector<std::string> expected{live, other, "results.dat"};
  std::sort(expected.begin(), expected.end());
  CHECK(directory.entries() == expected);
  CHECK(Scratch::content(target) == "new content\n");
}

TEST_SUITE_END();

}  // namespace mrm::cli
