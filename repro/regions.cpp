// Claims judged over regions: the sweep and its two analyses (regions.hpp).
//
// Why a sweep. Every verdict on the paper's claims 3 and 4 is a statement about a region of
// parameters: the ratio Δt/h, the mesh, the horizon, the scheme, the measure (mathematics.md §6). The
// period law (mathematics.md §8) says why the horizon matters for claim 3: Mod 1's period is short by
// 4h/3, Mod 2's by h/3, Mod 3's by O(h²), so the phase error of the impacts grows linearly in time and
// the mass-dependent error overtakes the mass-independent one (the smearing of the fronts) after a
// number of periods that grows as h decreases. Over one period the masses can rank in any order on a
// fine mesh; after enough periods they rank as the paper says. The predicted orders of convergence
// (mathematics.md §9) are the regularity limit of this benchmark: what a criterion on the orders must
// be judged against.
//
// One run per (scheme, mass, Δt/h, N) goes to the longest horizon; its errors over [0, T_k] at the
// shorter horizons are read at the levels where T_k is reached (run_configuration), so the horizons
// cost nothing more. The runs are independent and go to run_configurations's threads, the longest
// first (cost ∝ N²/(Δt/h)), so that no long run starts last.
#include "regions.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <doctest/doctest.h>

#include "studies/convergence.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "parallel.hpp"
#include "fem/period_law.hpp"
#include "sweep.hpp"

namespace mrm::repro {

const SweepRun& Sweep::find(const std::string& scheme, const std::string& mass, double courant, Index elements) const {
  for (const SweepRun& r : runs)
    if (r.scheme == scheme && r.mass == mass && r.courant == courant && r.elements == elements) return r;
  throw std::out_of_range("sweep: no run " + scheme + " " + mass + " dt/h = " + cli::format_real(courant) +
                          " N = " + std::to_string(elements));
}

Sweep run_sweep(const SweepGrid& grid, unsigned threads, std::ostream* progress) {
  if (grid.horizons.empty() || grid.courants.empty() || grid.elements.empty())
    throw std::invalid_argument("sweep: the grid needs horizons, ratios dt/h and meshes");
  Sweep sweep;
  sweep.grid = grid;
  std::vector<Configuration> configurations;
  const double periods = grid.horizons.back();
  for (const std::string& scheme : grid.schemes) {
    for (const std::string& mass : grid.masses) {
      for (double c : grid.courants) {
        for (Index n : grid.elements) {
          sweep.runs.push_back({scheme, mass, c, n, {}, 0, std::nullopt});
          configurations.push_back(paper_configuration(scheme, "algebraic", mass, n, c, 3 * periods));
        }
      }
    }
  }
  if (grid.baseline) {
    for (double c : grid.courants) {
      for (Index n : grid.elements) {
        sweep.runs.push_back({"ps-consistent", "consistent", c, n, {}, 0, std::nullopt});
        configurations.push_back(
            paper_configuration(Scheme::paoli_schatzman, "literal", "consistent", n, c, 3 * periods));
      }
    }
  }
  for (Configuration& c : configurations)
    for (double h : grid.horizons) c.horizons.push_back(3 * h);
  // The longest runs first (their order does not change any result).
  const std::vector<std::size_t> order = costliest_first(configurations.size(), [&](std::size_t k) {
    const double n = static_cast<double>(configurations[k].elements);
    return n * n / configurations[k].courant;
  });
  std::vector<Configuration> sorted;
  for (std::size_t k : order) sorted.push_back(configurations[k]);
  if (progress) *progress << "sweep: " << sorted.size() << " runs to " << cli::format_real(periods) << " periods\n";
  SweepSettings settings = sweep_settings();
  if (threads > 0) settings.threads = threads;
  const std::vector<Measures> measures = run_batched(sorted, settings);
  for (std::size_t j = 0; j < order.size(); ++j) {
    SweepRun& r = sweep.runs[order[j]];
    const Measures& m = measures[j];
    for (const ErrorNorms& e : m.horizon_errors) r.errors.push_back(ErrorAccumulator::values(e));
    if (!m.phase || !m.phase->drift_per_period)
      throw std::runtime_error("sweep: the run " + r.scheme + " " + r.mass + " has fewer than two impacts");
    r.first_impact_error = m.phase->first_impact_error;
    r.drift_per_period = m.phase->drift_per_period;
  }
  if (progress) *progress << "sweep: done\n";
  return sweep;
}

namespace {

template <class T>
std::string list(const std::vector<T>& values) {
  std::string s;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) s += ' ';
    if constexpr (std::is_same_v<T, std::string>)
      s += values[k];
    else if constexpr (std::is_same_v<T, double>)
      s += cli::format_real(values[k]);
    else
      s += std::to_string(values[k]);
  }
  return s;
}

}  // namespace

void write_sweep(std::ostream& out, const Sweep& sweep) {
  const SweepGrid& g = sweep.grid;
  out << "# sweep: the benchmark over schemes x masses x dt/h x N, errors at every horizon (repro/regions.cpp)\n"
      << "# schemes = " << list(g.schemes) << "\n# masses = " << list(g.masses)
      << "\n# baseline = " << (g.baseline ? "true" : "false") << "\n# courants = " << list(g.courants)
      << "\n# elements = " << list(g.elements) << "\n# horizons = " << list(g.horizons) << '\n'
      << "# horizon in periods of 3L; first_impact_error and drift_per_period (time units per period, early < 0)\n"
      << "# are those of the whole run\n# columns: scheme mass courant elements horizon";
  for (const char* name : ErrorAccumulator::names) out << ' ' << name;
  out << " first_impact_error drift_per_period\n";
  for (const SweepRun& r : sweep.runs) {
    for (std::size_t k = 0; k < r.errors.size(); ++k) {
      out << r.scheme << ' ' << r.mass << ' ' << cli::format_real(r.courant) << ' ' << r.elements << ' '
          << cli::format_real(g.horizons[k]);
      for (double e : r.errors[k]) out << ' ' << cli::format_real(e);
      out << ' ' << cli::format_real(r.first_impact_error) << ' ' << cli::format_real(*r.drift_per_period) << '\n';
    }
  }
}

Sweep read_sweep(std::istream& in) {
  Sweep sweep;
  SweepGrid& g = sweep.grid;
  g = SweepGrid{};
  std::string line;
  long number = 0;
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error("sweep file, line " + std::to_string(number) + ": " + what);
  };
  const auto words = [](const std::string& text) {
    std::istringstream s(text);
    std::vector<std::string> w;
    for (std::string x; s >> x;) w.push_back(x);
    return w;
  };
  const auto real = [&](const std::string& text) {
    try {
      return cli::parse_real("sweep", text);
    } catch (const std::exception&) {
      fail(cli::quoted_text(text) + " is not a number");
    }
    return 0.0;
  };
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    if (line[0] == '#') {
      const std::size_t eq = line.find(" = ");
      if (eq == std::string::npos) continue;
      const std::string key = line.substr(2, eq - 2);
      const std::vector<std::string> v = words(line.substr(eq + 3));
      if (key == "schemes")
        g.schemes = v;
      else if (key == "masses")
        g.masses = v;
      else if (key == "baseline")
        g.baseline = v.size() == 1 && v[0] == "true";
      else if (key == "courants") {
        g.courants.clear();
        for (const std::string& x : v) g.courants.push_back(real(x));
      } else if (key == "elements") {
        g.elements.clear();
        for (const std::string& x : v) g.elements.push_back(static_cast<Index>(real(x)));
      } else if (key == "horizons") {
        g.horizons.clear();
        for (const std::string& x : v) g.horizons.push_back(real(x));
      }
      continue;
    }
    const std::vector<std::string> w = words(line);
    if (w.size() != 15) fail("expected 15 columns, found " + std::to_string(w.size()));
    const double courant = real(w[2]), horizon = real(w[4]);
    const Index elements = static_cast<Index>(real(w[3]));
    if (sweep.runs.empty() || sweep.runs.back().scheme != w[0] || sweep.runs.back().mass != w[1] ||
        sweep.runs.back().courant != courant || sweep.runs.back().elements != elements)
      sweep.runs.push_back({w[0], w[1], courant, elements, {}, real(w[13]), real(w[14])});
    SweepRun& r = sweep.runs.back();
    if (r.errors.size() >= g.horizons.size() || g.horizons[r.errors.size()] != horizon)
      fail("horizon " + w[4] + " out of the header's order");
    std::array<double, 8> e{};
    for (std::size_t k = 0; k < 8; ++k) e[k] = real(w[5 + k]);
    r.errors.push_back(e);
  }
  for (const SweepRun& r : sweep.runs)
    if (r.errors.size() != g.horizons.size())
      throw std::runtime_error("sweep file: the run " + r.scheme + " " + r.mass + " N = " + std::to_string(r.elements) +
                               " lacks horizons");
  if (sweep.runs.empty()) throw std::runtime_error("sweep file: no run");
  return sweep;
}

Sweep read_sweep_file(const std::string& path, const std::string& option) {
  // A regular file only: a FIFO without a writer would block the program.
  const std::string problem = cli::input_file_problem(path);
  if (!problem.empty() && problem.rfind("is ", 0) == 0)
    throw cli::UsageError(option + ": cannot read " + cli::quoted_text(path) + ": it " + problem +
                          " (allowed: a regular file written by check_claims --sweep)");
  std::ifstream in(path);
  if (!in)
    throw cli::UsageError(option + ": cannot read " + cli::quoted_text(path) +
                          " (allowed: a file written by check_claims --sweep)");
  return read_sweep(in);
}

std::vector<std::size_t> judged_measures(const std::string& scheme) {
  if (scheme == to_string(Scheme::paoli_schatzman)) return {4, 7};
  return {0, 1, 2, 3, 4, 5, 6, 7};
}

int OrderingCell::count(const std::vector<std::size_t>& measures) const {
  int n = 0;
  for (std::size_t k : measures) n += ordered[k];
  return n;
}

std::vector<OrderingCell> ordering_cells(const Sweep& sweep, const std::vector<std::string>& ordered) {
  if (ordered.size() < 2) throw std::invalid_argument("ordering: needs at least two masses");
  std::vector<OrderingCell> cells;
  for (const std::string& scheme : sweep.grid.schemes)
    for (double c : sweep.grid.courants)
      for (Index n : sweep.grid.elements)
        for (std::size_t h = 0; h < sweep.grid.horizons.size(); ++h) {
          OrderingCell cell{scheme, c, n, h, {}};
          for (std::size_t q = 0; q < 8; ++q) {
            bool holds = true;
            for (std::size_t k = 0; k + 1 < ordered.size(); ++k)
              holds = holds && sweep.find(scheme, ordered[k + 1], c, n).errors[h][q] <
                                   sweep.find(scheme, ordered[k], c, n).errors[h][q];
            cell.ordered[q] = holds;
          }
          cells.push_back(cell);
        }
  return cells;
}

bool displacement_measure(std::size_t k) { return k == 0 || k == 2 || k == 5; }

double PredictedOrders::of(std::size_t measure) const { return displacement_measure(measure) ? displacement : energy; }

PredictedOrders predicted_orders(const std::string& scheme) {
  if (scheme == to_string(Scheme::backward_euler)) return {0.5, 0.25, 0.125};
  return {2.0 / 3, 1.0 / 3, 1.0 / 6};
}

bool mass_drifts(const std::string& mass) {
  const UniformMesh mesh(1.0, 100);
  return std::abs(predict_period(mesh, mass_redistribution_by_name(mass)).period_error) > 0.1 * mesh.h();
}

std::pair<double, double> allowed_order(const std::string& scheme, const std::string& mass, std::size_t measure) {
  const PredictedOrders p = predicted_orders(scheme);
  const double centre = p.of(measure);
  double upper = centre + p.tolerance;
  if (scheme != to_string(Scheme::backward_euler) && mass_drifts(mass)) {
    const DriftOrders d;
    upper = (displacement_measure(measure) ? d.displacement : d.energy) + p.tolerance;
  }
  return {centre - p.tolerance, upper};
}

double observed_order(const std::vector<double>& x, const std::vector<double>& y) {
  try {
    return fit_order(x, y).order;
  } catch (const std::invalid_argument&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

std::vector<OrderCell> order_cells(const Sweep& sweep) {
  std::vector<OrderCell> cells;
  std::vector<double> h;
  for (Index n : sweep.grid.elements) h.push_back(1.0 / static_cast<double>(n));
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& s : sweep.grid.schemes)
    for (const std::string& m : sweep.grid.masses) pairs.emplace_back(s, m);
  if (sweep.grid.baseline) pairs.emplace_back("ps-consistent", "consistent");
  for (const auto& [scheme, mass] : pairs)
    for (double c : sweep.grid.courants)
      for (std::size_t k = 0; k < sweep.grid.horizons.size(); ++k) {
        OrderCell cell{scheme, mass, c, k, {}, {}};
        for (std::size_t q = 0; q < 8; ++q) {
          std::vector<double> e;
          for (Index n : sweep.grid.elements) e.push_back(sweep.find(scheme, mass, c, n).errors[k][q]);
          cell.order[q] = observed_order(h, e);
          const std::pair<double, double> allowed = allowed_order(scheme, mass, q);
          cell.within[q] = cell.order[q] >= allowed.first && cell.order[q] <= allowed.second;
        }
        cells.push_back(cell);
      }
  return cells;
}

std::vector<double> StabilityGrid::stability_courants() {
  std::vector<double> c;
  for (int k = 0; k <= 14; ++k) c.push_back(0.25 * std::pow(2.0, 0.5 * k));  // ¼ … 32
  c.push_back(40);
  return c;
}
std::vector<Index> StabilityGrid::scan_meshes(Index first, Index last) {
  std::vector<Index> n;
  for (Index k = first; k <= last; ++k) n.push_back(k);
  return n;
}

StabilityRegion run_stability_region(const StabilityGrid& grid) {
  StabilityRegion region{grid, {}, {}, {}};
  std::vector<Configuration> configurations;
  std::vector<std::pair<std::vector<StabilityCell>*, StabilityCell>> cells;
  const auto add = [&](std::vector<StabilityCell>* to, const std::string& mass, Index n, double c, double periods) {
    cells.push_back({to, {mass, n, c, periods, 0}});
    configurations.push_back(paper_configuration(Scheme::crank_nicolson, "algebraic", mass, n, c, 3 * periods));
    configurations.back().measure_errors = false;  // the energy is all a cell keeps
  };
  for (Index n : grid.meshes)
    for (double c : grid.courants) add(&region.large, "mod3", n, c, grid.periods);
  for (Index n : grid.scan)
    for (double c : grid.courants)
      if (c <= grid.scan_up_to) add(&region.scan, "mod3", n, c, grid.periods);
  for (const std::string& mass : mass_names())
    for (Index n : grid.meshes) add(&region.long_runs, mass, n, grid.long_courant, grid.long_periods);
  const std::vector<Measures> m = run_batched(configurations);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    cells[k].second.largest = m[k].energy_max / m[k].energy_initial;
    cells[k].first->push_back(cells[k].second);
  }
  return region;
}

double StabilityRegion::worst_at(double courant) const {
  double worst = 0;
  for (const StabilityCell& cell : large)
    if (cell.courant == courant) worst = std::max(worst, cell.largest);
  return worst;
}

double StabilityRegion::bounded_up_to() const {
  double up_to = 0;
  for (double c : grid.courants) {
    if (worst_at(c) > grid.threshold) break;
    up_to = c;
  }
  return up_to;
}

std::vector<std::pair<Index, double>> StabilityRegion::scan_failures() const {
  std::vector<std::pair<Index, double>> failures;
  for (Index n : grid.scan) {
    double worst = 0;
    for (const StabilityCell& cell : scan)
      if (cell.elements == n) worst = std::max(worst, cell.largest);
    if (worst > grid.threshold) failures.emplace_back(n, worst);
  }
  return failures;
}

Index StabilityRegion::bounded_from() const {
  const std::vector<std::pair<Index, double>> failures = scan_failures();
  return failures.empty() ? grid.scan.front() : failures.back().first + 1;
}

// ---------------------------------------------------------------------------------------------------

namespace {
const std::string cn = to_string(Scheme::crank_nicolson);  // the id of the tests' sweeps
}  // namespace

TEST_CASE("a sweep written and read back is the same sweep, and a malformed file names its line") {
  SweepGrid grid;
  grid.schemes = {cn};
  grid.courants = {0.5};
  grid.elements = {10, 20};
  grid.horizons = {1, 2};
  const Sweep sweep = run_sweep(grid, 2);
  REQUIRE(sweep.runs.size() == 3 * 2 + 2);
  std::ostringstream out;
  write_sweep(out, sweep);
  std::istringstream in(out.str());
  const Sweep back = read_sweep(in);
  REQUIRE(back.runs.size() == sweep.runs.size());
  for (std::size_t k = 0; k < sweep.runs.size(); ++k) {
    CHECK(back.runs[k].scheme == sweep.runs[k].scheme);
    CHECK(back.runs[k].errors == sweep.runs[k].errors);
    CHECK(back.runs[k].drift_per_period == sweep.runs[k].drift_per_period);
  }
  CHECK(back.grid.horizons == grid.horizons);
  CHECK(back.grid.elements == grid.elements);
  std::istringstream bad(out.str() + "cn mod1 0.5 10 1 x\n");
  CHECK_THROWS_WITH_AS(read_sweep(bad), doctest::Contains("columns"), std::runtime_error);
}

TEST_CASE(
    "the ordering cells count the measures in which the masses rank as given, and reversing the ranking reverses "
    "them") {
  // Over 10 periods on N = 20, 40 with Δt = h/2, the period law's drift (−4h/3, −h/3, 0 per period)
  // dominates Crank–Nicolson's errors: the paper's ranking holds in most measures, and the reversed
  // list can hold in none of those (strict inequalities).
  SweepGrid grid;
  grid.schemes = {cn};
  grid.courants = {0.5};
  grid.elements = {20, 40};
  grid.horizons = {1, 10};
  grid.baseline = false;
  const Sweep sweep = run_sweep(grid, 2);
  const std::vector<OrderingCell> right = ordering_cells(sweep, {"mod1", "mod2", "mod3"});
  const std::vector<OrderingCell> reversed = ordering_cells(sweep, {"mod3", "mod2", "mod1"});
  REQUIRE(right.size() == 4);
  const std::vector<std::size_t> all = judged_measures(cn);
  for (std::size_t k = 0; k < right.size(); ++k) {
    CAPTURE(k);
    CHECK(right[k].count(all) + reversed[k].count(all) <= 8);
    for (std::size_t q = 0; q < 8; ++q) CHECK(!(right[k].ordered[q] && reversed[k].ordered[q]));
  }
  CHECK(right[1].count(all) >= 6);  // N = 20, 10 periods (measured 8 when this test was written)
  CHECK(right[3].count(all) >= 6);  // N = 40, 10 periods (measured 8)
  CHECK(judged_measures(to_string(Scheme::paoli_schatzman)) == std::vector<std::size_t>{4, 7});
}

TEST_CASE("the order cells fit the orders in h and judge them against the predicted classes") {
  // A synthetic sweep: errors C h^{2/3} in the displacement measures (the prediction) and h^{0.05} in the
  // others (a stagnating error, as a mass that is not 1 + O(h) gives): the first are within 1/6 of
  // 2/3, the second are not within 1/6 of 1/3.
  CHECK(std::abs(predicted_orders(cn).of(0) - 2.0 / 3) < 1e-15);
  CHECK(std::abs(predicted_orders(cn).of(1) - 1.0 / 3) < 1e-15);
  CHECK(std::abs(predicted_orders(to_string(Scheme::backward_euler)).of(3) - 0.25) < 1e-15);
  Sweep sweep;
  sweep.grid.schemes = {cn};
  sweep.grid.masses = {"mod3"};
  sweep.grid.baseline = false;
  sweep.grid.courants = {0.5};
  sweep.grid.elements = {10, 20, 40, 80};
  sweep.grid.horizons = {1};
  for (Index n : sweep.grid.elements) {
    const double h = 1.0 / static_cast<double>(n);
    std::array<double, 8> e{};
    for (std::size_t q = 0; q < 8; ++q) e[q] = displacement_measure(q) ? 0.3 * std::pow(h, 2.0 / 3) : std::pow(h, 0.05);
    sweep.runs.push_back({cn, "mod3", 0.5, n, {e}, 0.0, 0.0});
  }
  const std::vector<OrderCell> cells = order_cells(sweep);
  REQUIRE(cells.size() == 1);
  for (std::size_t q = 0; q < 8; ++q) {
    CAPTURE(q);
    CHECK(std::abs(cells[0].order[q] - (displacement_measure(q) ? 2.0 / 3 : 0.05)) < 1e-12);
    CHECK(cells[0].within[q] == displacement_measure(q));
  }
}

}  // namespace mrm::repro
