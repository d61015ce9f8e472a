#!/usr/bin/env bash
# Regenerates every header in generated/ with the command stamped in it and fails if a byte
# differs (the checked-in headers are what users embed without GiNaC).
#   check_generated.sh ROTGEN_EXE SOURCE_DIR
set -euo pipefail
rotgen=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
ln -s "$src/models" "$work/models" # the stamped command names models/... relative to the root
mkdir "$work/generated"
cd "$work"
count=0
for header in "$src"/generated/*.hpp; do
  command=$(sed -n '/^\/\/ Do not edit; regenerate with$/{n;p;q}' "$header" | sed 's#^//   rotgen ##')
  if [ -z "$command" ]; then echo "no regenerate command in $header"; exit 1; fi
  eval "\"$rotgen\" $command" >/dev/null
  name=$(basename "$header")
  if ! cmp -s "$header" "generated/$name"; then
    echo "generated/$name differs from what '$command' writes now:"
    diff "$header" "generated/$name" | head -20
    exit 1
  fi
  count=$((count + 1))
done
[ "$count" -ge 4 ] || { echo "expected the shipped headers in $src/generated, found $count"; exit 1; }
echo "$count headers regenerate byte-for-byte"
