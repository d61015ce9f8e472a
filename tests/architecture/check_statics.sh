#!/usr/bin/env bash
# No hidden mutable state in the generator (issue 46): state is passed, not stored. Lists the
# writable data of the stage libraries (nm types B b D d: .bss and .data, and the guard variables
# `_ZGV...` that every function-local static with a dynamic initialiser has) and fails on any
# object that is neither
#   - declared const (or constexpr) in the source file its object file was compiled from: a table
#     or symbol set made once, on first use (the guard makes that thread-safe), never written
#     after; a `static` (or namespace-scope) object of the same name that is not const in that
#     file disqualifies it, nor
#   - on the short allow-list below, each entry with the lock that guards it or why it is safe.
# Compiler and library objects that are not the program's state are left out: typeinfo and vtables
# (read-only after relocation), <iostream>'s std::__ioinit, and GiNaC's registration objects that
# its headers put in every file that includes them (`*_unarchiver_instance`,
# `unarch_table_instance`, `library_initializer`: constructed at start-up, GiNaC's own).
# An allow-list entry that no longer matches is an error too, so that the list stays short.
#   check_statics.sh BUILD_DIR SOURCE_DIR [EXTRA_LIBRARY...]
set -euo pipefail
build=${1:?build dir}
root=${2:?source dir}
shift 2

# Substrings of demangled names. Keep this short: prefer passing the state (issue 46).
allowed=(
  # The one lock GiNaC's users take (GiNaC is not thread-safe); a std::mutex is made to be shared.
  'rotgen::symbolic_mutex()::m'
  # Lowering's memo of normal() (n/d of a coefficient): a pure function of its key, so what it
  # holds never changes a result; lowering runs under symbolic_mutex() (GiNaC), which guards it.
  'rotgen::lowering::dag_builder::single_fraction(GiNaC::ex const&)::memo'
  # Models and scenes held in memory (Python's Scene text, support/memory_files.hpp): the map and
  # the mutex that guards every access to it.
  'rotgen::(anonymous namespace)::files()::f'
  'rotgen::(anonymous namespace)::files_mutex()::m'
  # The signal handler's state (support/signals.cpp): the temporaries a SIGINT or SIGTERM removes
  # and the line it prints. A handler reaches only globals; the slots are sig_atomic_t flags
  # and fixed buffers, written before a flag is set; process-wide by nature (one set of outputs
  # per process). Written under g_writers.
  'rotgen::(anonymous namespace)::g_temporaries'
  'rotgen::(anonymous namespace)::g_used'
  'rotgen::(anonymous namespace)::g_notes'
  'rotgen::(anonymous namespace)::g_note'
  'rotgen::(anonymous namespace)::g_hook'
  'rotgen::(anonymous namespace)::g_written'
  # The lock every writer of the handler's state above takes (threads of one process register
  # their temporaries at once); the handler itself reads only flags set after their buffers.
  'rotgen::(anonymous namespace)::g_writers'
  # The same for a streaming sweep (sweep/journal.cpp): the handler's copy of its journal (fixed
  # storage and atomics), what a SIGINT truncates the summary to.
  'rotgen::(anonymous namespace)::g_journal'
  # A thread's own memo of a pure function (run/quad_start.cpp's decimal_of: the decimal a double
  # prints as, read back in quad precision): thread_local, so never shared; bounded (256).
  'rotgen::(anonymous namespace)::decimal_of(double)::seen'
)

libs=("$build"/generator/librotgen_*.a "$@")
if [[ ! -e ${libs[0]} ]]; then
  echo "no stage libraries under $build/generator (build first)"
  exit 1
fi

# "library:object: ADDRESS TYPE NAME" -> "library<TAB>object<TAB>NAME" for writable data.
symbols=$(nm -A -C --defined-only "${libs[@]}" 2>/dev/null |
  sed -nE 's/^([^:]+):([^:]+): *[0-9a-f]+ [BbDd] (.*)$/\1\t\2\t\3/p' |
  grep -vE $'\t''(typeinfo for |typeinfo name for |vtable for |std::__ioinit$|GiNaC::[A-Za-z0-9_]+_unarchiver_instance$|GiNaC::library_initializer$|GiNaC::unarch_table_instance$)' |
  sort -u || true)

# The source file an object file of a stage library was compiled from (empty if none): the
# stage's folder, or (an extra library) the library's own folder.
source_of() {
  local lib=$1 object=$2 stage file
  stage=$(basename "$lib" .a)
  stage=${stage#librotgen_}
  for file in "$root/generator/$stage/${object%.o}" "$(dirname "$lib")/${object%.o}"; do
    if [[ -f $file ]]; then
      echo "$file"
      return
    fi
  done
}

# Whether NAME is declared const in FILE and nowhere there as a static that is not.
declared_const() {
  local file=$1 name=$2
  [[ -n $file ]] || return 1
  grep -qP "^\s*((inline|static)\s+)*(const|constexpr)\b[^;]*\b\Q$name\E\b\s*(=|\{|\(|;|\[)" "$file" ||
    return 1
  ! grep -qP "^\s*((inline|static|thread_local)\s+)+(?!const\b|constexpr\b|inline\b|static\b|thread_local\b)[^;(]*\b\Q$name\E\b\s*(=|\{|;)" "$file"
}

bad=0
declare -A used
while IFS=$'\t' read -r lib object name; do
  [[ -n $name ]] || continue
  object_name=${name#guard variable for }
  ok=0
  for entry in "${allowed[@]}"; do
    if [[ $object_name == *"$entry"* ]]; then
      ok=1
      used[$entry]=1
    fi
  done
  (( ok )) && continue
  local_name=${object_name##*::}
  declared_const "$(source_of "$lib" "$object" || true)" "$local_name" && continue
  echo "$(basename "$lib") ($object): mutable static state: $name"
  bad=1
done <<<"$symbols"

for entry in "${allowed[@]}"; do
  if [[ -z ${used[$entry]+x} ]]; then
    echo "tests/architecture/check_statics.sh: the allowed '$entry' is not in any stage library (remove it)"
    bad=1
  fi
done

if (( bad )); then
  echo "pass the state instead (issue 46), or, where a lock guards it by design, add it to the allow-list with the reason"
  exit 1
fi
echo "no mutable statics in ${#libs[@]} stage libraries ($(grep -c . <<<"$symbols") writable data symbols, ${#allowed[@]} allowed by name, the rest const after initialisation)"
