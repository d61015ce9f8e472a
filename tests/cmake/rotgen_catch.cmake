# rotgen_catch_tests(TARGET [PREFIX prefix]): each Catch2 case of TARGET becomes a ctest test.
#
# - `-w NoTests`: a ctest test whose name matches no case (a name Catch's test-spec parser reads
#   differently, e.g. one with '[') fails instead of passing with nothing run;
# - catch2_cases_all_run_<TARGET>: the cases the executable lists and the tests ctest discovered
#   for it are the same names (catch_discover_tests splits a name at ';', dropping the case).
include_guard(GLOBAL)
include(Catch)

function(rotgen_catch_tests target)
  cmake_parse_arguments(arg "" "PREFIX" "" ${ARGN})
  catch_discover_tests(${target} TEST_PREFIX "${arg_PREFIX}" EXTRA_ARGS -w NoTests)
  add_test(NAME catch2_cases_all_run_${target}
           COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:${target}> -DCTEST=${CMAKE_CTEST_COMMAND}
                   -DDIR=${CMAKE_CURRENT_BINARY_DIR} "-DPREFIX=${arg_PREFIX}"
                   -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/check_discovered.cmake)
endfunction()
