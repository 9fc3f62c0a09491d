/// @file sweep/batched.cpp
/// @brief The batched scheduler: the runs of a sweep stepped together on vector lanes, with the references they share.
#include "sweep/batched.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <fstream>
#include <future>
#include <map>
#include <mutex>
#include <thread>
#include <tuple>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <doctest/doctest.h>

#include "measures/errors.hpp"
#include "exact/impact_solution.hpp"
#include "batched/batched_step.hpp"
#include "classes/contact_classes.hpp"
#include "fem/p1.hpp"
#include "fem/mass_redistribution.hpp"
#include "options.hpp"
#include "parallel.hpp"
#include "run_limits.hpp"

namespace mrm::repro {

// ---- The batched sweep ------------------------------------------------------------------------------

namespace {

// What a unit configuration's reference depends on (unit_reference in configurations/scaling.cpp): its data
// or its field chain, by content (the unit configuration of each run holds its own scaled copy of
// either, so runs of the same benchmark, whatever their mass or scheme, share one reference), or the
// benchmark's name and the paper's length and amplitude; its mesh (the grading too: a graded mesh takes
// the characteristic solution where a uniform one takes the closed form or a table), Δt and the horizon.
using ReferenceKey = std::tuple<std::string, std::string, std::string, double, double, double, Index, double, double>;
void put(std::string& bytes, double v) { bytes.append(reinterpret_cast<const char*>(&v), sizeof v); }
void put(std::string& bytes, const std::vector<double>& v) {
  put(bytes, static_cast<double>(v.size()));
  for (double c : v) put(bytes, c);
}
std::string data_bytes(const InitialData* data) {
  if (!data) return {};
  std::string bytes;
  for (const InitialDataPiece& piece : data->pieces) {
    put(bytes, piece.a), put(bytes, piece.b);
    put(bytes, piece.displacement), put(bytes, piece.velocity);
  }
  return bytes;
}
// What the field's exact solution reads (ImpactReference: the chain and its data; the horizon is the
// key's own): every member of the chain and the data.
std::string field_bytes(const ImpactBenchmark* field) {
  if (!field) return {};
  const ImpactConfiguration& chain = field->configuration;
  std::string bytes = data_bytes(&field->data);
  for (const BarSegment& segment : chain.segments)
    put(bytes, segment.length), put(bytes, segment.modulus), put(bytes, segment.density), put(bytes, segment.load);
  for (const SegmentJunction& junction : chain.junctions)
    put(bytes, junction.contact ? 1.0 : 0.0), put(bytes, junction.gap);
  put(bytes, chain.obstacle ? 1.0 : 0.0), put(bytes, chain.obstacle_gap);
  put(bytes, static_cast<double>(chain.far_end));
  return bytes;
}
ReferenceKey reference_key(const Configuration& unit, double horizon) {
  return {data_bytes(unit.data.get()),
          unit.data ? std::string() : unit.benchmark,
          field_bytes(unit.field.get()),
          unit.length,
          unit.amplitude,
          unit.grading,
          unit.elements,
          unit.step(),
          horizon};
}

}  // namespace

struct ReferenceCache::Store {
  mutable std::mutex mutex;
  std::map<ReferenceKey, std::shared_future<std::shared_ptr<const ReferenceSolution>>> references;
  std::size_t computed = 0;
};

ReferenceCache::ReferenceCache() : store_(std::make_unique<Store>()) {}
ReferenceCache::~ReferenceCache() = default;

std::size_t ReferenceCache::computed() const {
  std::lock_guard<std::mutex> lock(store_->mutex);
  return store_->computed;
}

// The first caller of a key computes its reference outside the lock (other keys go on); a caller of the
// same key meanwhile waits on the shared future. A failure is stored too: every caller of that key sees it.
std::shared_ptr<const ReferenceSolution> ReferenceCache::operator()(const Configuration& unit, double horizon) {
  const ReferenceKey key = reference_key(unit, horizon);
  std::promise<std::shared_ptr<const ReferenceSolution>> promise;
  std::shared_future<std::shared_ptr<const ReferenceSolution>> future;
  {
    std::lock_guard<std::mutex> lock(store_->mutex);
    const auto found = store_->references.find(key);
    if (found != store_->references.end()) return found->second.get();
    future = promise.get_future().share();
    store_->references.emplace(key, future);
    ++store_->computed;
  }
  try {
    promise.set_value(unit_configuration_reference(unit, horizon));
  } catch (...) {
    promise.set_exception(std::current_exception());
  }
  return future.get();
}

SweepSettings& sweep_settings() {
  static SweepSettings settings;
  return settings;
}

void add_sweep_options(cli::Parser& parser, SweepOptions& options) {
  cli::add_threads_option(parser, &options.threads, "one per hardware thread");
  std::vector<std::string> widths{"widest", "none"};
  for (const BatchTarget& t : batch_targets()) widths.push_back(t.name);
  parser.add_choice("--vector", "", "W",
                    "the vector target whose lanes carry the runs: widest (default), none (every run alone), or one "
                    "this processor has; the output does not depend on it",
                    widths, &options.vector);
}

void apply_sweep_options(const SweepOptions& options) {
  sweep_settings().threads = static_cast<unsigned>(options.threads);
  sweep_settings().batched = options.vector != "none";
  use_batch_target(0);
  for (const BatchTarget& t : batch_targets())
    if (t.name == options.vector) use_batch_target(t.bit);
}

// The runs stepped at once, at most: the batches of the largest mesh's runs (lanes of the target, or one run
// each when not batched), on as many workers as there are such batches, at most the threads; the runs of
// smaller meshes on other workers need less.
void require_batched_memory(std::string_view option, const std::vector<Configuration>& configurations,
                            const SweepSettings& settings) {
  double largest = 0, at_largest = 0;
  for (const Configuration& c : configurations) {
    const double n = static_cast<double>(c.elements);
    if (n > largest) largest = n, at_largest = 0;
    if (n == largest) ++at_largest;
  }
  if (at_largest == 0) return;
  const double lanes =
      settings.batched ? static_cast<double>(std::max<std::size_t>(1, current_batch_target().lanes)) : 1;
  const double threads = settings.threads > 0 ? static_cast<double>(settings.threads)
                                              : static_cast<double>(std::max(1u, std::thread::hardware_concurrency()));
  const double copies = std::min(threads, std::ceil(at_largest / lanes)) * std::min(lanes, at_largest);
  cli::require_mesh_memory(option, largest, batched_bytes_per_lane_element, copies);
}

namespace {

// The cost of one batch step of a group of `runs` runs stepped together in lockstep, per node, in units of
// the scalar step, on a target of `width` lanes. The batched step gives 2 runs 2 lanes, 3 or 4 runs 4, more
// the full width (batched_step.cpp), and a lane costs about the same at 2 and 4 lanes as a scalar step per
// 2 and 4 runs: on the 2-core Zen 4 (bench_step's batched table, N = 1024, its columns SSE4x2, AVX2x4 and
// AVX3x8 for 2, 4 and 8 lanes; chosen after that run) 1.67 ns per node and run, 0.83 and 0.70, the scalar
// step 3.25 — so a group of up to 4 runs costs one scalar step, and one of 8 costs 1.7. The cut changes no
// bit of a run (each lane is its run alone), only the time.
double lockstep_cost(std::size_t runs, std::size_t width) {
  const std::size_t lanes = runs <= 1 ? 1 : runs == 2 ? 2 : runs <= 4 ? 4 : width;
  return lanes <= 4 ? 1.0 : 1.7 * static_cast<double>(lanes) / 8.0;
}

// A key's runs, costliest first (steps[0] ≥ steps[1] ≥ …), cut into consecutive batches of at most `width`:
// in lockstep a batch steps as long as its longest run, its first, so its cost is lockstep_cost × steps of
// its first run. The cut of least total cost, by dynamic programming from the last run (best[i]: the runs
// i … end; among equal costs the longer batch, so that runs of the same length stay together).
std::vector<std::size_t> lockstep_batches(const std::vector<double>& steps, std::size_t width) {
  const std::size_t m = steps.size();
  std::vector<double> best(m + 1, 0.0);
  std::vector<std::size_t> size(m + 1, 0);
  for (std::size_t i = m; i-- > 0;) {
    best[i] = HUGE_VAL;
    for (std::size_t k = std::min(width, m - i); k >= 1; --k) {
      const double c = lockstep_cost(k, width) * steps[i] + best[i + k];
      if (c < best[i]) best[i] = c, size[i] = k;
    }
  }
  std::vector<std::size_t> sizes;
  for (std::size_t i = 0; i < m; i += size[i]) sizes.push_back(size[i]);
  return sizes;
}

}  // namespace

TEST_CASE("a key's runs are cut into the lockstep batches of least cost") {
  // Eight runs of one length: one batch of 8 (1.7 steps) rather than two of 4 (2).
  CHECK(lockstep_batches(std::vector<double>(8, 100.0), 8) == std::vector<std::size_t>{8});
  // Runs of three lengths (fig_stress's finest mesh): 4 + 2 (192 + 12 = 204) rather than one batch of 6,
  // which steps the short ones as long as the long ones (1.7 · 192 = 326), or 3 + 3 (192 + 37).
  CHECK(lockstep_batches({192, 192, 153, 37, 12, 12}, 8) == std::vector<std::size_t>{4, 2});
  // A run alone costs what a group of 4 costs: it is never split off a group of up to 4.
  CHECK(lockstep_batches({100, 10, 10, 10}, 8) == std::vector<std::size_t>{4});
  // 4 lanes at most (AVX2): batches of 4.
  CHECK(lockstep_batches(std::vector<double>(9, 5.0), 4) == std::vector<std::size_t>{4, 4, 1});
  CHECK(lockstep_batches({}, 8).empty());
}

// The batches. Runs of the same N and scheme family have the same sequence of operations node by node
// (the batched step groups them further by layout, and steps the others alone); within a key
// the costliest runs (the most steps) go first, and they are cut into batches of at most the vector width
// of least lockstep cost (lockstep_batches), so that the runs of a batch have nearly the same number of
// steps; with `most` (the caller's batches: runs that share their instants at their own rates) into batches
// of `most`. A batch steps its runs together (with own_rates, each at its own rate when their Δt are whole
// multiples of the smallest, BatchedSimulation::step(advance), and a lane whose run has ended, or whose
// observer wants no more, is kept as it is; otherwise such a lane is stepped on, no longer observed, except
// a contact class's run, which is kept: its step checks finiteness and could throw past the run's horizon).
// Each batch is one task of run_in_parallel, and so is each whole run (two bodies, a caller's task):
// costliest first (a batch's cost: its first run's).
void step_in_batches(const std::vector<BatchKey>& keys, const std::vector<double>& costs, const BatchStart& start,
                     const BatchObserve& observe, const std::function<void(std::size_t k)>& finish,
                     const SweepSettings& settings, const BatchLaneObserve& lane_observe,
                     const BatchLevelPrepare& prepare, std::size_t most, bool own_rates, const std::vector<char>& whole,
                     const std::function<void(std::size_t k)>& run_whole) {
  const std::size_t count = keys.size();
  if (costs.size() != count) throw std::invalid_argument("step_in_batches: one cost per run");
  if (!whole.empty() && (whole.size() != count || !run_whole))
    throw std::invalid_argument("step_in_batches: one whole flag per run, and a run_whole");
  std::map<BatchKey, std::vector<std::size_t>> groups;
  for (std::size_t k = 0; k < count; ++k)
    if (whole.empty() || !whole[k]) groups[keys[k]].push_back(k);
  const std::size_t width = most > 0           ? most
                            : settings.batched ? std::max<std::size_t>(1, current_batch_target().lanes)
                                               : 1;
  std::vector<std::vector<std::size_t>> batches;
  std::vector<double> batch_cost;
  for (auto& [key, members] : groups) {
    std::stable_sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
    // The runs of one key have one N (the default keys, N and family; the callers' keys too): their costs,
    // N × steps, are their steps to a common factor.
    std::vector<std::size_t> sizes;
    if (most == 0 && width > 1) {
      std::vector<double> steps;
      for (std::size_t k : members) steps.push_back(costs[k]);
      sizes = lockstep_batches(steps, width);
    } else {
      for (std::size_t first = 0; first < members.size(); first += width)
        sizes.push_back(std::min(width, members.size() - first));
    }
    std::size_t first = 0;
    for (const std::size_t size : sizes) {
      batches.emplace_back(members.begin() + static_cast<std::ptrdiff_t>(first),
                           members.begin() + static_cast<std::ptrdiff_t>(first + size));
      batch_cost.push_back(costs[batches.back().front()]);
      first += size;
    }
  }
  // The whole runs after the batches: task b ≥ batches.size() is whole run wholes[b − batches.size()].
  std::vector<std::size_t> wholes;
  for (std::size_t k = 0; k < whole.size(); ++k)
    if (whole[k]) wholes.push_back(k), batch_cost.push_back(costs[k]);
  const unsigned threads = settings.threads > 0 ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  run_in_parallel(costliest_first(batch_cost.size(), [&](std::size_t b) { return batch_cost[b]; }),
                  static_cast<long>(threads), [&](std::size_t b) {
                    if (b >= batches.size()) return run_whole(wholes[b - batches.size()]);
                    const std::vector<std::size_t>& batch = batches[b];
                    std::vector<BarSimulation> simulations;
                    std::vector<Index> steps(batch.size(), 0);
                    std::vector<char> watching(batch.size(), 1);
                    Index most = 0;
                    for (std::size_t j = 0; j < batch.size(); ++j) {
                      simulations.push_back(start(batch[j], steps[j]));
                      most = std::max(most, steps[j]);
                    }
                    if (batch.size() == 1) {
                      BarSimulation& alone = simulations.front();
                      bool more = observe(batch[0], alone.sample());
                      for (Index n = 1; more && n <= steps[0]; ++n) {
                        alone.step();
                        more = observe(batch[0], alone.sample());
                      }
                    } else {
                      // With own_rates, each run at its own rate: run j steps at the batch steps n that are
                      // multiples of rate[j] = Δt_j/Δt_min when that ratio is a whole number, so that runs of
                      // Δt, 2Δt, 4Δt to the same horizon reach their common instants at the same batch step
                      // (and share the exact solution's evaluation there, add_lanes). Used when it does not
                      // lengthen the batch (a run of 2Δt to a later horizon would): else every run at every
                      // step. Only for the caller's keys: in the batches of the default keys (N, family),
                      // whose runs are put together by cost, check_claims took 1.05–1.08 of the CPU time with
                      // rates (medians of 3 timed sets of runs), though a profile of one pair said less.
                      std::vector<Index> rate(batch.size(), 1);
                      std::vector<char> is_class(batch.size()), stepped(batch.size());
                      bool classes = false;
                      for (std::size_t j = 0; j < batch.size(); ++j) {
                        is_class[j] =
                            find_entry(contact_class_schemes(), simulations[j].parameters().scheme) != nullptr;
                        classes = classes || is_class[j];
                      }
                      if (own_rates) {
                        double dt_min = simulations.front().dt();
                        for (const BarSimulation& s : simulations) dt_min = std::min(dt_min, s.dt());
                        std::vector<Index> r(batch.size(), 1);
                        Index span = 0, widest = 1;
                        for (std::size_t j = 0; j < batch.size(); ++j) {
                          const double q = simulations[j].dt() / dt_min;
                          const double whole = std::round(q);
                          if (whole >= 1 && std::abs(q - whole) <= 1e-9 * q) r[j] = static_cast<Index>(whole);
                          span = std::max(span, steps[j] * r[j]);
                          widest = std::max(widest, r[j]);
                        }
                        if (span <= most + widest) rate = r;
                      }
                      BatchedSimulation lanes(std::move(simulations));
                      // Level n of lane j: from the lanes when the observer takes them, else copied out.
                      const auto look = [&](std::size_t j) {
                        if (lane_observe) {
                          LaneVectors where{};
                          const Sample s = lanes.sample(j, where);
                          if (const std::optional<bool> more = lane_observe(batch[j], s, where)) return *more;
                        }
                        return observe(batch[j], lanes.run(j).sample());
                      };
                      // The new levels of the lanes that stepped (every lane at level 0): with `prepare`,
                      // their samples in place are gathered and prepared first, then observed one by one.
                      std::vector<std::size_t> ks, js;
                      std::vector<Sample> samples;
                      std::vector<LaneVectors> wheres;
                      std::vector<char> advance(batch.size(), 1);
                      const auto look_all = [&]() {
                        if (!(lane_observe && prepare)) {
                          for (std::size_t j = 0; j < batch.size(); ++j)
                            if (advance[j]) watching[j] = look(j);
                          return;
                        }
                        ks.clear(), js.clear(), samples.clear(), wheres.clear();
                        for (std::size_t j = 0; j < batch.size(); ++j)
                          if (advance[j]) {
                            LaneVectors where{};
                            samples.push_back(lanes.sample(j, where));
                            wheres.push_back(where);
                            ks.push_back(batch[j]);
                            js.push_back(j);
                          }
                        prepare(ks, samples, wheres);
                        for (std::size_t m = 0; m < js.size(); ++m) {
                          const std::optional<bool> more = lane_observe(ks[m], samples[m], wheres[m]);
                          watching[js[m]] = more ? *more : observe(ks[m], lanes.run(js[m]).sample());
                        }
                      };
                      look_all();
                      // A run that has ended, or whose observer wants no more, stays where it is.
                      std::vector<Index> level(batch.size(), 0);
                      for (Index n = 1;; ++n) {
                        bool any = false, moves = false;
                        for (std::size_t j = 0; j < batch.size(); ++j) {
                          const bool on = watching[j] && level[j] < steps[j];
                          any = any || on;
                          advance[j] = on && n % rate[j] == 0;
                          moves = moves || advance[j];
                          level[j] += advance[j];
                        }
                        if (!any) break;
                        if (!moves) continue;
                        if (own_rates) {
                          lanes.step(advance);  // the others stay
                        } else if (!classes) {
                          lanes.step();  // every run, observed or not (the lockstep)
                        } else {
                          // The lockstep, except that a contact class's run that has ended stays: its step
                          // checks the energy's finiteness, and an explicit run stepped past its horizon could
                          // lose it and throw (the batched steps of the paper's schemes check nothing).
                          for (std::size_t j = 0; j < batch.size(); ++j) stepped[j] = advance[j] || !is_class[j];
                          lanes.step(stepped);
                        }
                        look_all();
                      }
                    }
                    for (std::size_t k : batch) finish(k);
                  });
}

std::vector<Measures> run_batched(const std::vector<Configuration>& configurations, const SweepSettings& settings,
                                  const std::function<void(std::size_t k, const Sample& sample)>& observe,
                                  const std::vector<BatchKey>& given_keys, bool observer_reads_vectors,
                                  const std::vector<SweepTask>& tasks) {
  const std::size_t count = configurations.size();
  if (!given_keys.empty() && given_keys.size() != count)
    throw std::invalid_argument("run_batched: one key per configuration");
  // Runs 0 … count − 1 are the configurations, count … the tasks; the two-body runs and the tasks are whole.
  std::vector<BatchKey> keys(count + tasks.size());
  std::vector<double> costs(count + tasks.size());
  std::vector<char> whole(count + tasks.size(), 1);
  for (std::size_t k = 0; k < count; ++k) {
    const Configuration& c = configurations[k];
    const double steps = c.steps >= 0 ? static_cast<double>(c.steps) : c.final_time / c.step();
    costs[k] = static_cast<double>(c.elements) * steps;
    keys[k] = given_keys.empty() ? BatchKey{c.elements, batch_family(c.scheme.scheme)} : given_keys[k];
    whole[k] = is_two_body_configuration(c);
    if (whole[k] && observe)
      throw std::invalid_argument("run_batched: two bodies take no observer (a Sample is one body's)");
  }
  for (std::size_t t = 0; t < tasks.size(); ++t) costs[count + t] = tasks[t].cost;
  ReferenceCache cache;
  const ReferenceSource source = [&cache](const Configuration& unit, double horizon) { return cache(unit, horizon); };
  // Each slot is written by the worker of its batch only.
  std::vector<std::unique_ptr<ConfigurationRun>> runs(count);
  std::vector<Measures> results(count);
  std::vector<char> errors_added(count, 0);  // run k's errors of the level being observed are added
  step_in_batches(
      keys, costs,
      [&](std::size_t k, Index& steps) {
        std::function<void(const Sample&)> of_k;
        if (observe) of_k = [&observe, k](const Sample& s) { observe(k, s); };
        runs[k] = std::make_unique<ConfigurationRun>(configurations[k], std::move(of_k), nullptr, source);
        runs[k]->set_observer_reads_vectors(observer_reads_vectors);
        steps = runs[k]->steps();
        return std::move(runs[k]->simulation());
      },
      [&](std::size_t k, const Sample& s) {
        runs[k]->add(s);
        return true;
      },
      [&](std::size_t k) {
        results[k] = runs[k]->measures();
        runs[k].reset();
      },
      settings,
      [&](std::size_t k, const Sample& s, const LaneVectors& lanes) -> std::optional<bool> {
        if (!runs[k]->takes_lanes(s, lanes)) return std::nullopt;
        runs[k]->add(s, lanes, errors_added[k] != 0);
        errors_added[k] = 0;
        return true;
      },
      // The errors of a level of a batch's runs in one pass over the nodes (ErrorAccumulator::add_lanes).
      [&](const std::vector<std::size_t>& ks, const std::vector<Sample>& samples,
          const std::vector<LaneVectors>& lanes) {
        thread_local std::vector<ErrorAccumulator::Lane> level;  // this worker's, kept from level to level
        level.clear();
        for (std::size_t m = 0; m < ks.size(); ++m)
          if (ErrorAccumulator* errors = runs[ks[m]]->lane_errors(samples[m], lanes[m])) {
            level.push_back({errors, &samples[m], lanes[m]});
            errors_added[ks[m]] = 1;
          }
        ErrorAccumulator::add_lanes(level.data(), level.size());
      },
      given_keys.empty() || !settings.batched ? 0 : count, !given_keys.empty(), whole,
      [&](std::size_t k) {
        if (k < count)
          results[k] = run_configuration(configurations[k]);
        else
          tasks[k - count].run();
      });
  return results;
}

namespace {

// Every measure of a run as text, each double in hexadecimal (std::hexfloat: two texts are equal iff
// the doubles are the same bits, up to the sign of a NaN, which no measure has).
std::string measure_bytes(const Measures& m) {
  std::ostringstream out;
  out << std::hexfloat;
  const auto norms = [&](const ErrorNorms& e) {
    for (double v : ErrorAccumulator::values(e)) out << v << ' ';
    out << '\n';
  };
  norms(m.errors);
  for (const ErrorNorms& e : m.horizon_errors) norms(e);
  out << m.energy_initial << ' ' << m.energy_final << ' ' << m.energy_min << ' ' << m.energy_max << ' ' << m.steps
      << '\n';
  for (double t : m.impacts) out << t << ' ';
  if (m.phase) {
    out << "\nphase " << m.phase->matched << ' ' << m.phase->first_impact_error << ' ' << m.phase->period;
    if (m.phase->drift_per_period) out << ' ' << *m.phase->drift_per_period;
  }
  for (const ContactInterval& w : m.contact_windows) out << "\nwindow " << w.start << ' ' << w.end << ' ' << w.open;
  if (m.lambda_tv_ratio) out << "\ntv " << *m.lambda_tv_ratio;
  out << "\npenetration " << m.max_penetration << '\n';
  if (m.stress_history) {  // kept: the multiplier's and the recovered strain's histories
    const StressHistory& h = *m.stress_history;
    for (const std::vector<double>* v :
         {&h.time, &h.multiplier, &h.exact, &h.recovered_time, &h.recovered, &h.exact_at_levels}) {
      for (double x : *v) out << x << ' ';
      out << '\n';
    }
    out << h.h << ' ' << h.spacing << ' ' << h.order.mu << ' ' << h.order.coefficient << '\n';
  }
  return out.str();
}

// Each configuration run alone (run_configuration): its measures (measure_bytes) and its observed samples,
// each as `text` writes it.
[[maybe_unused]] std::pair<std::vector<std::string>, std::vector<std::string>> alone_bytes(
    const std::vector<Configuration>& configurations, const std::function<std::string(const Sample&)>& text) {
  std::vector<std::string> measures, seen(configurations.size());
  for (std::size_t k = 0; k < configurations.size(); ++k)
    measures.push_back(
        measure_bytes(run_configuration(configurations[k], [&](const Sample& s) { seen[k] += text(s); })));
  return {measures, seen};
}

}  // namespace

TEST_CASE("the batched sweep gives each run's measures bit for bit, for any thread count and vector width") {
  // Prediction: every lane of the batched step is bitwise its run stepped alone (batched_step.cpp), the
  // measures see the same samples in the same order, and a shared reference is the same object a run
  // would build: so run_batched gives run_configuration's bytes for every run, whatever the threads,
  // the vector target (each one this machine has) or batching at all. The runs: the five schemes of
  // the batched step and the three Newmark-type classes (newmark, penalty, nitsche: one family, β = ¼),
  // two masses, two meshes, two steps (runs of one batch end at different levels),
  // with horizons; the other four classes (moreau-jean, dke and the two explicit ones, each family in lanes);
  // and
  // two runs of each smooth benchmark on the same mesh and Δt, which share one reference
  // per benchmark (and must not get the other's); and runs that keep the stress histories (the recovered
  // strain read from the lanes), with and without the error measures.
  std::vector<Configuration> configurations;
  for (const char* scheme : {"cn", "be", "ps", "ec", "cn-switch", "newmark", "penalty", "nitsche"})
    for (const char* mass : {"mod1", "mod3"})
      for (Index n : {10, 13})
        for (double courant : {0.5, 1.0}) {
          configurations.push_back(paper_configuration(scheme, "algebraic", mass, n, courant, 3.5));
          configurations.back().horizons = {1.0, 3.0};
        }
  // The other classes (moreau-jean, dke, and the explicit ones sharing a family): the inertial ones with the
  // consistent mass, the explicit one with Mod 3 below its stability limit.
  for (const char* scheme : {"moreau-jean", "dke", "taylor-flanagan", "explicit"})
    for (Index n : {10, 13})
      for (double courant : {0.5, 0.9}) {
        const bool explicit_row = std::string(scheme) == "explicit";
        configurations.push_back(paper_configuration(scheme, explicit_row ? "algebraic" : "literal",
                                                     explicit_row ? "mod3" : "consistent", n, courant, 3.5));
        configurations.back().horizons = {1.0, 3.0};
      }
  for (const char* benchmark : {"smooth-impact", "grazing"})
    for (const char* mass : {"mod1", "mod3"}) {
      Configuration c = paper_configuration("cn", "algebraic", mass, 16, 0.5, 2.0);
      c.benchmark = benchmark;
      configurations.push_back(c);
    }
  for (const char* scheme : {"cn", "be", "cn-switch"})
    for (bool errors : {true, false}) {
      Configuration c = paper_configuration(scheme, "algebraic", "mod3", 13, 0.5, 3.5);
      c.keep_stress_history = true;
      c.measure_errors = errors;
      configurations.push_back(c);
    }
  std::vector<std::string> expected;
  for (const Configuration& c : configurations) expected.push_back(measure_bytes(run_configuration(c)));
  std::vector<std::int64_t> targets{0};
  for (const BatchTarget& t : batch_targets()) targets.push_back(t.bit);
  for (std::int64_t bit : targets) {
    use_batch_target(bit);
    for (unsigned threads : {1u, 2u})
      for (bool batched : {true, false}) {
        CAPTURE(current_batch_target().name);
        CAPTURE(threads);
        CAPTURE(batched);
        const std::vector<Measures> got = run_batched(configurations, {threads, batched});
        REQUIRE(got.size() == configurations.size());
        for (std::size_t k = 0; k < got.size(); ++k) {
          CAPTURE(k);
          CHECK(measure_bytes(got[k]) == expected[k]);
        }
      }
  }
  use_batch_target(0);
}

TEST_CASE("two bodies and a sweep's own tasks run on the sweep's workers, each once, with run_configuration's bytes") {
  // Prediction: a two-body run is run whole (run_configuration) as a task among the batches, and a task
  // that is not a configuration is run once; neither changes a batch. So every configuration's measures
  // are run_configuration's, and every task has run exactly once, for 1 and 2 threads, in lanes or not,
  // with the default keys and with the caller's. An observer cannot see a two-body run: refused before any
  // run.
  std::vector<Configuration> configurations;
  for (const char* mass : {"mod1", "mod3"})
    for (const char* benchmark : {"paper", "two-bars", "bouncing"}) {
      Configuration c = paper_configuration("cn", "algebraic", mass, 10, 0.5, 3.0);
      c.benchmark = benchmark;
      if (mrm::benchmark(benchmark).field) c.final_time = mrm::benchmark(benchmark).final_time;
      configurations.push_back(c);
    }
  REQUIRE(is_two_body_configuration(configurations[1]));
  std::vector<std::string> expected;
  for (const Configuration& c : configurations) expected.push_back(measure_bytes(run_configuration(c)));
  std::vector<BatchKey> keys;
  for (std::size_t k = 0; k < configurations.size(); ++k) keys.push_back({10, static_cast<int>(k % 3)});
  for (unsigned threads : {1u, 2u})
    for (bool batched : {true, false})
      for (bool own_keys : {false, true}) {
        CAPTURE(threads);
        CAPTURE(batched);
        CAPTURE(own_keys);
        std::vector<int> ran(5, 0);
        std::vector<SweepTask> tasks;
        for (std::size_t t = 0; t < ran.size(); ++t)
          tasks.push_back({static_cast<double>(t) * 1e3, [&ran, t] { ++ran[t]; }});
        const std::vector<Measures> got =
            run_batched(configurations, {threads, batched}, {}, own_keys ? keys : std::vector<BatchKey>{}, true, tasks);
        REQUIRE(got.size() == configurations.size());
        for (std::size_t k = 0; k < got.size(); ++k) {
          CAPTURE(k);
          CHECK(measure_bytes(got[k]) == expected[k]);
        }
        CHECK(ran == std::vector<int>(5, 1));
      }
  CHECK_THROWS_AS(run_batched(configurations, {1, true}, [](std::size_t, const Sample&) {}), std::invalid_argument);
}

TEST_CASE("runs keyed together by the caller share a batch, each with its measures and observed samples bit for bit") {
  // Prediction: with the caller's keys the runs of one key are one batch: the runs of one family among
  // them share vector lanes (their samples copied out for the observer), the others are stepped alone
  // and read on their own vectors (which the observer may read too), and their error measures take the
  // closed form's runs from one another at the same instants (add_lanes). Each run sees the samples it
  // sees alone: its measures and every observed sample (instants, λ, energy, U and V, in hexadecimal)
  // are run_configuration's, for 1 and 2 threads. Keys: (N, Δt), so two schemes of one family (cn, be)
  // share lanes, three (ps, ec, cn-switch) are alone.
  std::vector<Configuration> configurations;
  std::vector<BatchKey> keys;
  for (const char* scheme : {"cn", "be", "ps", "ec", "cn-switch"})
    for (Index n : {10, 13})
      for (int c = 0; c < 2; ++c) {
        configurations.push_back(paper_configuration(scheme, "algebraic", "mod3", n, c == 0 ? 0.5 : 1.0, 3.5));
        configurations.back().horizons = {1.0};
        keys.push_back({n, c});
      }
  const auto text = [](const Sample& s) {
    std::ostringstream out;
    out << std::hexfloat << s.level << ' ' << s.time << ' ' << s.velocity_time << ' ' << s.multiplier << ' '
        << s.energy;
    for (double x : *s.displacement) out << ' ' << x;
    for (double x : *s.velocity) out << ' ' << x;
    return out.str() + '\n';
  };
  const auto [expected, expected_seen] = alone_bytes(configurations, text);
  for (unsigned threads : {1u, 2u}) {
    CAPTURE(threads);
    std::vector<std::string> seen(configurations.size());
    const std::vector<Measures> got = run_batched(
        configurations, {threads, true}, [&](std::size_t k, const Sample& s) { seen[k] += text(s); }, keys);
    REQUIRE(got.size() == configurations.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
      CAPTURE(k);
      CHECK(measure_bytes(got[k]) == expected[k]);
      CHECK(seen[k] == expected_seen[k]);
    }
  }
  CHECK_THROWS_AS(run_batched(configurations, {1, true}, {}, {keys.front()}), std::invalid_argument);
}

TEST_CASE("runs of dt, 2dt and 4dt in one batch step at their own rates, each bit for bit, observed in time order") {
  // Prediction: in a batch whose Δt are whole multiples of the smallest and whose runs reach the same
  // horizon, run j steps only at the batch steps that are multiples of its rate Δt_j/Δt_min
  // (BatchedSimulation::step(advance), each lane bitwise its run alone), so its measures and observed
  // samples are run_configuration's, and every run is observed at the batch step that reaches its instant:
  // the instants seen, in the order they are seen, never decrease (stepped in lockstep, the 4Δt run would
  // be seen at 4t when the Δt run is at t). Runs to different horizons (key 1: 2Δt to twice the horizon)
  // would take a longer batch at their rates: they step in lockstep, bit for bit as well. The observer
  // reads the scalars only (observer_reads_vectors false): its samples' vectors are null.
  std::vector<Configuration> configurations;
  std::vector<BatchKey> keys;
  for (const char* scheme : {"cn", "ps", "ec", "cn-switch"})
    for (double courant : {0.25, 0.5, 1.0}) {
      configurations.push_back(paper_configuration(scheme, "algebraic", "mod3", 12, courant, 2.5));
      configurations.back().horizons = {1.0};
      keys.push_back({12, 0});
    }
  for (double courant : {0.5, 1.0}) {
    configurations.push_back(paper_configuration("cn", "algebraic", "mod1", 12, courant, courant * 5.0));
    keys.push_back({12, 1});
  }
  const auto text = [](const Sample& s) {
    std::ostringstream out;
    out << std::hexfloat << s.level << ' ' << s.time << ' ' << s.velocity_time << ' ' << s.multiplier << ' '
        << s.multiplier_time << ' ' << s.energy << '\n';
    return out.str();
  };
  const auto [expected, expected_seen] = alone_bytes(configurations, text);
  for (unsigned threads : {1u, 2u}) {
    CAPTURE(threads);
    std::vector<std::string> seen(configurations.size());
    std::vector<double> instants, lockstep;  // key 0's and key 1's, in the order seen (one thread)
    bool vectors = false;
    const std::vector<Measures> got = run_batched(
        configurations, {threads, true},
        [&](std::size_t k, const Sample& s) {
          seen[k] += text(s);
          vectors = vectors || s.displacement || s.velocity;
          if (threads == 1) (keys[k].second == 0 ? instants : lockstep).push_back(s.time);
        },
        keys, false);
    REQUIRE(got.size() == configurations.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
      CAPTURE(k);
      CHECK(measure_bytes(got[k]) == expected[k]);
      CHECK(seen[k] == expected_seen[k]);
    }
    CHECK(!vectors);
    if (threads == 1) {
      REQUIRE(instants.size() > 100);
      CHECK(std::is_sorted(instants.begin(), instants.end()));
      CHECK(!std::is_sorted(lockstep.begin(), lockstep.end()));
    }
  }
}

TEST_CASE("in lockstep, a contact class's run that has ended is not stepped past its last level") {
  // Prediction: explicit penalty (Newmark β = 0, γ = ½, γ₀ = 1, the consistent mass, N = 16) at 0.9 of the
  // linear limit gains energy and loses finiteness at level 150911 (its step then throws, measured alone
  // below). In one lockstep batch (the same family and mesh: two lanes) with a stable run of 160000 levels
  // (β = ¼), the explicit run of 1000 levels stays at its last level, so the sweep completes. Stepped on (as
  // the batches of the paper's schemes are), it would throw at level 150911 of the batch (checked: it did).
  const UniformMesh mesh(1.0, 16);
  const MassRedistribution mass = mass_redistribution_by_name("consistent");
  SchemeParameters p;
  p.scheme = Scheme::penalty, p.newmark_beta = 0.0, p.newmark_gamma = 0.5, p.penalty = 1.0;
  const double dt = 0.9 * newmark_stability_limit(modified_mass(mesh, mass), p1_stiffness(mesh), p, mesh.h());
  const Index levels_short = 1000, levels_long = 160000;
  BarSimulation alone(benchmark_problem(), mesh, mass, p, dt);
  Index lost = 0;
  try {
    for (; lost < levels_long; ++lost) alone.step();
  } catch (const std::runtime_error&) {
  }
  // The premise: it throws after the short run's end and before the long run's (measured: from level 150910).
  REQUIRE(lost > levels_short);
  REQUIRE(lost < levels_long);
  const std::vector<Index> levels{levels_short, levels_long};
  std::vector<Index> last(2, -1);
  CHECK_NOTHROW(step_in_batches(
      {{16, 4}, {16, 4}}, {2.0, 1.0},
      [&](std::size_t k, Index& steps) {
        steps = levels[k];
        SchemeParameters q = p;
        if (k == 1) q.newmark_beta = 0.25;
        return BarSimulation(benchmark_problem(), mesh, mass, q, dt);
      },
      [&](std::size_t k, const Sample& s) {
        last[k] = s.level;
        return true;
      },
      [](std::size_t) {}, {1, true}));
  CHECK(last == levels);
}

TEST_CASE("a cached reference gives the same bytes as one computed directly, and is computed once") {
  // Prediction: the cache returns the object unit_configuration_reference builds for the first run of
  // a key, and the same object to every later run of that key: the same values at every point (here
  // the nodes at a few instants), and the same measures as a run that builds its own; another Δt is
  // another key.
  Configuration c = paper_configuration("cn", "algebraic", "mod3", 16, 0.5, 2.0);
  c.benchmark = "smooth-impact";
  ConfigurationRun direct_run(c);
  const Configuration& unit = direct_run.unit();
  const double horizon = reference_horizon(direct_run.steps(), unit.step());
  ReferenceCache cache;
  const std::shared_ptr<const ReferenceSolution> first = cache(unit, horizon), second = cache(unit, horizon);
  CHECK(first.get() == second.get());
  CHECK(cache.computed() == 1);
  const std::shared_ptr<const ReferenceSolution> direct = unit_configuration_reference(unit, horizon);
  const UniformMesh mesh = configuration_mesh(unit);
  std::vector<double> x(static_cast<std::size_t>(mesh.unknowns()));
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = mesh.x(static_cast<Index>(i));
  for (double t : {0.0, 0.3125, 1.0, 1.96875}) {
    std::vector<double> a(x.size()), b(x.size());
    first->displacement_at_points(t, x.data(), static_cast<long>(x.size()), a.data());
    direct->displacement_at_points(t, x.data(), static_cast<long>(x.size()), b.data());
    CAPTURE(t);
    CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
  }
  const ReferenceSource source = [&cache](const Configuration& u, double h) { return cache(u, h); };
  ConfigurationRun cached_run(c, nullptr, nullptr, source);
  run(cached_run.simulation(), cached_run.steps(), [&](const Sample& s) { cached_run.add(s); });
  CHECK(cache.computed() == 1);
  CHECK(measure_bytes(cached_run.measures()) == measure_bytes(run_configuration(c)));
  Configuration other = c;
  other.courant = 0.25;
  ConfigurationRun other_run(other, nullptr, nullptr, source);
  CHECK(cache.computed() == 2);
  // A graded mesh of the same data, N and Δt takes the characteristic solution (not the table): another key.
  Configuration graded = c;
  graded.grading = 1.01;
  graded.dt = c.step();  // the same Δt: only the grading differs
  ConfigurationRun graded_run(graded, nullptr, nullptr, source);
  run(graded_run.simulation(), graded_run.steps(), [&](const Sample& s) { graded_run.add(s); });
  CHECK(cache.computed() == 3);
  CHECK(measure_bytes(graded_run.measures()) == measure_bytes(run_configuration(graded)));
  // A field benchmark: each run's unit configuration holds its own copy of the scaled chain; two masses
  // and two schemes of one benchmark, mesh and Δt share one reference (by the chain's content), another
  // benchmark or mesh does not.
  std::deque<ConfigurationRun> alive;
  const auto field_reference = [&](const char* benchmark, const char* scheme, const char* mass, Index n) {
    Configuration f = paper_configuration(scheme, "algebraic", mass, n, 0.5, 1.0);
    f.benchmark = benchmark;
    f.final_time = impact_benchmark(benchmark).final_time;
    const ConfigurationRun& r = alive.emplace_back(f);  // kept: its chain's address is not reused
    return cache(r.unit(), reference_horizon(r.steps(), r.unit().step())).get();
  };
  const auto bouncing = field_reference("bouncing", "cn", "mod1", 10);
  CHECK(cache.computed() == 4);
  CHECK(field_reference("bouncing", "cn", "mod3", 10) == bouncing);
  CHECK(field_reference("bouncing", "be", "mod2", 10) == bouncing);
  CHECK(cache.computed() == 4);
  CHECK(field_reference("layered", "cn", "mod1", 10) != bouncing);
  CHECK(field_reference("bouncing", "cn", "mod1", 20) != bouncing);
  CHECK(cache.computed() == 6);
}

}  // namespace mrm::repro
