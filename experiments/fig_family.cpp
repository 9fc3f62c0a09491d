// fig_family: which redistribution, and why — the weighted family against the period law.
//
// What it computes. For some twenty members of the weighted family of mathematics.md §3 (Mod 1/2/3;
// the lost mass spread over the first 2, 3, 10 and N/2 nodes; beta:B, a point mass B h on node 1 with
// the rest uniform, B from 1/6 to 4/3; node1:X, M̄_11 = X h without renormalising, X from 1/3 to 2,
// GetFEM's 7/12 and 7/6 among them), Crank–Nicolson on the benchmark at N = 100 and 400, Δt = h/2 and
// h, over 10 and 30 periods, each run's
//   - drift of the impact times per period, measured (lib/phase: least-squares slope of the impact
//     time errors), beside the period law's prediction ΔP = 2δm_loc + (3/2)δm_glob computed from the
//     matrix (mass_redistribution.cpp: period_law_masses) and the discrete period from the first
//     eigenvalues of the reduced pencils (lib/period_law);
//   - the eight relative errors of mathematics.md §5 and their ratio to Mod 3's in the same
//     configuration, summed up as the geometric mean over the eight measures.
// The law predicts that the long-time error is a function of the drift: a V with its tip near zero
// drift (Mod 3), whatever the member.
//
// Sample runs:
//   fig_family --output output/data/fig_family.dat --tex output/data/fig_family.tex
//   fig_family --threads 1 --output f.dat
//
// Description. Steps: (1) options; (2) outputs; (3) the list of runs, one per (member, N, Δt/h) to the
// longest horizon (the shorter ones are its prefixes), costliest first; (4) the runs, on --threads
// workers (repro/parallel.hpp); (5) the data blocks, one per (N, Δt/h, horizon), in a
// fixed order, and the values the report quotes. The output does not depend on the number of threads.
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "figure_program.hpp"
#include "mass_spec.hpp"
#include "options.hpp"
#include "parallel.hpp"
#include "sweep.hpp"
#include "report_values.hpp"

#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"
#include "fem/mass_redistribution.hpp"
#include "measures/phase.hpp"
#include "fem/period_law.hpp"

namespace cli = mrm::cli;

namespace {

// One member: its spec on a mesh of N elements ("spread:N/2" becomes "spread:50" at N = 100), the
// family it belongs to and the family's parameter (for the plots).
struct Member {
  std::string label;   ///< the name in the data file and the report ("spread:N/2")
  std::string family;  ///< mod, spread, beta, node1
  double parameter;    ///< K, B or X (0 for the Mod's)
  std::string spec(mrm::Index n) const { return label == "spread:N/2" ? "spread:" + std::to_string(n / 2) : label; }
};

const std::vector<Member>& members() {
  static const std::vector<Member> list{{"mod1", "mod", 1},
                                        {"mod2", "mod", 2},
                                        {"mod3", "mod", 3},
                                        {"spread:2", "spread", 2},
                                        {"spread:3", "spread", 3},
                                        {"spread:10", "spread", 10},
                                        {"spread:N/2", "spread", 0},
                                        {"beta:1/6", "beta", 1. / 6},
                                        {"beta:1/3", "beta", 1. / 3},
                                        {"beta:1/2", "beta", 0.5},
                                        {"beta:5/6", "beta", 5. / 6},
                                        {"beta:1", "beta", 1},
                                        {"beta:4/3", "beta", 4. / 3},
                                        {"node1:1/3", "node1", 1. / 3},
                                        {"node1:1/2", "node1", 0.5},
                                        {"node1:7/12", "node1", 7. / 12},
                                        {"node1:5/6", "node1", 5. / 6},
                                        {"node1:1", "node1", 1},
                                        {"node1:7/6", "node1", 7. / 6},
                                        {"node1:3/2", "node1", 1.5},
                                        {"node1:2", "node1", 2}};
  return list;
}

// A report key from a member's label: "node1:7/12" → "node1-7_12" (keys take no '/' or ':').
std::string key_of(const std::string& label) {
  std::string k = label;
  std::replace(k.begin(), k.end(), '/', '_');
  std::replace(k.begin(), k.end(), ':', '-');
  return k;
}

// The grid: the meshes, the ratios Δt/h and the horizons (periods); the reference member, Mod 3.
const std::vector<mrm::Index> meshes{100, 400};
const std::vector<double> courants{0.5, 1.0};
const std::vector<long> horizons{10, 30};    // periods
constexpr std::size_t reference_member = 2;  // Mod 3

struct Run {
  std::size_t member, mesh, courant, horizon;
  // results
  double total_mass = 0, local = 0, uniform = 0, predicted = 0, predicted_eigen = 0;
  double first_impact_error = 0, drift = 0;
  std::array<double, 8> errors{};
};

// The slot of (mesh a, Δt/h b, horizon c, member m) in the runs, in the order of the data blocks.
std::size_t run_index(std::size_t a, std::size_t b, std::size_t c, std::size_t m) {
  return ((a * courants.size() + b) * horizons.size() + c) * members().size() + m;
}

// One run per (member, mesh, Δt/h), to the longest horizon; its cost ∝ N² T / C orders the jobs.
struct Job {
  std::size_t member, mesh, courant;
  double cost;
};

// Job `job`'s measures at every horizon, written to its own slots of `runs`. The phase is lib/phase's, as
// in run_configuration: the impacts read off the contact indicator, their errors against the exact impacts
// L + 3Lk, the least-squares drift per period.
void measure_job(const Job& job, const mrm::repro::Configuration& configuration, const mrm::repro::Measures& measures,
                 const mrm::ExactSolution& exact, std::vector<Run>& runs) {
  const Member& member = members()[job.member];
  const mrm::Index n = meshes[job.mesh];
  const mrm::UniformMesh mesh(1.0, n);
  const double h = mesh.h();
  const double dt = configuration.step();
  const mrm::PeriodLawMasses masses = mrm::period_law_masses(mesh, configuration.mass);
  // The split subtracts L from a sum of 3N + 1 entries (round-off of about N ulps of L, 1e-13 h here):
  // rounded to 1e-9 h, far below anything measured.
  auto in_h = [h](double v) { return std::round(v / h * 1e9) / 1e9 + 0.0; };
  const double predicted_eigen = mrm::predict_period(mesh, configuration.mass).period_error / h;
  for (std::size_t c = 0; c < horizons.size(); ++c) {
    Run& r = runs[run_index(job.mesh, job.courant, c, job.member)];
    const double end =
        static_cast<double>(mrm::steps_to_reach(exact.period() * static_cast<double>(horizons[c]), dt)) * dt;
    std::vector<double> impacts;
    for (double t : measures.impacts)
      if (t <= end) impacts.push_back(t);
    if (impacts.size() < 2)
      throw std::runtime_error("fig_family: " + member.spec(n) + " at N = " + std::to_string(n) +
                               ": fewer than two impacts, no drift can be measured");
    const std::optional<mrm::PhaseMeasures> paired = mrm::benchmark_phase(impacts, exact);
    if (!paired || paired->matched != impacts.size())
      throw std::runtime_error("fig_family: " + member.spec(n) + " at N = " + std::to_string(n) +
                               ": an impact farther than 3L/2 from its exact partner");
    const mrm::PhaseMeasures& phase = *paired;
    r.total_mass = mrm::total_mass(mesh, configuration.mass);
    r.local = in_h(masses.local);
    r.uniform = in_h(masses.uniform);
    r.predicted = in_h(mrm::predicted_period_change(masses.local, masses.uniform));
    r.predicted_eigen = predicted_eigen;
    r.first_impact_error = phase.first_impact_error / h;
    r.drift = *phase.drift_per_period / h;
    r.errors = mrm::ErrorAccumulator::values(c + 1 < horizons.size() ? measures.horizon_errors[c] : measures.errors);
  }
}

// The ratio to Mod 3 of the members the law puts at zero drift: its range and those members, over every
// block.
struct ZeroDrift {
  double lo = INFINITY, hi = 0;
  std::vector<std::string> members;
};

// Block `block` of the data file (N = elements, Δt/h = courant, `periods` periods), one row per member of
// `rows` (in members() order), and its values for the prose.
void write_block(std::ostream& out, std::ostream& defs, const Run* rows, std::size_t block, mrm::Index elements,
                 double courant, long periods, ZeroDrift& zero) {
  const std::size_t per_block = members().size();
  const Run& reference = rows[reference_member];
  out << (block ? "\n\n" : "") << "# block " << block << ": N = " << elements
      << ", dt/h = " << cli::format_real(courant) << ", periods = " << periods
      << "\n# columns: index member family parameter total_mass dm_loc dm_glob predicted predicted_eigen "
         "first_impact_error drift drift_rel ratio";
  for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
  out << '\n';
  const std::string where =
      "N" + std::to_string(elements) + ":c" + cli::format_real(courant) + ":T" + std::to_string(periods);
  // Each member's mean of log(error / Mod 3's error) over the eight measures: its ratio to Mod 3
  // is the exponential (the geometric mean), and the best member has the smallest.
  std::vector<double> mean_log(per_block);
  for (std::size_t m = 0; m < per_block; ++m) {
    double log_sum = 0;
    for (std::size_t q = 0; q < 8; ++q) {
      if (!(rows[m].errors[q] > 0 && reference.errors[q] > 0))
        throw std::runtime_error("fig_family: a zero error, no ratio to Mod 3 (" + members()[m].label + ")");
      log_sum += std::log(rows[m].errors[q] / reference.errors[q]);
    }
    mean_log[m] = log_sum / 8;
  }
  for (std::size_t m = 0; m < per_block; ++m) {
    const Run& r = rows[m];
    const Member& member = members()[m];
    const double ratio = std::exp(mean_log[m]), relative = r.drift - reference.drift;
    out << m << ' ' << member.spec(elements) << ' ' << member.family << ' '
        << cli::format_real(member.label == "spread:N/2" ? static_cast<double>(elements / 2) : member.parameter) << ' '
        << cli::format_real(r.total_mass) << ' ' << cli::format_real(r.local) << ' ' << cli::format_real(r.uniform)
        << ' ' << cli::format_real(r.predicted) << ' ' << cli::format_real(r.predicted_eigen) << ' '
        << cli::format_real(r.first_impact_error) << ' ' << cli::format_real(r.drift) << ' '
        << cli::format_real(relative) << ' ' << cli::format_real(ratio);
    for (double e : r.errors) out << ' ' << cli::format_real(e);
    out << '\n';
    const std::string key = "family:" + where + ":" + key_of(member.label);
    mrm::tex_define(defs, key + ":predicted", mrm::tex_number(r.predicted, 2));
    mrm::tex_define(defs, key + ":eigen", mrm::tex_number(r.predicted_eigen, 2));
    mrm::tex_define(defs, key + ":drift", mrm::tex_number(r.drift, 2));
    mrm::tex_define(defs, key + ":rel", mrm::tex_number(relative, 2));
    mrm::tex_define(defs, key + ":ratio", mrm::tex_number(ratio, 3));
  }
  // The member with the smallest geometric-mean error in this block, and how far the law's
  // prediction is from the measured drift relative to Mod 3 over the members whose non-uniform
  // mass sits next to the contact node (all but spread:10 and spread:N/2).
  const std::size_t best =
      static_cast<std::size_t>(std::min_element(mean_log.begin(), mean_log.end()) - mean_log.begin());
  double worst_gap = 0;
  for (std::size_t m = 0; m < per_block; ++m) {
    const std::string& label = members()[m].label;
    if (rows[m].predicted == 0 && m != reference_member) {  // the spread among the members the law
      zero.lo = std::min(zero.lo, std::exp(mean_log[m]));   // puts at zero drift, Mod 3 aside
      zero.hi = std::max(zero.hi, std::exp(mean_log[m]));
      if (std::find(zero.members.begin(), zero.members.end(), label) == zero.members.end())
        zero.members.push_back(label);
    }
    if (label != "spread:10" && label != "spread:N/2")
      worst_gap = std::max(worst_gap, std::abs(rows[m].drift - reference.drift - rows[m].predicted));
  }
  mrm::tex_define(defs, "family:" + where + ":best", members()[best].label);
  mrm::tex_define(defs, "family:" + where + ":bestratio", mrm::tex_number(std::exp(mean_log[best]), 3));
  mrm::tex_define(defs, "family:" + where + ":gap", mrm::tex_number(worst_gap, 2));
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_family", [&] {
    // 1. Options.
    long threads = 2;
    mrm::repro::FigureProgram program(
        "fig_family",
        "Writes, for some twenty members of the weighted mass-redistribution family and Crank-Nicolson "
        "at N = 100 and 400, dt = h/2 and h, over 10 and 30 periods, the measured drift of the impact "
        "times per period beside the period law's prediction, and the errors relative to Mod 3.",
        {"fig_family --output output/data/fig_family.dat --tex output/data/fig_family.tex",
         "fig_family --threads 1 --output f.dat"});
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the values the report quotes")) return 0;

    // 2. Outputs.
    program.open();
    const mrm::ExactSolution exact;  // L = 1, u⁰ = (1 − x)/2: period 3
    if (members()[reference_member].label != "mod3") throw std::logic_error("fig_family: Mod 3 is not member 2");

    // 3. One run per (member, mesh, Δt/h), to the longest horizon: a shorter horizon is a prefix of it
    // (run_configuration's horizons give the errors of the run stopped there, bit for bit, and the
    // impacts up to its last level are those of the shorter run). `runs` holds the results per
    // (mesh, Δt/h, horizon, member), in the order of the data blocks; the jobs go costliest first
    // (cost ∝ N² T / C).
    std::vector<Run> runs;
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < courants.size(); ++b)
        for (std::size_t c = 0; c < horizons.size(); ++c)
          for (std::size_t m = 0; m < members().size(); ++m) runs.push_back({m, a, b, c});
    std::vector<Job> jobs;
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < courants.size(); ++b)
        for (std::size_t m = 0; m < members().size(); ++m)
          jobs.push_back(
              {m, a, b,
               static_cast<double>(meshes[a] * meshes[a]) * static_cast<double>(horizons.back()) / courants[b]});
    const std::vector<std::size_t> order =
        mrm::repro::costliest_first(jobs.size(), [&](std::size_t k) { return jobs[k].cost; });

    // The configuration of job k: CN, the member's mass on its mesh, to the longest horizon, measured at
    // the shorter ones.
    const auto job_configuration = [&](std::size_t k) {
      const Job& job = jobs[k];
      const Member& member = members()[job.member];
      const mrm::Index n = meshes[job.mesh];
      const mrm::UniformMesh mesh(1.0, n);
      mrm::repro::Configuration configuration =
          mrm::repro::paper_configuration(mrm::Scheme::crank_nicolson, "algebraic", member.spec(n), n,
                                          courants[job.courant], exact.period() * static_cast<double>(horizons.back()));
      configuration.mass = mrm::repro::mass_redistribution_from_spec(member.spec(n), mesh);
      for (std::size_t c = 0; c + 1 < horizons.size(); ++c)
        configuration.horizons.push_back(exact.period() * static_cast<double>(horizons[c]));
      return configuration;
    };
    // The runs through the sweep layer (repro/sweep.hpp: batched in vector lanes on `threads` workers;
    // each run's measures are its own, bit for bit), then each job's analysis on the workers.
    std::vector<mrm::repro::Configuration> configurations;
    for (std::size_t k = 0; k < jobs.size(); ++k) configurations.push_back(job_configuration(k));
    mrm::repro::SweepSettings settings = mrm::repro::sweep_settings();
    settings.threads = static_cast<unsigned>(threads);
    const std::vector<mrm::repro::Measures> all_measures = mrm::repro::run_batched(configurations, settings);

    // 4. The runs, on `threads` workers (repro/parallel.hpp). Each writes only its own slots. The phase
    // is lib/phase's, as in run_configuration: the impacts read off the contact indicator, their errors
    // against the exact impacts L + 3Lk, the least-squares drift per period.
    mrm::repro::run_in_parallel(
        order, threads, [&](std::size_t k) { measure_job(jobs[k], configurations[k], all_measures[k], exact, runs); },
        [&](std::size_t position, std::size_t k) {
          const Job& job = jobs[k];
          std::cerr << "fig_family: " << position << '/' << order.size() << ' '
                    << members()[job.member].spec(meshes[job.mesh]) << " N=" << meshes[job.mesh]
                    << " dt/h=" << courants[job.courant] << " periods=" << horizons.back() << '\n';
        });

    // 5. The data blocks: block 4a + 2b + c for mesh a, Δt/h b, horizon c; one row per member.
    std::ostream& out =
        program.header("the weighted family against the period law (mathematics.md sec. 8), Crank-Nicolson");
    out << "# length = 1\n# amplitude = 0.5\n# period = " << cli::format_real(exact.period())
        << "\n# scheme = cn\n# initial_contact_node = consistent\n"
        << "# blocks: 4 a + 2 b + c for N in (100, 400) [a], dt/h in (0.5, 1) [b], periods in (10, 30) [c]\n"
        << "# All lengths and times are in units of h (dm_loc, dm_glob, predicted rounded to 1e-9). predicted = 2 "
           "dm_loc + 1.5 dm_glob (the period law);\n"
        << "# predicted_eigen = 2 l_f + l_c - 3 from the first eigenvalues of the reduced pencils; drift = the\n"
        << "# measured drift of the impact times per period; drift_rel = drift - Mod 3's drift (same block);\n"
        << "# ratio = geometric mean over the eight measures of error / Mod 3's error (same block).\n";
    std::ostream& defs = program.values();
    ZeroDrift zero;
    const std::size_t per_block = members().size();
    std::size_t block = 0;
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < courants.size(); ++b)
        for (std::size_t c = 0; c < horizons.size(); ++c, ++block) {
          write_block(out, defs, &runs[block * per_block], block, meshes[a], courants[b], horizons[c], zero);
        }
    std::string zero_list;
    for (const std::string& label : zero.members) zero_list += (zero_list.empty() ? "" : ", ") + label;
    mrm::tex_define(defs, "family:zerodrift:members", zero_list);
    mrm::tex_define(defs, "family:zerodrift:range", mrm::tex_number(zero.lo, 3) + "--" + mrm::tex_number(zero.hi, 3));
    mrm::tex_define(defs, "family:members", std::to_string(members().size()));
    // The parameters the prose names (the keys above carry them too, so that a change shows at once).
    mrm::tex_define(defs, "family:Ncoarse", std::to_string(meshes.front()));
    mrm::tex_define(defs, "family:Nfine", std::to_string(meshes.back()));
    mrm::tex_define(defs, "family:Tshort", std::to_string(horizons.front()));
    mrm::tex_define(defs, "family:Tlong", std::to_string(horizons.back()));
    program.commit();
    return 0;
  });
}
