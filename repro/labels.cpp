// The table of labels: see labels.hpp.
#include "labels.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include <doctest/doctest.h>

#include "exact/benchmarks.hpp"
#include "measures/errors.hpp"
#include "fem/mass_redistribution.hpp"

namespace mrm::repro {

const Label& scheme_label(Scheme scheme) {
  // One label per entry of mrm::scheme_registry(), read from the entry (lib/time/scheme_registry.cpp).
  static const std::vector<Label> labels = [] {
    std::vector<Label> all;
    for (const SchemeInfo& info : scheme_registry())
      all.push_back({info.id, info.plain, info.latex, info.abbreviation});
    return all;
  }();
  const auto& registry = scheme_registry();
  for (std::size_t k = 0; k < registry.size(); ++k)
    if (registry[k].scheme == scheme) return labels[k];
  throw std::logic_error("scheme_label: a scheme without a registry entry");
}

const Label& scheme_label(const std::string& id) { return scheme_label(scheme_by_name(id)); }

std::string scheme_row_label(const std::string& id, const std::string& ps_form) {
  const Scheme scheme = scheme_by_name(id);
  return scheme_label(scheme).latex + (takes(scheme, SchemeParameter::contact_row) ? ", " + ps_form + " row" : "");
}

Label mass_label(const std::string& spec) {
  static const std::array<Label, 4> labels{{{"consistent", "consistent mass", "consistent mass", "consistent"},
                                            {"mod1", "Mod 1", "Mod~1", "Mod 1"},
                                            {"mod2", "Mod 2", "Mod~2", "Mod 2"},
                                            {"mod3", "Mod 3", "Mod~3", "Mod 3"}}};
  for (const Label& label : labels)
    if (label.id == spec) return label;
  return {spec, spec, spec, spec};
}

const std::array<Label, 8>& measure_labels() {
  static const std::array<Label, 8> labels{{
      {ErrorAccumulator::names[0], "u(0,·), L²_t", "$u(0,\\cdot)$, $L^2_t$"},
      {ErrorAccumulator::names[1], "λ, L²_t", "$\\lambda$, $L^2_t$"},
      {ErrorAccumulator::names[2], "u, L∞_t L²", "$u$, $L^\\infty_t L^2$"},
      {ErrorAccumulator::names[3], "u, L∞_t H¹", "$u$, $L^\\infty_t H^1$"},
      {ErrorAccumulator::names[4], "u_t, L∞_t L²", "$u_t$, $L^\\infty_t L^2$"},
      {ErrorAccumulator::names[5], "u, L²_t L²", "$u$, $L^2_t L^2$"},
      {ErrorAccumulator::names[6], "u, L²_t H¹", "$u$, $L^2_t H^1$"},
      {ErrorAccumulator::names[7], "u_t, L²_t L²", "$u_t$, $L^2_t L^2$"},
  }};
  return labels;
}

std::vector<std::string> benchmark_names() {
  std::vector<std::string> names;
  for (const Benchmark& b : benchmarks()) names.push_back(b.id);
  return names;
}

const std::vector<std::string>& scheme_names() {
  static const std::vector<std::string> names{to_string(Scheme::crank_nicolson), to_string(Scheme::backward_euler),
                                              to_string(Scheme::paoli_schatzman)};
  return names;
}

const std::vector<std::string>& mass_names() {
  static const std::vector<std::string> names{"mod1", "mod2", "mod3"};
  return names;
}

std::vector<std::string> scheme_ids() {
  std::vector<std::string> ids;
  for (const SchemeInfo& info : scheme_registry()) ids.push_back(info.id);
  return ids;
}

std::string scheme_help(const std::string& what) {
  std::string help = what + ":";
  for (const SchemeInfo& info : scheme_registry()) help += "\n" + info.id + " = " + info.summary;
  return help;
}

std::string benchmark_help(const std::string& what) {
  std::string help = what + ":";
  for (const Benchmark& b : benchmarks()) help += "\n" + b.id + " = " + b.summary;
  return help;
}

void write_labels(std::ostream& out) {
  for (const SchemeInfo& info : scheme_registry())
    out << "# label " << info.id << " = " << scheme_label(info.scheme).plain << '\n';
  for (const std::string& id : mass_redistribution_names())
    out << "# label " << id << " = " << mass_label(id).plain << '\n';
}

void write_scheme_titles(std::ostream& out, const std::string& contact_row) {
  for (const SchemeInfo& info : scheme_registry())
    out << "# title " << info.id << " = " << scheme_label(info.scheme).plain
        << (takes(info.scheme, SchemeParameter::contact_row) ? ", " + contact_row + " contact row" : "") << '\n';
}

TEST_CASE("every scheme and named mass of the library's registries has its label, under its id") {
  for (const SchemeInfo& info : scheme_registry()) {
    CAPTURE(info.id);
    CHECK(scheme_label(info.scheme).id == info.id);
    CHECK(scheme_label(info.id).id == info.id);
  }
  for (const std::string& id : mass_redistribution_names()) {
    CAPTURE(id);
    CHECK(mass_label(id).plain != id);
  }
  CHECK(mass_label("node1:7/6").latex == "node1:7/6");
  for (std::size_t k = 0; k < measure_labels().size(); ++k) CHECK(measure_labels()[k].id == ErrorAccumulator::names[k]);
}

TEST_CASE("a table row names Paoli-Schatzman's contact row, and only for the scheme that takes one") {
  CHECK(scheme_row_label(to_string(Scheme::paoli_schatzman), "literal") ==
        "Paoli--Schatzman $(\\frac14, 0)$, literal row");
  CHECK(scheme_row_label(to_string(Scheme::crank_nicolson), "literal") == "Crank--Nicolson");
}

TEST_CASE("a figure's row title names Paoli-Schatzman's contact row, and only for the scheme that takes one") {
  std::ostringstream out;
  write_scheme_titles(out, "literal");
  const std::string titles = out.str();
  CHECK(titles.find("# title " + to_string(Scheme::paoli_schatzman) +
                    " = Paoli–Schatzman (¼, 0), literal contact row\n") != std::string::npos);
  CHECK(titles.find("# title " + to_string(Scheme::crank_nicolson) + " = Crank–Nicolson\n") != std::string::npos);
}

}  // namespace mrm::repro
