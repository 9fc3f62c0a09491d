// Output files and standard descriptors: the promises of output_file.hpp, and how each is kept.
//
// Complete or absent. rename(2) replaces a name atomically within one file system, so the data go to
// a temporary file in the target's own directory, renamed over the target once written out, closed
// (close can report a delayed write error) and checked. Until then the target is untouched; a failure
// removes the temporary (the destructor, on any exception). A process killed by a signal runs no
// destructor: its temporary stays, hidden, and the target is untouched; nothing is done about it, as
// in `make`'s own recipes.
//
// The temporary's name is `.<target name>.tmp.<pid>.<n>`: hidden, and distinct between two runs
// writing the same target. It is created with O_CREAT|O_EXCL|O_NOFOLLOW: whatever already exists
// under that name (a file, a link, left by a killed run or put there by anyone) is neither followed
// nor reused; the next n is tried. The target name is cut to 200 bytes in it, so that any valid
// target name (up to NAME_MAX = 255 bytes) gets a valid temporary name.
//
// Permissions. The temporary is created with mode 0600 and, when complete, gets the permission bits
// of the file it replaces, or those a new file gets (0666 minus the umask).
//
// Standard descriptors. A program started with descriptor 1 closed would give that number to the first
// file it opens, and everything it prints would land in the data file: prepare_standard_descriptors
// opens the closed ones on /dev/null first (standard output read-only, so that printing fails and the
// run fails). commit_all checks both standard streams before any rename.
#include "output_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "options.hpp"

namespace mrm::cli {

TEST_SUITE_BEGIN("output files");

const char* const output_files_help =
    "Each FILE is written under a hidden temporary name in its directory and renamed over FILE only "
    "when complete: a failed run leaves FILE as it was, an interrupted one at most a hidden "
    ".FILE.tmp.* beside it. A replaced FILE keeps its permissions; a symbolic link to a file is "
    "followed. FILE - is the standard output. A FILE that exists and is not a regular file (a "
    "directory, a device) is refused.";

namespace {

// A refusal of an output path: a UsageError naming the option, or, for a path that does not come
// from an option, a plain runtime error.
[[noreturn]] void refuse(std::string_view option, const std::string& path, const std::string& reason) {
  const std::string message = "cannot write " + quoted_text(path) + ": " + reason;
  if (option.empty()) throw std::runtime_error(message);
  throw UsageError(std::string(option) + ": " + message);
}

mode_t current_umask() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return mask;
}

bool standard_output_closed = false;

}  // namespace

// ---- Non-finite values --------------------------------------------------------------------------------

const NonFiniteWatch* standard_output_watch = nullptr;

namespace {
bool non_finite_word(const std::string& word) {
  std::string lower = word;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == "nan" || lower == "inf" || lower == "infinity";
}
}  // namespace

void NonFiniteWatch::end_word() {
  if (found_line_ == 0 && non_finite_word(word_)) {
    found_line_ = line_;
    found_word_ = word_;
  }
  word_.clear();
}

bool NonFiniteWatch::found() const { return found_line_ > 0 || non_finite_word(word_); }

void NonFiniteWatch::scan(const char* data, std::size_t size) {
  for (std::size_t k = 0; k < size; ++k) {
    const char c = data[k];
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      if (word_.size() < 9)
        word_ += c;  // longer than "infinity": not one of the words
      else
        word_ = "#########";
      continue;
    }
    end_word();
    if (c == '\n') ++line_;
  }
}

std::string NonFiniteWatch::what() const {
  const bool pending = found_line_ == 0;  // the last word, not followed by anything
  return "line " + std::to_string(pending ? line_ : found_line_) + " holds " +
         json_string(pending ? word_ : found_word_) +
         ", a value that could not be computed (allowed: numbers, or words saying why a value is absent)";
}

WatchedBuffer::int_type WatchedBuffer::overflow(int_type character) {
  if (traits_type::eq_int_type(character, traits_type::eof())) return traits_type::not_eof(character);
  const char c = traits_type::to_char_type(character);
  watch_.scan(&c, 1);
  return target_->sputc(c);
}

std::streamsize WatchedBuffer::xsputn(const char* data, std::streamsize size) {
  watch_.scan(data, static_cast<std::size_t>(size));
  return target_->sputn(data, size);
}

int WatchedBuffer::sync() { return target_->pubsync(); }

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
  watch_.scan(data, size);
  while (size > 0 && error_ == 0) {
    const ssize_t written = ::write(descriptor_, data, size);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      error_ = written < 0 ? errno : EIO;
    } else {
      data += written;
      size -= static_cast<std::size_t>(written);
    }
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  return error_ == 0;
}

DescriptorBuffer::int_type DescriptorBuffer::overflow(int_type character) {
  if (!drain()) return traits_type::eof();
  if (!traits_type::eq_int_type(character, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(character);
    pbump(1);
  }
  return traits_type::not_eof(character);
}

int DescriptorBuffer::sync() { return drain() ? 0 : -1; }

// ---- Opening ---------------------------------------------------------------------------------------

AtomicFile::AtomicFile(std::string path, std::string_view option)
    : path_(std::move(path)), target_(path_), file_stream_(&buffer_), stream_(&file_stream_) {
  namespace fs = std::filesystem;
  if (path_ == "-") {
    stream_ = &std::cout;
    return;
  }
  if (path_.empty()) refuse(option, path_, std::strerror(ENOENT));
  struct stat existing {};
  if (::stat(path_.c_str(), &existing) == 0) {
    if (S_ISDIR(existing.st_mode)) refuse(option, path_, std::strerror(EISDIR));
    if (!S_ISREG(existing.st_mode))
      refuse(option, path_, "not a regular file (allowed: a regular file, a new file, -)");
    mode_ = static_cast<int>(existing.st_mode & 07777);
    std::error_code ignored;
    if (fs::is_symlink(path_, ignored)) target_ = fs::canonical(path_).string();
  } else if (errno != ENOENT) {
    refuse(option, path_, std::strerror(errno));
  }
  const fs::path target(target_);
  if (!target.has_filename()) refuse(option, path_, std::strerror(EISDIR));
  const std::string name = target.filename().string();
  if (name.size() > 255) refuse(option, path_, std::strerror(ENAMETOOLONG));
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = "." + name.substr(0, 200) + ".tmp." + std::to_string(::getpid()) + ".";
  for (int n = 0; descriptor_ < 0; ++n) {
    const std::string candidate = (directory / (prefix + std::to_string(n))).string();
    descriptor_ = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (descriptor_ >= 0) {
      temporary_path_ = candidate;
    } else if (errno != EEXIST || n == 999) {
      refuse(option, path_, std::strerror(errno));
    }
  }
  buffer_.reset(descriptor_);
}

// ---- Committing ------------------------------------------------------------------------------------

// Everything buffered written out and checked, the permission bits set, the file closed. Throws on
// failure, leaving the cleaning to discard().
void AtomicFile::finish_writing() {
  if (finished_) throw std::logic_error("AtomicFile: " + quoted_text(path_) + " is already committed");
  if (temporary_path_.empty()) return;  // `-`: checked with the standard output
  file_stream_.flush();
  if (!buffer_.drain() || !file_stream_) {
    throw std::runtime_error(
        "cannot write " + quoted_text(path_) + ": " +
        (buffer_.error() != 0 ? std::strerror(buffer_.error()) : "writing the data failed (is the disk full?)"));
  }
  if (buffer_.watch().found())
    throw std::runtime_error("not writing " + quoted_text(path_) + ": " + buffer_.watch().what());
  ::fchmod(descriptor_, mode_ >= 0 ? static_cast<mode_t>(mode_) : 0666 & ~current_umask());
  const int descriptor = descriptor_;
  descriptor_ = -1;
  if (::close(descriptor) != 0 && errno != EINTR) {
    throw std::runtime_error("cannot write " + quoted_text(path_) + ": " + std::strerror(errno));
  }
}

void AtomicFile::discard() noexcept {
  finished_ = true;
  if (descriptor_ >= 0) ::close(descriptor_);
  descriptor_ = -1;
  if (!temporary_path_.empty()) ::unlink(temporary_path_.c_str());
}

AtomicFile::~AtomicFile() {
  if (!finished_) discard();
}

void AtomicFile::commit() { commit_all({this}); }

void commit_all(const std::vector<AtomicFile*>& given) {
  std::vector<AtomicFile*> files;
  std::copy_if(given.begin(), given.end(), std::back_inserter(files), [](AtomicFile* file) { return file; });
  const auto fail = [&](const std::string& message) {
    for (AtomicFile* file : files) {
      if (!file->finished_) file->discard();
    }
    throw std::runtime_error(message);
  };
  // 1. The standard streams: what the program printed is part of what it delivers.
  std::cout.flush();
  if (!std::cout) {
    fail(standard_output_closed ? "writing the standard output failed: it is closed"
                                : "writing the standard output failed");
  }
  if (!std::cerr) fail("writing the standard error failed");
  if (standard_output_watch != nullptr && standard_output_watch->found())
    fail("the standard output: " + standard_output_watch->what());
  // 2. Every file written out and checked.
  for (AtomicFile* file : files) {
    try {
      file->finish_writing();
    } catch (const std::logic_error&) {
      throw;
    } catch (const std::exception& error) {
      fail(error.what());
    }
  }
  // 3. The renames.
  for (AtomicFile* file : files) {
    if (!file->temporary_path_.empty() && ::rename(file->temporary_path_.c_str(), file->target_.c_str()) != 0) {
      fail("cannot write " + quoted_text(file->path_) + ": " + std::strerror(errno));
    }
    file->finished_ = true;
  }
}

// ---- Input files ----------------------------------------------------------------------------------------

std::string input_file_problem(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return std::strerror(errno);
  if (S_ISREG(status.st_mode)) return "";
  if (S_ISDIR(status.st_mode)) return "is a directory, not a file";
  if (S_ISFIFO(status.st_mode)) return "is a FIFO or a pipe (a process substitution <(...) is one), not a regular file";
  if (S_ISCHR(status.st_mode)) return "is a character device, not a regular file";
  if (S_ISBLK(status.st_mode)) return "is a block device, not a regular file";
  if (S_ISSOCK(status.st_mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

// ---- Standard descriptors ----------------------------------------------------------------------------

bool prepare_standard_descriptors() noexcept {
  for (int descriptor = 0; descriptor <= 2; ++descriptor) {
    if (::fcntl(descriptor, F_GETFD) != -1 || errno != EBADF) continue;
    // The lowest free descriptor is this one: the lower ones are open by now.
    const int opened = ::open("/dev/null", (descriptor == 2 ? O_WRONLY : O_RDONLY) | O_NOCTTY);
    if (opened >= 0 && opened != descriptor) {
      ::dup2(opened, descriptor);
      ::close(opened);
    }
    if (descriptor == 1) standard_output_closed = true;
  }
  return standard_output_closed;
}

// ---- Doctests ------------------------------------------------------------------------------------------

namespace {

// A scratch directory, removed with everything in it.
class Scratch {
 public:
  Scratch() {
    std::string pattern = (std::filesystem::temp_directory_path() / "mrm_output_test.XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
  }
  ~Scratch() {
    std::error_code ignored;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ignored);
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
  static unsigned mode(const std::string& path) {
    struct stat status {};
    return ::stat(path.c_str(), &status) == 0 ? status.st_mode & 07777 : 0u;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace

TEST_CASE("a committed AtomicFile replaces the target with the complete content, written under a hidden name") {
  Scratch directory;
  const std::string target = directory.file("results.dat");
  SUBCASE("new target") {}
  SUBCASE("existing target") { Scratch::write(target, "old content\n"); }
  AtomicFile file(target, "--output");
  CHECK(file.temporary_path() == directory.file(".results.dat.tmp." + std::to_string(::getpid()) + ".0"));
  file.stream() << "# elements = 4\n1 2\n";
  CHECK(Scratch::content(target) != "# elements = 4\n1 2\n");
  file.commit();
  CHECK(Scratch::content(target) == "# elements = 4\n1 2\n");
  CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
  CHECK_THROWS_AS(file.commit(), std::logic_error);
}

TEST_CASE("a new file gets the umask's permissions, a replaced file keeps its own") {
  Scratch directory;
  const std::string target = directory.file("results.dat");
  for (const unsigned old_mode : {0600u, 0640u, 0664u}) {
    CAPTURE(old_mode);
    Scratch::write(target, "old\n");
    std::filesystem::permissions(target, static_cast<std::filesystem::perms>(old_mode));
    AtomicFile file(target, "--output");
    file.stream() << "new\n";
    file.commit();
    CHECK(Scratch::mode(target) == old_mode);
  }
  AtomicFile fresh(directory.file("new.dat"), "--output");
  fresh.commit();
  CHECK(Scratch::mode(directory.file("new.dat")) == (0666 & ~current_umask()));
}

TEST_CASE("an AtomicFile destroyed without commit leaves no file and the old target intact") {
  Scratch directory;
  const std::string target = directory.file("results.dat");
  Scratch::write(target, "old content\n");
  {
    AtomicFile file(target);
    file.stream() << std::string(100000, 'x') << std::flush;  // more than the buffer: on disk already
  }
  CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
  CHECK(Scratch::content(target) == "old content\n");
}

TEST_CASE("a link or a file at a temporary name is never followed nor reused") {
  // A killed run's leftover and links under the first names the program would use: the creation is
  // exclusive and does not follow links, so none of them is written and the next name is used.
  Scratch directory;
  const std::string victim = directory.file("victim");
  Scratch::write(victim, "victim\n");
  const std::string prefix = ".out.dat.tmp." + std::to_string(::getpid()) + ".";
  Scratch::write(directory.file(prefix + "0"), "left by a killed run\n");
  for (int n = 1; n < 4; ++n) std::filesystem::create_symlink(victim, directory.file(prefix + std::to_string(n)));
  AtomicFile file(directory.file("out.dat"), "--output");
  CHECK(file.temporary_path() == directory.file(prefix + "4"));
  file.stream() << "data\n";
  file.commit();
  CHECK(Scratch::content(victim) == "victim\n");
  CHECK(Scratch::content(directory.file(prefix + "0")) == "left by a killed run\n");
  CHECK(Scratch::content(directory.file("out.dat")) == "data\n");
  CHECK(directory.entries().size() == 6);
}

TEST_CASE("a symbolic link to a file is followed: the file is replaced, the link stays") {
  Scratch directory;
  std::filesystem::create_directory(directory.file("elsewhere"));
  Scratch::write(directory.file("elsewhere/real.dat"), "old\n");
  std::filesystem::create_symlink("elsewhere/real.dat", directory.file("link.dat"));
  AtomicFile file(directory.file("link.dat"), "--output");
  file.stream() << "new\n";
  file.commit();
  CHECK(std::filesystem::is_symlink(directory.file("link.dat")));
  CHECK(Scratch::content(directory.file("elsewhere/real.dat")) == "new\n");
}

TEST_CASE("a name of NAME_MAX bytes gets a temporary name that fits") {
  Scratch directory;
  const std::string name(255, 'x');
  AtomicFile file(directory.file(name), "--output");
  file.stream() << "data\n";
  file.commit();
  CHECK(Scratch::content(directory.file(name)) == "data\n");
  CHECK_THROWS_WITH_AS(AtomicFile(directory.file(std::string(256, 'x')), "--output"),
                       doctest::Contains("File name too long"), UsageError);
}

TEST_CASE("- is the standard output: no file is made") {
  Scratch directory;
  const auto here = std::filesystem::current_path();
  std::filesystem::current_path(directory.file(""));
  {
    AtomicFile file("-", "--output");
    CHECK(&file.stream() == &std::cout);
    CHECK(file.temporary_path().empty());
    file.commit();
  }
  std::filesystem::current_path(here);
  CHECK(directory.entries().empty());
}

TEST_CASE("commit_all replaces every target or none") {
  Scratch directory;
  const std::string a = directory.file("a.dat"), b = directory.file("b.dat");
  Scratch::write(a, "old a\n");
  Scratch::write(b, "old b\n");
  AtomicFile first(a, "--output"), second(b, "--tex");
  first.stream() << "new a\n";
  second.stream() << "new b\n";
  SUBCASE("both") {
    commit_all({&first, nullptr, &second});
    CHECK(Scratch::content(a) == "new a\n");
    CHECK(Scratch::content(b) == "new b\n");
  }
  SUBCASE("the second fails to write: the first keeps its old content") {
    second.stream().setstate(std::ios::badbit);
    CHECK_THROWS_WITH_AS(commit_all({&first, &second}),
                         ("cannot write " + json_string(b) + ": writing the data failed (is the disk full?)").c_str(),
                         std::runtime_error);
    CHECK(Scratch::content(a) == "old a\n");
    CHECK(Scratch::content(b) == "old b\n");
  }
  SUBCASE("the standard output failed: nothing committed") {
    const std::ios::iostate state = std::cout.rdstate();
    std::cout.setstate(std::ios::badbit);
    CHECK_THROWS_WITH_AS(commit_all({&first, &second}), doctest::Contains("standard output"), std::runtime_error);
    std::cout.clear(state);
    CHECK(Scratch::content(a) == "old a\n");
  }
  CHECK(directory.entries() == std::vector<std::string>{"a.dat", "b.dat"});
}

TEST_CASE("a data file holding a non-finite value is not committed, and neither are the others") {
  Scratch directory;
  const std::string a = directory.file("a.dat"), b = directory.file("b.dat");
  Scratch::write(a, "old a\n");
  Scratch::write(b, "old b\n");
  int cases = 0;
  for (const std::string bad : {"nan", "-nan", "inf", "-inf", "NaN", "Infinity", "1 2 nan", "\\mrmdef{x}{nan}",
                                "# slope = inf\n", "x nan(0x1) y"}) {
    CAPTURE(bad);
    ++cases;
    AtomicFile first(a, "--output"), second(b, "--tex");
    first.stream() << "1 2\n" << std::string(100000, ' ') << "\n";  // the bad word after a drain
    second.stream() << "# header\n3 4\n" << bad;
    CHECK_THROWS_WITH_AS(commit_all({&first, &second}), doctest::Contains("line 3 holds"), std::runtime_error);
    CHECK(Scratch::content(a) == "old a\n");
    CHECK(Scratch::content(b) == "old b\n");
  }
  // Words that only contain the letters, numbers and "n/a" are data.
  for (const std::string good : {"err_u_LinfL2 = 0.5", "nanosecond info infinite", "n/a: fewer than two levels",
                                 "1e-300 -0 5e-324", "Linf_nan inf2 nan_"}) {
    CAPTURE(good);
    ++cases;
    AtomicFile file(a, "--output");
    file.stream() << good << '\n';
    CHECK_NOTHROW(file.commit());
    CHECK(Scratch::content(a) == good + "\n");
  }
  CHECK(cases == 15);
  NonFiniteWatch split;  // a word cut between two writes
  split.scan("1 n", 3);
  split.scan("an\n", 3);
  CHECK(split.found());
  CHECK(split.what() ==
        "line 1 holds \"nan\", a value that could not be computed (allowed: numbers, or words "
        "saying why a value is absent)");
}

TEST_CASE("an output that cannot be written is refused at once, naming the option and the reason") {
  Scratch directory;
  Scratch::write(directory.file("plain"), "");
  std::filesystem::create_directory(directory.file("sub"));
  const auto refused = [](const std::string& path, const std::string& reason) {
    CAPTURE(path);
    CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                         ("--output: cannot write " + json_string(path) + ": " + reason).c_str(), UsageError);
  };
  refused(directory.file("missing/x.dat"), "No such file or directory");
  refused(directory.file("sub"), "Is a directory");
  refused(directory.file("sub/"), "Is a directory");
  refused(directory.file("plain/x.dat"), "Not a directory");
  refused("", "No such file or directory");
  refused("/dev/null", "not a regular file (allowed: a regular file, a new file, -)");
  CHECK_THROWS_WITH_AS(AtomicFile{directory.file("missing/x.dat")}, doctest::Contains("cannot write"),
                       std::runtime_error);
  if (::geteuid() != 0) {
    std::filesystem::permissions(directory.file("sub"),
                                 std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    refused(directory.file("sub/x.dat"), "Permission denied");
  }
  CHECK(directory.entries() == std::vector<std::string>{"plain", "sub"});
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

TEST_SUITE_END();

}  // namespace mrm::cli
