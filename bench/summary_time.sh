# Sourced by the bench scripts: the seconds of a summary's time line,
#   "  time    <number> <s|ms|us> <what>"  (rotgen prints a duration in the unit that fits).
#   rotgen sweep ... | summary_seconds "running the members"
summary_seconds() {
  sed -n "s/^  time    \([0-9.]*\) \(s\|ms\|us\) $1.*/\1 \2/p" |
    awk '{ print $1 * ($2 == "s" ? 1 : $2 == "ms" ? 1e-3 : 1e-6) }'
}
