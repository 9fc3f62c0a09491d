/// @file scheme_options.hpp
/// @brief The options that set a scheme's parameters, offered from the registry's specs
/// (lib/time/scheme_registry.hpp): each parameter's option, range and help are spelled once, in the
/// library, and every program that offers them loops over the specs.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "options.hpp"
#include "time/scheme_registry.hpp"

namespace mrm::repro {

/// The scheme parameters a program offers as options, and the values its command line gave.
///
///   SchemeParameterOptions scheme_options;
///   scheme_options.declare(parser);                        // --beta, --restitution, ..., --lumping
///   parser.parse(argc, argv, std::cout);
///   SchemeParameters p = scheme_options.parameters(parser, scheme, preset);  // refuses an untaken option
class SchemeParameterOptions {
 public:
  /// Declares the option of every parameter in `which` (all of them when empty), with its spec's help
  /// and range: a real parameter's value outside [lowest, highest] (or at an excluded lowest) and a
  /// named parameter's value outside its choices are refused by the parser (exit 2). Several calls may
  /// declare disjoint sets, each where the program's help lists them. Each option's default is its
  /// parameter's value in `defaults`: SchemeParameters{}, or the value a program's figure is drawn with
  /// (fig_energy's Paoli–Schatzman takes the literal contact row), which its help then shows.
  void declare(mrm::cli::Parser& parser, const std::vector<mrm::SchemeParameter>& which = {},
               const mrm::SchemeParameters& defaults = mrm::SchemeParameters{});
  /// The parameters of `scheme` from the command line: each parameter the scheme takes has its given
  /// value, or else its value in `preset`; every other parameter keeps its default. An option given for
  /// a parameter the scheme does not take is refused (UsageError: "--beta: the scheme cn does not take
  /// it (allowed: omit it, or --scheme ps)"), before any work.
  mrm::SchemeParameters parameters(const mrm::cli::Parser& parser, mrm::Scheme scheme,
                                   const mrm::SchemeParameters& preset = mrm::SchemeParameters{}) const;
  /// Every declared parameter at its value from the command line, or else at its default (declare's
  /// `defaults`); every other parameter at SchemeParameters{}. For a program that runs several schemes
  /// with the same parameters (the figures of the paper: cn, be and ps with the one --ps-form).
  mrm::SchemeParameters values() const;
  /// The library's name of each declared parameter beside its option ("contact_row" → "--ps-form"),
  /// for as_usage_error (figure_program.hpp).
  std::vector<std::pair<std::string, std::string>> option_names() const;

 private:
  std::vector<mrm::SchemeParameter> declared_;
  std::vector<double> numbers_;       // a real parameter's value, by its index in the specs
  std::vector<std::string> choices_;  // a named parameter's value, likewise
};

}  // namespace mrm::repro
