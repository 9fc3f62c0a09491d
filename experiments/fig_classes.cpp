// fig_classes: the field's contact treatments side by side: every contact class of the
// scheme registry, with the standard mass and, where the class allows it, with Mod 3, on every benchmark
// the harness can run, four meshes and three steps.
//
// What it computes. The classes are the registry's schemes (mrm::scheme_registry) except backward Euler
// (the paper's dissipative reference, not one of Doyen–Ern–Piperno's contact treatments): today cn, ps,
// ec, cn-switch, newmark, penalty, nitsche, moreau-jean, taylor-flanagan, explicit and dke; a scheme added to the registry appears here without a
// change. Each runs with the consistent ("standard") mass and with Mod 3; a pair the library refuses
// (ec with a contact node that has inertia, taylor-flanagan with a massless one, explicit with inertia)
// is listed as refused with the library's reason. Paoli–Schatzman is (¼, 0), its literal row with the
// consistent mass, the algebraic row with Mod 3. The benchmarks are the harness's (benchmark_names())
// that run_configuration accepts (a probe run of one step decides: the field's benchmarks join when the
// finite element side runs them). The grid: N ∈ {25, 50, 100, 200}, Δt = C h with C ∈ {½, 1/√3, 1}:
// 1/√3 is the explicit limit of central differences with the consistent mass (explicit_schemes.cpp),
// 1 the limit with the lumped mass (both explicit schemes), ½ a step every class takes. Each run goes to
// T = 6 (the paper's benchmark: two periods) or 2 (the smooth benchmarks, bar1d's default), and gives:
// the eight relative errors (mathematics.md §5), TV(λ)/TV(λ_exact) over the run and the largest
// penetration max(−u₀) (repro::Measures::lambda_tv_ratio, max_penetration), the energy change per impact (E(T) − E(0))/(E(0) · impacts), and the work
// N × steps; per (benchmark, class, mass, C) the observed order of each error (least-squares slope of
// log error against log h over the four meshes). The long run: the paper's benchmark for 10³ periods
// (10³ impacts, T = 3000) on N = 25 at each C, E(T)/E(0) and the energy every 10 periods.
//
// Cost. ~3·10⁸ node-steps for the matrix and ~10⁸ for the long runs, 2 threads: the program prints
// its own wall time (within 60 s on the 2-core machine; no timed test), and the measured cost of a
// step per node of each class (wall time, so not in the data file: the data stay deterministic).
//
// Sample runs:
//   fig_classes --output output/data/fig_classes.dat --tex output/data/fig_classes.tex
//   fig_classes --threads 1 --no-timing --output c.dat
//
// Data file: block 0 the runs (columns benchmark scheme mass courant elements h dt, the eight errors,
// tv_ratio max_penetration energy_change_per_impact impacts node_steps); block 1 the observed orders
// (benchmark scheme mass courant, the eight orders); block 2 the long runs (scheme mass courant impacts
// energy_ratio); block 3 the long runs' energy every 10 periods (scheme mass courant periods energy_ratio);
// block 4 the largest nodal error at dt = h (scheme mass elements T max_nodal_error); block 5 explicit penalty's
// measured region (elements gamma0 fraction periods energy_max_ratio stopped); block 6 explicit Nitsche's
// (elements theta gamma0 fraction periods energy_max_ratio stopped).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "figure_program.hpp"
#include "labels.hpp"
#include "memoized_reference.hpp"
#include "options.hpp"
#include "report_values.hpp"
#include "sweep.hpp"
#include "table.hpp"

#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"
#include "exact/impact_solution.hpp"
#include "fem/mass_redistribution.hpp"
#include "classes/contact_classes.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;
namespace repro = mrm::repro;

namespace {

// One class with one mass.
struct ClassWithMass {
  mrm::Scheme scheme;
  std::string mass;
  std::string id() const { return mrm::to_string(scheme) + "+" + mass; }
};

// What one run measures.
struct MatrixRunMeasures {
  bool run = false;
  std::array<double, 8> errors{};
  double tv_ratio = 0, penetration = 0, energy_per_impact = 0, work = 0, seconds = 0;
  std::size_t impacts = 0;
};

// What one long run measures.
struct LongRunMeasures {
  bool run = false;
  double energy_ratio = 0, work = 0;
  std::size_t impacts = 0;
  std::vector<double> every_ten;  // E/E(0) every 10 periods
};

repro::Configuration configuration_of(const ClassWithMass& c, const std::string& benchmark, mrm::Index elements,
                                      double courant, double final_time) {
  repro::Configuration configuration = repro::paper_configuration(
      c.scheme, c.mass == "consistent" ? "literal" : "algebraic", c.mass, elements, courant, final_time);
  configuration.benchmark = benchmark;
  // two-bars by symmetry (repro::reduce_two_bars_by_symmetry: each body as one free bar against a wall at
  // g₀/2, γ₀' = 2γ₀ for penalty and Nitsche): every class runs it, where the two-body run takes cn only.
  if (benchmark == "two-bars") repro::reduce_two_bars_by_symmetry(configuration);
  return configuration;
}

// Why a class refuses a mass (the library's reason), or "" if it runs it.
std::string refusal(const ClassWithMass& c) {
  try {
    const repro::Configuration configuration = configuration_of(c, "paper", 25, 0.5, 3.0);
    const mrm::UniformMesh mesh(1.0, 25);
    mrm::BarSimulation(repro::configuration_problem(configuration), mesh, configuration.mass, configuration.scheme,
                       configuration.step(), configuration.initial);
  } catch (const mrm::InvalidParameter& e) {
    return e.what();
  }
  return "";
}

// The horizon of a benchmark's runs: its registry entry's default (two periods of 3 on the paper's, 2 on
// the smooth ones, a field benchmark's own in its time unit).
double horizon_of(const std::string& benchmark) { return mrm::benchmark(benchmark).final_time; }

// Whether run_configuration runs a benchmark with every case of the matrix (a probe of one step each), and
// why not: the first refusal, named by its case. A benchmark joins the matrix only whole, so that every
// table compares every class on it (the field's benchmarks with a gap or a load are refused by the classes
// that take neither, e.g. EC and a gap).
std::string benchmark_refusal(const std::string& benchmark, const std::vector<ClassWithMass>& cases) {
  for (const ClassWithMass& c : cases) {
    try {
      repro::Configuration probe = configuration_of(c, benchmark, 10, 0.5, horizon_of(benchmark));
      probe.steps = 1;
      repro::run_configuration(probe);
    } catch (const std::exception& e) {
      return c.id() + ": " + e.what();
    }
  }
  return "";
}

double slope(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(h.size());
  for (std::size_t k = 0; k < h.size(); ++k) {
    const double x = std::log(h[k]), y = std::log(e[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The geometric mean of the measures `used` (a benchmark's common set, below).
double geometric_mean(const std::array<double, 8>& values, const std::array<bool, 8>& used) {
  double log_sum = 0;
  int count = 0;
  for (std::size_t q = 0; q < 8; ++q)
    if (used[q]) log_sum += std::log(values[q]), ++count;
  return count ? std::exp(log_sum / count) : std::nan("");
}

// Blocks 5 and 6 and their tables: the measured regions of explicit penalty and explicit Nitsche (the
// comment at the call says what is run and checked).
void write_explicit_regions(std::ostream& out, std::ostream& defs, long threads, bool no_timing) {
  const std::vector<double> fractions{0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.99};
  const std::vector<double> horizons{10.0, 100.0, 1000.0};
  struct RegionRun {
    mrm::Scheme scheme;
    mrm::Index elements;
    double theta, gamma0, fraction;
    std::vector<double> ratio;  // per horizon; 1e3 when stopped
    std::vector<bool> stopped;
    double seconds = 0;
  };
  std::vector<RegionRun> region;
  for (const mrm::Index n : {16, 64}) {
    for (const double g : {1.0, 10.0, 100.0})
      for (const double r : fractions) region.push_back({mrm::Scheme::penalty, n, 0.0, g, r, {}, {}});
    for (const double theta : {0.0, 1.0})
      for (const double g : {5.0, 50.0})
        for (const double r : fractions) region.push_back({mrm::Scheme::nitsche, n, theta, g, r, {}, {}});
  }
  // Through the sweep layer (repro/sweep.hpp): the runs of one mesh and law make one batch (the caller's
  // keys), stepped in vector lanes (the Newmark-type kernel, lib/batched/batched_step.cpp: each lane bitwise its run
  // alone); a run that stops, or has reached its last horizon, stays as it is while the others go on.
  std::vector<repro::BatchKey> keys;
  std::vector<double> costs;
  std::vector<double> e0(region.size()), largest(region.size(), 1.0);
  std::vector<char> stopped(region.size(), 0);  // (not vector<bool>: runs on different threads write it)
  std::vector<std::vector<mrm::Index>> horizon_steps(region.size());
  using Clock = std::chrono::steady_clock;
  std::vector<Clock::time_point> began(region.size()), ended(region.size());
  // Run k: Newmark (0, ½) with the law and the consistent mass, Δt = r Δt_max; its levels of the horizons.
  const mrm::MassRedistribution mass = mrm::mass_redistribution_by_name("consistent");
  std::vector<mrm::SchemeParameters> parameters(region.size());
  std::vector<double> dt(region.size());
  for (std::size_t k = 0; k < region.size(); ++k) {
    const RegionRun& x = region[k];
    const mrm::UniformMesh mesh(1.0, x.elements);
    mrm::SchemeParameters& p = parameters[k];
    p.scheme = x.scheme;
    p.newmark_beta = 0.0;
    p.newmark_gamma = 0.5;
    if (x.scheme == mrm::Scheme::penalty) p.penalty = x.gamma0;
    if (x.scheme == mrm::Scheme::nitsche) p.nitsche_gamma = x.gamma0, p.nitsche_theta = x.theta;
    const double limit =
        mrm::newmark_stability_limit(mrm::modified_mass(mesh, mass), mrm::p1_stiffness(mesh), p, mesh.h());
    dt[k] = x.fraction * limit;
    for (const double periods : horizons) {
      if (x.elements > 16 && periods > 100) break;
      horizon_steps[k].push_back(mrm::steps_to_reach(3.0 * periods, dt[k]));
    }
    // One batch per mesh and law; in it, runs of similar numbers of steps share the lanes of a group.
    keys.emplace_back(x.elements, x.scheme == mrm::Scheme::penalty ? 0 : 1);
    costs.push_back(static_cast<double>(x.elements * horizon_steps[k].back()));
  }
  // The largest E/E₀ up to each horizon's level, 1e3 once the run has passed 1e3 E₀ (it then stops).
  const auto follow = [&](std::size_t k, const mrm::Sample& s) {
    RegionRun& x = region[k];
    if (s.level == 0) {
      e0[k] = s.energy;
      return true;
    }
    largest[k] = std::max(largest[k], s.energy / e0[k]);
    stopped[k] = !(largest[k] <= 1e3);
    while (x.ratio.size() < horizon_steps[k].size() && (stopped[k] || s.level == horizon_steps[k][x.ratio.size()])) {
      x.ratio.push_back(stopped[k] ? 1e3 : largest[k]);
      x.stopped.push_back(stopped[k]);
    }
    return x.ratio.size() < horizon_steps[k].size();
  };
  repro::SweepSettings settings;
  settings.threads = static_cast<unsigned>(threads);
  repro::step_in_batches(
      keys, costs,
      [&](std::size_t k, mrm::Index& steps) {
        began[k] = Clock::now();
        steps = horizon_steps[k].back();
        return mrm::BarSimulation(mrm::benchmark_problem(), mrm::UniformMesh(1.0, region[k].elements), mass,
                                  parameters[k], dt[k]);
      },
      follow, [&](std::size_t k) { ended[k] = Clock::now(); }, settings,
      // The energy only: the lanes are read in place.
      [&](std::size_t k, const mrm::Sample& s, const mrm::LaneVectors&) -> std::optional<bool> { return follow(k, s); },
      {}, region.size(), /*own_rates=*/true);
  // Each key is one batch: a law's time is the sum of its batches' wall times, a run's its share (printed, not
  // in the data).
  for (RegionRun& x : region) {
    Clock::time_point first = Clock::time_point::max(), last = Clock::time_point::min();
    std::size_t count = 0;
    for (std::size_t m = 0; m < region.size(); ++m)
      if (region[m].scheme == x.scheme && region[m].elements == x.elements)
        first = std::min(first, began[m]), last = std::max(last, ended[m]), ++count;
    x.seconds = std::chrono::duration<double>(last - first).count() / static_cast<double>(count);
  }
  for (const mrm::Scheme law : {mrm::Scheme::penalty, mrm::Scheme::nitsche}) {
    const bool penalty = law == mrm::Scheme::penalty;
    const std::string name = mrm::to_string(law);
    out << "\n\n# block " << (penalty ? 5 : 6) << ": explicit " << name
        << " (Newmark beta = 0, gamma = 1/2, consistent mass, paper's benchmark): E_max/E0 up to a horizon at dt = "
           "fraction * dt_max (the linear limit); 1e3 with stopped = 1: the run passed 1e3 E0 and was stopped\n"
        << (penalty ? "# columns: elements gamma0 fraction periods energy_max_ratio stopped\n"
                    : "# columns: elements theta gamma0 fraction periods energy_max_ratio stopped\n");
    std::vector<std::string> head{"$N$"};
    if (!penalty) head.push_back("$\\theta$");
    head.insert(head.end(), {"$\\gamma_0$", "periods"});
    for (const double r : fractions) head.push_back(cli::format_real(r));
    repro::Table region_table(head);
    double seconds = 0;
    for (const RegionRun& x : region)
      if (x.scheme == law) seconds += x.seconds;
    std::string mismatch;  // thrown after the table is printed
    for (std::size_t h = 0; h < horizons.size(); ++h) {
      // The edge: the largest grid fraction r such that every run at every r' <= r kept E_max <= 2 E0.
      double edge = 0;
      for (const double r : fractions) {
        bool safe = true;
        for (const RegionRun& x : region)
          if (x.scheme == law && x.fraction <= r && h < x.ratio.size())
            safe = safe && !x.stopped[h] && x.ratio[h] <= 2.0;
        if (!safe) break;
        edge = r;
      }
      mrm::tex_define(defs, "classes:" + name + "-region:edge:" + cli::format_real(horizons[h]),
                      cli::format_real(edge));
      std::cout << "explicit " << name << ": E_max <= 2 E0 up to " << horizons[h] << " periods for dt <= " << edge
                << " dt_max (measured)\n";
      const double library =
          penalty ? mrm::penalty_measured_safe_fraction(horizons[h]) : mrm::nitsche_measured_safe_fraction(horizons[h]);
      if (edge != library && mismatch.empty())
        mismatch = ("block " + std::string(penalty ? "5" : "6") + ": the measured edge of explicit " + name +
                    "'s region up to " + cli::format_real(horizons[h]) + " periods is " + cli::format_real(edge) +
                    ", but lib/classes/contact_classes.cpp's " + name + "_measured_safe_fraction says " +
                    cli::format_real(library) + " (bar1d's warning uses it): update the one or the other");
      for (const RegionRun& x : region) {
        if (x.scheme != law || h >= x.ratio.size() || x.fraction != fractions.front()) continue;
        std::vector<std::string> row{std::to_string(x.elements)};
        if (!penalty) row.push_back(cli::format_real(x.theta));
        row.insert(row.end(), {cli::format_real(x.gamma0), cli::format_real(horizons[h])});
        for (const RegionRun& y : region)
          if (y.scheme == law && y.elements == x.elements && y.gamma0 == x.gamma0 && y.theta == x.theta)
            row.push_back(y.stopped[h] ? "$>10^3$" : mrm::tex_number(y.ratio[h], 3));
        region_table.add_row(row);
      }
      region_table.add_rule();
    }
    for (const RegionRun& x : region) {
      if (x.scheme != law) continue;
      for (std::size_t h = 0; h < x.ratio.size(); ++h) {
        out << x.elements << ' ';
        if (!penalty) out << cli::format_real(x.theta) << ' ';
        out << cli::format_real(x.gamma0) << ' ' << cli::format_real(x.fraction) << ' ' << cli::format_real(horizons[h])
            << ' ' << cli::format_real(x.ratio[h]) << ' ' << x.stopped[h] << '\n';
      }
    }
    std::ostringstream tex;
    repro::LatexLayout layout;
    layout.columns = std::string(penalty ? "rrr" : "rrrr") + std::string(fractions.size(), 'r');
    region_table.write_latex(tex, layout);
    mrm::tex_define(defs, "classes:" + name + "-region", tex.str());
    std::cout << "explicit " << name << ", E_max/E0 (rows N, " << (penalty ? "" : "theta, ")
              << "gamma0, periods; columns dt/dt_max):\n";
    region_table.write_markdown(std::cout);
    if (!no_timing)
      std::cout << "explicit " << name << "'s region: " << cli::format_real(std::round(seconds * 100) / 100)
                << " CPU-s\n";
    if (!mismatch.empty()) throw std::runtime_error(mismatch);
  }
}

// Block 4: the largest nodal error at Δt = h on the paper's benchmark (the comment at the call says which
// schemes and horizons), with its values.
void write_nodal_errors(std::ostream& out, std::ostream& defs) {
  out << "\n\n# block 4: the largest nodal error at dt = h on the paper's benchmark (t <= T)\n"
         "# columns: scheme mass elements T max_nodal_error\n";
  const mrm::ExactSolution exact;
  const auto nodal = [&](mrm::Scheme scheme, const std::string& mass, mrm::Index n, double horizon) {
    const mrm::UniformMesh mesh(1.0, n);
    mrm::SchemeParameters p;
    p.scheme = scheme;
    mrm::BarSimulation simulation(mrm::benchmark_problem(), mesh, mrm::mass_redistribution_by_name(mass), p, mesh.h());
    double worst = 0;
    mrm::run(simulation, mrm::steps_to_reach(horizon, mesh.h()) - (horizon < 1.5 ? 1 : 0), [&](const mrm::Sample& x) {
      for (mrm::Index i = 0; i < n; ++i)
        worst = std::max(worst, std::abs((*x.displacement)[i] - exact.displacement(mesh.x(i), x.time)));
    });
    out << mrm::to_string(scheme) << ' ' << mass << ' ' << n << ' ' << cli::format_real(horizon) << ' '
        << cli::format_real(worst) << '\n';
    return worst;
  };
  for (const mrm::Index n : {20, 40, 80}) {
    const std::string N = std::to_string(n);
    mrm::tex_define(defs, "classes:dth:explicit:" + N,
                    mrm::tex_number(nodal(mrm::Scheme::explicit_central, "mod3", n, 3.0), 2));
    mrm::tex_define(defs, "classes:dth:cn:" + N,
                    mrm::tex_number(nodal(mrm::Scheme::crank_nicolson, "mod3", n, 3.0), 2));
    mrm::tex_define(defs, "classes:dth:tf-free:" + N,
                    mrm::tex_number(nodal(mrm::Scheme::taylor_flanagan, "consistent", n, 1.0), 2));
    mrm::tex_define(defs, "classes:dth:tf:" + N,
                    mrm::tex_number(nodal(mrm::Scheme::taylor_flanagan, "consistent", n, 3.0), 2));
  }
}

// The grid of the matrix: the meshes and the ratios Δt/h; the long runs' mesh and horizon (periods).
const std::vector<mrm::Index> meshes{25, 50, 100, 200};
const std::vector<double> courants{0.5, 1 / std::sqrt(3.0), 1.0};
constexpr double long_periods = 1000;
constexpr mrm::Index long_mesh = 25;

// The matrix, decided before any long work: the class-mass pairs run and those refused (with the reason),
// the benchmarks run and those left out (a probe run decides).
struct Matrix {
  std::vector<ClassWithMass> cases;
  std::vector<std::pair<std::string, std::string>> refused;
  std::vector<std::string> benchmarks;
  std::vector<std::pair<std::string, std::string>> skipped;
};

Matrix decide_matrix() {
  Matrix matrix;
  for (const mrm::SchemeInfo& info : mrm::scheme_registry()) {
    if (info.scheme == mrm::Scheme::backward_euler) continue;
    for (const std::string mass : {"consistent", "mod3"}) {
      const ClassWithMass c{info.scheme, mass};
      // dke with a massless contact node is Crank–Nicolson's run with the same mass (the projection moves
      // no node with mass; lib/classes/contact_classes.cpp, the doctest "dke: ...": 4e-13): not run twice.
      const std::string why = info.scheme == mrm::Scheme::dke && mass == "mod3"
                                  ? "not run: the same run as cn+mod3 (with a massless contact node the projection "
                                    "moves no node with mass; doctest in lib/classes/contact_classes.cpp)"
                                  : refusal(c);
      if (why.empty())
        matrix.cases.push_back(c);
      else
        matrix.refused.emplace_back(c.id(), why);
    }
  }
  for (const std::string& b : repro::benchmark_names()) {
    const std::string why = benchmark_refusal(b, matrix.cases);
    if (why.empty())
      matrix.benchmarks.push_back(b);
    else
      matrix.skipped.emplace_back(b, why);
  }
  return matrix;
}

// The data file's header: the refusals, the two-bars reduction, the colours of the plots and the long runs.
void write_header(std::ostream& out, const Matrix& matrix) {
  for (const auto& [id, why] : matrix.refused) out << "# refused: " << id << ": " << why << '\n';
  for (const auto& [b, why] : matrix.skipped) out << "# benchmark not run: " << b << ": " << why << '\n';
  if (std::find(matrix.benchmarks.begin(), matrix.benchmarks.end(), "two-bars") != matrix.benchmarks.end())
    out << "# two-bars by symmetry: each body as one free bar (L = 10, velocity -0.1) against a wall at g0/2 = 0, "
           "penalty and Nitsche with gamma0' = 2 gamma0 (repro::reduce_two_bars_by_symmetry), the chain's exact "
           "solution "
           "seen from one body as the reference\n";
  // One colour per class (its position in the registry); the mass is the line's dash (figures/fig_classes_*.gp).
  static const char* const palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                        "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};
  for (std::size_t k = 0; k < mrm::scheme_registry().size(); ++k)
    out << "# colour " << mrm::scheme_registry()[k].id << " = " << palette[k % 10] << '\n';
  out << "# long_mesh = " << long_mesh << "\n# long_periods = " << long_periods << '\n';
}

// One run of the matrix (benchmark, class-mass pair, mesh, Δt/h), or of the long runs (c and courant).
struct Job {
  std::size_t benchmark, c, mesh, courant;
};

// The runs and what they measured: the matrix's, in the order (benchmark, pair, mesh, Δt/h), then the
// long runs', in the order (pair, Δt/h).
struct Study {
  const Matrix& matrix;
  std::vector<Job> jobs;
  std::size_t long_first = 0;  ///< the index of the first long run in jobs
  std::vector<MatrixRunMeasures> cells;
  std::vector<LongRunMeasures> longs;

  explicit Study(const Matrix& m) : matrix(m) {
    for (std::size_t b = 0; b < matrix.benchmarks.size(); ++b)
      for (std::size_t c = 0; c < matrix.cases.size(); ++c)
        for (std::size_t a = 0; a < meshes.size(); ++a)
          for (std::size_t k = 0; k < courants.size(); ++k) jobs.push_back({b, c, a, k});
    long_first = jobs.size();
    for (std::size_t c = 0; c < matrix.cases.size(); ++c)
      for (std::size_t k = 0; k < courants.size(); ++k) jobs.push_back({0, c, 0, k});
    cells.resize(long_first);
    longs.resize(jobs.size() - long_first);
  }
  const MatrixRunMeasures& cell(std::size_t b, std::size_t c, std::size_t a, std::size_t k) const {
    return cells[((b * matrix.cases.size() + c) * meshes.size() + a) * courants.size() + k];
  }
  const LongRunMeasures& long_run(std::size_t c, std::size_t k) const { return longs[c * courants.size() + k]; }
  // The observed orders of (benchmark b, pair c, Δt/h k). An error that is 0 on some mesh (the exact
  // u(0, ·) ≡ 0 held exactly on gravity-paper) has no order: NaN, written as a word.
  std::array<double, 8> orders(std::size_t b, std::size_t c, std::size_t k) const {
    std::array<double, 8> p{};
    for (std::size_t q = 0; q < 8; ++q) {
      std::vector<double> hs, es;
      bool zero = false;
      for (std::size_t a = 0; a < meshes.size(); ++a) {
        hs.push_back(1.0 / static_cast<double>(meshes[a])), es.push_back(cell(b, c, a, k).errors[q]);
        zero = zero || !(es.back() > 0);
      }
      p[q] = zero ? std::nan("") : slope(hs, es);
    }
    return p;
  }
};

// The long runs through the sweep layer (repro/sweep.hpp: the runs of one scheme family in vector lanes,
// each bitwise its run alone), observed for the energy only (the lanes read in place).
void run_long(Study& study, long threads) {
  std::vector<repro::Configuration> configurations;
  std::vector<mrm::Index> every;
  std::vector<double> e0(study.longs.size());
  for (std::size_t k = study.long_first; k < study.jobs.size(); ++k) {
    const Job& job = study.jobs[k];
    repro::Configuration configuration =
        configuration_of(study.matrix.cases[job.c], "paper", long_mesh, courants[job.courant], 3 * long_periods);
    configuration.measure_errors = false;  // a long run keeps its energy and its impacts only
    every.push_back(mrm::steps_to_reach(30.0, configuration.step()));
    configurations.push_back(configuration);
  }
  repro::SweepSettings settings;
  settings.threads = static_cast<unsigned>(threads);
  const std::vector<repro::Measures> measures = repro::run_batched(
      configurations, settings,
      [&](std::size_t k, const mrm::Sample& s) {
        if (s.level == 0) e0[k] = s.energy;
        if (s.level > 0 && s.level % every[k] == 0) study.longs[k].every_ten.push_back(s.energy / e0[k]);
      },
      {}, /*observer_reads_vectors=*/false);
  for (std::size_t k = 0; k < study.longs.size(); ++k) {
    const repro::Measures& m = measures[k];
    LongRunMeasures& l = study.longs[k];
    l.run = true;
    l.energy_ratio = m.energy_final / m.energy_initial;
    l.impacts = m.impacts.size();
    l.work = static_cast<double>(long_mesh) * static_cast<double>(m.steps);
  }
}

// Run k of the matrix, timed. The exact solution of one group of the matrix: the runs of every class-mass
// pair on one benchmark, mesh and Δt ask it the same questions (u and u_t at the nodes, u(0, ·) and λ at
// the instants of their samples: kΔt, and (k ± ½)Δt where a class samples its velocity or its
// multiplier between levels), so it is made once for the group and seen through a record
// (repro::GroupReferences; the same doubles, so the same bytes). A group holds up to ~10 MB: its runs
// come one after the other in the order of the runs (costliest_first), so few are alive at once.
void run_matrix_cell(Study& study, std::size_t k, repro::GroupReferences& references) {
  const Job& job = study.jobs[k];
  const auto start = std::chrono::steady_clock::now();
  MatrixRunMeasures& cell = study.cells[k];
  const std::string& benchmark = study.matrix.benchmarks[job.benchmark];
  const repro::Configuration configuration = configuration_of(study.matrix.cases[job.c], benchmark, meshes[job.mesh],
                                                              courants[job.courant], horizon_of(benchmark));
  // run_configuration(configuration) with the group's reference (its measures but the phase, which a
  // record does not give and this program does not use: repro::MemoizedReference).
  const repro::GroupReferences::Key group{job.benchmark, job.mesh, job.courant};
  repro::ConfigurationRun run(configuration, {}, nullptr, references.source(group));
  mrm::run(run.simulation(), run.steps(), [&](const mrm::Sample& s) { run.add(s); });
  const repro::Measures m = run.measures();
  references.done(group);
  if (!m.lambda_tv_ratio)
    throw std::runtime_error("fig_classes: the exact contact stress does not vary on " + benchmark);
  cell.run = true;
  cell.errors = mrm::ErrorAccumulator::values(m.errors);
  cell.tv_ratio = *m.lambda_tv_ratio;  // repro::Measures (configurations.hpp)
  cell.penetration = m.max_penetration;
  // two-bars' one contact starts at t = 0 (the bars touch), which the impact list (instants t > 0 where
  // a contact begins) leaves out: the run's contact windows (same chatter rule) count it.
  cell.impacts = benchmark == "two-bars" ? m.contact_windows.size() : m.impacts.size();
  // Under a load (bouncing, gravity-paper) the mechanical energy is not conserved by the exact flow (it
  // changes by the load's work; the bouncing bar starts with E = 0): no energy change per impact, NaN
  // (the word "loaded" in the data, n/a in the table).
  const bool loaded = static_cast<bool>(repro::configuration_problem(configuration).load);
  cell.energy_per_impact =
      loaded         ? std::nan("")
      : cell.impacts ? (m.energy_final - m.energy_initial) / (m.energy_initial * static_cast<double>(cell.impacts))
                     : 0.0;
  cell.work = static_cast<double>(meshes[job.mesh]) * static_cast<double>(m.steps);
  cell.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (double v : cell.errors)
    if (!std::isfinite(v))
      throw std::runtime_error("fig_classes: a non-finite error in " + study.matrix.cases[job.c].id());
}

// The matrix's runs as the sweep layer's tasks (repro/sweep.hpp), costliest first: each is stepped
// alone and timed, for the cost per step and node of its class, which a batch would mix.
void run_matrix(Study& study, long threads, repro::GroupReferences& references) {
  std::vector<repro::SweepTask> tasks;
  for (std::size_t k = 0; k < study.long_first; ++k) {
    const Job& job = study.jobs[k];
    const double n = static_cast<double>(meshes[job.mesh]);
    const double cost = n * n * horizon_of(study.matrix.benchmarks[job.benchmark]) / courants[job.courant];
    tasks.push_back({cost, [&study, &references, k] { run_matrix_cell(study, k, references); }});
  }
  repro::SweepSettings settings;
  settings.threads = static_cast<unsigned>(threads);
  repro::run_batched({}, settings, {}, {}, true, tasks);
}

// The measures of a benchmark's geometric mean g: those nonzero in every run on it (on gravity-paper
// the exact u(0, ·) ≡ 0, which exact enforcement reproduces exactly: a mean with a zero in it would be
// 0 for those classes and say nothing), so that g compares the classes on the same measures. Listed in
// the data file's header.
std::vector<std::array<bool, 8>> common_measures(std::ostream& out, const Study& study) {
  const std::vector<std::string>& benchmarks = study.matrix.benchmarks;
  std::vector<std::array<bool, 8>> common(benchmarks.size());
  for (std::size_t b = 0; b < benchmarks.size(); ++b) {
    common[b].fill(true);
    for (std::size_t k = 0; k < study.cells.size(); ++k)
      if (study.jobs[k].benchmark == b)
        for (std::size_t q = 0; q < 8; ++q) common[b][q] = common[b][q] && study.cells[k].errors[q] > 0;
    out << "# geometric mean g on " << benchmarks[b] << " over:";
    for (std::size_t q = 0; q < 8; ++q)
      if (common[b][q]) out << ' ' << mrm::ErrorAccumulator::names[q];
    out << '\n';
  }
  return common;
}

// Blocks 0 to 3: the runs, the observed orders, the long runs and their energy every 10 periods.
void write_data_blocks(std::ostream& out, const Study& study) {
  const std::vector<std::string>& benchmarks = study.matrix.benchmarks;
  const std::vector<ClassWithMass>& cases = study.matrix.cases;
  out << "# block 0: the runs\n# columns: benchmark scheme mass courant elements h dt";
  for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
  out << " tv_ratio max_penetration energy_change_per_impact impacts node_steps\n";
  for (std::size_t b = 0; b < benchmarks.size(); ++b)
    for (std::size_t c = 0; c < cases.size(); ++c)
      for (std::size_t k = 0; k < courants.size(); ++k)
        for (std::size_t a = 0; a < meshes.size(); ++a) {
          const MatrixRunMeasures& x = study.cell(b, c, a, k);
          const double h = 1.0 / static_cast<double>(meshes[a]);
          out << benchmarks[b] << ' ' << mrm::to_string(cases[c].scheme) << ' ' << cases[c].mass << ' '
              << cli::format_real(courants[k]) << ' ' << meshes[a] << ' ' << cli::format_real(h) << ' '
              << cli::format_real(courants[k] * h);
          for (double v : x.errors) out << ' ' << cli::format_real(v);
          out << ' ' << cli::format_real(x.tv_ratio) << ' ' << cli::format_real(x.penetration) << ' '
              << (std::isfinite(x.energy_per_impact) ? cli::format_real(x.energy_per_impact) : "loaded") << ' '
              << x.impacts << ' ' << cli::format_real(x.work) << '\n';
        }
  out << "\n\n# block 1: the observed orders (least-squares slope over N = 25..200)\n"
         "# columns: benchmark scheme mass courant";
  for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
  out << '\n';
  for (std::size_t b = 0; b < benchmarks.size(); ++b)
    for (std::size_t c = 0; c < cases.size(); ++c)
      for (std::size_t k = 0; k < courants.size(); ++k) {
        out << benchmarks[b] << ' ' << mrm::to_string(cases[c].scheme) << ' ' << cases[c].mass << ' '
            << cli::format_real(courants[k]);
        for (double p : study.orders(b, c, k)) out << ' ' << (std::isfinite(p) ? cli::format_real(p) : "no-order");
        out << '\n';
      }
  out << "\n\n# block 2: the long runs (paper, N = " << long_mesh << ", " << long_periods
      << " periods)\n# columns: scheme mass courant impacts energy_ratio\n";
  for (std::size_t c = 0; c < cases.size(); ++c)
    for (std::size_t k = 0; k < courants.size(); ++k)
      out << mrm::to_string(cases[c].scheme) << ' ' << cases[c].mass << ' ' << cli::format_real(courants[k]) << ' '
          << study.long_run(c, k).impacts << ' ' << cli::format_real(study.long_run(c, k).energy_ratio) << '\n';
  out << "\n\n# block 3: the long runs' energy every 10 periods\n# columns: scheme mass courant periods "
         "energy_ratio\n";
  for (std::size_t c = 0; c < cases.size(); ++c)
    for (std::size_t k = 0; k < courants.size(); ++k) {
      const LongRunMeasures& l = study.long_run(c, k);
      for (std::size_t j = 0; j < l.every_ten.size(); ++j)
        out << mrm::to_string(cases[c].scheme) << ' ' << cases[c].mass << ' ' << cli::format_real(courants[k]) << ' '
            << 10 * (j + 1) << ' ' << cli::format_real(l.every_ten[j]) << '\n';
      out << '\n';
    }
}

// The summary's cell: the finest mesh (N = 200) and Δt = h/2.
const std::size_t fine = meshes.size() - 1, half = 0;

// The summary table (stdout and the report): per class and mass, on each benchmark at N = 200 and
// Δt = h/2, the geometric mean of the eight errors, the λ error, TV(λ)/TV(λ_exact), the largest
// penetration, the energy change per impact; the paper's benchmark's order of the geometric mean;
// E(T)/E(0) after 10³ impacts at N = 25, Δt = h/2.
repro::Table summary_table(const Study& study, const std::vector<std::array<bool, 8>>& common) {
  const std::vector<std::string>& benchmarks = study.matrix.benchmarks;
  const std::vector<ClassWithMass>& cases = study.matrix.cases;
  repro::Table table({"benchmark", "class", "mass", "$g$", "$\\lambda$ err", "TV ratio", "max pen.",
                      "$\\Delta E$/impact", "order $g$", "$E/E_0$, $10^3$ imp."});
  for (std::size_t b = 0; b < benchmarks.size(); ++b) {
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const MatrixRunMeasures& x = study.cell(b, c, fine, half);
      std::vector<double> hs, gs;
      for (std::size_t a = 0; a < meshes.size(); ++a)
        hs.push_back(1.0 / static_cast<double>(meshes[a])),
            gs.push_back(geometric_mean(study.cell(b, c, a, half).errors, common[b]));
      table.add_row({benchmarks[b] == "two-bars" ? "two-bars (sym.)" : benchmarks[b], mrm::to_string(cases[c].scheme),
                     cases[c].mass, mrm::tex_number(geometric_mean(x.errors, common[b]), 3),
                     mrm::tex_number(x.errors[1], 3), mrm::tex_number(x.tv_ratio, 3), mrm::tex_number(x.penetration, 2),
                     mrm::tex_number(x.energy_per_impact, 2), mrm::tex_number(slope(hs, gs), 2),
                     b == 0 ? mrm::tex_number(study.long_run(c, half).energy_ratio, 3) : "--"});
    }
    table.add_rule();
  }
  return table;
}

// The summary table for the report, and the matrix the report names: refusals, benchmarks, number of runs.
void write_summary_values(std::ostream& defs, const Study& study, const repro::Table& table) {
  std::ostringstream tex;
  repro::LatexLayout layout;
  layout.columns = "lll" + std::string(table.columns() - 3, 'r');
  layout.longtable = true;  // seven benchmarks × 16 pairs: more than a page
  table.write_latex(tex, layout);
  mrm::tex_define(defs, "classes:summary", tex.str());
  std::string refusals;
  for (const auto& [id, why] : study.matrix.refused) refusals += (refusals.empty() ? "" : "; ") + id;
  mrm::tex_define(defs, "classes:refused", refusals.empty() ? "none" : refusals);
  std::string benchmark_list;
  for (const std::string& b : study.matrix.benchmarks) benchmark_list += (benchmark_list.empty() ? "" : ", ") + b;
  mrm::tex_define(defs, "classes:benchmarks", benchmark_list);
  mrm::tex_define(defs, "classes:runs", std::to_string(study.cells.size() + study.longs.size()));
}

// Values of the summary the report's sentences quote: per benchmark and pair at N = 200, Δt = h/2.
void write_quoted_values(std::ostream& defs, const Study& study, const std::vector<std::array<bool, 8>>& common) {
  const std::vector<std::string>& benchmarks = study.matrix.benchmarks;
  const std::vector<ClassWithMass>& cases = study.matrix.cases;
  for (std::size_t b = 0; b < benchmarks.size(); ++b)
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const MatrixRunMeasures& x = study.cell(b, c, fine, half);
      const std::string key =
          "classes:" + benchmarks[b] + ":" + mrm::to_string(cases[c].scheme) + ":" + cases[c].mass + ":";
      mrm::tex_define(defs, key + "tv", mrm::tex_number(x.tv_ratio, 3));
      mrm::tex_define(defs, key + "g", mrm::tex_number(geometric_mean(x.errors, common[b]), 3));
      mrm::tex_define(defs, key + "lambda", mrm::tex_number(x.errors[1], 3));
      if (b == 0) mrm::tex_define(defs, key + "long", mrm::tex_number(study.long_run(c, half).energy_ratio, 3));
    }
}

// Standard output: the matrix, its refusals and the summary table.
void print_summary(const Study& study, const repro::Table& table) {
  const Matrix& matrix = study.matrix;
  std::cout << "fig_classes: " << matrix.cases.size() << " class-mass pairs x " << matrix.benchmarks.size()
            << " benchmarks x " << meshes.size() << " meshes x " << courants.size() << " steps = " << study.cells.size()
            << " runs, and " << study.longs.size() << " runs of 1000 impacts\n";
  for (const auto& [id, why] : matrix.refused) std::cout << "refused: " << id << ": " << why << '\n';
  for (const auto& [b, why] : matrix.skipped) std::cout << "benchmark not run: " << b << ": " << why << '\n';
  std::cout << "summary (N = 200, dt = h/2; g: geometric mean of the errors nonzero in every run of the benchmark, "
               "listed in the data header; last column: N = 25, dt = h/2):\n";
  table.write_markdown(std::cout);
}

// Standard output, unless --no-timing: the cost of a step per node, per class and mass (wall time over
// node-steps of its matrix runs), how much the groups shared and the wall time.
void print_timing(const Study& study, long threads, const repro::GroupReferences& references, double wall) {
  std::cout << "cost per step and node (ns, all runs of the matrix, " << threads << " threads):\n";
  for (std::size_t c = 0; c < study.matrix.cases.size(); ++c) {
    double seconds = 0, work = 0;
    for (std::size_t k = 0; k < study.cells.size(); ++k)
      if (study.jobs[k].c == c) seconds += study.cells[k].seconds, work += study.cells[k].work;
    std::cout << "  " << study.matrix.cases[c].id() << ": "
              << cli::format_real(std::round(1e9 * seconds / work * 10) / 10) << '\n';
  }
  // How much the groups shared (not in the data file: two runs of a group that ask the same instant at
  // the same moment both evaluate it, so the count varies by a few from run to run).
  std::cout << "exact solution of the field and smooth benchmarks: " << references.evaluations() << " evaluations for "
            << references.questions() << " questions of the runs\n";
  std::cout << "wall_seconds = " << cli::format_real(std::round(wall * 100) / 100) << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_classes", [&] {
    const auto wall_start = std::chrono::steady_clock::now();
    // 1. Options.
    long threads = 2;
    bool no_timing = false;
    repro::FigureProgram program(
        "fig_classes",
        "Runs every contact class of the scheme registry (all but be) with the consistent mass and Mod 3 on the "
        "benchmarks the harness runs, N = 25, 50, 100, 200 and dt/h = 1/2, 1/sqrt(3), 1: the eight errors, "
        "TV(lambda)/TV(lambda_exact), the largest penetration, the energy per impact, the observed orders, and "
        "1000 impacts on N = 25.",
        {"fig_classes --output output/data/fig_classes.dat --tex output/data/fig_classes.tex",
         "fig_classes --threads 1 --no-timing --output c.dat"});
    cli::add_threads_option(program.parser, &threads);
    program.parser.add_flag("--no-timing", "",
                            "leave out the wall times and costs per step on standard output (the only values "
                            "that vary from run to run; they are never in the data file)",
                            &no_timing);
    if (!program.parse(argc, argv, "also write the tables and the values the report quotes")) return 0;

    // 2. The matrix, decided before any long work: classes × masses (refusals listed), benchmarks (probe).
    program.open();
    const Matrix matrix = decide_matrix();
    std::ostream& out = program.header("the contact classes side by side");
    write_header(out, matrix);

    // 3. The runs: the long runs (the sweep layer), then the matrix, costliest first, on --threads workers.
    Study study(matrix);
    run_long(study, threads);
    repro::GroupReferences references(matrix.cases.size());
    run_matrix(study, threads, references);
    const std::vector<std::array<bool, 8>> common = common_measures(out, study);

    // 4. The data, the tables and the values the report quotes.
    write_data_blocks(out, study);
    const repro::Table table = summary_table(study, common);
    std::ostream& defs = program.values();
    write_summary_values(defs, study, table);
    // Is a scheme exact at the nodes at Δt = h (explicit_schemes.cpp, "Is the scheme "explicit" exact ...")? The
    // largest nodal error max_n max_i |u_i − u(x_i, t_n)| of the paper's benchmark over one period, for
    // explicit + Mod 3 and cn + Mod 3, and for taylor-flanagan (lumped) up to the first impact (t < 1,
    // the free wave equation) and over the period.
    write_nodal_errors(out, defs);
    // Blocks 5 and 6: the measured regions of explicit penalty and explicit Nitsche (contact_classes.cpp,
    // "Central differences with a penalty" and "... with Nitsche's terms": the linear limit is necessary,
    // not sufficient, and no sufficient limit is derived). Newmark (0, ½) with the law and the consistent
    // mass on the paper's benchmark, Δt = r Δt_max (the linear limit), r on a grid fixed before the runs;
    // penalty γ₀ = 1, 10, 100; Nitsche (θ, γ₀) ∈ {0, 1} × {5, 50} (θ = 0 GetFEM's default, θ = 1 the
    // symmetric form with the energy identity; γ₀ = 5 the demo's); N = 16 up to 10³ periods, N = 64 up to
    // 10² (cost); the largest E/E₀ up to 10, 10², 10³ periods (E the class's energy, the law's energy
    // counted). A run stops once E > 10³ E₀ (the problem is positively homogeneous: a gain that large goes
    // on growing; the later horizons then read "> 1e3"). The region's edge per horizon (the largest r below
    // which every run of the law kept E_max ≤ 2E₀) must equal the library's penalty_measured_safe_fraction
    // and nitsche_measured_safe_fraction, which bar1d's warnings use: checked here.
    write_explicit_regions(out, defs, threads, no_timing);
    write_quoted_values(defs, study, common);
    print_summary(study, table);
    if (!no_timing)
      print_timing(study, threads, references,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());

    // 5. Commit.
    program.commit();
    return 0;
  });
}
