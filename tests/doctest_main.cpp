// The runner of the doctests embedded in the .cpp files of lib/ and repro/ (see CMakeLists.txt): the library
// and harness sources are compiled into this program with the tests switched on.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
