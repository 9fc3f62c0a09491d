/// @file scheme_options.cpp
/// @brief The options of the scheme parameters, from the registry's specs (scheme_options.hpp).
#include "scheme_options.hpp"

#include <algorithm>
#include <sstream>

#include <doctest/doctest.h>

#include "figure_program.hpp"

namespace mrm::repro {

namespace cli = mrm::cli;

void SchemeParameterOptions::declare(cli::Parser& parser, const std::vector<mrm::SchemeParameter>& which,
                                     const mrm::SchemeParameters& defaults) {
  const std::vector<mrm::ParameterSpec>& specs = mrm::scheme_parameter_specs();
  // Sized once, before any option points into them (the parser keeps the addresses): a program may
  // declare the parameters in several calls, to place them among its other options.
  if (numbers_.empty()) {
    numbers_.assign(specs.size(), 0.0);
    choices_.assign(specs.size(), std::string());
  }
  for (const mrm::ParameterSpec& spec : specs) {
    if (!which.empty() && std::find(which.begin(), which.end(), spec.parameter) == which.end()) continue;
    if (std::find(declared_.begin(), declared_.end(), spec.parameter) != declared_.end())
      throw std::logic_error("SchemeParameterOptions: " + spec.option + " declared twice");
    const auto k = static_cast<std::size_t>(spec.parameter);
    declared_.push_back(spec.parameter);
    if (spec.choices.empty()) {
      numbers_[k] = mrm::number(defaults, spec.parameter);
      const double lowest = spec.lowest, highest = spec.highest;
      const bool excluded = spec.lowest_excluded;
      parser.add_real(spec.option, spec.short_option, spec.placeholder, spec.help, &numbers_[k],
                      [lowest, highest, excluded](std::string_view option, double value) {
                        if (excluded && lowest == 0) cli::require_positive(option, value);
                        cli::require_in_closed_range(option, value, lowest, highest);
                      });
    } else {
      choices_[k] = mrm::choice(defaults, spec.parameter);
      parser.add_choice(spec.option, spec.short_option, spec.placeholder, spec.help, spec.choices, &choices_[k]);
    }
  }
}

mrm::SchemeParameters SchemeParameterOptions::parameters(const cli::Parser& parser, mrm::Scheme scheme,
                                                         const mrm::SchemeParameters& preset) const {
  SchemeOptions options;
  for (const mrm::SchemeParameter parameter : declared_)
    options.emplace_back(mrm::parameter_spec(parameter).option, parameter);
  refuse_untaken(parser, scheme, options);
  mrm::SchemeParameters p;
  p.scheme = scheme;
  for (const mrm::ParameterSpec& spec : mrm::scheme_parameter_specs()) {
    if (!mrm::takes(scheme, spec.parameter)) continue;
    const auto k = static_cast<std::size_t>(spec.parameter);
    const bool given =
        std::find(declared_.begin(), declared_.end(), spec.parameter) != declared_.end() && parser.given(spec.option);
    if (spec.choices.empty())
      mrm::set_number(p, spec.parameter, given ? numbers_[k] : mrm::number(preset, spec.parameter));
    else
      mrm::set_choice(p, spec.parameter, given ? choices_[k] : mrm::choice(preset, spec.parameter));
  }
  return p;
}

mrm::SchemeParameters SchemeParameterOptions::values() const {
  mrm::SchemeParameters p;
  for (const mrm::SchemeParameter parameter : declared_) {
    const auto k = static_cast<std::size_t>(parameter);
    if (mrm::parameter_spec(parameter).choices.empty())
      mrm::set_number(p, parameter, numbers_[k]);
    else
      mrm::set_choice(p, parameter, choices_[k]);
  }
  return p;
}

std::vector<std::pair<std::string, std::string>> SchemeParameterOptions::option_names() const {
  std::vector<std::pair<std::string, std::string>> names;
  for (const mrm::SchemeParameter parameter : declared_)
    names.emplace_back(mrm::parameter_spec(parameter).name, mrm::parameter_spec(parameter).option);
  return names;
}

TEST_CASE("the scheme options set what the scheme takes, from the command line or the preset, and refuse the rest") {
  const auto parse = [](std::vector<std::string> words, mrm::Scheme scheme, const mrm::SchemeParameters& preset) {
    cli::Parser parser("program", "a program", {});
    SchemeParameterOptions options;
    options.declare(parser);
    std::ostringstream out;
    parser.parse(words, out);
    return options.parameters(parser, scheme, preset);
  };
  mrm::SchemeParameters preset;
  preset.newmark_beta = 0.0;
  preset.beta = 0.3;
  // Given, taken: the given value. Not given, taken: the preset's. Not taken: the default.
  const mrm::SchemeParameters p = parse({"--newmark-gamma", "0.75"}, mrm::Scheme::newmark, preset);
  CHECK(p.scheme == mrm::Scheme::newmark);
  CHECK(p.newmark_gamma == 0.75);
  CHECK(p.newmark_beta == 0.0);
  CHECK(p.beta == mrm::SchemeParameters{}.beta);
  const mrm::SchemeParameters q =
      parse({"--ps-form", "literal", "--ps-start", "explicit"}, mrm::Scheme::paoli_schatzman, mrm::SchemeParameters{});
  CHECK(q.contact_row == mrm::ContactRow::literal);
  CHECK(q.ps_explicit_start);
  // Given, not taken: refused, naming the option and the schemes that take it.
  CHECK_THROWS_WITH_AS(parse({"--beta", "0.3"}, mrm::Scheme::crank_nicolson, mrm::SchemeParameters{}),
                       "--beta: the scheme cn does not take it (allowed: omit it, or --scheme ps)", cli::UsageError);
  CHECK_THROWS_WITH_AS(
      parse({"--lumping", "none"}, mrm::Scheme::explicit_central, mrm::SchemeParameters{}),
      "--lumping: the scheme explicit does not take it (allowed: omit it, or --scheme taylor-flanagan)",
      cli::UsageError);
  // Out of the spec's range: refused by the parser.
  CHECK_THROWS_AS(parse({"--penalty", "0"}, mrm::Scheme::penalty, mrm::SchemeParameters{}), cli::UsageError);
  CHECK_THROWS_AS(parse({"--moreau-theta", "0.4"}, mrm::Scheme::moreau_jean, mrm::SchemeParameters{}), cli::UsageError);
}

TEST_CASE("a program's own default of a scheme parameter: shown in its help, its value when not given") {
  const auto values = [](std::vector<std::string> words) {
    cli::Parser parser("program", "a program", {});
    SchemeParameterOptions options;
    mrm::SchemeParameters defaults;
    defaults.contact_row = mrm::ContactRow::literal;
    options.declare(parser, {mrm::SchemeParameter::contact_row}, defaults);
    std::ostringstream out;
    parser.parse(words, out);
    return std::make_pair(options.values(), out.str());
  };
  CHECK(values({}).first.contact_row == mrm::ContactRow::literal);
  CHECK(values({"--ps-form", "algebraic"}).first.contact_row == mrm::ContactRow::algebraic);
  CHECK(values({"--help"}).second.find("default: literal") != std::string::npos);
  // A parameter not declared keeps SchemeParameters{}'s value.
  CHECK(values({}).first.beta == mrm::SchemeParameters{}.beta);
}

}  // namespace mrm::repro
