// Output files sized for the threat model (doc/robustness.md, "Output files"): the programs are run by
// their user on their own files. What an option naming a file to write (`--output FILE`) promises:
//
//   - the output is complete or absent: it is written to a temporary file in FILE's directory, opened
//     exclusively (an existing file or symbolic link at that name is never followed nor reused),
//     renamed over FILE once complete, removed on failure; the outputs of one program are all
//     written out and checked before the first is renamed (commit_all);
//   - a write error, a closed or failing standard output or standard error, is an error (exit 1),
//     never bytes in a data file; so is a non-finite value ("nan", "inf") in a data file or in what the
//     program prints (NonFiniteWatch): nothing is committed;
//   - an interrupted run may leave its hidden temporary `.FILE.XXXXXX`, never a partial FILE;
//   - a replaced FILE keeps its permission bits; a new one gets those the umask gives; a symbolic
//     link to a file is followed (the file is replaced, the link stays);
//   - `-` is the standard output (written as the program's other standard output, not atomically);
//   - a FILE that cannot be written (missing directory, a directory, anything that exists and is not
//     a regular file) is refused when the AtomicFile is made, before any work, as a UsageError
//     naming the option (exit 2 under guarded_main).
#pragma once

#include <ostream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

namespace mrm::cli {

/// What every program's --help says of its FILE options (the rules above, in one paragraph).
extern const char* const output_files_help;

/// Watches the text of an output for a value that could not be computed: a word (a run of letters,
/// digits and '_') that reads "nan", "inf" or "infinity" in any case, which is how format_real,
/// printf and iostreams write a non-finite double whatever its sign. A data file holds numbers, or
/// words saying why a value is absent ("n/a"), never these: an output holding one is an error.
class NonFiniteWatch {
 public:
  void scan(const char* data, std::size_t size);
  bool found() const;
  /// "line 12 holds \"nan\", a value that could not be computed"
  std::string what() const;

 private:
  void end_word();
  std::string word_;
  long line_ = 1, found_line_ = 0;
  std::string found_word_;
};

/// A stream buffer that passes everything to another one and watches it (NonFiniteWatch):
/// guarded_main puts one in front of the standard output.
class WatchedBuffer : public std::streambuf {
 public:
  explicit WatchedBuffer(std::streambuf* target) : target_(target) {}
  const NonFiniteWatch& watch() const { return watch_; }

 protected:
  int_type overflow(int_type character) override;
  std::streamsize xsputn(const char* data, std::streamsize size) override;
  int sync() override;

 private:
  std::streambuf* target_;
  NonFiniteWatch watch_;
};

/// The watch of the standard output while guarded_main runs (null otherwise): commit_all refuses to
/// commit a program's files when what it printed holds a non-finite value.
extern const NonFiniteWatch* standard_output_watch;

/// A stream buffer over a file descriptor that remembers the first failed write (its errno) and
/// fails every write after it, so that the stream's state tells whether all the data got out.
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(int descriptor = -1);
  void reset(int descriptor);
  int error() const { return error_; }
  const NonFiniteWatch& watch() const { return watch_; }
  /// Writes out what is buffered; false if this or any earlier write failed.
  bool drain();

 protected:
  int_type overflow(int_type character) override;
  int sync() override;

 private:
  int descriptor_;
  std::vector<char> buffer_;
  int error_ = 0;
  NonFiniteWatch watch_;
};

/// One output file: complete under its name after commit(), or absent (the old file intact).
class AtomicFile {
 public:
  explicit AtomicFile(std::string path, std::string_view option = "");
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return *stream_; }
  /// Equivalent to commit_all({this}).
  void commit();

  const std::string& path() const { return path_; }
  /// The hidden file being written ("" for `-`, the standard output).
  const std::string& temporary_path() const { return temporary_path_; }

 private:
  friend void commit_all(const std::vector<AtomicFile*>& files);
  void finish_writing();
  void discard() noexcept;

  std::string path_, target_, temporary_path_;
  int descriptor_ = -1;
  int mode_ = -1;  // permission bits of the file replaced, -1 for a new file
  DescriptorBuffer buffer_;
  std::ostream file_stream_;
  std::ostream* stream_;
  bool finished_ = false;
};

/// Commits several outputs together. First the standard streams are checked (what the program
/// printed is part of what it delivers), then every file is written out, closed and checked; any
/// failure so far removes every temporary and leaves every target as it was. Then the temporaries
/// are renamed over their targets. Throws std::runtime_error naming the output that failed. Null
/// pointers (outputs not asked for) are skipped.
void commit_all(const std::vector<AtomicFile*>& files);

/// Why `path` cannot be read as an input file, or "" if it can: what stat says of a path it cannot examine
/// ("No such file or directory"), "is a directory, not a file", or, for anything else that is not a
/// regular file, what it is ("is a FIFO or a pipe (a process substitution <(...) is one), not a regular
/// file", "is a character device, not a regular file", ...). The readers read their file twice (counted,
/// then parsed) or must not block on a FIFO without a writer: they take regular files only, and say so.
std::string input_file_problem(const std::string& path);

/// Makes sure descriptors 0, 1 and 2 are open, so that no output file the program opens takes their
/// place (and receives what the program prints): a closed one is opened on /dev/null, standard
/// output read-only, so that printing results to it fails. Returns true if standard output was
/// closed. guarded_main calls it first.
bool prepare_standard_descriptors() noexcept;

}  // namespace mrm::cli
