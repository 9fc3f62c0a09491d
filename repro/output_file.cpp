// Atomic output files: every data file, table and report fragment of the project is written under a
// temporary name and renamed into place only when complete. See output_file.hpp for the interface.
#include "output_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "options.hpp"

namespace mrm::cli {

TEST_SUITE_BEGIN("output_file");

namespace {

// The reason for refusing an output path, as a UsageError naming the option, or, for a path that
// does not come from an option, as a plain runtime error.
[[noreturn]] void throw_cannot_write(std::string_view option, const std::string& path,
                                     int error_number) {
    const std::string message =
        "cannot write " + json_string(path) + ": " + std::strerror(error_number);
    if (option.empty()) {
        throw std::runtime_error(message);
    }
    throw UsageError(std::string(option) + ": " + message);
}

// Numbers the temporary files of one process, so that two AtomicFiles never share one.
std::atomic<unsigned long> temporary_file_count{0};

// Interrupted runs. A process ended by a signal runs no destructor, so an AtomicFile could not
// remove its temporary file. For the signals that end a process by default and that a user or a
// system sends to stop a run (SIGHUP, SIGINT, SIGQUIT, SIGTERM, and SIGPIPE, SIGXFSZ on a closed
// pipe or an exceeded file size), a handler removes the temporary files of the AtomicFiles not yet
// committed, then restores the default action and raises the signal again, so that the process
// ends exactly as it would have (same signal, same exit status for the shell). The handler must be
// async-signal-safe: it only reads a fixed table of paths prepared in advance, calls unlink(2) on
// them and raise(3). A slot holds a heap copy of the path, published and withdrawn by atomic
// exchange, so that the handler sees either a complete path or none. Each new AtomicFile installs
// the handler for the signals whose action is (still, or again) the default: a program that
// ignores a signal or handles it itself keeps its choice. SIGKILL cannot be caught: its temporary
// file stays, and the next AtomicFile for the same target removes it (remove_stale_temporaries).
constexpr std::size_t max_pending_temporaries = 64;
std::atomic<char*> pending_temporaries[max_pending_temporaries];
constexpr int cleanup_signals[] = {SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGXFSZ};

extern "C" void remove_pending_temporaries_and_reraise(int signal_number) {
    const int saved_errno = errno;
    for (std::atomic<char*>& slot : pending_temporaries) {
        if (const char* path = slot.load()) {
            ::unlink(path);
        }
    }
    ::signal(signal_number, SIG_DFL);  // already reset by SA_RESETHAND; stated for clarity
    ::raise(signal_number);            // delivered when the handler returns
    errno = saved_errno;
}

void install_cleanup_handlers() {
    for (const int signal_number : cleanup_signals) {
        struct sigaction current {};
        if (::sigaction(signal_number, nullptr, &current) != 0 ||
            (current.sa_flags & SA_SIGINFO) != 0 || current.sa_handler != SIG_DFL) {
            continue;
        }
        struct sigaction action {};
        action.sa_handler = remove_pending_temporaries_and_reraise;
        sigemptyset(&action.sa_mask);
        action.sa_flags = SA_RESETHAND;
        ::sigaction(signal_number, &action, nullptr);
    }
}

// Registers a temporary path with the handler; returns the slot, or max_pending_temporaries when
// the table is full (the file is then only removed by destructors, as without the handler).
std::size_t register_pending_temporary(const std::string& path) {
    install_cleanup_handlers();
    char* copy = ::strdup(path.c_str());
    if (copy == nullptr) {
        return max_pending_temporaries;
    }
    for (std::size_t slot = 0; slot < max_pending_temporaries; ++slot) {
        char* expected = nullptr;
        if (pending_temporaries[slot].compare_exchange_strong(expected, copy)) {
            return slot;
        }
    }
    std::free(copy);
    return max_pending_temporaries;
}

void withdraw_pending_temporary(std::size_t slot) noexcept {
    if (slot < max_pending_temporaries) {
        std::free(pending_temporaries[slot].exchange(nullptr));
    }
}

// Temporary files of the same target left by processes that no longer exist (killed by SIGKILL, or
// by a power cut) are removed when the target is written again. A temporary file of a live process
// (another run writing the same target at this moment) is left alone; its name carries its pid.
void remove_stale_temporaries(const std::filesystem::path& target) noexcept {
    try {
        namespace fs = std::filesystem;
        const std::string prefix = "." + target.filename().string() + ".tmp.";
        const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
        std::error_code error;
        std::vector<fs::path> stale;
        for (fs::directory_iterator entry(directory, error), end; !error && entry != end;
             entry.increment(error)) {
            const std::string name = entry->path().filename().string();
            if (name.compare(0, prefix.size(), prefix) != 0) {
                continue;
            }
            const std::string_view rest = std::string_view(name).substr(prefix.size());
            long pid = 0;
            const auto [end_of_pid, status] =
                std::from_chars(rest.data(), rest.data() + rest.size(), pid);
            if (status != std::errc() || end_of_pid == rest.data() ||
                end_of_pid == rest.data() + rest.size() || *end_of_pid != '.' || pid <= 0 ||
                pid == ::getpid()) {
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

}  // namespace

// Opening: the temporary file is created next to the target, because rename is atomic only within
// one file system. It is created with open(2) rather than by the stream, because open reliably sets
// errno, which gives the reason of a failure. A target that is a directory is refused here: the
// rename would fail only at the end.
AtomicFile::AtomicFile(std::string path, std::string_view option) : path_(std::move(path)) {
    namespace fs = std::filesystem;
    const fs::path target(path_);
    if (path_.empty()) {
        throw_cannot_write(option, path_, ENOENT);
    }
    std::error_code ignored;
    if (!target.has_filename() || fs::is_directory(target, ignored)) {
        throw_cannot_write(option, path_, EISDIR);
    }
    const std::string name = "." + target.filename().string() + ".tmp." +
                             std::to_string(::getpid()) + "." +
                             std::to_string(temporary_file_count++);
    temporary_path_ = (target.parent_path() / name).string();

    const int descriptor =
        ::open(temporary_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (descriptor < 0) {
        throw_cannot_write(option, path_, errno);
    }
    ::close(descriptor);
    pending_slot_ = register_pending_temporary(temporary_path_);
    remove_stale_temporaries(target);
    stream_.open(temporary_path_, std::ios::binary | std::ios::trunc);
    if (!stream_) {
        const int error_number = errno != 0 ? errno : EIO;
        std::remove(temporary_path_.c_str());
        withdraw_pending_temporary(pending_slot_);
        throw_cannot_write(option, path_, error_number);
    }
}

// Committing: a stream records a failed write (a full disk, an I/O error) only in its state, so
// the state is checked after the last flush and after closing; only then does the file replace the
// target. On any failure the temporary file is removed and the target keeps its old content.
void AtomicFile::commit() {
    if (finished_) {
        throw std::logic_error("AtomicFile: " + json_string(path_) + " is already committed");
    }
    stream_.flush();
    const bool written = !stream_.fail();
    stream_.close();
    if (!written || stream_.fail()) {
        discard();
        throw std::runtime_error("cannot write " + json_string(path_) +
                                 ": writing the data failed (is the disk full?)");
    }
    if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0) {
        const int error_number = errno;
        discard();
        throw std::runtime_error("cannot write " + json_string(path_) + ": renaming " +
                                 json_string(temporary_path_) + " failed: " +
                                 std::strerror(error_number));
    }
    withdraw_pending_temporary(pending_slot_);
    finished_ = true;
}

// Discarding: close the stream and remove the temporary file, without ever throwing, since this
// runs in the destructor, possibly during the unwinding of another exception.
void AtomicFile::discard() noexcept {
    finished_ = true;
    try {
        stream_.close();
    } catch (...) {
    }
    std::remove(temporary_path_.c_str());
    withdraw_pending_temporary(pending_slot_);
}

AtomicFile::~AtomicFile() {
    if (!finished_) {
        discard();
    }
}

namespace {

// A fresh directory for the tests of AtomicFile, removed with its content when the test ends,
// whether it passes or not.
class ScratchDirectory {
public:
    ScratchDirectory()
        : path_(std::filesystem::temp_directory_path() /
                ("mrm_cli_test." + std::to_string(::getpid()) + "." +
                 std::to_string(temporary_file_count++))) {
        std::filesystem::create_directory(path_);
    }
    ~ScratchDirectory() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;

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

    static void write(const std::string& path, std::string_view text) {
        std::ofstream(path, std::ios::binary) << text;
    }

private:
    std::filesystem::path path_;
};

}  // namespace

TEST_CASE("a committed AtomicFile replaces the target with the complete content") {
    ScratchDirectory directory;
    const std::string target = directory.file("results.dat");
    SUBCASE("new target") {}
    SUBCASE("existing target") { ScratchDirectory::write(target, "old content\n"); }

    AtomicFile file(target, "--output");
    CHECK(std::filesystem::path(file.temporary_path()).parent_path() ==
          std::filesystem::path(target).parent_path());
    CHECK(std::filesystem::path(file.temporary_path()).filename().string().rfind(
              ".results.dat.tmp." + std::to_string(::getpid()) + ".", 0) == 0);
    CHECK(std::filesystem::exists(file.temporary_path()));
    file.stream() << "# elements = 4\n1 2\n";
    file.commit();
    CHECK(ScratchDirectory::content(target) == "# elements = 4\n1 2\n");
    CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
    CHECK_THROWS_AS(file.commit(), std::logic_error);
}

TEST_CASE("an AtomicFile destroyed without commit leaves no file and the old target intact") {
    ScratchDirectory directory;
    const std::string target = directory.file("results.dat");
    SUBCASE("new target") {
        {
            AtomicFile file(target);
            file.stream() << "half of the data";
        }
        CHECK(directory.entries().empty());
    }
    SUBCASE("existing target") {
        ScratchDirectory::write(target, "old content\n");
        {
            AtomicFile file(target);
            file.stream() << "half of the data";
        }
        CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
        CHECK(ScratchDirectory::content(target) == "old content\n");
    }
}

TEST_CASE("a failed write makes the commit throw and leaves the old target intact") {
    ScratchDirectory directory;
    const std::string target = directory.file("results.dat");
    ScratchDirectory::write(target, "old content\n");
    AtomicFile file(target, "--output");
    file.stream() << "new content\n";
    file.stream().setstate(std::ios::badbit);
    CHECK_THROWS_WITH_AS(file.commit(),
                         ("cannot write " + json_string(target) +
                          ": writing the data failed (is the disk full?)")
                             .c_str(),
                         std::runtime_error);
    CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
    CHECK(ScratchDirectory::content(target) == "old content\n");
}

TEST_CASE("an unwritable output path is refused at once with the option's name and the reason") {
    ScratchDirectory directory;
    SUBCASE("missing directory") {
        const std::string path = directory.file("missing/x.dat");
        CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                             ("--output: cannot write " + json_string(path) +
                              ": No such file or directory")
                                 .c_str(),
                             UsageError);
    }
    SUBCASE("path is a directory") {
        const std::string path = directory.file("");
        CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                             ("--output: cannot write " + json_string(path) + ": Is a directory")
                                 .c_str(),
                             UsageError);
        const std::string without_slash = directory.file(".");
        CHECK_THROWS_WITH_AS(AtomicFile(without_slash, "--output"),
                             doctest::Contains(": Is a directory"), UsageError);
    }
    SUBCASE("parent is a file") {
        ScratchDirectory::write(directory.file("plain"), "");
        const std::string path = directory.file("plain/x.dat");
        CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                             ("--output: cannot write " + json_string(path) + ": Not a directory")
                                 .c_str(),
                             UsageError);
    }
    SUBCASE("empty path") {
        CHECK_THROWS_WITH_AS(AtomicFile("", "--output"),
                             "--output: cannot write \"\": No such file or directory", UsageError);
    }
    SUBCASE("directory without write permission") {
        std::filesystem::permissions(directory.file(""), std::filesystem::perms::owner_read |
                                                             std::filesystem::perms::owner_exec);
        if (::geteuid() == 0) {
            MESSAGE("skipped: permissions do not apply to root");
        } else {
            const std::string path = directory.file("x.dat");
            CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                                 ("--output: cannot write " + json_string(path) +
                                  ": Permission denied")
                                     .c_str(),
                                 UsageError);
        }
        std::filesystem::permissions(directory.file(""), std::filesystem::perms::owner_all);
    }
    SUBCASE("a path not given by an option") {
        const std::string path = directory.file("missing/x.dat");
        CHECK_THROWS_WITH_AS(AtomicFile{path},
                             ("cannot write " + json_string(path) + ": No such file or directory")
                                 .c_str(),
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
TEST_CASE("a run stopped by a signal leaves the old target intact and no temporary file") {
    for (const int signal_number : {SIGTERM, SIGINT, SIGHUP, SIGPIPE}) {
        CAPTURE(signal_number);
        ScratchDirectory directory;
        const std::string target = directory.file("results.dat");
        ScratchDirectory::write(target, "old content\n");
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
        CHECK(ScratchDirectory::content(target) == "old content\n");
    }
}

TEST_CASE("a temporary file left by a process that no longer exists is removed on the next write") {
    ScratchDirectory directory;
    const std::string target = directory.file("results.dat");
    ScratchDirectory::write(target, "old content\n");
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
        ScratchDirectory::write(directory.file(name), "left over");
    }
    AtomicFile file(target, "--output");
    file.stream() << "new content\n";
    file.commit();
    std::vector<std::string> expected{live, other, "results.dat"};
    std::sort(expected.begin(), expected.end());
    CHECK(directory.entries() == expected);
    CHECK(ScratchDirectory::content(target) == "new content\n");
}

TEST_SUITE_END();

}  // namespace mrm::cli
