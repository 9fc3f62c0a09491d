/// @file scheme_registry.hpp
/// @brief The registry of time schemes: every scheme's entry (SchemeInfo, steps/step.hpp: its id, summary,
/// labels, parameters, checks, step builder and batched kernel's family), gathered from the files of the
/// families that register them: the paper's one-step form (steps/one_step_form.cpp), central differences
/// (steps/explicit_schemes.cpp) and the contact classes (classes/contact_classes.cpp). Every name of a
/// scheme in the library and the harness is read from here.
#pragma once

#include <string>
#include <vector>

#include "classes/contact_classes.hpp"
#include "steps/explicit_schemes.hpp"
#include "steps/one_step_form.hpp"
#include "steps/step.hpp"

namespace mrm {

/// Every scheme of the library, in the order of the enum: the entries of the one-step form
/// (one_step_form_schemes), of central differences (central_difference_schemes) and of the contact classes
/// (contact_class_schemes). Adding a scheme is: its step with its doctests, and one entry in its family's
/// list (a new family: its list, named in scheme_registry.cpp).
const std::vector<SchemeInfo>& scheme_registry();
/// The registry entry of a scheme.
const SchemeInfo& scheme_info(Scheme);
/// Whether `scheme` takes `parameter` (its registry entry lists it).
bool takes(Scheme scheme, SchemeParameter parameter);

std::string to_string(Scheme);  ///< the registry's id: "cn", "be", "ps", "ec", "cn-switch", ...
/// The scheme of a registry id; throws std::invalid_argument listing the ids.
Scheme scheme_by_name(const std::string&);

}  // namespace mrm
