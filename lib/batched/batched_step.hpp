/// @file batched_step.hpp
/// @brief Many runs of the same mesh size and scheme family advanced together, one run per lane of the
/// machine's vector registers (Google Highway, the vector width chosen at run time), each lane
/// bitwise identical to its run stepped alone (batched_step.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "measures/errors.hpp"
#include "time/schemes.hpp"

namespace mrm {

class NewmarkTypeStep;  // contact_classes.hpp
class OneSolveStep;     // contact_classes.hpp

/// A vector target the batched step can run on: its name (Highway's: "AVX3", "AVX2", "SSE4", "EMU128",
/// "NEON", ...), its number of double lanes, and its Highway target bit.
struct BatchTarget {
  std::string name;   ///< Highway's name of the target
  std::size_t lanes;  ///< doubles per vector
  std::int64_t bit;   ///< Highway's target bit (use_batch_target)
};

/// The targets compiled into this binary that this processor supports and that have at least two
/// lanes, widest first (the batched step is left on the widest).
std::vector<BatchTarget> batch_targets();
/// Restricts the batched step to the target `bit` (one of batch_targets()) for the whole process, or
/// with 0 returns to the widest supported one (the default). For benchmarks and tests; not thread-safe
/// against a concurrent BatchedSimulation::step.
void use_batch_target(std::int64_t bit);
/// The target the batched step uses now.
BatchTarget current_batch_target();

/// The family of a scheme's batched kernel: 0 for the two-level steps (Crank–Nicolson and backward
/// Euler: the same sweeps, the scheme only in each lane's factors and rates), 1 Paoli–Schatzman (three
/// levels), 2 EC, 3 CN-switch, 4 the Newmark-type classes (newmark, penalty, nitsche: contact_classes.hpp,
/// NewmarkTypeStep), 5 Moreau–Jean and 6 DKE (OneSolveStep), 7 the explicit classes (Taylor–Flanagan and
/// explicit: ExplicitStep, lumped and consistent masses in groups of their own). Runs of the same number of
/// unknowns and family, on the fast kernel, share the lanes of a group whatever their scheme, mass, Δt or
/// data, and, for families 0–3, their steady load or none (a load that changes with t, or one on a class of
/// families 4–7, is stepped alone); runs of different families never do. Every scheme of the registry has a
/// family (a doctest checks it). The sweep layer batches runs by it (repro/sweep.hpp).
/// It is the scheme's registry entry's batch_family (lib/time/scheme_registry.hpp).
int batch_family(Scheme scheme);

/// A batch of runs (BarSimulation's at level 0, moved in) advanced one step at a time. Runs whose steps can
/// share vector registers (the fast kernel, without a load or with a steady one (families 0–3), and the same
/// number of unknowns, scheme family — two-level, Paoli–Schatzman, EC, CN-switch, Newmark-type, Moreau–Jean,
/// DKE, explicit (the classes: at least 4 unknowns, no load; the explicit ones on a uniform homogeneous
/// mesh) — and fast-step layout, FastStep's explicit head rows) are grouped by lanes of the current target:
/// groups of the target's full width, and the remainder of a family in one group of the narrowest width
/// that holds it (2, 4 or the full width: padding lanes cost as much as runs); every other run (the
/// reference kernel, a load that changes with t, a remainder of one) is stepped alone. Paoli–Schatzman's
/// Crank–Nicolson first step and CN-switch's θ-step at a status change are each lane's own scalar step.
/// Every run ends in the same state, bit for bit, as if stepped alone by BarSimulation::step (the doctests
/// of lanes_alone.cpp).
class BatchedSimulation {
 public:
  /// Takes the runs (each at level 0), groups them by lanes of the current target and copies the
  /// grouped runs' states and factors into the lanes.
  explicit BatchedSimulation(std::vector<BarSimulation> runs);
  ~BatchedSimulation();
  BatchedSimulation(BatchedSimulation&&) noexcept;             ///< moves the runs and their lanes
  BatchedSimulation& operator=(BatchedSimulation&&) noexcept;  ///< moves the runs and their lanes

  /// Advances every run by one step.
  void step();
  /// Advances the runs k with advance[k] ≠ 0 by one step and leaves the others as they are, bit for bit
  /// (a run's lane is kept, not stepped): runs of different Δt share a batch, each stepped at its own rate
  /// (the sweep layer, repro/sweep/batched.cpp). Throws std::invalid_argument unless there is one flag per run.
  void step(const std::vector<char>& advance);
  /// The number of runs.
  std::size_t size() const { return runs_.size(); }
  /// Run k with its current state (copied out of the vector lanes when needed).
  const BarSimulation& run(std::size_t k);
  /// Run k's sample without copying its vectors out of the lanes: the sample of its simulation (its
  /// instants, λ, energy and the displacement's first entry are current; the rest of its vectors may be
  /// older) and where its displacement and velocity are now, in the interleaved lanes of its group
  /// (stride: the group's width, 2, 4 or lanes()) or in its own vectors (stride 1). The same entries as
  /// run(k).sample()'s.
  Sample sample(std::size_t k, LaneVectors& lanes) const;
  /// The number of runs advanced in vector lanes (the others are stepped alone).
  std::size_t batched_runs() const;
  /// The interior rows whose factors the sweeps hold in registers (the plateau, batched_step.cpp), summed
  /// over the groups.
  std::size_t plateau_rows() const;
  /// The target's full width in doubles: the lanes of a full group (a remainder's group may be
  /// narrower, group_widths()).
  std::size_t lanes() const { return lanes_; }
  /// The lanes of each group, in the order the groups are stepped (for tests and diagnostics).
  std::vector<std::size_t> group_widths() const;

 private:
  struct Group;
  static void load_lane(Group& g, std::size_t j, BarSimulation& run);         // run's vectors → lane j
  static void store_lane(const Group& g, std::size_t j, BarSimulation& run);  // lane j → run's vectors
  static void find_plateau(Group& g);  // the interior rows whose factors repeat (batched_step.cpp)
  static void fill_newmark(Group& g, std::vector<BarSimulation>& runs);              // a Newmark-type group's lanes
  void advance_newmark(Group& g, const char* flags);                                 // its step
  static NewmarkTypeStep& newmark_step(BarSimulation& run);                          // a Newmark-type run's step
  static void fill_one_solve(Group& g, std::vector<BarSimulation>& runs, bool dke);  // Moreau–Jean's or DKE's
  void advance_one_solve(Group& g, const char* flags);                               // its step
  static OneSolveStep& one_solve_step(BarSimulation& run);                           // such a run's step
  static void fill_explicit(Group& g, std::vector<BarSimulation>& runs);             // an explicit group's lanes
  void advance_explicit(Group& g, const char* flags);                                // its step
  void advance(const char* flags);  // step(flags) without the check; null: every run
  // A class group's step: the family's passes(moves, all), then each advancing run's finish(j, run, state)
  // and its bookkeeping (batched_step.cpp).
  template <class Passes, class Finish>
  void advance_class(Group& g, const char* flags, const Passes& passes, const Finish& finish);
  std::vector<BarSimulation> runs_;
  std::vector<std::unique_ptr<Group>> groups_;
  std::vector<std::size_t> alone_;  // the runs stepped alone
  std::vector<char> stale_;         // run k's vectors are older than its lane's
  std::vector<std::size_t> group_of_, lane_of_;
  std::size_t lanes_ = 1;
};

}  // namespace mrm
