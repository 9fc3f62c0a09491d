/// @file configurations.hpp
/// @brief The paper's named configurations and the one function that runs a configuration and returns its
/// measures (every program and check that needs the errors or the energy range of a run calls it).
/// The configuration (configurations/configuration.hpp), the scaling law (configurations/scaling.hpp),
/// the stresses (configurations/stress.hpp), a run's measures (configurations/run.hpp) and the two
/// bodies (configurations/two_bodies.hpp), included together.
#pragma once

#include "configurations/configuration.hpp"
#include "configurations/run.hpp"
#include "configurations/scaling.hpp"
#include "configurations/stress.hpp"
#include "configurations/two_bodies.hpp"
