/// @file memoized_reference.hpp
/// @brief A reference solution that answers a question it was asked before from its record: runs on the
/// same mesh and time grid (the class-mass pairs of fig_classes) ask the exact solution the same
/// questions at the same instants, and its evaluation (a field benchmark's chain, a characteristic
/// solution) costs more than the run's step.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "configurations.hpp"
#include "exact/reference_solution.hpp"

namespace mrm::repro {

/// `inner` seen through a record of its answers. displacement_at_points and velocity_at_points at the
/// points of the first call (a mesh's nodes), contact_displacement and contact_multiplier are
/// evaluated once per instant (the instant's bits: −0 and 0 are two instants) and copied from the record
/// afterwards: the same doubles as `inner`'s, whoever asked first. At other points, and for the pointwise
/// values, `inner` is asked directly. Safe on several threads (a question asked by two runs at once may
/// be evaluated twice; both give the same bits). The record grows with the instants asked: one per run
/// group, dropped with it. It is not `inner`'s type: a caller that looks through the type of a reference
/// (repro::run_configuration's phase measures, ErrorAccumulator's closed-form path) does not see it, so
/// a closed form is not wrapped (the caller's choice), and the phase of a run measured against a record
/// is absent.
class MemoizedReference final : public ReferenceSolution {
 public:
  /// Throws std::invalid_argument for a null `inner`.
  explicit MemoizedReference(std::shared_ptr<const ReferenceSolution> inner);

  double length() const override { return inner_->length(); }
  double displacement(double x, double t) const override { return inner_->displacement(x, t); }
  double strain(double x, double t) const override { return inner_->strain(x, t); }
  double velocity(double x, double t) const override { return inner_->velocity(x, t); }
  double contact_displacement(double t) const override;
  double contact_multiplier(double t) const override;
  double energy() const override { return inner_->energy(); }
  void displacement_at_points(double t, const double* x, long count, double* u) const override;
  void velocity_at_points(double t, const double* x, long count, double* v) const override;

  const ReferenceSolution& inner() const { return *inner_; }  ///< the solution recorded
  /// The questions answered so far, and how many of them `inner` evaluated (the others: from the record).
  std::size_t questions() const;
  std::size_t evaluations() const;

 private:
  // A record is split in shards by its instants (shard_of), each with its own lock: a shard is read under a
  // shared lock (the runs of the threads at once) and inserted into under an exclusive one. The runs of a
  // group ask the same instants, one run a few steps behind the other: under one lock for the whole record
  // the one behind would wait, asleep, for each insertion of the one ahead (a futex call per question:
  // measured, a third of fig_classes's time); in 64 shards two runs meet in one for 1 question in 64.
  static constexpr std::size_t shards = 64;
  template <typename Map>
  struct alignas(64) Shard {
    std::shared_mutex mutex;
    Map map;
  };
  using Vectors = std::array<Shard<std::unordered_map<std::uint64_t, std::vector<double>>>, shards>;
  using Scalars = std::array<Shard<std::unordered_map<std::uint64_t, double>>, shards>;
  void at_points(Vectors& record, bool velocity, double t, const double* x, long count, double* out) const;
  double scalar(Scalars& record, bool multiplier, double t) const;

  std::shared_ptr<const ReferenceSolution> inner_;
  mutable std::once_flag points_once_;
  mutable std::vector<double> points_;  // the points of the first *_at_points call, never changed after it
  mutable Vectors displacements_, velocities_;
  mutable Scalars contact_displacements_, contact_multipliers_;
  mutable std::atomic<std::size_t> questions_{0}, evaluations_{0};
};

/// The exact solutions of a program's run groups: the runs of one group (one benchmark, mesh and Δt,
/// and as many masses or contact classes as the group has runs) ask the same questions at the same
/// instants, so the group's reference (unit_configuration_reference) is made once, by the first run
/// that asks, seen through a record (MemoizedReference: the same doubles as each run's own reference,
/// so the same bytes), shared by the group's runs, and dropped when the last of its `runs_per_group`
/// runs ends (done). A closed form (ExactSolution, the paper's benchmark) is shared as it is, not
/// wrapped: its error sums take a path of their own, cheaper than a record. A record holds the nodal
/// values of every instant asked, about 2 (N + 1) doubles per level of the runs: the caller schedules a
/// group's runs one after the other so that few groups are alive at once. Safe on several threads.
/// (fig_classes' class matrix.)
class GroupReferences {
 public:
  /// A group: three indices of the caller's (fig_classes: benchmark, mesh, Δt).
  using Key = std::tuple<std::size_t, std::size_t, std::size_t>;
  /// Throws std::invalid_argument for runs_per_group = 0.
  explicit GroupReferences(std::size_t runs_per_group);

  /// The reference of `group` for a run's unit configuration up to `horizon` (a ReferenceSource's
  /// arguments): made by the first run that asks (the others wait for it; its exception, if any, is
  /// rethrown to each); std::logic_error if a later run of the group asks about another mesh, Δt or
  /// horizon.
  std::shared_ptr<const ReferenceSolution> operator()(const Key& group, const Configuration& unit, double horizon);
  /// The source of a run of `group` (ConfigurationRun's `source`); `*this` must outlive it.
  ReferenceSource source(const Key& group);
  /// A run of `group` has ended: the last one drops the group's reference (its runs still hold it while
  /// they measure), after adding its record's counts to the totals.
  void done(const Key& group);
  /// The questions the dropped groups' records answered and how many of them were evaluated.
  std::size_t questions() const;
  std::size_t evaluations() const;
  /// The groups whose reference is held (asked for and not yet dropped).
  std::size_t alive() const;

 private:
  struct Group {
    bool made = false;
    double horizon = 0, dt = 0;
    Index elements = 0;
    std::size_t ended = 0;
    std::shared_future<std::shared_ptr<const ReferenceSolution>> reference;
  };
  std::size_t runs_per_group_;
  mutable std::mutex mutex_;
  std::map<Key, Group> groups_;
  std::size_t questions_ = 0, evaluations_ = 0;
};

}  // namespace mrm::repro
