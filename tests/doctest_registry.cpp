/// @file doctest_registry.cpp
/// @brief doctest's registry and runner, without a main: part of the objects that the doctest runner and
/// every program share (CMakeLists.txt, mrm_objects). The test cases of lib/ and repro/ register here when
/// a program starts; only tests/doctest_main.cpp runs them.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>
