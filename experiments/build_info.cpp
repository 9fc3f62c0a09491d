// build_info: what this build is made of, for the back of the report's title page.
//
// What it prints. The compiler and the versions of the libraries that CMake found when it configured
// this build (Eigen, GSL, Google Highway, doctest, CLI11: CMakeLists.txt passes them to this program as
// compile definitions, so they are the versions the programs were compiled against), the build type,
// and the vector target the batched step chooses on this processor at run time (Highway's name and its
// number of double lanes: the width in which the sweeps' runs share vector registers,
// lib/batched/batched_step.cpp). Written as the report's values `\mrmdef{meta:KEY}{VALUE}`.
//
// The same build on the same machine gives the same bytes (no time, no host name); another machine may
// choose another vector target, and says so.
//
// Sample runs:
//   build_info --tex output/data/build_info.tex
//   build_info               (the values on standard output)
//
// Description. Steps: (1) read the options; (2) open the output; (3) write the values and commit.
#include <iostream>
#include <string>

#include "batched/batched_step.hpp"
#include "claims.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "report_values.hpp"

namespace cli = mrm::cli;

#ifndef MRM_BUILD_COMPILER
#define MRM_BUILD_COMPILER "unknown"
#endif
#ifndef MRM_BUILD_TYPE
#define MRM_BUILD_TYPE "unknown"
#endif
#ifndef MRM_BUILD_EIGEN
#define MRM_BUILD_EIGEN "unknown"
#endif
#ifndef MRM_BUILD_GSL
#define MRM_BUILD_GSL "unknown"
#endif
#ifndef MRM_BUILD_HIGHWAY
#define MRM_BUILD_HIGHWAY "unknown"
#endif
#ifndef MRM_BUILD_DOCTEST
#define MRM_BUILD_DOCTEST "unknown"
#endif
#ifndef MRM_BUILD_CLI11
#define MRM_BUILD_CLI11 "unknown"
#endif

int main(int argc, char** argv) {
  return cli::guarded_main("build_info", [&] {
    // 1. Options.
    std::string tex = "-";
    cli::Parser parser("build_info",
                       "Writes the compiler, the library versions CMake found for this build and the vector target "
                       "the batched step uses on this processor as \\mrmdef lines for the report's title page.",
                       {"build_info --tex output/data/build_info.tex"});
    parser.add_output("--tex", "", "write the values (\\mrmdef lines) to FILE, or - for standard output", &tex);
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;

    // 2. The output.
    cli::AtomicFile out(tex, "--tex");

    // 3. The values: the versions as CMake found them, the vector target as the processor allows it.
    const mrm::BatchTarget target = mrm::current_batch_target();
    auto define = [&](const std::string& key, const std::string& value) {
      mrm::tex_define(out.stream(), "meta:" + key, mrm::claims::latex_escape(value));
    };
    define("compiler", MRM_BUILD_COMPILER);
    define("buildtype", MRM_BUILD_TYPE);
    define("eigen", MRM_BUILD_EIGEN);
    define("gsl", MRM_BUILD_GSL);
    define("highway", MRM_BUILD_HIGHWAY);
    define("doctest", MRM_BUILD_DOCTEST);
    define("cli11", MRM_BUILD_CLI11);
    define("vector:target", target.name);
    define("vector:lanes", std::to_string(target.lanes));
    define("vector:bits", std::to_string(64 * target.lanes));
    out.commit();
    return 0;
  });
}
