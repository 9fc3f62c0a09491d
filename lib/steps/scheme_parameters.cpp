/// @file scheme_parameters.cpp
/// @brief The specs of the scheme parameters (scheme_parameters.hpp): one per parameter, spelled once,
/// read and written through it, with the doctest that every spec is complete.
#include "steps/scheme_parameters.hpp"

#include <algorithm>
#include <stdexcept>

#include <doctest/doctest.h>

namespace mrm {

std::string to_string(SchemeParameter p) { return parameter_spec(p).name; }

std::string to_string(ContactRow r) { return r == ContactRow::algebraic ? "algebraic" : "literal"; }
std::string to_string(InitialContactNode i) {
  return i == InitialContactNode::consistent ? "consistent" : "interpolant";
}
std::string to_string(StepKernel k) { return k == StepKernel::reference ? "reference" : "fast"; }

ContactRow contact_row_by_name(const std::string& name) {
  if (name == "algebraic") return ContactRow::algebraic;
  if (name == "literal") return ContactRow::literal;
  throw std::invalid_argument("unknown contact-row form \"" + name + "\" (allowed: algebraic, literal)");
}
InitialContactNode initial_contact_node_by_name(const std::string& name) {
  if (name == "consistent") return InitialContactNode::consistent;
  if (name == "interpolant") return InitialContactNode::interpolant;
  throw std::invalid_argument("unknown initial contact-node value \"" + name + "\" (allowed: consistent, interpolant)");
}

std::string to_string(MassLumping lumping) { return lumping == MassLumping::row_sum ? "row-sum" : "none"; }

MassLumping mass_lumping_by_name(const std::string& name) {
  if (name == "row-sum") return MassLumping::row_sum;
  if (name == "none") return MassLumping::none;
  throw std::invalid_argument("unknown mass lumping \"" + name + "\" (allowed: row-sum, none)");
}

// ---------------------------------------------------------------------------------------------------
// The scheme parameters: each one's name, option, allowed values and help, in the order of the enum.
// The ranges are what the programs accept: the library's own checks (BarSimulation, contact_classes.cpp)
// are wider where a bound only keeps a run's numbers far from overflow (1e6, 1e12), and CN-switch's θ
// is offered at the one value whose energy identity proves that no step gains energy
// (switch_theta_without_gain; the library keeps [½, 1] for the checks of the θ-step itself).

SchemeParameters parameters_of(Scheme scheme, ContactRow row, StepKernel kernel) {
  SchemeParameters p;
  p.scheme = scheme;
  p.contact_row = row;
  p.kernel = kernel;
  return p;
}

const std::vector<ParameterSpec>& scheme_parameter_specs() {
  using P = SchemeParameter;
  static const std::vector<ParameterSpec> specs = {
      {P::beta,
       "beta",
       "--beta",
       "-b",
       "B",
       "Paoli-Schatzman's beta, in [0, 1e6]; at least 1/4 with --ps-form literal and a massless contact node",
       {},
       0,
       1e6,
       false},
      {P::restitution,
       "restitution",
       "--restitution",
       "-e",
       "E",
       "restitution coefficient e in [0, 1] of the schemes with an impact law (ps: the constraint on "
       "(u0^{n+1} + e u0^{n-1})/(1 + e); moreau-jean: v+ = -e v-)",
       {},
       0,
       1,
       false},
      {P::contact_row,
       "contact_row",
       "--ps-form",
       "",
       "F",
       "Paoli-Schatzman's contact row: algebraic at every level, or the literal three-level formula (the "
       "consistent mass needs literal, which is then the default)",
       {"algebraic", "literal"},
       0,
       0,
       false},
      {P::switch_theta,
       "switch_theta",
       "--switch-theta",
       "",
       "TH",
       "cn-switch: theta of the step that replaces a Crank-Nicolson step across a change of the contact "
       "status; only 1 (backward Euler), the one theta whose energy identity proves that no step gains "
       "energy (below 1 a release may gain: doc/mathematics.md sec. 12)",
       {},
       switch_theta_without_gain,
       1,
       false},
      {P::newmark_beta,
       "newmark_beta",
       "--newmark-beta",
       "",
       "B",
       "Newmark's beta of newmark, penalty, nitsche, in [0, 1e6] (0: explicit, the step solves with the mass; "
       "1/4 with gamma 1/2 is Crank-Nicolson)",
       {},
       0,
       1e6,
       false},
      {P::newmark_gamma,
       "newmark_gamma",
       "--newmark-gamma",
       "",
       "G",
       "Newmark's gamma of newmark, penalty, nitsche, in [0.5, 1e6] (below 1/2 Newmark amplifies)",
       {},
       0.5,
       1e6,
       false},
      {P::penalty,
       "penalty",
       "--penalty",
       "",
       "G0",
       "penalty: the parameter gamma0 of the contact force (gamma0/h) min(0, u0), in (0, 1e12]",
       {},
       0,
       1e12,
       true},
      {P::nitsche_theta,
       "nitsche_theta",
       "--nitsche-theta",
       "",
       "TH",
       "nitsche: the symmetry parameter theta in [-1, 1] (1 symmetric, 0 skew-free, -1 skew-symmetric), below "
       "--nitsche-gamma",
       {},
       -1,
       1,
       false},
      {P::nitsche_gamma,
       "nitsche_gamma",
       "--nitsche-gamma",
       "",
       "G0",
       "nitsche: the parameter gamma0 (gamma = gamma0/h), in (0, 1e12]",
       {},
       0,
       1e12,
       true},
      {P::moreau_theta,
       "moreau_theta",
       "--moreau-theta",
       "",
       "TH",
       "moreau-jean: theta of the theta-method, in [0.5, 1] (below 1/2 the method amplifies)",
       {},
       0.5,
       1,
       false},
      {P::ps_start,
       "ps_start",
       "--ps-start",
       "",
       "S",
       "Paoli-Schatzman's first step: cn (one Crank-Nicolson step) or explicit (the explicit Newmark step of "
       "GetFEM's demo; a contact node with inertia)",
       {"cn", "explicit"},
       0,
       0,
       false},
      {P::mass_lumping,
       "mass_lumping",
       "--lumping",
       "",
       "K",
       "taylor-flanagan's mass: row-sum lumped (the default; dt <= h), or none, the consistent mass solved at "
       "every step as GetFEM's demo (dt <= h/sqrt(3))",
       {"row-sum", "none"},
       0,
       0,
       false},
  };
  return specs;
}

const ParameterSpec& parameter_spec(SchemeParameter parameter) {
  const std::vector<ParameterSpec>& specs = scheme_parameter_specs();
  const auto k = static_cast<std::size_t>(parameter);
  if (k >= specs.size() || specs[k].parameter != parameter)
    throw std::logic_error("parameter_spec: the specs are not in the order of SchemeParameter");
  return specs[k];
}

namespace {

// The member of SchemeParameters that holds a real parameter; null for a named one.
double SchemeParameters::*real_member(SchemeParameter parameter) {
  switch (parameter) {
    case SchemeParameter::beta:
      return &SchemeParameters::beta;
    case SchemeParameter::restitution:
      return &SchemeParameters::restitution;
    case SchemeParameter::switch_theta:
      return &SchemeParameters::switch_theta;
    case SchemeParameter::newmark_beta:
      return &SchemeParameters::newmark_beta;
    case SchemeParameter::newmark_gamma:
      return &SchemeParameters::newmark_gamma;
    case SchemeParameter::penalty:
      return &SchemeParameters::penalty;
    case SchemeParameter::nitsche_theta:
      return &SchemeParameters::nitsche_theta;
    case SchemeParameter::nitsche_gamma:
      return &SchemeParameters::nitsche_gamma;
    case SchemeParameter::moreau_theta:
      return &SchemeParameters::moreau_theta;
    case SchemeParameter::contact_row:
    case SchemeParameter::ps_start:
    case SchemeParameter::mass_lumping:
      return nullptr;
  }  // no default: a parameter added without a case is a -Wswitch warning
  return nullptr;
}

double SchemeParameters::*checked_real_member(SchemeParameter parameter) {
  double SchemeParameters::*member = real_member(parameter);
  if (!member) throw std::invalid_argument(to_string(parameter) + " is not a real parameter (it is named)");
  return member;
}

}  // namespace

double number(const SchemeParameters& parameters, SchemeParameter parameter) {
  return parameters.*checked_real_member(parameter);
}

void set_number(SchemeParameters& parameters, SchemeParameter parameter, double value) {
  parameters.*checked_real_member(parameter) = value;
}

std::string choice(const SchemeParameters& p, SchemeParameter parameter) {
  switch (parameter) {
    case SchemeParameter::contact_row:
      return to_string(p.contact_row);
    case SchemeParameter::ps_start:
      return p.ps_explicit_start ? "explicit" : "cn";
    case SchemeParameter::mass_lumping:
      return to_string(p.lumping);
    default:
      throw std::invalid_argument(to_string(parameter) + " is not a named parameter (it is real)");
  }
}

void set_choice(SchemeParameters& p, SchemeParameter parameter, const std::string& value) {
  switch (parameter) {
    case SchemeParameter::contact_row:
      p.contact_row = contact_row_by_name(value);
      return;
    case SchemeParameter::ps_start:
      if (value != "cn" && value != "explicit")
        throw std::invalid_argument("unknown first step \"" + value + "\" (allowed: cn, explicit)");
      p.ps_explicit_start = value == "explicit";
      return;
    case SchemeParameter::mass_lumping:
      p.lumping = mass_lumping_by_name(value);
      return;
    default:
      throw std::invalid_argument(to_string(parameter) + " is not a named parameter (it is real)");
  }
}

bool is_default(const SchemeParameters& parameters, SchemeParameter parameter) {
  const SchemeParameters defaults;
  if (parameter_spec(parameter).choices.empty()) return number(parameters, parameter) == number(defaults, parameter);
  return choice(parameters, parameter) == choice(defaults, parameter);
}

TEST_CASE("every scheme parameter has one spec, named as to_string says, read and written through it") {
  const std::vector<ParameterSpec>& specs = scheme_parameter_specs();
  REQUIRE(specs.size() == static_cast<std::size_t>(SchemeParameter::mass_lumping) + 1);
  std::vector<std::string> options;
  for (std::size_t k = 0; k < specs.size(); ++k) {
    const ParameterSpec& spec = specs[k];
    CAPTURE(spec.name);
    CHECK(static_cast<std::size_t>(spec.parameter) == k);
    CHECK(to_string(spec.parameter) == spec.name);
    CHECK(spec.option.rfind("--", 0) == 0);
    CHECK(!spec.help.empty());
    CHECK(std::find(options.begin(), options.end(), spec.option) == options.end());  // each option once
    options.push_back(spec.option);
    SchemeParameters p;
    CHECK(is_default(p, spec.parameter));
    if (spec.choices.empty()) {
      // The default lies in the range a program accepts, and a value written is the value read.
      const double d = number(p, spec.parameter);
      CHECK((spec.lowest_excluded ? d > spec.lowest : d >= spec.lowest));
      CHECK(d <= spec.highest);
      set_number(p, spec.parameter, spec.highest);
      CHECK(number(p, spec.parameter) == spec.highest);
      CHECK(is_default(p, spec.parameter) == (d == spec.highest));
      CHECK_THROWS_AS(choice(p, spec.parameter), std::invalid_argument);
    } else {
      // Every choice reads back; the default is one of them.
      CHECK(std::find(spec.choices.begin(), spec.choices.end(), choice(p, spec.parameter)) != spec.choices.end());
      for (const std::string& value : spec.choices) {
        set_choice(p, spec.parameter, value);
        CHECK(choice(p, spec.parameter) == value);
      }
      CHECK_THROWS_AS(set_choice(p, spec.parameter, "no-such-choice"), std::invalid_argument);
      CHECK_THROWS_AS(number(p, spec.parameter), std::invalid_argument);
    }
  }
}

}  // namespace mrm
