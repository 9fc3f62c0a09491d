/// @file doctest_main.cpp
/// @brief The runner of the doctests embedded in the .cpp files of lib/ and repro/: it links every object
/// of the library and the harness, compiled once with their tests (CMakeLists.txt, mrm_objects), and runs
/// the test cases they registered (doctest's registry: tests/doctest_registry.cpp).
#include <doctest/doctest.h>

int main(int argc, char** argv) { return doctest::Context(argc, argv).run(); }
