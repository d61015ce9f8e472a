#!/usr/bin/env bash
# Checks that the transcripts of the README and of the documentation's pages are what rotgen
# prints now.
#   check_transcripts.sh BUILD_DIR SOURCE_DIR [FILE.md ...]
# Without FILEs: SOURCE_DIR/README.md and every SOURCE_DIR/docs/*.md (a page without transcripts
# is fine; no transcript at all is an error).
# A transcript is a ```console block whose first line starts with "$ ". Each "$ " line is a command
# (run by bash, stderr merged into stdout, in the order written); the lines after it, up to the
# next "$ " line or the end of the block, are its expected output. The commands of a block run in
# one shell (so `echo $?` reports the previous command's status) in a scratch folder where
# `models/` and `examples/` are the source tree's and `build/` is BUILD_DIR, so that paths read as
# they do from the repository root and nothing is written into the source tree. A block that
# runs the Python module (PYTHONPATH=build/python) is skipped when the build has no module.
# Only timings may differ: a line "  time    ..." of the simulate summary and a line
# "rotgen: timing ..." compare equal whatever they hold. On a difference it prints a unified diff
# (the page above, program below) and exits 1.
set -euo pipefail
build=$(realpath "${1:?usage: check_transcripts.sh BUILD_DIR SOURCE_DIR [README]}")
src=$(realpath "${2:?usage: check_transcripts.sh BUILD_DIR SOURCE_DIR [README]}")
shift 2
if (($#)); then
  files=("$@")
else
  files=("$src/README.md" "$src"/docs/*.md)
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Timings are the only thing allowed to differ.
normalise() { sed -E -e 's/^(  time    ).*/\1<timings>/' -e 's/^(rotgen: timing ).*/\1<timings>/'; }

blocks=0 failed=0 blocks_seen=0
run_block() { # $1: the page's name and the line of the block, $2: file holding the block's lines
  local where=$1 body=$2 dir="$work/block$blocks_seen"
  blocks_seen=$((blocks_seen + 1))
  # A block that imports the Python module runs only where the build made it (pybind11, NumPy).
  if grep -q 'PYTHONPATH=build/python' "$body" && [[ ! -d $build/python/rotgen ]]; then
    echo "$where: skipped (no Python module in $build: pybind11 or NumPy missing)"
    return
  fi
  mkdir -p "$dir"
  ln -s "$src/models" "$dir/models"
  ln -s "$src/examples" "$dir/examples"
  ln -s "$build" "$dir/build"
  # The script: each command prints its expected-output header, then runs with stderr merged.
  local script="$dir/.transcript.sh" expected="$dir/.expected" actual="$dir/.actual"
  echo 'st=0' >"$script"; : >"$expected"
  while IFS= read -r l; do
    if [[ $l == '$ '* ]]; then
      printf '%s\n' "$l" >>"$expected"
      # The header line must not disturb $?: the status is kept across it.
      printf 'printf "%%s\\n" %q\n(exit $st)\n{ %s\n} 2>&1\nst=$?\n' "$l" "${l#\$ }" >>"$script"
    else
      printf '%s\n' "$l" >>"$expected"
    fi
  done <"$body"
  (cd "$dir" && bash "$script") >"$actual" 2>&1 || true
  if ! diff -u --label "$where (the transcript)" --label "what rotgen prints now" \
      <(normalise <"$expected") <(normalise <"$actual"); then
    failed=$((failed + 1))
  fi
  blocks=$((blocks + 1))
}

# Collect the blocks of each page and run them.
run_page() { # $1: the page (Markdown)
  local page=$1 name in_block=0 start=0 n=0 body="" l
  name=$(realpath --relative-to="$src" "$page")
  while IFS= read -r l; do
    n=$((n + 1))
    if ((in_block)); then
      if [[ $l == '```'* ]]; then
        in_block=0
        [[ -s $body ]] && [[ $(head -n 1 "$body") == '$ '* ]] && run_block "$name line $start" "$body"
      else
        printf '%s\n' "$l" >>"$body"
      fi
    elif [[ $l == '```console' ]]; then
      in_block=1 start=$n body="$work/body.$blocks_seen.$n"
      : >"$body"
    fi
  done <"$page"
}
for page in "${files[@]}"; do
  run_page "$(realpath "$page")"
done

if ((blocks == 0)); then
  echo "no transcripts (\`\`\`console blocks starting with '\$ ') in ${files[*]}"
  exit 1
fi
if ((failed)); then
  echo "$failed of $blocks transcripts differ from what rotgen prints now (diffs above);"
  echo "update the page (or the program) so that they agree."
  exit 1
fi
echo "$blocks transcripts in ${#files[@]} pages match what rotgen prints"
