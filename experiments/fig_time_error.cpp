// fig_time_error: the error estimate in time, at a fixed mesh, into the asymptotic range.
//
// What it computes. The paper states an error estimate in time for Crank–Nicolson applied to the
// semi-discrete problem (6) (its Section 2). To see it, the mesh is fixed (h = 1/N) and only Δt varies:
// Crank–Nicolson, and backward Euler for contrast, with Δt = P h, P h/2, …, P h/2^(K−1) are compared
// with a reference run of the same mesh and mass, Crank–Nicolson with a much smaller step Δt_ref = h/R,
// at the instants they share (mrm::ReferenceComparison). The reference stands for the semi-discrete
// solution; the differences are the errors of the time discretisation alone, in the eight measures of
// mathematics.md §5, the velocity of the massless node taken from its algebraic row (mathematics.md §7).
// Two series: a fine mesh (default h = 1/256, Δt = 4h … h/8, R = 128), where the steps stay near h,
// and a coarse one (default h = 1/32, Δt = 4h … h/256, R = 4096: the reference 16 times finer than the
// finest step), where Δt goes far below the period of the mesh's highest frequency (about 2/h) and the
// asymptotic range is reached.
//
// The prediction (mathematics.md §9). At fixed h the semi-discrete problem is an ODE whose right-hand
// side is Lipschitz and switches at each impact and release (the massless node keeps λ continuous).
// The trapezoidal rule keeps its local error O(Δt³) away from the switches and loses one order only in
// the one step that contains a switch, so its global error is C Δt² (order 2) once Δt resolves the
// mesh's frequencies; backward Euler's is C Δt (order 1). The switch falls anywhere inside its step, so
// C is not a smooth function of Δt: it fluctuates with the position of the impacts on the grid.
//
// The verdict and its tolerance. The order is the least-squares slope of log e against log Δt over the
// finest three steps (--fit-points). For three steps halving each time the middle point has no weight,
// and the slope is p = p₀ + ½ log₂(c₁/c₃) where c_j = e_j/Δt_j^p₀: |p − p₀| ≤ 0.2 admits an error
// constant that changes by up to 2^0.4 ≈ 1.32 between the largest and the smallest of the three steps
// (the fluctuation above), while it stays below 0.25, half the distance from 2 to 1.5 and from 1 to ½,
// the orders a measure would show whose error is dominated by a one-step misplacement of a jump
// (O(Δt^½) in L²_t of the jump, O(Δt³ᐟ²)-type mixtures). A measure is "within" if |p − p₀| ≤ 0.2.
//
// One further number per run: the levels at which the run and the reference are in different contact
// states (one has λ < 0, the other λ = 0). There the massless node's velocity is V₁ + hḞ₀ in one run
// and 0 in the other, an O(1) difference: such a level is a misplaced switch seen by the sampled norm,
// and it shows why a step's velocity error can stand out of the line.
//
// Sample runs:
//   fig_time_error --output output/data/fig_time_error.dat --tex output/data/fig_time_error.tex
//   fig_time_error --elements 128 --reference-ratio 128 --mass mod1 --threads 1 --output t.dat
//
// Description. Steps: (1) options; (2) outputs; (3) the two series on the worker threads, each its
// reference and its runs in lockstep, every run compared at each of its levels; (4) the fitted orders
// and verdicts; (5) the data blocks; (6) the tables and the quoted values; (7) commit.
//
// Two further studies.
// The round-off benchmark: the first impact time at N = 40 (--impact-elements), Mod 1, Crank–Nicolson,
// for Δt = h/1024, h/4096, …, h/262144 (--impact-finest), by the library's step, which solves for the
// increment Uⁿ⁺¹ − Uⁿ, and by the same matrices solved for Uⁿ⁺¹ with the velocity recovered from the
// difference (the form before; lib/time/schemes.cpp, "the increment form", derives the ε|U|/Δt per-step loss
// of the latter and its Δt⁻² growth). The prediction for the increment form: flat to the truncation
// error, C Δt² ≈ 1e-9 · (1024 Δt/h)², plus a round-off √K ε ≈ 1e-12.
// The family: the same error in time on every mesh N = 24, 28, …, 80 and the powers of two up to 256
// (--family-*), each reference (h/2048) checked against h/4096, every halving of Δt in the asymptotic
// range judged, the velocity measures on the levels where both runs are in the same contact state
// (repro/time_family.cpp derives each criterion and why the velocity cannot converge on all levels).
//
// Data file: blocks 0 and 1 are Crank–Nicolson and backward Euler on the fine mesh, blocks 2 and 3 on
// the coarse one; columns dt dt_over_h, the eight relative differences (same names as the errors
// against the exact solution) and mismatched_levels. The fitted orders and verdicts are header lines.
// Block 4: the round-off benchmark (columns dt_over_h_inverse t_for_u t_increment and each one's
// difference from the finest increment value). Block 5: the family, one row per mesh and step (elements
// dt_over_h, the eight judged errors, the two velocity errors on all levels, mismatched_levels); the
// reference bounds, local orders and verdicts are header lines.
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "time_family.hpp"
#include "figure_program.hpp"
#include "studies/convergence.hpp"
#include "measures/errors.hpp"
#include "options.hpp"
#include "report_values.hpp"
#include "time/schemes.hpp"
#include "sweep.hpp"
#include "table.hpp"

namespace cli = mrm::cli;

namespace {
const std::vector<mrm::Scheme> schemes{mrm::Scheme::crank_nicolson, mrm::Scheme::backward_euler};
/// The predicted order in Δt of each scheme (mathematics.md §9) and the tolerance of the verdict
/// (derived in the header comment).
double predicted_order(mrm::Scheme scheme) { return scheme == mrm::Scheme::crank_nicolson ? 2.0 : 1.0; }
constexpr double order_tolerance = 0.2;

/// One series: a mesh, its reference ratio R and its steps Δt_j = m_j Δt_ref (m_j = P R / 2^j).
struct Series {
  long elements, reference_ratio;
  mrm::MassRedistribution mass;  ///< the --mass spec, checked on this mesh
  std::vector<long> ratio;       ///< m_j
  // Results, per scheme s and step j at s * ratio.size() + j.
  std::vector<std::array<double, 8>> differences;
  std::vector<long> mismatched;
  double final_time_used = 0;

  double h() const { return 1.0 / static_cast<double>(elements); }
  double dt_ref() const { return h() / static_cast<double>(reference_ratio); }
  double dt(std::size_t j) const { return static_cast<double>(ratio[j]) * dt_ref(); }
};

bool in_contact(const mrm::Sample& s) { return s.has_multiplier && s.multiplier < 0; }

/// A mass whose contact node does not reach the obstacle before T (a node-1 mass so heavy that the node hardly
/// moves: node1:100 on N = 16 already, node1:1e300 anywhere) leaves every run without a multiplier, whose
/// relative error is then 0/0: the study could not be made, and would fail only after all its runs. One
/// Crank-Nicolson run per mesh at the study's largest step (its cheapest run, a few hundred steps) finds it
/// before any work: refused naming --mass.
void require_contact(const std::string& spec, long elements, const mrm::MassRedistribution& mass, double dt,
                     double final_time) {
  mrm::BarSimulation run(mrm::benchmark_problem(), mrm::UniformMesh(1.0, elements), mass,
                         mrm::repro::scheme_parameters(mrm::Scheme::crank_nicolson, "algebraic", spec), dt);
  const mrm::Index steps = mrm::steps_to_reach(final_time, dt);
  for (mrm::Index k = 1; k <= steps; ++k) {
    run.step();
    if (in_contact(run.sample())) return;
  }
  throw cli::UsageError("--mass: " + cli::quoted_text(spec) +
                        ": the contact node does not reach the obstacle before T = " + cli::format_real(final_time) +
                        " on N = " + std::to_string(elements) + " (Crank-Nicolson, dt = " + cli::format_real(dt) +
                        "): no multiplier to measure the errors of (allowed: a mass whose runs reach the obstacle, "
                        "or a longer --final-time)");
}

/// The reference and every run of the series in lockstep: run j makes one step every m_j reference steps
/// and is compared each time. T is rounded up to a whole number of the largest step so that all runs end
/// at the same instant.
void compute(Series& series, double final_time, const std::string& mass) {
  const mrm::UniformMesh mesh(1.0, series.elements);
  const mrm::MassRedistribution& redistribution = series.mass;
  const double dt_ref = series.dt_ref();
  const mrm::Index coarse_steps = mrm::steps_to_reach(final_time, static_cast<double>(series.ratio[0]) * dt_ref);
  const mrm::Index reference_steps = coarse_steps * series.ratio[0];
  series.final_time_used = static_cast<double>(reference_steps) * dt_ref;
  mrm::BarSimulation reference(mrm::benchmark_problem(), mesh, redistribution,
                               mrm::repro::scheme_parameters(mrm::Scheme::crank_nicolson, "algebraic", mass), dt_ref);
  std::vector<std::unique_ptr<mrm::BarSimulation>> runs;
  std::vector<mrm::ReferenceComparison> comparisons;
  series.mismatched.assign(schemes.size() * series.ratio.size(), 0);
  for (mrm::Scheme scheme : schemes)
    for (long m : series.ratio) {
      runs.push_back(std::make_unique<mrm::BarSimulation>(mrm::benchmark_problem(), mesh, redistribution,
                                                          mrm::repro::scheme_parameters(scheme, "algebraic", mass),
                                                          static_cast<double>(m) * dt_ref));
      comparisons.emplace_back(mesh);
      comparisons.back().add(runs.back()->sample(), reference.sample());
    }
  for (mrm::Index k = 1; k <= reference_steps; ++k) {
    reference.step();
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const long m = series.ratio[r % series.ratio.size()];
      if (k % m != 0) continue;
      runs[r]->step();
      const mrm::Sample run = runs[r]->sample(), ref = reference.sample();
      comparisons[r].add(run, ref);
      if (in_contact(run) != in_contact(ref)) ++series.mismatched[r];
    }
  }
  series.differences.resize(runs.size());
  for (std::size_t r = 0; r < runs.size(); ++r) series.differences[r] = comparisons[r].relative();
}

/// The least-squares order over the finest `points` steps of scheme s in measure k; NaN if fewer than
/// two of them have a positive error.
/// With `shift` > 0, over the `points` steps that end `shift` steps before the finest.
double finest_order(const Series& series, std::size_t s, std::size_t k, std::size_t points, std::size_t shift = 0) {
  std::vector<double> steps, errors;
  const std::size_t end = series.ratio.size() - shift;
  for (std::size_t j = end - points; j < end; ++j) {
    const double e = series.differences[s * series.ratio.size() + j][k];
    if (!(e > 0)) continue;
    steps.push_back(series.dt(j));
    errors.push_back(e);
  }
  return steps.size() >= 2 ? mrm::fit_order(steps, errors).order : std::nan("");
}
// The round-off benchmark's table and values: the first impact time solved for U^{n+1} and for the
// increment at each step h/R, against the finest.
void write_impact_table(std::ostream& defs, const std::vector<long>& impact_ratios,
                        const std::vector<double>& impact_times, double impact_finest_value, double impact_spread_after,
                        double impact_spread_before, long impact_elements) {
  mrm::repro::Table table({"$h/\\Delta t$", "for $U^{n+1}$ (before)", "increment (after)", "before $-$ finest after",
                           "after $-$ finest after"});
  for (std::size_t j = 0; j < impact_ratios.size(); ++j)
    table.add_row({std::to_string(impact_ratios[j]), mrm::tex_number(impact_times[2 * j], 12),
                   mrm::tex_number(impact_times[2 * j + 1], 12),
                   mrm::tex_number(impact_times[2 * j] - impact_finest_value, 2),
                   mrm::tex_number(impact_times[2 * j + 1] - impact_finest_value, 2)});
  defs << "\\mrmdef{time:impact:table}{" << mrm::repro::latex_tabular(table, "rllrr") << "}\n";
  mrm::tex_define(defs, "time:impact:elements", std::to_string(impact_elements));
  mrm::tex_define(defs, "time:impact:coarsest", std::to_string(impact_ratios.front()));
  mrm::tex_define(defs, "time:impact:finest", std::to_string(impact_ratios.back()));
  mrm::tex_define(defs, "time:impact:spreadafter", mrm::tex_number(impact_spread_after, 2));
  mrm::tex_define(defs, "time:impact:spreadbefore", mrm::tex_number(impact_spread_before, 2));
}

// The family's verdict table (meshes x measures: the range of the judged local orders, pass/fail) and
// its values: where order 2 holds, and from which step on.
void write_family_table(std::ostream& defs, const std::vector<mrm::repro::TimeFamilyMesh>& family,
                        const std::vector<long>& family_meshes, long family_reference_ratio, int family_all_holds,
                        const std::array<int, 8>& family_holds, int meshes_with_region, double onset_smallest,
                        double onset_largest, double onset_slope) {
  std::vector<std::string> headers{"$N$"};
  for (const mrm::repro::Label& label : mrm::repro::measure_labels())
    headers.push_back("\\rotatebox{70}{" + label.latex + "}");
  headers.push_back("\\rotatebox{70}{mismatched levels}");
  mrm::repro::Table table(headers);
  for (const mrm::repro::TimeFamilyMesh& f : family) {
    std::vector<std::string> cells{std::to_string(f.elements)};
    for (std::size_t k = 0; k < 8; ++k) {
      const double onset = 1.0 / (f.dt[f.onset[k]] * static_cast<double>(f.elements));
      std::string cell =
          "$h/" + std::to_string(std::lround(onset)) + "$; " +
          (f.judged_count[k] == 0 ? std::string("none judged")
                                  : mrm::tex_number(f.lowest[k], 2) + "--" + mrm::tex_number(f.highest[k], 2));
      cells.push_back(cell + (f.holds[k] ? " \\checkmark" : " \\textbf{fail}"));
    }
    long mismatched = 0;
    for (long m : f.mismatched) mismatched += m;
    cells.push_back(std::to_string(mismatched));
    table.add_row(cells);
  }
  // Split in two (the first four measures, then the other four and the mismatched levels): the
  // ten columns in one row are wider than the page.
  defs << "\\mrmdef{time:family:table:a}{"
       << mrm::repro::latex_tabular(table.columns_subset({0, 1, 2, 3, 4}), "r" + std::string(4, 'r')) << "}\n";
  defs << "\\mrmdef{time:family:table:b}{"
       << mrm::repro::latex_tabular(table.columns_subset({0, 5, 6, 7, 8, 9}), "r" + std::string(5, 'r')) << "}\n";
  std::string meshes;
  for (long n : family_meshes) meshes += (meshes.empty() ? "" : ", ") + std::to_string(n);
  mrm::tex_define(defs, "time:family:meshes", meshes);
  mrm::tex_define(defs, "time:family:count", std::to_string(family.size()));
  mrm::tex_define(defs, "time:family:R", std::to_string(family_reference_ratio));
  mrm::tex_define(defs, "time:family:allhold", std::to_string(family_all_holds));
  std::string per_measure;
  for (std::size_t k = 0; k < 8; ++k) {
    mrm::tex_define(defs, std::string("time:family:holds:") + mrm::ErrorAccumulator::names[k],
                    std::to_string(family_holds[k]));
    if (family_holds[k] < static_cast<int>(family.size()))
      per_measure += (per_measure.empty() ? "" : "; ") + mrm::repro::measure_labels()[k].latex + ": " +
                     std::to_string(family_holds[k]);
  }
  if (meshes_with_region == 0) onset_smallest = onset_largest = 0;  // printed as "on no mesh" below
  mrm::tex_define(defs, "time:family:verdict",
                  "from $\\Delta t = h/2$ on, order 2 holds at every halving in all 8 measures on " +
                      std::to_string(family_all_holds) + " of the " + std::to_string(family.size()) + " meshes" +
                      (per_measure.empty() ? std::string("") : " (meshes where a measure holds: " + per_measure + ")") +
                      "; it holds at every halving from $\\Delta t = h/" + std::to_string(std::lround(onset_smallest)) +
                      "$ to $h/" + std::to_string(std::lround(onset_largest)) +
                      "$ on, depending on the mesh, in all 8 "
                      "measures on " +
                      std::to_string(meshes_with_region) + " of the " + std::to_string(family.size()) + " meshes");
  mrm::tex_define(defs, "time:family:onsetslope", std::isfinite(onset_slope) ? mrm::tex_number(onset_slope, 2) : "n/a");
  mrm::tex_define(defs, "time:family:onsetfrom", std::to_string(std::lround(onset_smallest)));
  mrm::tex_define(defs, "time:family:onsetto", std::to_string(std::lround(onset_largest)));
}

/// The fitted orders orders[i][s][k] of mesh i, scheme s, measure k over the finest `points` steps, and
/// the same fit one step coarser (the steps ending at the second finest), to show how the verdict
/// depends on where the range stops.
struct Orders {
  const std::vector<Series>& series;
  std::size_t points;
  std::vector<std::vector<std::array<double, 8>>> finest, shifted;

  /// The verdict: within the tolerance of the predicted order.
  bool within(std::size_t i, std::size_t s, std::size_t k) const {
    return std::abs(finest[i][s][k] - predicted_order(schemes[s])) <= order_tolerance;
  }
  /// The shifted fit in words. Where it cannot be formed, the row says why (never a NaN): "n/a: fewer
  /// than F + 1 steps" (K = F), or "n/a: fewer than two positive errors" there.
  std::string shifted_text(std::size_t i, std::size_t s, std::size_t k, bool tex) const {
    const double p = shifted[i][s][k];
    if (std::isfinite(p)) return tex ? mrm::tex_number(p, 3) : cli::format_real(p);
    return std::string(series[i].ratio.size() > points ? "n/a: fewer than two positive errors"
                                                       : "n/a: fewer than fit_points + 1 steps");
  }
};

Orders fit_orders(const std::vector<Series>& series, std::size_t points) {
  Orders o{series,
           points,
           std::vector<std::vector<std::array<double, 8>>>(series.size(),
                                                           std::vector<std::array<double, 8>>(schemes.size())),
           {}};
  for (std::size_t i = 0; i < series.size(); ++i)
    for (std::size_t s = 0; s < schemes.size(); ++s)
      for (std::size_t k = 0; k < 8; ++k) {
        o.finest[i][s][k] = finest_order(series[i], s, k, points);
        if (!std::isfinite(o.finest[i][s][k]))
          throw std::runtime_error("no order over the finest steps: an error is zero (" + mrm::to_string(schemes[s]) +
                                   ", " + mrm::ErrorAccumulator::names[k] + ")");
      }
  o.shifted = o.finest;
  for (std::size_t i = 0; i < series.size(); ++i)
    for (std::size_t s = 0; s < schemes.size(); ++s)
      for (std::size_t k = 0; k < 8; ++k)
        o.shifted[i][s][k] = series[i].ratio.size() > points ? finest_order(series[i], s, k, points, 1) : std::nan("");
  return o;
}

// Blocks 0 to 3: the errors of each scheme on each mesh against the step, with the fitted orders and
// their verdicts in the block's header.
void write_series_blocks(std::ostream& out, const std::vector<Series>& series, const Orders& orders) {
  out << "# reference: Crank-Nicolson with the same mesh and mass\n"
      << "# predicted_order_" << mrm::to_string(schemes[0]) << " = " << predicted_order(schemes[0]) << '\n'
      << "# predicted_order_" << mrm::to_string(schemes[1]) << " = " << predicted_order(schemes[1]) << '\n'
      << "# order_tolerance = " << cli::format_real(order_tolerance)
      << "\n# verdict: within if |order over the finest fit_points steps - predicted| <= order_tolerance\n"
      << "# blocks: 2 i + s, mesh i in (fine, coarse), scheme s in (" << mrm::to_string(schemes[0]) << ", "
      << mrm::to_string(schemes[1]) << ")\n";
  for (std::size_t i = 0; i < series.size(); ++i)
    out << "# mesh " << i << ": h = " << cli::format_real(series[i].h())
        << ", dt_ref = " << cli::format_real(series[i].dt_ref()) << ", total_mass = "
        << cli::format_real(mrm::total_mass(mrm::UniformMesh(1.0, series[i].elements), series[i].mass))
        << ", final_time_used = " << cli::format_real(series[i].final_time_used) << '\n';
  for (std::size_t i = 0; i < series.size(); ++i)
    for (std::size_t s = 0; s < schemes.size(); ++s) {
      const Series& se = series[i];
      out << (i + s ? "\n\n" : "") << "# block " << 2 * i + s << ": scheme = " << mrm::to_string(schemes[s])
          << ", elements = " << se.elements << ", reference_ratio = " << se.reference_ratio << '\n';
      for (std::size_t k = 0; k < 8; ++k)
        out << "# order_finest " << mrm::ErrorAccumulator::names[k] << " = " << cli::format_real(orders.finest[i][s][k])
            << " (" << (orders.within(i, s, k) ? "within" : "outside")
            << "); one step coarser: " << orders.shifted_text(i, s, k, false) << '\n';
      out << "# columns: dt dt_over_h";
      for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
      out << " mismatched_levels\n";
      for (std::size_t j = 0; j < se.ratio.size(); ++j) {
        out << cli::format_real(se.dt(j)) << ' ' << cli::format_real(se.dt(j) / se.h());
        for (double e : se.differences[s * se.ratio.size() + j]) out << ' ' << cli::format_real(e);
        out << ' ' << se.mismatched[s * se.ratio.size() + j] << '\n';
      }
    }
}

// The round-off benchmark's first impact times against the finest one.
struct ImpactSummary {
  double finest = 0;                           ///< the first impact time at the finest step (increment form)
  double spread_after = 0, spread_before = 0;  ///< the largest |time - finest| of each form
};

// Block 4: the first impact time of the round-off benchmark, solved for U^{n+1} and for the increment.
ImpactSummary write_impact_block(std::ostream& out, const std::vector<long>& impact_ratios,
                                 const std::vector<double>& impact_times, long impact_elements) {
  ImpactSummary summary;
  summary.finest = impact_times.back();
  out << "\n\n# block 4: first impact time, N = " << impact_elements
      << ", Mod 1, Crank-Nicolson, solved for U^{n+1} (before) and for the increment (after)\n"
      << "# columns: dt_over_h_inverse t_for_u t_increment for_u_minus_finest increment_minus_finest\n";
  for (std::size_t j = 0; j < impact_ratios.size(); ++j) {
    const double before = impact_times[2 * j], after = impact_times[2 * j + 1];
    summary.spread_after = std::max(summary.spread_after, std::abs(after - summary.finest));
    summary.spread_before = std::max(summary.spread_before, std::abs(before - summary.finest));
    out << impact_ratios[j] << ' ' << cli::format_real(before) << ' ' << cli::format_real(after) << ' '
        << cli::format_real(before - summary.finest) << ' ' << cli::format_real(after - summary.finest) << '\n';
  }
  return summary;
}

// What the family's meshes show: per measure the meshes where order 2 holds, the meshes where it holds in
// all 8, and the region where it holds (its onset's range in h/Δt and its slope against h).
struct FamilySummary {
  std::array<int, 8> holds{};
  int all_holds = 0, meshes_with_region = 0;
  double onset_smallest = HUGE_VAL, onset_largest = 0, onset_slope = 0;
};

// Block 5: the family of meshes, each mesh's verdicts in the header and its errors against the step.
FamilySummary write_family_block(std::ostream& out, const std::vector<mrm::repro::TimeFamilyMesh>& family,
                                 const std::string& mass, long family_reference_ratio,
                                 const mrm::repro::TimeFamilySettings& family_settings) {
  std::array<int, 8> family_holds{};
  int family_all_holds = 0;
  for (const mrm::repro::TimeFamilyMesh& f : family) {
    bool all8 = true;
    for (std::size_t k = 0; k < 8; ++k) family_holds[k] += f.holds[k], all8 = all8 && f.holds[k];
    family_all_holds += all8;
  }
  out << "\n\n# block 5: family of meshes, Crank-Nicolson, " << mrm::repro::mass_label(mass).abbreviation
      << ", reference h/" << family_reference_ratio << " checked against h/" << 2 * family_reference_ratio
      << "; judged: every halving from dt <= h/2 whose errors are >= " << family_settings.floor_factor
      << " x the reference bound, |local order - 2| <= " << family_settings.tolerance
      << "; velocity measures on matched levels (repro/time_family.cpp)\n";
  for (std::size_t k = 0; k < 8; ++k)
    out << "# family_holds " << mrm::ErrorAccumulator::names[k] << " = " << family_holds[k] << " of " << family.size()
        << " meshes\n";
  out << "# family_all_measures_hold = " << family_all_holds << " of " << family.size() << " meshes\n";
  // The region where order 2 holds: on each mesh the largest step from which every halving holds in
  // all 8 measures (the latest onset of the measures), and how it scales with h (a conjecture: the
  // accumulated phase error of the highest modes, ω³Δt²T/12 with ω ~ 1/h, must be small, so the onset
  // should scale like h^{3/2}); the least-squares slope of log onset against log h.
  std::vector<double> onset_h, onset_dt;
  double onset_smallest = HUGE_VAL, onset_largest = 0;
  int meshes_with_region = 0;  // the meshes where at least the finest halving holds in all 8 measures
  for (const mrm::repro::TimeFamilyMesh& f : family) {
    std::size_t latest = 0;
    for (std::size_t k = 0; k < 8; ++k) latest = std::max(latest, f.onset[k]);
    if (latest + 1 >= f.dt.size()) continue;
    ++meshes_with_region;
    onset_h.push_back(1.0 / static_cast<double>(f.elements));
    onset_dt.push_back(f.dt[latest]);
    const double ratio = 1.0 / (f.dt[latest] * static_cast<double>(f.elements));
    onset_smallest = std::min(onset_smallest, ratio), onset_largest = std::max(onset_largest, ratio);
  }
  const double onset_slope = onset_h.size() >= 2 ? mrm::fit_order(onset_h, onset_dt).order : std::nan("");
  out << "# family_onset: order 2 at every halving from "
      << (meshes_with_region > 0
              ? "dt = h/" + cli::format_real(onset_smallest) + " to h/" + cli::format_real(onset_largest) + " on"
              : std::string("n/a: no mesh has such a step"))
      << " (all 8 measures); slope of log onset vs log h = "
      << (std::isfinite(onset_slope) ? cli::format_real(onset_slope) : std::string("n/a: fewer than two meshes"))
      << " (conjecture: 1.5); meshes with such a region: " << meshes_with_region << " of " << family.size() << '\n';
  for (const mrm::repro::TimeFamilyMesh& f : family) {
    out << "# mesh N = " << f.elements << ": reference_bound";
    for (double b : f.reference_bound) out << ' ' << cli::format_real(b);
    out << "; reference_mismatched_levels " << f.reference_mismatched << '\n';
    for (std::size_t k = 0; k < 8; ++k) {
      out << "#   " << mrm::ErrorAccumulator::names[k] << ": " << (f.holds[k] ? "holds" : "fails")
          << " from dt = h/2, judged " << f.judged_count[k]
          << "; order 2 from dt/h = " << cli::format_real(f.dt[f.onset[k]] * static_cast<double>(f.elements))
          << "; local orders";
      for (std::size_t j = 0; j < f.local[k].size(); ++j)
        out << ' ' << (std::isfinite(f.local[k][j]) ? cli::format_real(f.local[k][j]) : std::string("n/a"))
            << (f.judged[k][j] ? "" : "(not judged)");
      out << '\n';
    }
  }
  out << "# columns: elements dt_over_h";
  for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
  out << " err_v_LinfL2_all_levels err_v_L2L2_all_levels mismatched_levels\n";
  for (const mrm::repro::TimeFamilyMesh& f : family)
    for (std::size_t j = 0; j < f.dt.size(); ++j) {
      out << f.elements << ' ' << cli::format_real(f.dt[j] * static_cast<double>(f.elements));
      for (std::size_t k = 0; k < 8; ++k) out << ' ' << cli::format_real(f.judged_errors(j, k)[k]);
      out << ' ' << cli::format_real(f.all[j][4]) << ' ' << cli::format_real(f.all[j][7]) << ' ' << f.mismatched[j]
          << '\n';
    }
  return {family_holds, family_all_holds, meshes_with_region, onset_smallest, onset_largest, onset_slope};
}

// The table of mesh i (errors with the order between consecutive steps, the fitted orders) and its
// quoted values: the keys time:… for the fine mesh, time:coarse:… for the coarse one.
void write_series_values(std::ostream& defs, const Series& se, std::size_t i, const Orders& orders) {
  const std::string prefix = i == 0 ? "time:" : "time:coarse:";
  // A step as a multiple of h, for the prose: "4h", "h", "h/8".
  auto step_text = [&](long m) {
    const double q = static_cast<double>(m) / static_cast<double>(se.reference_ratio);
    if (q == 1) return std::string("h");
    return q > 1 ? std::to_string(static_cast<long>(q)) + "h" : "h/" + std::to_string(static_cast<long>(1 / q));
  };
  mrm::tex_define(defs, prefix + "elements", std::to_string(se.elements));
  mrm::tex_define(defs, prefix + "steps", std::to_string(se.ratio.size()));
  mrm::tex_define(defs, prefix + "R", std::to_string(se.reference_ratio));
  mrm::tex_define(defs, prefix + "T", mrm::tex_number(se.final_time_used, 3));
  mrm::tex_define(defs, prefix + "largest", step_text(se.ratio.front()));
  mrm::tex_define(defs, prefix + "smallest", step_text(se.ratio.back()));
  mrm::tex_define(defs, prefix + "fitlargest", step_text(se.ratio[se.ratio.size() - orders.points]));
  if (se.ratio.size() > orders.points) {
    mrm::tex_define(defs, prefix + "shiftlargest", step_text(se.ratio[se.ratio.size() - orders.points - 1]));
    mrm::tex_define(defs, prefix + "shiftsmallest", step_text(se.ratio[se.ratio.size() - 2]));
  }
  std::vector<std::string> headers{"scheme", "$\\Delta t/h$"};
  for (const mrm::repro::Label& label : mrm::repro::measure_labels())
    headers.push_back("\\rotatebox{70}{" + label.latex + "}");
  headers.push_back("\\rotatebox{70}{mismatched levels}");
  mrm::repro::Table table(headers);
  const std::size_t half = se.ratio.size() / 2;
  for (std::size_t s = 0; s < schemes.size(); ++s) {
    std::vector<double> steps;
    for (std::size_t j = 0; j < se.ratio.size(); ++j) steps.push_back(se.dt(j));
    for (std::size_t j = 0; j < se.ratio.size(); ++j) {
      const double q = static_cast<double>(se.ratio[j]) / static_cast<double>(se.reference_ratio);
      std::vector<std::string> cells{
          j == 0 ? mrm::repro::scheme_label(schemes[s]).abbreviation : std::string(),
          q >= 1 ? std::to_string(static_cast<long>(q)) : "1/" + std::to_string(static_cast<long>(1 / q))};
      for (std::size_t k = 0; k < 8; ++k) {
        const double e = se.differences[s * se.ratio.size() + j][k];
        cells.push_back(mrm::tex_number(e, 2));
        if (j > 0) {  // the local order of this halving of the step
          const double local = mrm::repro::local_orders({steps[j - 1], steps[j]},
                                                        {se.differences[s * se.ratio.size() + j - 1][k], e})[1];
          cells.back() += " (" + mrm::tex_number(local, 2) + ")";
        }
      }
      cells.push_back(std::to_string(se.mismatched[s * se.ratio.size() + j]));
      table.add_row(cells);
    }
    std::vector<std::string> fitted{"", "order"};
    for (std::size_t k = 0; k < 8; ++k) fitted.push_back(mrm::tex_number(orders.finest[i][s][k], 2));
    fitted.push_back("");
    table.add_row(fitted);
    table.add_rule();
    std::size_t count = 0;
    for (std::size_t k = 0; k < 8; ++k) {
      const std::string key = mrm::to_string(schemes[s]) + ":" + mrm::ErrorAccumulator::names[k];
      mrm::tex_define(defs, prefix + "orderfinest:" + key, mrm::tex_number(orders.finest[i][s][k], 3));
      mrm::tex_define(defs, prefix + "ordershifted:" + key, orders.shifted_text(i, s, k, true));
      mrm::tex_define(defs, prefix + "verdict:" + key, orders.within(i, s, k) ? "within" : "outside");
      count += orders.within(i, s, k);
      mrm::tex_define(defs, prefix + "errfine:" + key,
                      mrm::tex_number(se.differences[s * se.ratio.size() + se.ratio.size() - 1][k], 2));
      if (i == 0) {  // the fine mesh: the fit over all steps and over the finer half
        std::vector<double> all_steps, all_errors, fine_steps, fine_errors;
        for (std::size_t j = 0; j < se.ratio.size(); ++j) {
          const double e = se.differences[s * se.ratio.size() + j][k];
          if (!(e > 0)) continue;
          all_steps.push_back(steps[j]);
          all_errors.push_back(e);
          if (j >= half) fine_steps.push_back(steps[j]), fine_errors.push_back(e);
        }
        mrm::tex_define(
            defs, prefix + "order:" + key,
            all_steps.size() >= 2 ? mrm::tex_number(mrm::fit_order(all_steps, all_errors).order, 2) : "n/a");
        mrm::tex_define(
            defs, prefix + "orderfine:" + key,
            fine_steps.size() >= 2 ? mrm::tex_number(mrm::fit_order(fine_steps, fine_errors).order, 2) : "n/a");
      }
    }
    mrm::tex_define(defs, prefix + "within:" + mrm::to_string(schemes[s]), std::to_string(count));
    // The steps whose run has levels in the other contact state than the reference.
    std::string mismatch;
    for (std::size_t j = 0; j < se.ratio.size(); ++j)
      if (se.mismatched[s * se.ratio.size() + j] > 0)
        mismatch += (mismatch.empty() ? "" : ", ") + std::string("$") + step_text(se.ratio[j]) + "$";
    mrm::tex_define(defs, prefix + "mismatch:" + mrm::to_string(schemes[s]), mismatch.empty() ? "none" : mismatch);
    std::size_t mismatched_steps = 0, finest_mismatched = se.ratio.size();
    for (std::size_t j = 0; j < se.ratio.size(); ++j)
      if (se.mismatched[s * se.ratio.size() + j] > 0) ++mismatched_steps, finest_mismatched = j;
    mrm::tex_define(defs, prefix + "mismatchsteps:" + mrm::to_string(schemes[s]), std::to_string(mismatched_steps));
    mrm::tex_define(defs, prefix + "mismatchfinest:" + mrm::to_string(schemes[s]),
                    finest_mismatched < se.ratio.size() ? "$" + step_text(se.ratio[finest_mismatched]) + "$" : "none");
    mrm::tex_define(defs, prefix + "withinwords:" + mrm::to_string(schemes[s]),
                    count == 8 ? "all 8 measures" : std::to_string(count) + " of the 8 measures");
  }
  if (i == 0) mrm::tex_define(defs, "time:finehalf", step_text(se.ratio[half]));
  // The table in two halves at the text size (measures 1-4, then 5-8 of mathematics.md §5 and the
  // mismatched levels), not shrunk.
  for (std::size_t part = 0; part < 2; ++part) {
    std::vector<std::size_t> keep{0, 1};
    for (std::size_t k = 4 * part; k < 4 * part + 4; ++k) keep.push_back(2 + k);
    if (part == 1) keep.push_back(10);
    defs << "\\mrmdef{" << prefix << "table" << (part == 0 ? ":a" : ":b") << "}{"
         << mrm::repro::latex_tabular(table.columns_subset(keep), "ll" + std::string(keep.size() - 2, 'r')) << "}\n";
  }
}

// The options of the program beyond the mesh and the final time (FigureProgram's), with their defaults.
struct Options {
  long reference_ratio = 128, largest = 4, steps_count = 6;
  long coarse_elements = 32, coarse_reference_ratio = 4096, coarse_steps_count = 11;
  long fit_points = 3, threads = 2;
  long impact_elements = 40, impact_finest = 262144;
  long family_from = 24, family_to = 80, family_powers_to = 256, family_reference_ratio = 2048;
  std::string mass = "mod3";
};

// Step 1: the options, declared on the program's parser.
void declare_options(mrm::repro::FigureProgram& program, Options& o) {
  program.add_elements(256, "fine mesh: number of elements N (h = 1/N), in [2, 1e7]");
  program.parser.add_integer("--reference-ratio", "-r", "R",
                             "fine mesh: reference step dt_ref = h/R; a power of 2 in [2, 2^30]", &o.reference_ratio,
                             cli::in_closed_range(2, 1 << 30));
  program.parser.add_integer("--steps", "-k", "K",
                             "fine mesh: number of steps dt = P h, P h/2, ..., P h/2^(K-1), in [3, 50]", &o.steps_count,
                             cli::in_closed_range(3, 50));
  program.parser.add_integer("--coarse-elements", "", "N", "coarse mesh: number of elements, in [2, 1e7]",
                             &o.coarse_elements, mrm::repro::elements_range());
  program.parser.add_integer("--coarse-reference-ratio", "", "R",
                             "coarse mesh: dt_ref = h/R; a power of 2 in [2, 2^30]", &o.coarse_reference_ratio,
                             cli::in_closed_range(2, 1 << 30));
  program.parser.add_integer("--coarse-steps", "", "K",
                             "coarse mesh: number of steps dt = P h, ..., P h/2^(K-1), in [3, 50]",
                             &o.coarse_steps_count, cli::in_closed_range(3, 50));
  program.parser.add_integer("--largest", "", "P", "largest step dt = P h of both meshes; a power of 2 in [1, 2^20]",
                             &o.largest, cli::in_closed_range(1, 1 << 20));
  program.parser.add_integer("--fit-points", "", "F", "the order is fitted over the finest F steps (>= 2, <= each K)",
                             &o.fit_points, cli::at_least(2));
  program.add_final_time(3.0, "final time (> 0); one period is 3");
  program.parser.add_string("--mass", "-m", "M", mrm::repro::mass_option_help("a redistributed mass (not consistent)"),
                            &o.mass);
  cli::add_threads_option(program.parser, &o.threads);
  program.parser.add_integer("--impact-elements", "", "N",
                             "round-off benchmark: elements of its mesh (Mod 1), in [2, 1000]", &o.impact_elements,
                             cli::in_closed_range(2, 1000));
  program.parser.add_integer("--impact-finest", "", "R",
                             "round-off benchmark: finest step h/R; steps h/R, h/(R/4), ... down to h/1024; a "
                             "power of 2 in [4, 2^22]",
                             &o.impact_finest, cli::in_closed_range(4, 1 << 22));
  program.parser.add_integer("--family-from", "", "N", "family: smallest mesh, in [4, 1000]", &o.family_from,
                             cli::in_closed_range(4, 1000));
  program.parser.add_integer("--family-to", "", "N",
                             "family: meshes from --family-from to N in steps of 4, in [4, 1000]", &o.family_to,
                             cli::in_closed_range(4, 1000));
  program.parser.add_integer("--family-powers-to", "", "N",
                             "family: then the powers of 2 above --family-to up to N, in [4, 4096]",
                             &o.family_powers_to, cli::in_closed_range(4, 4096));
  program.parser.add_integer("--family-reference-ratio", "", "R",
                             "family: reference h/R checked against h/(2R); a power of 2 in [64, 2^16]",
                             &o.family_reference_ratio, cli::in_closed_range(64, 1 << 16));
}

// The checks of the options that the parser's ranges cannot make, before any file is touched.
void check_options(const Options& o, long elements, double final_time) {
  // The ranges were checked by the parser; here the powers of 2 within them.
  auto require_power_of_two = [](const char* option, long v, const char* range) {
    if (v <= 0 || (v & (v - 1)) != 0)
      throw cli::UsageError(std::string(option) + ": " + std::to_string(v) +
                            " is not allowed (expected a power of 2 in " + range + ")");
  };
  require_power_of_two("--reference-ratio", o.reference_ratio, "[2, 2^30]");
  require_power_of_two("--coarse-reference-ratio", o.coarse_reference_ratio, "[2, 2^30]");
  require_power_of_two("--largest", o.largest, "[1, 2^20]");
  require_power_of_two("--impact-finest", o.impact_finest, "[4, 2^22]");
  require_power_of_two("--family-reference-ratio", o.family_reference_ratio, "[64, 2^16]");
  if (o.family_to < o.family_from)
    throw cli::UsageError("--family-to: " + std::to_string(o.family_to) +
                          " is below --family-from (allowed: at least --family-from)");
  // Every step Δt_j = P h / 2^j must be a multiple m_j = P R / 2^j ≥ 2 of the reference step.
  // P R <= 2^50 and K <= 50 by the ranges: no shift below overflows.
  auto require_steps = [&](const char* option, long count, long ratio) {
    if (((o.largest * ratio) >> (count - 1)) < 2)
      throw cli::UsageError(std::string(option) +
                            ": the smallest step P h/2^(K-1) must be at least twice the reference step h/R");
  };
  require_steps("--steps", o.steps_count, o.reference_ratio);
  require_steps("--coarse-steps", o.coarse_steps_count, o.coarse_reference_ratio);
  // The reference run of each mesh makes T/dt_ref steps (T rounded up to a whole largest step); its 2K
  // runs and their comparisons are held at once with the reference: about 256 bytes per element each.
  auto require_run = [&](const char* elements_option, const char* ratio_option, long n, long ratio, long count) {
    const double h = 1.0 / static_cast<double>(n);
    const mrm::Index coarse_steps =
        cli::checked_steps("--final-time", final_time, static_cast<double>(o.largest) * h, "--largest");
    const double reference_steps = static_cast<double>(coarse_steps) * static_cast<double>(o.largest * ratio);
    if (!(reference_steps <= cli::max_steps))
      throw cli::UsageError(std::string(ratio_option) + ": " + std::to_string(ratio) + " gives the reference run " +
                            cli::format_real(reference_steps) +
                            " steps (allowed: at most 1e12 steps; lower it, the elements or --final-time)");
    cli::require_mesh_memory(elements_option, static_cast<double>(n), 256, 2 * static_cast<double>(count) + 2);
  };
  require_run("--elements", "--reference-ratio", elements, o.reference_ratio, o.steps_count);
  require_run("--coarse-elements", "--coarse-reference-ratio", o.coarse_elements, o.coarse_reference_ratio,
              o.coarse_steps_count);
  if (o.fit_points > o.steps_count || o.fit_points > o.coarse_steps_count)
    throw cli::UsageError("--fit-points: at most the number of steps of each mesh (--steps, --coarse-steps)");
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_time_error", [&] {
    // 1. Options.
    Options o;
    mrm::repro::FigureProgram program(
        "fig_time_error",
        "Writes the error of Crank-Nicolson and backward Euler against the time step at a fixed "
        "mesh, measured against a Crank-Nicolson reference run of the same mesh with a much smaller "
        "step, for a fine mesh and a coarse one whose steps reach the asymptotic range, and the "
        "fitted orders in time over the finest steps beside the predicted ones (2 and 1).",
        {"fig_time_error --output output/data/fig_time_error.dat --tex output/data/fig_time_error.tex",
         "fig_time_error --elements 128 --reference-ratio 128 --mass mod1 --threads 1 --output t.dat"});
    declare_options(program, o);
    if (!program.parse(argc, argv, "also write the tables and values the report quotes")) return 0;
    const long elements = program.elements;
    const double final_time = program.final_time;
    check_options(o, elements, final_time);
    const long reference_ratio = o.reference_ratio, largest = o.largest, steps_count = o.steps_count;
    const long coarse_elements = o.coarse_elements, coarse_reference_ratio = o.coarse_reference_ratio,
               coarse_steps_count = o.coarse_steps_count, fit_points = o.fit_points, threads = o.threads;
    const long impact_elements = o.impact_elements, impact_finest = o.impact_finest;
    const long family_from = o.family_from, family_to = o.family_to, family_powers_to = o.family_powers_to,
               family_reference_ratio = o.family_reference_ratio;
    const std::string& mass = o.mass;

    // The mass, checked on each mesh (a spread over more nodes than a mesh has, a matrix that is not
    // positive definite there) before any file is touched.
    std::vector<Series> series(2);
    const std::array<long, 2> series_elements{elements, coarse_elements},
        series_ratio{reference_ratio, coarse_reference_ratio}, series_steps{steps_count, coarse_steps_count};
    for (std::size_t i = 0; i < series.size(); ++i)
      series[i].mass = mrm::repro::mass_from_option("--mass", mass, mrm::UniformMesh(1.0, series_elements[i]), true);

    // The round-off benchmark's steps, h/R, h/(R/4), ... down to h/1024 (h/R alone if R < 1024), and the
    // family's meshes, each checked for the mass.
    std::vector<long> impact_ratios;
    for (long r = impact_finest; r >= std::min(1024L, impact_finest); r /= 4)
      impact_ratios.insert(impact_ratios.begin(), r);
    const std::vector<long> family_meshes = mrm::repro::time_family_meshes(family_from, family_to, 4, family_powers_to);
    std::vector<mrm::MassRedistribution> family_masses;
    for (long n : family_meshes)
      family_masses.push_back(mrm::repro::mass_from_option("--mass", mass, mrm::UniformMesh(1.0, n), true));
    // Every mesh's runs must reach the obstacle before T (require_contact), checked before any file is touched.
    for (std::size_t i = 0; i < series.size(); ++i)
      require_contact(mass, series_elements[i], series[i].mass,
                      static_cast<double>(largest) / static_cast<double>(series_elements[i]), final_time);
    for (std::size_t f = 0; f < family_meshes.size(); ++f)
      require_contact(mass, family_meshes[f], family_masses[f],
                      static_cast<double>(largest) / static_cast<double>(family_meshes[f]), final_time);
    mrm::repro::TimeFamilySettings family_settings;
    family_settings.reference_ratio = family_reference_ratio;
    family_settings.largest_courant = static_cast<double>(largest);
    family_settings.final_time = final_time;

    // 2. Outputs.
    program.open();

    // 3. The two series, one per worker (each is independent and deterministic; the output does not
    // depend on the threads).
    for (std::size_t i = 0; i < series.size(); ++i) {
      series[i].elements = series_elements[i];
      series[i].reference_ratio = series_ratio[i];
      series[i].ratio.resize(static_cast<std::size_t>(series_steps[i]));
      for (std::size_t j = 0; j < series[i].ratio.size(); ++j) series[i].ratio[j] = (largest * series_ratio[i]) >> j;
    }
    // With them on the same workers: the round-off benchmark (one task per step and form) and the family
    // (one task per mesh), the longest first.
    std::vector<double> impact_times(2 * impact_ratios.size());
    std::vector<mrm::repro::TimeFamilyMesh> family(family_meshes.size());
    const std::size_t impact_tasks = impact_times.size(), tasks = 2 + impact_tasks + family.size();
    const mrm::MassRedistribution impact_mass = mrm::mod1();
    const auto cost = [&](std::size_t t) {
      if (t < 2) return 1e12;  // the two series first: they are the longest
      if (t < 2 + impact_tasks)
        return static_cast<double>(impact_ratios[(t - 2) / 2]) * std::pow(static_cast<double>(impact_elements), 2);
      const double n = static_cast<double>(family_meshes[t - 2 - impact_tasks]);
      return 2.0 * static_cast<double>(family_reference_ratio) * n * n;
    };
    const auto task = [&](std::size_t t) {
      if (t < 2) return compute(series[t], final_time, mass);
      if (t < 2 + impact_tasks) {
        const std::size_t j = (t - 2) / 2;
        const double dt = 1.0 / static_cast<double>(impact_elements) / static_cast<double>(impact_ratios[j]);
        impact_times[t - 2] = mrm::first_impact_time(
            impact_elements, impact_mass, dt, (t - 2) % 2 == 0 ? mrm::StepForm::for_u : mrm::StepForm::increment);
        return;
      }
      const std::size_t f = t - 2 - impact_tasks;
      family[f] = mrm::repro::time_family_mesh(
          family_meshes[f], family_masses[f],
          mrm::repro::scheme_parameters(mrm::Scheme::crank_nicolson, "algebraic", mass), family_settings);
    };
    // The sweep layer's workers (repro/sweep.hpp) run them as its own tasks, costliest first: each task
    // steps its chains itself (a reference chain with its runs compared at the common instants; the
    // family's two reference chains share two vector lanes from N = 100 on, time_family.cpp).
    std::vector<mrm::repro::SweepTask> work;
    for (std::size_t t = 0; t < tasks; ++t) work.push_back({cost(t), [&task, t] { task(t); }});
    mrm::repro::SweepSettings settings = mrm::repro::sweep_settings();
    settings.threads = static_cast<unsigned>(threads);
    mrm::repro::run_batched({}, settings, {}, {}, true, work);
    for (const Series& se : series)
      for (const auto& e : se.differences)
        for (double v : e)
          if (!std::isfinite(v))
            throw std::runtime_error("a relative difference is not finite (a reference norm vanishes on this mesh)");

    // 4. Orders over the finest steps and the verdicts.
    const std::size_t points = static_cast<std::size_t>(fit_points);
    const Orders orders = fit_orders(series, points);

    // 5. Data blocks.
    std::ostream& out =
        program.header("error in time at fixed h against a reference with dt_ref = h/R (mathematics.md sec. 5, 7, 9)");
    write_series_blocks(out, series, orders);

    // Block 4: the round-off benchmark.
    const ImpactSummary impact = write_impact_block(out, impact_ratios, impact_times, impact_elements);
    // Block 5: the family.
    const FamilySummary summary = write_family_block(out, family, mass, family_reference_ratio, family_settings);

    // 6. The tables (errors with the order between consecutive steps) and the quoted values: the keys
    // time:… for the fine mesh, time:coarse:… for the coarse one.
    std::ostream& defs = program.values();
    mrm::tex_define(defs, "time:mass", mrm::repro::mass_label(mass).abbreviation);
    mrm::tex_define(defs, "time:tolerance", mrm::tex_number(order_tolerance, 2));
    mrm::tex_define(defs, "time:fitpoints", std::to_string(fit_points));
    for (std::size_t i = 0; i < series.size(); ++i) write_series_values(defs, series[i], i, orders);

    write_impact_table(defs, impact_ratios, impact_times, impact.finest, impact.spread_after, impact.spread_before,
                       impact_elements);
    write_family_table(defs, family, family_meshes, family_reference_ratio, summary.all_holds, summary.holds,
                       summary.meshes_with_region, summary.onset_smallest, summary.onset_largest, summary.onset_slope);

    // 7. Commit.
    program.commit();
    return 0;
  });
}
