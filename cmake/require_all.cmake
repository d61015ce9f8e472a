# ROTGEN_REQUIRE_ALL (default OFF; .ci/run turns it ON): every optional dependency becomes a
# required one, so that no test leaves the suite unnoticed because a package was not installed.
# Users without MPI, xsimd, libquadmath or Python build with it OFF and lose only those features.
option(ROTGEN_REQUIRE_ALL "fail the configure step, naming the package, when an optional dependency is missing" OFF)

# rotgen_optional(<variable> <what>): the optional dependency <what> (the package to install) is
# missing when <variable> is false; with ROTGEN_REQUIRE_ALL the configure step stops there.
function(rotgen_optional variable what)
  if(NOT ${variable})
    if(ROTGEN_REQUIRE_ALL)
      message(FATAL_ERROR "rotgen: ROTGEN_REQUIRE_ALL is ON and ${what} is missing")
    endif()
    message(STATUS "rotgen: optional ${what} not found: its features and tests are left out")
  endif()
endfunction()
