# Every Catch2 case of a test executable is a ctest test, and nothing else is.
#
#   cmake -DEXE=<test executable> -DCTEST=<ctest> -DDIR=<build dir holding its ctest tests>
#         [-DPREFIX=<catch_discover_tests TEST_PREFIX>] -P check_discovered.cmake
#
# catch_discover_tests splits a test name at ';' (and a name that Catch's test-spec parser reads
# differently, e.g. one with '[', matches no case when run): such a case is silently never run.
# This compares the names the executable lists (--list-test-names-only) with the tests ctest
# discovered for it (ctest --show-only=json-v1, tests whose command is EXE), as sets and counts.
cmake_minimum_required(VERSION 3.19) # string(JSON)

foreach(_var EXE CTEST DIR)
  if(NOT DEFINED ${_var})
    message(FATAL_ERROR "check_discovered.cmake: -D${_var}=... is required")
  endif()
endforeach()

execute_process(COMMAND ${EXE} --list-test-names-only OUTPUT_VARIABLE _listed RESULT_VARIABLE _rc)
if(_rc LESS 0)
  message(FATAL_ERROR "${EXE} --list-test-names-only failed: ${_rc}")
endif()
# Protect the characters CMake lists treat specially (; and brackets) before splitting into lines.
string(REPLACE ";" "<semicolon>" _listed "${_listed}")
string(REPLACE "[" "<lb>" _listed "${_listed}")
string(REPLACE "]" "<rb>" _listed "${_listed}")
string(REPLACE "\n" ";" _listed "${_listed}")
list(FILTER _listed EXCLUDE REGEX "^[ \t\r]*$")
list(LENGTH _listed _n_listed)

execute_process(COMMAND ${CTEST} --test-dir ${DIR} --show-only=json-v1
                OUTPUT_VARIABLE _json RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "ctest --show-only=json-v1 in ${DIR} failed: ${_rc}")
endif()
string(JSON _n_all LENGTH "${_json}" tests)
set(_discovered)
if(_n_all GREATER 0)
  math(EXPR _last "${_n_all} - 1")
  foreach(_i RANGE ${_last})
    string(JSON _cmd ERROR_VARIABLE _err GET "${_json}" tests ${_i} command 0)
    if(NOT _err STREQUAL "NOTFOUND" OR NOT _cmd STREQUAL EXE)
      continue()
    endif()
    string(JSON _name GET "${_json}" tests ${_i} name)
    string(REPLACE ";" "<semicolon>" _name "${_name}")
    string(REPLACE "[" "<lb>" _name "${_name}")
    string(REPLACE "]" "<rb>" _name "${_name}")
    list(APPEND _discovered "${_name}")
  endforeach()
endif()
list(LENGTH _discovered _n_discovered)

set(_expected)
foreach(_case IN LISTS _listed)
  list(APPEND _expected "${PREFIX}${_case}")
endforeach()
set(_missing)
foreach(_name IN LISTS _expected)
  if(NOT _name IN_LIST _discovered)
    list(APPEND _missing "${_name}")
  endif()
endforeach()
set(_extra)
foreach(_name IN LISTS _discovered)
  if(NOT _name IN_LIST _expected)
    list(APPEND _extra "${_name}")
  endif()
endforeach()

get_filename_component(_exe_name ${EXE} NAME)
if(_missing OR _extra OR NOT _n_listed EQUAL _n_discovered)
  string(REPLACE ";" "\n  " _missing "${_missing}")
  string(REPLACE ";" "\n  " _extra "${_extra}")
  foreach(_var _missing _extra)
    string(REPLACE "<semicolon>" ";" ${_var} "${${_var}}")
    string(REPLACE "<lb>" "[" ${_var} "${${_var}}")
    string(REPLACE "<rb>" "]" ${_var} "${${_var}}")
  endforeach()
  message(FATAL_ERROR "${_exe_name}: ${_n_listed} Catch2 cases, ${_n_discovered} ctest tests\n"
                      "cases ctest does not run (a ';' in the name?):\n  ${_missing}\n"
                      "ctest tests that are no case:\n  ${_extra}")
endif()
message(STATUS "${_exe_name}: ${_n_listed} Catch2 cases, ${_n_discovered} ctest tests, the same names")
