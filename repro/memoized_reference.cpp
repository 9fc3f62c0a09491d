// A reference solution answered from a record of its answers; see memoized_reference.hpp.
#include "memoized_reference.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>

#include <doctest/doctest.h>

#include "exact/exact_solution.hpp"
#include "exact/impact_solution.hpp"

namespace mrm::repro {

namespace {
// An instant as the key of the record: its bits (no two doubles share them; NaN never comes here).
std::uint64_t bits_of(double t) {
  std::uint64_t b;
  std::memcpy(&b, &t, sizeof b);
  return b;
}
// The shard of an instant (of 64): the top 6 bits of its bits times 2^64/φ (Fibonacci hashing), so that
// successive instants, which differ in their last bits, fall in different shards.
std::size_t shard_of(std::uint64_t key) { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 58); }
}  // namespace

MemoizedReference::MemoizedReference(std::shared_ptr<const ReferenceSolution> inner) : inner_(std::move(inner)) {
  if (!inner_) throw std::invalid_argument("MemoizedReference: the reference is null");
}

// A vector of the record is written once, when it is inserted, and never moved afterwards (the nodes of
// an unordered_map stay where they are when it grows): it is copied out without the lock. The recorded
// points are set once (the first call) and compared without the lock; a lookup takes its shard's lock
// shared, so that the runs of the threads read at once, and only an insertion takes it alone. A question not in
// the record is evaluated without the lock, so that the other runs go on reading meanwhile.
void MemoizedReference::at_points(Vectors& record, bool velocity, double t, const double* x, long count,
                                  double* out) const {
  const std::uint64_t key = bits_of(t);
  questions_.fetch_add(1, std::memory_order_relaxed);
  std::call_once(points_once_, [&] { points_.assign(x, x + count); });
  const bool recorded_points = static_cast<long>(points_.size()) == count &&
                               std::equal(points_.begin(), points_.end(), x);  // == on every point: the same doubles
  auto& shard = record[shard_of(key)];
  if (recorded_points) {
    const std::vector<double>* found = nullptr;
    {
      std::shared_lock<std::shared_mutex> lock(shard.mutex);
      const auto it = shard.map.find(key);
      if (it != shard.map.end()) found = &it->second;
    }
    if (found) {
      std::copy(found->begin(), found->end(), out);
      return;
    }
  }
  evaluations_.fetch_add(1, std::memory_order_relaxed);
  if (velocity)
    inner_->velocity_at_points(t, x, count, out);
  else
    inner_->displacement_at_points(t, x, count, out);
  if (!recorded_points) return;
  std::vector<double> values(out, out + count);
  std::unique_lock<std::shared_mutex> lock(shard.mutex);
  shard.map.emplace(key, std::move(values));  // a value already there has the same bits
}

double MemoizedReference::scalar(Scalars& record, bool multiplier, double t) const {
  const std::uint64_t key = bits_of(t);
  questions_.fetch_add(1, std::memory_order_relaxed);
  auto& shard = record[shard_of(key)];
  {
    std::shared_lock<std::shared_mutex> lock(shard.mutex);
    const auto it = shard.map.find(key);
    if (it != shard.map.end()) return it->second;
  }
  evaluations_.fetch_add(1, std::memory_order_relaxed);
  const double value = multiplier ? inner_->contact_multiplier(t) : inner_->contact_displacement(t);
  std::unique_lock<std::shared_mutex> lock(shard.mutex);
  shard.map.emplace(key, value);
  return value;
}

double MemoizedReference::contact_displacement(double t) const { return scalar(contact_displacements_, false, t); }
double MemoizedReference::contact_multiplier(double t) const { return scalar(contact_multipliers_, true, t); }
void MemoizedReference::displacement_at_points(double t, const double* x, long count, double* u) const {
  at_points(displacements_, false, t, x, count, u);
}
void MemoizedReference::velocity_at_points(double t, const double* x, long count, double* v) const {
  at_points(velocities_, true, t, x, count, v);
}

std::size_t MemoizedReference::questions() const { return questions_.load(); }
std::size_t MemoizedReference::evaluations() const { return evaluations_.load(); }

GroupReferences::GroupReferences(std::size_t runs_per_group) : runs_per_group_(runs_per_group) {
  if (runs_per_group_ == 0) throw std::invalid_argument("GroupReferences: a group has no runs");
}

// The first run that asks makes the reference outside the lock (the other groups' runs go on), and the
// group's other runs wait for it on the shared future.
std::shared_ptr<const ReferenceSolution> GroupReferences::operator()(const Key& group, const Configuration& unit,
                                                                     double horizon) {
  std::shared_future<std::shared_ptr<const ReferenceSolution>> future;
  std::promise<std::shared_ptr<const ReferenceSolution>> promise;
  bool make = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Group& g = groups_[group];
    if (!g.made) {
      g.made = true, g.horizon = horizon, g.dt = unit.step(), g.elements = unit.elements;
      g.reference = promise.get_future().share();
      make = true;
    } else if (g.horizon != horizon || g.dt != unit.step() || g.elements != unit.elements) {
      throw std::logic_error("GroupReferences: two runs of one group ask for different exact solutions");
    }
    future = g.reference;
  }
  if (make) {
    try {
      std::shared_ptr<const ReferenceSolution> reference = unit_configuration_reference(unit, horizon);
      if (!dynamic_cast<const ExactSolution*>(reference.get()))
        reference = std::make_shared<const MemoizedReference>(std::move(reference));
      promise.set_value(std::move(reference));
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  }
  return future.get();
}

ReferenceSource GroupReferences::source(const Key& group) {
  return [this, group](const Configuration& unit, double horizon) { return (*this)(group, unit, horizon); };
}

void GroupReferences::done(const Key& group) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = groups_.find(group);
  if (it == groups_.end() || ++it->second.ended < runs_per_group_) return;
  if (it->second.reference.valid() &&
      it->second.reference.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
    try {
      if (const auto* memo = dynamic_cast<const MemoizedReference*>(it->second.reference.get().get()))
        questions_ += memo->questions(), evaluations_ += memo->evaluations();
    } catch (...) {  // the group's reference could not be made: its runs threw; nothing to count
    }
  groups_.erase(it);
}

std::size_t GroupReferences::questions() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return questions_;
}
std::size_t GroupReferences::evaluations() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return evaluations_;
}
std::size_t GroupReferences::alive() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return groups_.size();
}

namespace {
// A reference that counts the questions it is asked (its values: any smooth functions of x and t).
class CountingReference : public ReferenceSolution {
 public:
  mutable std::atomic<int> calls{0};
  double length() const override { return 1; }
  double displacement(double x, double t) const override { return std::sin(3 * x + t); }
  double strain(double x, double t) const override { return 3 * std::cos(3 * x + t); }
  double velocity(double x, double t) const override { return std::cos(3 * x + t); }
  double contact_displacement(double t) const override { return ++calls, std::sin(t); }
  double contact_multiplier(double t) const override { return ++calls, 3 * std::cos(t); }
  double energy() const override { return 1; }
  void displacement_at_points(double t, const double* x, long count, double* u) const override {
    ++calls;
    for (long k = 0; k < count; ++k) u[k] = displacement(x[k], t);
  }
  void velocity_at_points(double t, const double* x, long count, double* v) const override {
    ++calls;
    for (long k = 0; k < count; ++k) v[k] = velocity(x[k], t);
  }
};
}  // namespace

TEST_CASE("MemoizedReference: a field benchmark's answers, bit for bit, each instant evaluated once") {
  // Prediction: every answer has the bits of the chain's own (the record holds the chain's values), and
  // the second time an instant is asked at the same points nothing is evaluated.
  const ImpactBenchmark& b = impact_benchmark("impacting");
  const auto chain = std::make_shared<const ImpactReference>(b.configuration, b.data, b.final_time);
  MemoizedReference memo(chain);
  const UniformMesh mesh(chain->length(), 40);
  std::vector<double> x(41), expected(41), got(41);
  for (long i = 0; i <= 40; ++i) x[i] = mesh.x(i);
  const double dt = b.final_time / 57.3;  // the benchmark's own time unit (seconds)
  for (int pass = 0; pass < 2; ++pass) {
    for (int n = 0; (n + 0.5) * dt <= b.final_time; ++n) {
      const double t = n * dt, half = (n + 0.5) * dt;
      chain->displacement_at_points(t, x.data(), 41, expected.data());
      memo.displacement_at_points(t, x.data(), 41, got.data());
      CHECK(std::memcmp(expected.data(), got.data(), sizeof(double) * 41) == 0);
      chain->velocity_at_points(half, x.data(), 41, expected.data());
      memo.velocity_at_points(half, x.data(), 41, got.data());
      CHECK(std::memcmp(expected.data(), got.data(), sizeof(double) * 41) == 0);
      CHECK(bits_of(memo.contact_displacement(t)) == bits_of(chain->contact_displacement(t)));
      CHECK(bits_of(memo.contact_multiplier(half)) == bits_of(chain->contact_multiplier(half)));
    }
    if (pass == 0) {
      CHECK(memo.evaluations() == memo.questions());
    } else {
      CHECK(memo.evaluations() * 2 == memo.questions());
    }
  }
  CHECK(bits_of(memo.energy()) == bits_of(chain->energy()));
  const double x_mid = 0.3 * chain->length(), t_mid = 0.7 * b.final_time;
  CHECK(bits_of(memo.displacement(x_mid, t_mid)) == bits_of(chain->displacement(x_mid, t_mid)));
}

TEST_CASE("MemoizedReference: other points are asked of the solution itself, and -0 and 0 are two instants") {
  const auto counting = std::make_shared<const CountingReference>();
  MemoizedReference memo(counting);
  const double nodes[3] = {0, 0.5, 1}, others[3] = {0, 0.25, 1}, shorter[2] = {0, 0.5};
  double u[3];
  memo.displacement_at_points(0.25, nodes, 3, u);
  memo.displacement_at_points(0.25, nodes, 3, u);
  CHECK(counting->calls == 1);
  memo.displacement_at_points(0.25, others, 3, u);  // not the recorded points: evaluated, not recorded
  CHECK(u[1] == std::sin(0.75 + 0.25));
  memo.displacement_at_points(0.25, others, 3, u);
  memo.displacement_at_points(0.25, shorter, 2, u);
  CHECK(counting->calls == 4);
  memo.displacement_at_points(0.25, nodes, 3, u);
  CHECK(u[1] == std::sin(1.5 + 0.25));
  CHECK(counting->calls == 4);
  memo.contact_multiplier(0.0);
  memo.contact_multiplier(-0.0);
  memo.contact_multiplier(0.0);
  CHECK(counting->calls == 6);
  CHECK(memo.questions() == 9);
  CHECK(memo.evaluations() == 6);
  CHECK_THROWS_AS(MemoizedReference(nullptr), std::invalid_argument);
}

TEST_CASE("MemoizedReference: two threads asking the same instants read the same bits") {
  const auto counting = std::make_shared<const CountingReference>();
  const MemoizedReference memo(counting);
  std::vector<double> x(101);
  for (int i = 0; i <= 100; ++i) x[i] = i / 100.0;
  std::vector<std::vector<double>> sums(2, std::vector<double>(500));
  const auto work = [&](int who) {
    std::vector<double> v(101);
    for (int n = 0; n < 500; ++n) {
      memo.velocity_at_points(n / 64.0, x.data(), 101, v.data());
      for (double y : v) sums[who][n] += y;
      sums[who][n] += memo.contact_displacement(n / 64.0);
    }
  };
  std::thread other(work, 1);
  work(0);
  other.join();
  CHECK(sums[0] == sums[1]);
  CHECK(memo.questions() == 2000);
  CHECK(memo.evaluations() >= 1000);
  CHECK(memo.evaluations() <= 2000);
}

TEST_CASE("GroupReferences: one record per group, shared by its runs, dropped after its last run") {
  // Prediction: the runs of one group (three masses on impacting, one mesh and Δt) get the same record,
  // and their measures have the bits of run_configuration's own (the record answers with the chain's
  // doubles); the three runs ask the same questions (their instants are the same), so the record
  // evaluates nothing after the first run: the totals are three times the first run's questions and its
  // evaluations; after the third run the group is dropped and the next question makes a new reference.
  // The paper's closed form is shared as it is; another group gets its own; a group asked about another
  // Δt throws.
  GroupReferences references(3);
  const GroupReferences::Key group{1, 0, 0};
  std::vector<std::shared_ptr<const ReferenceSolution>> seen;
  std::size_t first_questions = 0, first_evaluations = 0;  // the record's counts after the first run
  for (const char* mass : {"mod1", "mod2", "mod3"}) {
    Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", mass, 10, 0.5, 1.0);
    c.benchmark = "impacting";
    c.final_time = impact_benchmark("impacting").final_time;
    const ReferenceSource source = references.source(group);
    ConfigurationRun run(c, {}, nullptr, [&](const Configuration& unit, double horizon) {
      seen.push_back(source(unit, horizon));
      return seen.back();
    });
    mrm::run(run.simulation(), run.steps(), [&](const Sample& s) { run.add(s); });
    const Measures shared = run.measures();
    const auto* memo = dynamic_cast<const MemoizedReference*>(seen.back().get());
    REQUIRE(memo != nullptr);
    if (seen.size() == 1) first_questions = memo->questions(), first_evaluations = memo->evaluations();
    CHECK(references.alive() == 1);  // the group, held while its runs measure
    references.done(group);
    const Measures own = run_configuration(c);
    const auto a = ErrorAccumulator::values(shared.errors), b = ErrorAccumulator::values(own.errors);
    CHECK(std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0);
    REQUIRE(shared.lambda_tv_ratio.has_value());
    REQUIRE(own.lambda_tv_ratio.has_value());
    CHECK(bits_of(*shared.lambda_tv_ratio) == bits_of(*own.lambda_tv_ratio));
  }
  REQUIRE(seen.size() == 3);
  CHECK(seen[0] == seen[1]);
  CHECK(seen[1] == seen[2]);
  CHECK(references.alive() == 0);
  CHECK(first_evaluations > 0);
  CHECK(references.questions() == 3 * first_questions);
  CHECK(references.evaluations() == first_evaluations);

  Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 10, 0.5, 1.0);
  c.benchmark = "impacting";
  c.final_time = impact_benchmark("impacting").final_time;
  const Configuration unit = unit_configuration(c, configuration_scaling(c));
  const auto again = references(group, unit, 1.0);  // dropped: made anew (seen[0] is still held)
  CHECK(again != seen[0]);
  CHECK(references(GroupReferences::Key{1, 0, 1}, unit, 1.0) != again);
  CHECK(references.alive() == 2);
  Configuration finer = unit;
  finer.dt = unit.step() / 2;
  CHECK(finer.step() != unit.step());
  CHECK_THROWS_AS(references(group, finer, 1.0), std::logic_error);

  const Configuration paper = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 10, 0.5, 1.0);
  const GroupReferences::Key closed{0, 0, 0};
  CHECK(dynamic_cast<const ExactSolution*>(references(closed, paper, 1.0).get()) != nullptr);
  CHECK_THROWS_AS(GroupReferences(0), std::invalid_argument);
}

}  // namespace mrm::repro
