// Atomic output files (AtomicFile): a data file, a table or a report fragment appears complete or not
// at all.
#pragma once

#include <cstddef>
#include <fstream>
#include <string>
#include <string_view>

namespace mrm::cli {

// An output file that appears complete or not at all. The data are written to a hidden temporary
// file in the target's directory, `.<name>.tmp.<pid>.<sequence number>`; commit() checks that
// every write succeeded and renames it onto the target. If the object is destroyed without a
// commit (an exception, an early return) the temporary file is removed and an existing target is
// left as it was.
//
// The constructor creates the temporary file at once, so that a program can open its outputs
// before a long computation and fail immediately on a path it cannot write. That failure names
// the option and the reason:
//   --output: cannot write "/nonexistent/x.dat": No such file or directory
// and is a UsageError; with an empty `option` the message has no prefix and the error is a
// std::runtime_error. A failed commit throws std::runtime_error naming the target.
//
// A process ended by SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE or SIGXFSZ removes the temporary
// files of its uncommitted AtomicFiles before it ends (a handler that each AtomicFile installs for
// those of these signals whose action is the default). SIGKILL cannot be caught: the
// temporary file it leaves is removed by the next AtomicFile for the same target, once the process
// that wrote it no longer exists. In every case the target keeps its old content.
class AtomicFile {
public:
    explicit AtomicFile(std::string path, std::string_view option = "");
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return stream_; }
    void commit();

    const std::string& path() const { return path_; }
    const std::string& temporary_path() const { return temporary_path_; }

private:
    void discard() noexcept;

    std::string path_;
    std::string temporary_path_;
    std::ofstream stream_;
    bool finished_ = false;
    std::size_t pending_slot_ = static_cast<std::size_t>(-1);  // in the signal handler's table
};

}  // namespace mrm::cli
