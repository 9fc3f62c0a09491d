// A reference solution answered from a record of its answers; see memoized_reference.hpp.
#include "memoized_reference.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>

#include <doctest/doctest.h>

#include "impact_solution.hpp"

namespace mrm::repro {

namespace {
// An instant as the key of the record: its bits (no two doubles share them; NaN never comes here).
std::uint64_t bits_of(double t) {
  std::uint64_t b;
  std::memcpy(&b, &t, sizeof b);
  return b;
}
}  // namespace

MemoizedReference::MemoizedReference(std::shared_ptr<const ReferenceSolution> inner) : inner_(std::move(inner)) {
  if (!inner_) throw std::invalid_argument("MemoizedReference: the reference is null");
}

// A vector of the record is written once, when it is inserted, and never moved afterwards (the nodes of
// an unordered_map stay where they are when it grows): it is copied out without the lock. The recorded
// points are set once (the first call) and compared without the lock; a lookup takes the lock shared,
// so that the runs of the threads read at once, and only an insertion takes it alone. A question not in
// the record is evaluated without the lock, so that the other runs go on reading meanwhile.
void MemoizedReference::at_points(Vectors& record, bool velocity, double t, const double* x, long count,
                                  double* out) const {
  const std::uint64_t key = bits_of(t);
  questions_.fetch_add(1, std::memory_order_relaxed);
  std::call_once(points_once_, [&] { points_.assign(x, x + count); });
  const bool recorded_points = static_cast<long>(points_.size()) == count &&
                               std::equal(points_.begin(), points_.end(), x);  // == on every point: the same doubles
  if (recorded_points) {
    const std::vector<double>* found = nullptr;
    {
      std::shared_lock<std::shared_mutex> lock(mutex_);
      const auto it = record.find(key);
      if (it != record.end()) found = &it->second;
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
  std::unique_lock<std::shared_mutex> lock(mutex_);
  record.emplace(key, std::vector<double>(out, out + count));  // a value already there has the same bits
}

double MemoizedReference::scalar(Scalars& record, bool multiplier, double t) const {
  const std::uint64_t key = bits_of(t);
  questions_.fetch_add(1, std::memory_order_relaxed);
  {
    std::shared_lock<std::shared_mutex> lock(mutex_);
    const auto it = record.find(key);
    if (it != record.end()) return it->second;
  }
  evaluations_.fetch_add(1, std::memory_order_relaxed);
  const double value = multiplier ? inner_->contact_multiplier(t) : inner_->contact_displacement(t);
  std::unique_lock<std::shared_mutex> lock(mutex_);
  record.emplace(key, value);
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

TEST_CASE("MemoizedReference: other points are asked of the solution itself; -0 and 0 are two instants") {
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

}  // namespace mrm::repro
