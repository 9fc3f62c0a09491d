// The runner of the doctests embedded in lib/*.cpp and repro/*.cpp (see CMakeLists.txt): the library
// and harness sources are compiled into this program with the tests switched on.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
