// Output files that appear complete or not at all, whatever the target is, and the standard
// descriptors of a program. See output_file.cpp for the reasons behind each rule.
//
// What `--output FILE` (any option naming a file to write) does with FILE:
//
//   - a new name, or an existing regular file: the data are written to a new file with a random,
//     hidden name in the same directory, created exclusively (it never follows or reuses a link or
//     a file that is already there) and readable by its owner only while it is written; once
//     complete it gets the permissions the umask gives a new file and is renamed over FILE. An
//     interrupted or failed run leaves FILE as it was and no temporary file;
//   - a character device (/dev/null, /dev/full, a terminal) or a FIFO: written in place, as the
//     user asked (a FIFO must have a reader already: otherwise the program would block, and the
//     option is refused). What is written there cannot be taken back: it is not all or nothing;
//   - FILE open on standard output or standard error (/dev/stdout, /dev/stderr, /proc/self/fd/1,
//     reached through their symbolic links): written through that descriptor;
//   - a directory, a socket, a block device: refused;
//   - a symbolic link to anything else (a regular file, a missing file): refused; the link is
//     never followed nor replaced (a link planted in a shared directory cannot redirect a write);
//   - a regular file that is the standard output's own file (`prog -o F > F`), or the file of
//     another output of the same run (same path, another spelling, a hard link): refused.
//
// Every refusal comes when the AtomicFile is constructed, before any work, as a UsageError naming
// the option (exit status 2 under guarded_main).
#pragma once

#include <cstddef>
#include <memory>
#include <ostream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include <sys/types.h>

namespace mrm::cli {

// A stream buffer over a file descriptor that remembers the first failed write (its errno) and
// fails every write after it, so that the stream's state tells whether all the data got out.
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(int descriptor = -1);
  void reset(int descriptor);
  int error() const { return error_; }
  // Writes out what is buffered; false if this or any earlier write failed.
  bool drain();

 protected:
  int_type overflow(int_type character) override;
  int sync() override;

 private:
  int descriptor_;
  std::vector<char> buffer_;
  int error_ = 0;
};

class AtomicFile {
 public:
  explicit AtomicFile(std::string path, std::string_view option = "");
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return stream_; }
  // Equivalent to commit_all({this}).
  void commit();

  const std::string& path() const { return path_; }
  // The hidden file being written ("" when the target is written in place).
  const std::string& temporary_path() const { return temporary_path_; }
  bool in_place() const { return temporary_path_.empty(); }

 private:
  friend void commit_all(const std::vector<AtomicFile*>& files);
  void open_in_place(int descriptor);
  void open_temporary(std::string_view option);
  void finish_writing();
  void discard() noexcept;

  std::string path_, option_, temporary_path_;
  int descriptor_ = -1;
  DescriptorBuffer buffer_;
  std::ostream stream_;
  bool finished_ = false;
  std::size_t pending_slot_;
  std::size_t identity_slot_;
};

// Commits several outputs all or nothing. First what the program wrote on standard output is
// delivered and checked (and the state of standard error), then every file is finished (flushed,
// closed, checked); a failure there discards them all and leaves every target as it was. Then the
// temporary files are renamed over their targets, a hard link keeping each previous target until
// all are in place, so that a failed rename puts the earlier ones back. Throws std::runtime_error
// naming the output that failed. Outputs written in place are flushed first and cannot be taken
// back. Null pointers in `files` are skipped (outputs that were not asked for); with no file at all
// it still checks the standard streams.
void commit_all(const std::vector<AtomicFile*>& files);

// Makes sure descriptors 0, 1 and 2 are open, so that no file the program opens can take their
// place: a closed standard input or standard error is opened on /dev/null; a closed standard output
// on /dev/null read-only, so that writing results to it fails (a program whose results cannot be
// delivered must fail). Returns true if standard output was closed. guarded_main calls it first.
bool prepare_standard_descriptors() noexcept;

// The memory this process may still allocate, in bytes: the machine's physical memory, and the
// room left under the address-space and data-segment limits (setrlimit), whichever is smallest.
double available_memory();
// Throws a UsageError naming `option` when `bytes` (the memory the run needs) exceeds
// available_memory(): "--elements: 100000000 elements need about 40 GB of memory, more than the
// 23 GB available (allowed: ...)". `what` describes the request ("100000000 elements").
void require_memory(std::string_view option, std::string_view what, double bytes);

}  // namespace mrm::cli
