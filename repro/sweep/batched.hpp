/// @file sweep/batched.hpp
/// @brief The batched sweep: runs of the same N and scheme family stepped together on vector lanes, sharing their references.
#pragma once

#include "sweep/job_grid.hpp"

namespace mrm::repro {

/// The exact solutions shared by the runs of a sweep: the reference of a unit
/// configuration (unit_configuration_reference), computed once per benchmark or data, mesh, Δt and
/// horizon and handed to every run that asks for the same (safe on several threads; a second run that
/// asks while the first computes it waits for it).
class ReferenceCache {
 public:
  ReferenceCache();
  ~ReferenceCache();
  /// The reference of `unit` up to `horizon`: computed on the first call, the same object afterwards.
  std::shared_ptr<const ReferenceSolution> operator()(const Configuration& unit, double horizon);
  /// The number of references computed (not found in the cache).
  std::size_t computed() const;

 private:
  struct Store;
  std::unique_ptr<Store> store_;
};

/// How a batched sweep runs: `threads` workers (0: one per hardware thread) and the runs in vector
/// lanes (`batched`) or each alone. Neither changes a result.
struct SweepSettings {
  unsigned threads = 0;
  bool batched = true;
};
/// The settings of this process's sweeps (default: every hardware thread, batched); a program's
/// --threads and --vector set them (add_sweep_options), before any sweep runs.
SweepSettings& sweep_settings();

/// The options of a program whose runs go through the sweep layer: --threads J (default: one per
/// hardware thread) and --vector W (widest: the widest vector target of this processor; one of
/// batch_targets()' names; none: every run stepped alone). Neither changes an output byte: they exist
/// to show it (tests/sweep_widths.sh, with the program sweep) and to run on fewer cores.
struct SweepOptions {
  long threads = 0;
  std::string vector = "widest";
};
void add_sweep_options(cli::Parser& parser, SweepOptions& options);
/// Sets sweep_settings() and the batched step's target (use_batch_target) from the parsed options.
void apply_sweep_options(const SweepOptions& options);

/// The memory of a run stepped in a vector lane, per element: its simulation, the batched step's copy of its
/// vectors and factors, its error sums' interpolants (measured at N = 1e5, 8 lanes of AVX3: 524 bytes for
/// penalty and nitsche, the most of the registry's schemes, 320 for cn; 600 with a margin).
constexpr double batched_bytes_per_lane_element = 600;
/// A cli::UsageError naming `option` unless the runs of `configurations` fit in the memory the process may
/// use when they go through the sweep layer with `settings` (cli::require_mesh_memory): up to
/// `settings.threads` workers (0: one per hardware thread) each stepping a batch of up to the vector
/// target's lanes (1 unless batched) of runs of the largest mesh, at batched_bytes_per_lane_element a lane
/// and element. Called before run_batched, so that a sweep that cannot fit is refused before any work,
/// not ended by std::bad_alloc after it.
void require_batched_memory(std::string_view option, const std::vector<Configuration>& configurations,
                            const SweepSettings& settings = sweep_settings());

/// What groups runs into batches: their number of elements and their scheme's batch_family
/// (lib/batched/batched_step.hpp: Crank–Nicolson and backward Euler share one).
using BatchKey = std::pair<Index, int>;
/// Starts run k on a worker: returns its simulation at level 0 and sets `steps`, its number of steps.
using BatchStart = std::function<BarSimulation(std::size_t k, Index& steps)>;
/// Observes level n of run k (levels 0, 1, … in order, on the worker of its batch); returns whether
/// the run wants the next level (false: it is no longer observed, e.g. after a non-finite value).
using BatchObserve = std::function<bool(std::size_t k, const Sample& sample)>;
/// Observes level n of run k as BatchObserve does, with its displacement and velocity where the batch
/// keeps them (`lanes`: BatchedSimulation::sample, nothing copied; the sample's own vectors hold only
/// the displacement's first entry for certain). Returns whether the run wants the next level, or
/// nothing if it needs the sample's vectors: then the level is copied out and given to BatchObserve.
using BatchLaneObserve =
    std::function<std::optional<bool>(std::size_t k, const Sample& sample, const LaneVectors& lanes)>;
/// Sees one level of the runs of a batch that are read in place, before `lane_observe` sees them one by
/// one: the runs, their samples and their lanes (the same as lane_observe's), so that work over every
/// lane can be done in one pass (run_batched: the error sums, ErrorAccumulator::add_lanes).
using BatchLevelPrepare = std::function<void(const std::vector<std::size_t>& runs, const std::vector<Sample>& samples,
                                             const std::vector<LaneVectors>& lanes)>;
/// The sweep layer's engine: independent simulations, run k started by `start`, observed by `observe`
/// at each of its levels 0 … steps, then `finish(k)`. Runs of the same key are grouped, costliest first
/// (`costs`), into batches of the vector width (lib/batched/batched_step.hpp: each lane is bitwise its run
/// stepped alone), and the batches are spread over the threads (repro/parallel.hpp), costliest first.
/// `own_rates`: in a batch whose Δt are whole multiples of the smallest and whose runs reach the same
/// horizon, each run steps at its own rate (BatchedSimulation::step(advance)), so the runs reach their
/// common instants at the same batch step, and a run that has ended, or whose observer wants no more,
/// stays as it is (run_batched with the caller's keys). Otherwise every run of the batch steps at every
/// batch step, observed up to its own last level, except a contact class's run (contact_classes.hpp), which
/// stays once it has ended: its step checks the energy's finiteness, and an explicit run stepped past its
/// horizon could lose it and throw.
/// Each run sees the samples it would see stepped alone, so whatever a caller writes from them, in its
/// own order, has the same bytes for any thread count and any vector width. The first exception stops
/// the sweep and is rethrown.
/// With `lane_observe`, the runs stepped in vector lanes are observed through it first (no copy of their
/// vectors out of the lanes per level), each level of a batch's lanes first by `prepare` if given.
/// `most`: the most runs per batch (0: the vector width; the batched step groups a batch's runs by family
/// and width itself, and steps the others alone).
/// `whole` (if not empty, one flag per run): the runs k with whole[k] ≠ 0 are not one-body simulations
/// (two bodies, a program's own task): each is one task, `run_whole(k)`, on the same workers, placed among
/// the batches by its cost; `start`, `observe` and `finish` are not called for it, and its key is not used.
void step_in_batches(const std::vector<BatchKey>& keys, const std::vector<double>& costs, const BatchStart& start,
                     const BatchObserve& observe, const std::function<void(std::size_t k)>& finish,
                     const SweepSettings& settings = sweep_settings(), const BatchLaneObserve& lane_observe = {},
                     const BatchLevelPrepare& prepare = {}, std::size_t most = 0, bool own_rates = false,
                     const std::vector<char>& whole = {}, const std::function<void(std::size_t k)>& run_whole = {});

/// A task of a sweep that is not a configuration (a program's own study, e.g. a run on a graded mesh):
/// its cost in the units of a configuration's (elements × steps), for the order of the work, and the work,
/// which writes its result to a place of its own.
struct SweepTask {
  double cost = 0;            ///< elements × steps, or an estimate in those units
  std::function<void()> run;  ///< the work; run once, on one of the sweep's workers
};

/// Independent configurations, each measured as run_configuration measures it, through the sweep layer:
/// the runs of the same number of elements and scheme family (batch_family: Crank–Nicolson and backward
/// Euler together) are grouped, costliest first, into batches of the
/// vector width (lib/batched/batched_step.hpp: each lane is bitwise its run stepped alone), the batches spread
/// over the threads (repro/parallel.hpp), and the reference of each data, mesh, Δt and horizon is
/// computed once (ReferenceCache). The measures come back in the order given, the same bytes as
/// run_configurations for any thread count and any vector width; a run that throws stops the sweep
/// with its exception.
/// `observe` (if given) sees every sample of run k as run_configuration's observer would, called as
/// observe(k, sample) on the worker of k's batch (the samples of one run in order; those of different
/// runs interleaved: an observer writes only run k's own state).
/// `keys` (if given, one per configuration) replaces that grouping: the runs of one key make one batch,
/// whatever their number and families; for runs of different schemes on the same mesh, Δt and horizon,
/// whose error measures then evaluate the closed form once per instant for all of them
/// (ErrorAccumulator::add_lanes); the batched step still groups only runs of one family.
/// `observer_reads_vectors` false: `observe` reads only a sample's level, instants, λ and energy
/// (ConfigurationRun::set_observer_reads_vectors), so the runs in lanes are observed in place; its samples'
/// displacement and velocity are null.
/// Two bodies (is_two_body_configuration) are run whole by run_configuration on the same workers (they take
/// no observer: with `observe`, std::invalid_argument before any run). `tasks`: the sweep's work that is
/// not a configuration, each task run once on the same workers, ordered with the runs by cost.
std::vector<Measures> run_batched(const std::vector<Configuration>& configurations,
                                  const SweepSettings& settings = sweep_settings(),
                                  const std::function<void(std::size_t k, const Sample& sample)>& observe = {},
                                  const std::vector<BatchKey>& keys = {}, bool observer_reads_vectors = true,
                                  const std::vector<SweepTask>& tasks = {});

}  // namespace mrm::repro
