/// @file moreau_jean.cpp
/// @brief Moreau–Jean (θ, e): the θ-method with a velocity-level impact law (`moreau-jean`), in the
/// notation of contact_classes.cpp. The doctests that run it are in contact_classes.cpp.
///
/// ## Moreau–Jean (θ, e) (moreau-jean)
///
///     M(Vⁿ⁺¹ − Vⁿ) = −Δt S(θUⁿ⁺¹ + (1 − θ)Uⁿ) + p e₀,     Uⁿ⁺¹ = Uⁿ + Δt(θVⁿ⁺¹ + (1 − θ)Vⁿ),
///     if u₀ⁿ + ½Δt v₀ⁿ ≤ 0:  0 ≤ v₀ⁿ⁺¹ + e v₀ⁿ ⊥ p ≥ 0,   else p = 0,
///
/// the impulse p per step on the contact node, the impact law v⁺ = −e v⁻ on the node's velocity. The
/// index-set test (the predicted gap u₀ + ½Δt v₀) is our reading of Siconos' MoreauJeanOSI default
/// (reconstructed: the class's sources do not define it; doc/contact_treatments.md §5). Eliminating Uⁿ⁺¹:
/// (M + θ²Δt²S) Vⁿ⁺¹ = (M − θ(1 − θ)Δt²S) Vⁿ − Δt S Uⁿ + p e₀, one solve with the closed-form contact
/// step (the obstacle −e v₀ⁿ on v₀). The stress it reports is the mean force over the step, λ = −p/Δt
/// (the class has no stress, only impulses: doc/contact_treatments.md §5). Energy identity (write the averages as the
/// θ-values minus (θ − ½) times the increments):
///
///     Eⁿ⁺¹ − Eⁿ = p (θ v₀ⁿ⁺¹ + (1 − θ) v₀ⁿ) − (θ − ½)(‖Vⁿ⁺¹ − Vⁿ‖²_M + ‖Uⁿ⁺¹ − Uⁿ‖²_S),           (MJ)
///
/// so θ = ½, e = 1 conserves E exactly (p > 0 only where v₀ⁿ⁺¹ = −v₀ⁿ). Otherwise the impulse term is
/// p v₀ⁿ (1 − θ(1 + e)), which gains energy where the node is in the index set while leaving (v₀ⁿ > 0,
/// θ(1 + e) < 1) or arriving with θ(1 + e) > 1 (θ > ½, e = 1): e < 1 does not make the scheme dissipative
/// step by step (measured below: gains of 2e-4 E₀ at θ = ½, e = ½). It needs the contact node's inertia
/// (refused with a massless node).
///
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "classes/step_pieces.hpp"

namespace mrm::class_steps {

namespace {

// Moreau–Jean (θ, e) (file comment, (MJ)).
class MoreauJeanStep final : public OneSolveStep {
 public:
  MoreauJeanStep(const Tridiagonal& mass, const Tridiagonal& stiffness, const SchemeParameters& p, double dt,
                 bool has_load, double gap, const std::string& id)
      : id_(id),
        mass_(mass),
        stiffness_(stiffness),
        dt_(dt),
        theta_(p.moreau_theta),
        restitution_(p.restitution),
        has_load_(has_load),
        fused_(p.kernel == StepKernel::fast),
        gap_(gap) {
    solver_ = ContactSolver(mass.plus(theta_ * theta_ * dt * dt, stiffness));
    explicit_part_ = mass.plus(-theta_ * (1 - theta_) * dt * dt, stiffness);
  }

  // The initial level: no impulse yet, E⁰.
  void start(StepState& state) override {
    state.lambda = 0.0;
    state.active = false;
    state.energy = energy(state);
  }

  // The step as its derivation reads (StepKernel::reference): Vⁿ⁺¹ in state.u_new, Uⁿ⁺¹ in state.u;
  // returns the impulse p.
  double readable_advance(StepState& state) {
    const double dt = dt_;
    Eigen::VectorXd& v = state.u_new;  // Vⁿ⁺¹
    v = explicit_part_ * state.w - dt * (stiffness_ * state.u);
    if (has_load_) v += (dt * theta_) * state.f_next + (dt * (1 - theta_)) * state.f_now;  // Δt F_θ
    const double v0 = state.w[0];
    double impulse = 0;
    if (state.u[0] + gap_ + 0.5 * dt * v0 <= 0) {  // in the index set: the impact law on v₀
      const ContactStep contact = solver_.solve(v.data(), v.data(), 1.0, -restitution_ * v0);
      impulse = -contact.multiplier;
    } else {
      solve_free(solver_, v);
    }
    state.u += dt * (theta_ * v + (1 - theta_) * state.w);
    return impulse;
  }

  // The same step in two passes, each entry computed with the readable step's operations in the same
  // order, no allocation (StepKernel::fast; doctest "the fused class steps are their readable steps, bit
  // for bit"):
  //   1. b_i = (M − θ(1 − θ)Δt²S)Vⁿ)_i − Δt(SUⁿ)_i (+ ((Δtθ)Fⁿ⁺¹_i + (Δt(1 − θ))Fⁿ_i)), formed inside the
  //      sweep down of M + θ²Δt²S;
  //   2. the impact law on row 0 (the index set is known from Uⁿ, Vⁿ), then the sweep up of Vⁿ⁺¹ and, node
  //      by node, Uⁿ⁺¹_i = Uⁿ_i + Δt(θVⁿ⁺¹_i + (1 − θ)Vⁿ_i).
  double fused_advance(StepState& state) {
    const Index n = mass_.size();
    const double dt = dt_, c_next = dt * theta_, c_now = dt * (1 - theta_);
    const double *u = state.u.data(), *w = state.w.data();
    const double *f_next = has_load_ ? state.f_next.data() : nullptr, *f_now = has_load_ ? state.f_now.data() : nullptr;
    double* y = state.u_new.data();
    const auto b = [&](Index i, double explicit_w, double stiffness_u) {
      double bi = explicit_w - dt * stiffness_u;
      if (has_load_) bi += c_next * f_next[i] + c_now * f_now[i];
      return bi;
    };
    // 1. b inside the sweep down.
    sweep_down_forming(solver_, n, y, explicit_part_, w, stiffness_, u, b,
                       b(0, row_product(explicit_part_, w, 0, n), row_product(stiffness_, u, 0, n)));
    // 2. The impact law, the sweep up and Uⁿ⁺¹.
    const Decision d = decide(y[0], u[0], w[0]);
    double vi = d.x0;
    const double *ip = solver_.inverse_pivot().data(), *cu = solver_.upward().data();
    const double a = 1 - theta_;
    double* un = state.u.data();
    y[0] = vi;
    un[0] += dt * (theta_ * vi + a * w[0]);
    for (Index i = 1; i < n; ++i) {
      vi = ip[i] * y[i] - cu[i] * vi;
      y[i] = vi;
      un[i] += dt * (theta_ * vi + a * w[i]);
    }
    return d.value;
  }

  void step(StepState& state, Index level) override {
    state.u_new.resize(state.u.size());
    const double impulse = fused_ ? fused_advance(state) : readable_advance(state);
    state.w.swap(state.u_new);
    finish(state, {0.0, impulse}, 0.0, energy(state), level);
    if (has_load_) state.f_now.swap(state.f_next);
  }

  // The pieces of the batched step (OneSolveStep), each the fused step's own.
  bool batchable() const override { return fused_ && !has_load_; }
  Lanes lanes() const override {
    return {&mass_, &stiffness_, &explicit_part_, &solver_, &no_column_, dt_, dt_, theta_, gap_, false};
  }
  std::optional<double> projection(double, double) const override { return std::nullopt; }
  // The index set from the predicted gap u₀ + g₀ + ½Δt v₀: the impact law (v₀ⁿ⁺¹ ≥ −e v₀ⁿ) or a free row 0.
  Decision decide(double y0, double u0, double v0) const override {
    if (u0 + gap_ + 0.5 * dt_ * v0 <= 0) {
      const ContactStep contact = solver_.resolve_contact(y0, 1.0, -restitution_ * v0);
      return {contact.u0, -contact.multiplier};
    }
    return {y0 * solver_.inverse_pivot()[0], 0.0};
  }
  // λ = −p/Δt, the status, the energy.
  void finish(StepState& state, const Decision& d, double, double kinetic_and_strain, Index level) override {
    state.lambda = -d.value / dt_;
    state.active = d.value > 0;
    state.energy = kinetic_and_strain;
    require_finite(state.energy, id_, level + 1);
  }

 private:
  double energy(const StepState& s) const { return kinetic_and_strain(mass_, stiffness_, s); }
  std::string id_;
  Tridiagonal mass_, stiffness_, explicit_part_;
  double dt_, theta_, restitution_;
  bool has_load_, fused_;
  double gap_;
  ContactSolver solver_;
  Eigen::VectorXd no_column_;  // Lanes::column: no projection
};

// ---------------------------------------------------------------------------------------------------

}  // namespace

std::unique_ptr<ContactClassStep> make_moreau_jean_step(const Tridiagonal& mass, const Tridiagonal& stiffness,
                                                        const SchemeParameters& p, double dt, bool has_load, double gap,
                                                        const std::string& id) {
  return std::make_unique<MoreauJeanStep>(mass, stiffness, p, dt, has_load, gap, id);
}

}  // namespace mrm::class_steps
