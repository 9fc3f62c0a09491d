/// @file memoized_reference.hpp
/// @brief A reference solution that answers a question it was asked before from its record: runs on the
/// same mesh and time grid (the class-mass pairs of fig_classes) ask the exact solution the same
/// questions at the same instants, and its evaluation (a field benchmark's chain, a characteristic
/// solution) costs more than the run's step. Issue 24, item 2.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <vector>

#include "reference_solution.hpp"

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
  using Vectors = std::unordered_map<std::uint64_t, std::vector<double>>;
  using Scalars = std::unordered_map<std::uint64_t, double>;
  void at_points(Vectors& record, bool velocity, double t, const double* x, long count, double* out) const;
  double scalar(Scalars& record, bool multiplier, double t) const;

  std::shared_ptr<const ReferenceSolution> inner_;
  // The records: read under a shared lock (the runs of the threads at once), inserted into under an
  // exclusive one.
  mutable std::shared_mutex mutex_;
  mutable std::once_flag points_once_;
  mutable std::vector<double> points_;  // the points of the first *_at_points call, never changed after it
  mutable Vectors displacements_, velocities_;
  mutable Scalars contact_displacements_, contact_multipliers_;
  mutable std::atomic<std::size_t> questions_{0}, evaluations_{0};
};

}  // namespace mrm::repro
