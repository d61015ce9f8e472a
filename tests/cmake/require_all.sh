#!/usr/bin/env bash
# ROTGEN_REQUIRE_ALL (cmake/require_all.cmake): OFF, a missing optional dependency is noted and the
# configure goes on; ON, it stops with an error naming the package.
#   tests/cmake/require_all.sh SOURCE_DIR
set -uo pipefail
src=$1
check=$src/tests/cmake/require_all_check.cmake
off=$(cmake -DSRC="$src" -P "$check" 2>&1)
off_rc=$?
on=$(cmake -DSRC="$src" -DROTGEN_REQUIRE_ALL=ON -P "$check" 2>&1)
on_rc=$?
fail=0
[ "$off_rc" -eq 0 ] && grep -q "configured" <<<"$off" || { echo "OFF: configure stopped: $off"; fail=1; }
grep -q "optional absent-package (Debian: absent-dev) not found" <<<"$off" || { echo "OFF: no note: $off"; fail=1; }
[ "$on_rc" -ne 0 ] || { echo "ON: configure went on with a missing dependency"; fail=1; }
! grep -q "configured" <<<"$on" || { echo "ON: went past the missing dependency: $on"; fail=1; }
grep -q "ROTGEN_REQUIRE_ALL is ON and absent-package" <<<"$on" || { echo "ON: the package not named: $on"; fail=1; }
grep -q "present-package" <<<"$on$off" && { echo "a dependency that is there was named"; fail=1; }
[ "$fail" -eq 0 ] && echo "ROTGEN_REQUIRE_ALL: OFF notes, ON stops and names the package"
exit "$fail"
