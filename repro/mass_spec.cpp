// The mass option's spec strings: see mass_spec.hpp.
#include "mass_spec.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <system_error>

#include <doctest/doctest.h>

#include "fem/interior_mass.hpp"
#include "options.hpp"

namespace mrm::repro {

// The spec strings of the command line: mod1 | mod2 | mod3 | consistent | node1:X | spread:K | beta:B.
// X and B are a decimal ("1.25", "-0.5", "1e-1") or a fraction of two decimals ("7/6"); K is a positive
// integer. Without a mesh, only what is wrong on every mesh is rejected (unparseable, X ≤ 0, K < 1);
// with the mesh the run will use, also K > N − 1 and a matrix that is not positive definite on the
// nodes that keep inertia (both conditions are the library's: spread_over_first_nodes refuses K ≥ N and
// modified_mass a matrix that is not definite; the parser only words them for the option). The
// redistribution's name is the spec as given, so that a data header shows what the user typed
// ("node1:7/6").

std::string mass_redistribution_forms() {
  std::string forms;
  for (const MassFormInfo& form : mass_form_registry()) forms += (forms.empty() ? "" : ", ") + spelling(form);
  return forms +
         "; X and B decimals or fractions such as 7/6, X > 0, K an integer in 1..N-1, and the mass positive "
         "definite on nodes 1..N-1";
}

std::string mass_option_help(const std::string& what) { return what + ": " + mass_redistribution_forms(); }

namespace {

[[noreturn]] void reject_spec(const std::string& spec, const std::string& why) {
  throw std::invalid_argument(cli::quoted_text(spec) + ": " + why + " (allowed: " + mass_redistribution_forms() + ")");
}

// A finite decimal, the whole text, by the options' strict grammar (cli::parse_real: no spaces, no
// "inf", "nan" or hexadecimal). Returns false if the text is not of that form.
bool parse_decimal(const std::string& text, double& value) try {
  value = cli::parse_real("", text);
  return true;
} catch (const cli::UsageError&) {
  return false;
}

// A decimal or a fraction p/q of two decimals with q ≠ 0 and a finite quotient.
bool parse_fraction(const std::string& text, double& value) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return parse_decimal(text, value);
  double p = 0.0, q = 0.0;
  if (!parse_decimal(text.substr(0, slash), p) || !parse_decimal(text.substr(slash + 1), q) || q == 0.0) return false;
  value = p / q;
  return std::isfinite(value);
}

}  // namespace

MassRedistribution mass_redistribution_from_spec(const std::string& spec, double blend) {
  for (const std::string& name : mass_redistribution_names())
    if (spec == name) return mass_redistribution_by_name(name, blend);
  const std::size_t colon = spec.find(':');
  if (colon == std::string::npos) reject_spec(spec, "unknown mass choice");
  const std::string kind = spec.substr(0, colon), value = spec.substr(colon + 1);
  MassRedistribution r;
  if (kind == "node1" || kind == "beta") {
    double v = 0.0;
    if (!parse_fraction(value, v)) reject_spec(spec, cli::quoted_text(value) + " is not a decimal or a fraction");
    if (kind == "node1" && !(v > 0.0)) reject_spec(spec, "X must be positive");
    r = kind == "node1" ? node1(v, blend) : beta(v, blend);
  } else if (kind == "spread") {
    long k = 0;
    try {
      k = cli::parse_integer("", value);  // the options' grammar of an integer
    } catch (const cli::UsageError&) {
      reject_spec(spec, "K is not an integer");
    }
    if (k < 1) reject_spec(spec, "K must be at least 1");
    r = spread_over_first_nodes(static_cast<Index>(k), blend);
  } else {
    reject_spec(spec, "unknown mass choice");
  }
  r.name = spec;
  return r;
}

MassRedistribution mass_redistribution_from_spec(const std::string& spec, const UniformMesh& mesh, double blend) {
  return assembled_mass_from_spec(spec, mesh, blend).redistribution;
}

AssembledMass assembled_mass_from_spec(const std::string& spec, const UniformMesh& mesh, double blend) {
  const MassRedistribution r = mass_redistribution_from_spec(spec, blend);
  if (spec.rfind("spread:", 0) == 0 && std::stoll(spec.substr(7)) > mesh.elements - 1)
    reject_spec(spec, "K must be at most N - 1 = " + std::to_string(mesh.elements - 1));
  try {
    return assemble_mass(mesh, r);
  } catch (const std::invalid_argument&) {
    reject_spec(spec, "the mass is not positive definite on nodes 1..N-1 for N = " + std::to_string(mesh.elements));
  }
}

std::string interior_mass_forms() { return "consistent, lumped, blend:A with A a decimal or a fraction in [0, 1]"; }

double interior_blend_from_spec(const std::string& spec) {
  if (spec == "consistent") return 0.0;
  if (spec == "lumped") return 1.0;
  double a = 0.0;
  if (spec.rfind("blend:", 0) != 0 || !parse_fraction(spec.substr(6), a) || !(a >= 0.0 && a <= 1.0))
    throw std::invalid_argument(cli::quoted_text(spec) + ": not an interior mass (allowed: " + interior_mass_forms() +
                                ")");
  return interior_blend_from_value(a);
}

TEST_CASE("the interior mass specs read consistent, lumped and blend:A in [0, 1], fractions included") {
  CHECK(interior_blend_from_spec("consistent") == 0.0);
  CHECK(interior_blend_from_spec("lumped") == 1.0);
  CHECK(interior_blend_from_spec("blend:1/4") == 0.25);
  CHECK(interior_blend_from_spec("blend:0.3") == 0.3);
  CHECK(interior_blend_from_spec("blend:0") == 0.0);
  CHECK(interior_blend_from_spec("blend:1") == 1.0);
  for (const char* bad :
       {"blend:1.5", "blend:-0.1", "blend:", "blend:x", "blend:1/0", "blend: 0.5", "Lumped", "blend:nan"})
    CHECK_THROWS_WITH_AS(interior_blend_from_spec(bad), doctest::Contains("(allowed: consistent, lumped, blend:A"),
                         std::invalid_argument);
  // The member is built on the blend: Mod 3's M̄₁₁ = (4/3 + A/6) h.
  const UniformMesh mesh(1.0, 10);
  CHECK(modified_mass(mesh, mass_redistribution_from_spec("mod3", mesh, 0.25)).diag[1] ==
        doctest::Approx((4.0 / 3 + 0.25 / 6) * mesh.h()).epsilon(1e-14));
}

// ---------------------------------------------------------------------------------------------------

namespace {

// max over all entries of |A − B|, on all nodes 0..N (B subtracted exactly: A + (−1) B).
[[maybe_unused]] double max_entry_difference(const UniformMesh& mesh, const MassRedistribution& a,
                                             const MassRedistribution& b) {
  const Tridiagonal d = modified_mass_all_nodes(mesh, a).plus(-1.0, modified_mass_all_nodes(mesh, b));
  return std::max({d.lower.cwiseAbs().maxCoeff(), d.diag.cwiseAbs().maxCoeff(), d.upper.cwiseAbs().maxCoeff()});
}

}  // namespace

TEST_CASE("the spec strings give the members they name, with the spec as the name") {
  const UniformMesh mesh(1.0, 40);
  const double h = mesh.h();
  CHECK(max_entry_difference(mesh, mass_redistribution_from_spec("node1:7/6"), node1(7.0 / 6.0)) <= 1e-16 * h);
  CHECK(max_entry_difference(mesh, mass_redistribution_from_spec("node1:0.5"),
                             mass_redistribution_from_spec("node1:1/2")) == 0.0);
  CHECK(max_entry_difference(mesh, mass_redistribution_from_spec("beta:1/3"), beta(1.0 / 3.0)) <= 1e-16 * h);
  CHECK(max_entry_difference(mesh, mass_redistribution_from_spec("beta:-1e-1"), beta(-0.1)) == 0.0);
  CHECK(max_entry_difference(mesh, mass_redistribution_from_spec("spread:3", mesh), spread_over_first_nodes(3)) == 0.0);
  CHECK(max_entry_difference(mesh, mass_redistribution_from_spec("mod2"), mod2()) == 0.0);
  CHECK(mass_redistribution_from_spec("node1:7/6").name == "node1:7/6");
  CHECK(mass_redistribution_from_spec("spread:39", mesh).name == "spread:39");
  CHECK(mass_redistribution_from_spec("consistent").name == "consistent");
  CHECK(node1(0.5).name == "node1:0.5");
}

TEST_CASE("bad spec strings are rejected with the allowed forms") {
  const UniformMesh mesh(1.0, 40);
  for (const char* bad :
       {"",           "mod4",       "MOD3",      "node1",      "node1:",     "node1:abc", "node1:7/6x", "node1:1/0",
        "node1:0",    "node1:-1/3", "node1:inf", "node1:nan",  "node1:0x10", "node1: 1",  "beta:",      "beta:1//3",
        "beta:1e400", "spread:0",   "spread:-2", "spread:1.5", "spread:",    "spread:2x", "mod3:1"}) {
    CAPTURE(bad);
    CHECK_THROWS_WITH_AS(mass_redistribution_from_spec(bad), doctest::Contains("(allowed: consistent, mod1, mod2"),
                         std::invalid_argument);
  }
  // On the mesh at hand: K ≤ N − 1 and a definite matrix. The first two pivots of node1(X) are X h and
  // 2h/3 − h/(36 X), so X = 0.04 fails at node 2 and X = 0.05 passes (the tail then stays positive).
  CHECK_NOTHROW(mass_redistribution_from_spec("spread:39", mesh));
  CHECK_THROWS_WITH_AS(mass_redistribution_from_spec("spread:40", mesh), doctest::Contains("at most N - 1 = 39"),
                       std::invalid_argument);
  CHECK_NOTHROW(mass_redistribution_from_spec("node1:0.05", mesh));
  CHECK_THROWS_WITH_AS(mass_redistribution_from_spec("node1:0.04", mesh), doctest::Contains("not positive definite"),
                       std::invalid_argument);
  // beta:B needs w = (L − Bh)/(L − 2h/3) > 0, i.e. B < L/h = 40
  CHECK_NOTHROW(mass_redistribution_from_spec("beta:39", mesh));
  CHECK_THROWS_WITH_AS(mass_redistribution_from_spec("beta:41", mesh), doctest::Contains("allowed:"),
                       std::invalid_argument);
}

}  // namespace mrm::repro
