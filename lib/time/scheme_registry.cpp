/// @file scheme_registry.cpp
/// @brief The registry of schemes (scheme_registry.hpp): the families' entries gathered in the order of the
/// enum, with the doctests that every scheme has one complete entry.
#include "time/scheme_registry.hpp"

#include <algorithm>
#include <stdexcept>

#include <doctest/doctest.h>

namespace mrm {

// ---------------------------------------------------------------------------------------------------
// The registry of schemes: the entries of the families, each defined in its family's file, in the order of
// the enum. Every name of a scheme in the library and the harness (help texts, choice lists, data headers,
// claims rows, figure keys) is read from here.

const std::vector<SchemeInfo>& scheme_registry() {
  static const std::vector<SchemeInfo> registry = [] {
    std::vector<SchemeInfo> all;
    for (const std::vector<SchemeInfo>* family :
         {&one_step_form_schemes(), &contact_class_schemes(), &central_difference_schemes()})
      all.insert(all.end(), family->begin(), family->end());
    std::stable_sort(all.begin(), all.end(),
                     [](const SchemeInfo& a, const SchemeInfo& b) { return a.scheme < b.scheme; });
    return all;
  }();
  return registry;
}

const SchemeInfo& scheme_info(Scheme scheme) {
  for (const SchemeInfo& info : scheme_registry())
    if (info.scheme == scheme) return info;
  throw std::logic_error("scheme_info: a scheme without a registry entry");
}

bool takes(Scheme scheme, SchemeParameter parameter) { return scheme_info(scheme).takes(parameter); }

std::string to_string(Scheme s) { return scheme_info(s).id; }

Scheme scheme_by_name(const std::string& name) {
  std::string allowed;
  for (const SchemeInfo& info : scheme_registry()) {
    if (info.id == name) return info.scheme;
    allowed += (allowed.empty() ? "" : ", ") + info.id;
  }
  throw std::invalid_argument("unknown scheme \"" + name + "\" (allowed: " + allowed + ")");
}

TEST_CASE("the registry names every scheme once, and its ids read back") {
  REQUIRE(scheme_registry().size() == static_cast<std::size_t>(Scheme::dke) + 1);
  for (std::size_t k = 0; k < scheme_registry().size(); ++k)
    CHECK(static_cast<std::size_t>(scheme_registry()[k].scheme) == k);  // each enum value once, in order
  for (const SchemeInfo& info : scheme_registry()) {
    CAPTURE(info.id);
    CHECK(scheme_by_name(info.id) == info.scheme);
    CHECK(to_string(info.scheme) == info.id);
    CHECK(&scheme_info(info.scheme) == &info);
    CHECK(!info.summary.empty());
  }
  CHECK(to_string(Scheme::switching) == "cn-switch");
  CHECK(takes(Scheme::paoli_schatzman, SchemeParameter::beta));
  CHECK(!takes(Scheme::crank_nicolson, SchemeParameter::beta));
  CHECK(takes(Scheme::switching, SchemeParameter::switch_theta));
  CHECK(!takes(Scheme::backward_euler, SchemeParameter::restitution));
  CHECK(to_string(SchemeParameter::beta) == "beta");
  CHECK(to_string(SchemeParameter::restitution) == "restitution");
  CHECK(to_string(SchemeParameter::contact_row) == "contact_row");
  CHECK(to_string(SchemeParameter::switch_theta) == "switch_theta");
  CHECK(to_string(SchemeParameter::mass_lumping) == "mass_lumping");
  CHECK(takes(Scheme::taylor_flanagan, SchemeParameter::mass_lumping));
  CHECK(!takes(Scheme::explicit_central, SchemeParameter::mass_lumping));
  CHECK_THROWS_WITH_AS(
      scheme_by_name("rk4"),
      "unknown scheme \"rk4\" (allowed: cn, be, ps, ec, cn-switch, newmark, penalty, nitsche, moreau-jean, "
      "taylor-flanagan, explicit, dke)",
      std::invalid_argument);
}

TEST_CASE("every registry entry has its labels, its checks, its step builder and a batched kernel's family") {
  std::vector<std::string> texts;
  for (const SchemeInfo& info : scheme_registry()) {
    CAPTURE(info.id);
    CHECK(!info.plain.empty());
    CHECK(!info.latex.empty());
    CHECK(!info.abbreviation.empty());
    CHECK(std::find(texts.begin(), texts.end(), info.plain) == texts.end());  // labels tell schemes apart
    texts.push_back(info.plain);
    CHECK(info.batch_family >= 0);
    CHECK(static_cast<bool>(info.validate));
    CHECK(static_cast<bool>(info.make_step));
    // A contact class, and only one, has a batched kernel of families 4–6; central differences, 7.
    CHECK((find_entry(contact_class_schemes(), info.scheme) != nullptr) ==
          (info.batch_family >= 4 && info.batch_family <= 6));
    CHECK((find_entry(central_difference_schemes(), info.scheme) != nullptr) == (info.batch_family == 7));
  }
}

}  // namespace mrm
