# cmake -DSRC=<source tree> [-DROTGEN_REQUIRE_ALL=ON] -P require_all_check.cmake: one optional
# dependency found and one missing, through cmake/require_all.cmake (require_all.sh runs it).
include(${SRC}/cmake/require_all.cmake)
set(_have_it TRUE)
rotgen_optional(_have_it "present-package")
set(_not_it FALSE)
rotgen_optional(_not_it "absent-package (Debian: absent-dev)")
message(STATUS "configured")
