#!/usr/bin/env bash
# The generator's stages include only themselves and the stages before them (docs/architecture.md);
# the runtime never includes the generator or GiNaC. Prints every back edge and fails if any.
#   check_layers.sh SOURCE_DIR
set -euo pipefail
root=${1:?source dir}
stages=(support expr inertia spec derive forms lower emit inspect scene run view simulate bench sweep tune fit cli)
declare -A rank
for i in "${!stages[@]}"; do rank[${stages[$i]}]=$i; done
bad=0
for dir in "$root"/generator/*/; do
  stage=$(basename "$dir")
  if [[ -z ${rank[$stage]+x} ]]; then
    echo "generator/$stage: a folder that is not a stage (add it to tests/architecture/check_layers.sh and docs/architecture.md)"
    bad=1; continue
  fi
  while IFS=: read -r file line text; do
    used=$(sed -E 's|.*#include "([a-z_]+)/.*|\1|' <<<"$text")
    [[ -z ${rank[$used]+x} ]] && continue
    if (( rank[$used] > rank[$stage] )); then
      echo "${file#$root/}:$line: stage '$stage' includes the later stage '$used': $text"
      bad=1
    fi
  done < <(grep -Hn '^#include "[a-z_]*/' "$dir"*.[ch]pp || true)
done
if grep -rn '#include.*\(ginac\|generator/\|"[a-z]*/[a-z_]*\.hpp"\)' "$root"/runtime --include='*.hpp' | grep -v '"steppers/\|"integrate/' ; then
  echo "runtime/: includes the generator or GiNaC"
  bad=1
fi
(( bad == 0 )) && echo "stages include only earlier stages (${#stages[@]} stages)"
exit $bad
