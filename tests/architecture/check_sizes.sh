#!/usr/bin/env bash
# Small pieces: no function longer than 100 lines and no source file longer than 600 lines in
# generator/, runtime/, bench/'s and python/'s C++ (function extents from universal-ctags). Prints the
# offenders, and the longest function and largest file, and fails if any limit is broken.
#   check_sizes.sh SOURCE_DIR
set -euo pipefail
root=${1:?source dir}
cd "$root"
command -v ctags >/dev/null || { echo "needs universal-ctags (apt-get install universal-ctags)"; exit 1; }
files=$(find generator runtime bench python -name '*.cpp' -o -name '*.hpp' | sort)
bad=0
longest=$(ctags --fields=+ne --kinds-C++=f -o - $files 2>/dev/null |
  awk -F'\t' '{l=0; e=0; for (i = 4; i <= NF; i++) { if ($i ~ /^line:/) l = substr($i, 6); if ($i ~ /^end:/) e = substr($i, 5) }
               if (e > 0) print e - l + 1, $2 ":" l, $1 }' | sort -rn)
while read -r n where name; do
  (( n > 100 )) && { echo "$where: function $name is $n lines (limit 100)"; bad=1; }
done <<<"$longest"
while read -r n file; do
  [[ $file == total ]] && continue
  (( n > 600 )) && { echo "$file: $n lines (limit 600)"; bad=1; }
done < <(wc -l $files | sort -rn)
echo "longest function: $(head -1 <<<"$longest")"
echo "largest file: $(wc -l $files | sort -rn | sed -n 2p)"
exit $bad
