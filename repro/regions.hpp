// Claims judged over regions of parameters (mathematics.md §6, §8, §9): one sweep of the benchmark
// over schemes × masses × Δt/h × N, each run to the longest horizon with its errors at every horizon
// (run_configurations), and the two analyses the claims and the maps share: the ordering
// Mod 3 < Mod 2 < Mod 1 per cell (scheme, Δt/h, N, horizon), and the observed orders in h per
// (scheme, mass, Δt/h, horizon) against the predicted ones.
#pragma once

#include <array>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "configurations.hpp"
#include "measures/errors.hpp"
#include "labels.hpp"

namespace mrm::repro {

/// The grid of the sweep. Horizons are in periods of the benchmark (3L); every run goes to the last.
struct SweepGrid {
  std::vector<std::string> schemes = scheme_names();  ///< the paper's; Paoli–Schatzman with the algebraic row
  std::vector<std::string> masses = mass_names();
  bool baseline = true;  ///< also Paoli–Schatzman with the consistent mass (literal row) in every (Δt/h, N)
  std::vector<double> courants = {0.25, 0.5, 0.75, 1.0};
  std::vector<Index> elements = {25, 50, 100, 200, 400, 800};
  std::vector<double> horizons = {1, 4, 10, 30};
};

/// One run of the sweep: its errors at every horizon and its phase over the longest one.
struct SweepRun {
  std::string scheme;  ///< an id of the scheme registry (to_string(Scheme)), or "ps-consistent" (the baseline)
  std::string mass;    ///< "mod1", "mod2", "mod3" or "consistent"
  double courant = 0;
  Index elements = 0;
  std::vector<std::array<double, 8>> errors;  ///< one per horizon, in ErrorAccumulator::names order
  double first_impact_error = 0;
  std::optional<double> drift_per_period;
};

struct Sweep {
  SweepGrid grid;
  std::vector<SweepRun> runs;
  /// The run of (scheme, mass, Δt/h, N); throws std::out_of_range if the sweep has none.
  const SweepRun& find(const std::string& scheme, const std::string& mass, double courant, Index elements) const;
};

/// Runs every configuration of the grid on `threads` threads (0: all hardware threads); `progress`
/// (may be null) gets one line when it starts and one when it ends.
Sweep run_sweep(const SweepGrid& grid, unsigned threads = 0, std::ostream* progress = nullptr);

/// The sweep as a data file: `# key = value` lines for the grid, then one line per run and horizon,
/// `scheme mass courant elements horizon` and the eight errors (shortest round-trip numbers), and per
/// run the phase. read_sweep reads it back; it throws std::runtime_error naming the line for anything
/// else.
void write_sweep(std::ostream& out, const Sweep& sweep);
Sweep read_sweep(std::istream& in);
/// The sweep in the file `path`, given by the option `option` of a map program: throws
/// cli::UsageError naming the option if the file cannot be opened.
Sweep read_sweep_file(const std::string& path, const std::string& option);

/// The measures a scheme is judged in. Paoli–Schatzman (¼, 0) with the algebraic row computes the
/// displacements and λ of Crank–Nicolson exactly (a doctest of schemes.cpp): its displacement-type
/// measures and λ repeat Crank–Nicolson's and are merged into its rows; only its velocity, a difference
/// quotient at the half step, is its own. Indices into ErrorAccumulator::names.
std::vector<std::size_t> judged_measures(const std::string& scheme);

/// Claim 3 in one cell: for each of the eight measures, whether error(Mod 3) < error(Mod 2) <
/// error(Mod 1) strictly (the masses of `ordered`, worst first).
struct OrderingCell {
  std::string scheme;
  double courant = 0;
  Index elements = 0;
  std::size_t horizon = 0;  ///< index into the grid's horizons
  std::array<bool, 8> ordered{};
  int count(const std::vector<std::size_t>& measures) const;  ///< how many of `measures` are ordered
};
std::vector<OrderingCell> ordering_cells(const Sweep& sweep, const std::vector<std::string>& ordered);

/// The predicted orders in h of mathematics.md §9 for the benchmark: Crank–Nicolson (and the
/// Paoli–Schatzman forms, with Crank–Nicolson's phase error) 2/3 for the displacement measures (u and
/// u(0,·)) and 1/3 for the energy-type ones (H¹ of u, L² of u_t) and λ; backward Euler 1/2 and 1/4.
/// The tolerance is half the distance between a scheme's two predicted orders (1/6, 1/8): a measured
/// order is attributed to the nearer class, and an order 0 or 1 belongs to neither.
struct PredictedOrders {
  double displacement, energy, tolerance;
  double of(std::size_t measure) const;  ///< the prediction for measure `measure`
};
PredictedOrders predicted_orders(const std::string& scheme);
/// Whether measure `k` (ErrorAccumulator::names order) is of displacement type (u, u(0,·)).
bool displacement_measure(std::size_t k);

/// The orders of a mass whose period is off by O(h) (mathematics.md §8: Mod 1, Mod 2) once its phase
/// error dominates: the impacts are displaced by δ ∝ h t, which costs δ in the displacement measures (u
/// is Lipschitz) and δ^{1/2} in the energy-type ones and λ (an O(1) jump displaced by δ): orders 1 and ½.
/// For Crank–Nicolson the phase error overtakes the smearing (h²t)^{1/3} after t ∝ h^{−1/2}, within the
/// horizons of the sweep; for backward Euler the smearing (Δt t)^{1/2} stays larger.
struct DriftOrders {
  double displacement = 1.0, energy = 0.5;
};
/// Whether the mass's period differs from 3L by more than h/10 on N = 100 (the period law).
bool mass_drifts(const std::string& mass);
/// The interval an order in h must lie in: [p − tol, p + tol] around the prediction, stretched up to
/// the drift's order + tol for a drifting mass with a scheme whose smearing is the smaller
/// (Crank–Nicolson and the Paoli–Schatzman forms).
std::pair<double, double> allowed_order(const std::string& scheme, const std::string& mass, std::size_t measure);

/// The observed order: the slope of the least-squares line through (log x_k, log y_k) (mathematics.md §5,
/// lib/convergence's fit_order). Data that admit no order (steps that were not refined, an error that
/// vanished) give NaN, which fails every criterion on the order.
double observed_order(const std::vector<double>& x, const std::vector<double>& y);

/// Claim 4 in one cell: the least-squares orders in h over the grid's meshes, and whether each lies
/// in its allowed interval.
struct OrderCell {
  std::string scheme, mass;
  double courant = 0;
  std::size_t horizon = 0;
  std::array<double, 8> order{};
  std::array<bool, 8> within{};
};
std::vector<OrderCell> order_cells(const Sweep& sweep);

/// Claim 1 over a region (mathematics.md §12): Crank–Nicolson with a massless contact node conserves E_h
/// while the contact status is kept, loses energy at an impact and gains at most c²h v²/8 at a release
/// (c = Δt/h). The grid that claims.cpp's rows and fig_stability_map (the report's figure) share, so that
/// both speak of the same meshes: the largest E_hⁿ/E_h(0) over `periods` periods for Δt/h from ¼ to 40
/// (ratio √2, and 40) on `meshes` (Mod 3); every N of `scan` at the ratios up to `scan_up_to` (Mod 3,
/// the same periods: how far down in N the bound holds); and `long_periods` periods at Δt = h on
/// `meshes` with Mod 1, 2, 3. "Bounded": at most `threshold` E_h(0).
struct StabilityGrid {
  std::vector<Index> meshes = {16, 32, 64, 128};
  std::vector<double> courants = stability_courants();
  double periods = 100;
  std::vector<Index> scan = scan_meshes(4, 40);
  double scan_up_to = 2;
  double long_courant = 1, long_periods = 1000;
  double threshold = 2;
  static std::vector<double> stability_courants();  ///< ¼ √2^k, k = 0 … 14, and 40
  static std::vector<Index> scan_meshes(Index first, Index last);
};
/// One run of the grid: its largest E_hⁿ/E_h(0).
struct StabilityCell {
  std::string mass;
  Index elements;
  double courant, periods, largest;
};
struct StabilityRegion {
  StabilityGrid grid;
  std::vector<StabilityCell> large, scan, long_runs;
  /// The largest Δt/h of the grid up to which every mesh of `meshes` stays bounded (the ratios are
  /// increasing; the first one some mesh exceeds ends it).
  double bounded_up_to() const;
  /// The largest E_hⁿ/E_h(0) over the meshes at the ratio `courant`.
  double worst_at(double courant) const;
  /// The meshes of the scan that exceed the threshold at some Δt/h ≤ scan_up_to, with their largest ratio.
  std::vector<std::pair<Index, double>> scan_failures() const;
  /// The smallest N of the scan from which every scanned N stays bounded.
  Index bounded_from() const;
};
/// All runs of the grid (threads).
StabilityRegion run_stability_region(const StabilityGrid& grid = {});

}  // namespace mrm::repro
