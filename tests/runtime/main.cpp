// Catch2 main of the runtime tests.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
