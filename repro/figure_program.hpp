// The frame every figure program shares: its parser, the options of one mesh and one step
// (--elements, --courant, --final-time) for the programs that have them, its two outputs (--output,
// the data file; --tex, the values the report quotes), the limits of the run checked before any
// work, and the data header. A program reads
//
//   repro::FigureProgram program("fig_energy", "Writes ...", {"fig_energy --output e.dat"});
//   program.add_elements(20);
//   program.add_courant(0.5);
//   program.add_final_time(9.0);
//   program.parser.add_choice(...);                       // its own options, in echo order
//   if (!program.parse(argc, argv)) return 0;            // --help, --version
//   const mrm::Index steps = program.steps(9);           // 9 runs of steps + 1 lines each
//   program.open();                                       // a bad path fails before the runs
//   std::ostream& out = program.header("discrete energy ...");
//   program.write_step();                                 // # h, # dt, # steps
//   ...
//   program.commit();                                     // both outputs or neither
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "options.hpp"
#include "output_file.hpp"
#include "run_limits.hpp"
#include "time/schemes.hpp"

namespace mrm::repro {

/// The range of --elements and --courant in the figure programs (run_limits.hpp): N in [2, 1e7],
/// 0 < C <= 1e6.
mrm::cli::Check elements_range();
mrm::cli::Check courant_range();
/// The peak memory of the figure programs that hold one run at a time with its error accumulator and
/// the exact solution's interpolants, measured at N = 1e6: 410 bytes per element; 512 with a margin.
constexpr double bytes_per_element = 512;

/// The options that set the parameters of a scheme on a program's command line.
using SchemeOptions = std::vector<std::pair<std::string, mrm::SchemeParameter>>;
/// Refuses an option given for a parameter the scheme does not take (mrm::takes), as a usage error:
///   --beta: the scheme cn does not take it (allowed: omit it, or --scheme ps)
void refuse_untaken(const mrm::cli::Parser& parser, mrm::Scheme scheme, const SchemeOptions& options);
/// Runs `build` (which builds a simulation before any work) and turns the library's refusal
/// (mrm::InvalidParameter, naming the parameter) into the usage error naming the option that sets it
/// (`options`: parameter → option, e.g. "contact_row" → "--ps-form"; an unnamed parameter is rethrown).
void as_usage_error(const std::vector<std::pair<std::string, std::string>>& options,
                    const std::function<void()>& build);

class FigureProgram {
 public:
  FigureProgram(std::string name, std::string description, std::vector<std::string> sample_runs);
  FigureProgram(const FigureProgram&) = delete;  // the parser points at the members
  FigureProgram& operator=(const FigureProgram&) = delete;

  mrm::cli::Parser parser;
  long elements = 20;
  double courant = 0.5;
  double final_time = 9.0;
  long exact_points = 400;  ///< intervals of an exact curve (--exact-points), for the programs that draw one

  /// The usual options, registered where the program calls them (the echo follows that order); h = 1/N.
  void add_elements(long value, std::string help = "number of elements N (h = 1/N), in [2, 1e7]",
                    mrm::cli::Check range = elements_range());
  void add_courant(double value, std::string help = "time step dt = C h (0 < C <= 1e6)",
                   mrm::cli::Check range = courant_range());
  void add_final_time(double value, std::string help = "final time (> 0); the period is 3");
  void add_exact_points(long value,
                        std::string help = "number of intervals of the exact solution's curve, in [10, 1e6]");

  /// Registers --output and --tex, then reads the command line; false when the help or the version
  /// was printed (the program then ends with status 0).
  bool parse(int argc, const char* const* argv,
             const std::string& tex_help = "also write the values the report quotes, as \\mrmdef lines");

  double h() const { return 1.0 / static_cast<double>(elements); }
  double dt() const { return courant * h(); }
  /// The steps of Δt = C h that reach --final-time, checked (run_limits.hpp) with the data file of
  /// `runs` histories of steps + 1 lines and one mesh in memory: a usage error before any work.
  mrm::Index steps(double runs);

  /// Opens both outputs (a bad path fails now); the values are written only if --tex was given.
  void open();
  /// Writes "# <name>: <title>", the effective options and the labels (labels.hpp: write_labels) into
  /// the data file, and returns it.
  std::ostream& header(std::string_view title);
  /// "# h = ...", "# dt = ..." and "# steps = ..." of the last steps().
  void write_step();
  std::ostream& data() { return data_->stream(); }
  std::ostream& values() { return values_; }
  /// Both outputs or neither (mrm::cli::commit_all).
  void commit();

 private:
  std::string name_, output_, tex_;
  mrm::Index steps_ = 0;
  std::unique_ptr<mrm::cli::AtomicFile> data_, values_file_;
  std::ostringstream values_;
};

}  // namespace mrm::repro
