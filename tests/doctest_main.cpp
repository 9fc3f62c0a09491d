// The runner of the doctests embedded in lib/*.cpp (see CMakeLists.txt): the library sources are
// compiled into this program with the tests switched on.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
