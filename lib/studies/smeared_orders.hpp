/// @file smeared_orders.hpp
/// @brief The orders in h that a scheme's dispersion leaves to a field with jumps or kinks, and to a
/// contact released by a smeared front (smeared_orders.cpp): the derivation behind the conjectured orders
/// of the field's benchmarks.
#pragma once

#include "measures/contact_stress.hpp"

namespace mrm {

/// The order in h of the L² error of a field whose Fourier coefficients decay like k^{−s} (s = `decay`:
/// 1 for a jump, 2 for a kink, 3 for a kink of the derivative) carried by a scheme of phase error
/// C ξ^μ (PhaseOrder): μ min(1, (2s − 1)/(2(μ + 1))) (smeared_orders.cpp §1). Throws
/// std::invalid_argument unless s ≥ 1 and μ ≥ 1.
double smeared_field_order(int decay, const PhaseOrder& phase);

/// The order in h of the error of a release triggered by a front smeared over W, δ = O(W):
/// μ/(μ + 1) (smeared_orders.cpp §2). Throws std::invalid_argument unless μ ≥ 1.
double release_shift_order(const PhaseOrder& phase);

}  // namespace mrm
