#!/usr/bin/env bash
# check_statics.sh must be able to fail: a library beside the stage libraries with a function-local
# static that is written after its initialisation (a cache) and a namespace-scope counter is
# refused, each by name, while a const table in the same file is not.
#   check_statics_detects.sh BUILD_DIR SOURCE_DIR CXX
set -euo pipefail
build=${1:?build dir}
root=${2:?source dir}
cxx=${3:-c++}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/planted.cpp" <<'EOF'
#include <map>
#include <string>
#include <vector>
namespace rotgen {
int planted_counter = 0;
const std::string& planted_cache(int k) {
    static std::map<int, std::string> memo;
    ++planted_counter;
    return memo.emplace(k, std::to_string(k)).first->second;
}
const std::vector<std::string>& planted_table() {
    static const std::vector<std::string> table{"a", "b"};
    return table;
}
} // namespace rotgen
EOF
"$cxx" -std=c++17 -O2 -c "$tmp/planted.cpp" -o "$tmp/planted.cpp.o"
ar rcs "$tmp/librotgen_planted.a" "$tmp/planted.cpp.o"
status=0
out=$(bash "$root/tests/architecture/check_statics.sh" "$build" "$root" "$tmp/librotgen_planted.a") ||
  status=$?
echo "$out"
fail=0
(( status != 0 )) || { echo "FAILED: the check passed with a planted mutable static"; fail=1; }
grep -q 'mutable static state: rotgen::planted_cache.*(int)::memo$' <<<"$out" ||
  { echo "FAILED: the function-local memo is not named"; fail=1; }
grep -q 'mutable static state: guard variable for rotgen::planted_cache.*(int)::memo$' <<<"$out" ||
  { echo "FAILED: its guard variable is not named"; fail=1; }
grep -q 'mutable static state: rotgen::planted_counter$' <<<"$out" ||
  { echo "FAILED: the namespace-scope counter is not named"; fail=1; }
if grep -q 'planted_table' <<<"$out"; then
  echo "FAILED: the const table was refused"
  fail=1
fi
(( fail == 0 )) && echo "the check refuses the planted statics by name"
exit $fail
