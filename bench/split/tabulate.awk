# Tables of bench/split/split_bench's runs (columns: body spin method knob steps error seconds).
# The cost of a method at an error target: the time of its cheapest run from which every finer
# run (tighter rtol) also meets the target.
NR == 1 { next }
{
  key = $1 SUBSEP $2 SUBSEP $3
  n = ++count[key]
  err[key, n] = $6; sec[key, n] = $7; knob[key, n] = $4
  if (!($1 in seen_body)) { seen_body[$1] = 1; bodies[++nb] = $1 }
  if (!(($1, $2) in seen_spin)) { seen_spin[$1, $2] = 1; spins[$1, ++ns[$1]] = $2 }
}
# index of the cheapest run from which every later run meets target; 0 if none
function meets(key, target,   i, n, first) {
  n = count[key]; first = 0
  for (i = n; i >= 1; i--) { if (err[key, i] <= target) first = i; else break }
  return first
}
function ms(s) { return sprintf("%.3g", s * 1e3) }
END {
  split("split2 split4 split6", sm, " ")
  for (b = 1; b <= nb; b++) {
    body = bodies[b]
    printf "## %s body\n\n", body
    print "| spin (rad/s) | DOP853 at 1e-6: ms (rtol) | best split at 1e-6: ms (method, rtol) | ratio | DOP853 at 1e-9: ms (rtol) | best split at 1e-9: ms (method, rtol) | ratio |"
    print "|---|---|---|---|---|---|---|"
    for (s = 1; s <= ns[body]; s++) {
      spin = spins[body, s]
      line = "| " spin
      for (t = 1; t <= 2; t++) {
        target = t == 1 ? 1e-6 : 1e-9
        dk = body SUBSEP spin SUBSEP "dop853"; di = meets(dk, target)
        best = -1; bm = ""
        for (m = 1; m <= 3; m++) {
          k = body SUBSEP spin SUBSEP sm[m]; i = meets(k, target)
          if (i > 0 && (best < 0 || sec[k, i] < best)) { best = sec[k, i]; bm = sm[m] ", " knob[k, i] }
        }
        line = line " | " (di ? ms(sec[dk, di]) " (" knob[dk, di] ")" : "-")
        line = line " | " (best >= 0 ? ms(best) " (" bm ")" : "-")
        line = line " | " (di && best > 0 ? sprintf("%.3g", sec[dk, di] / best) : "-")
      }
      print line " |"
    }
    print ""
  }
  # DOP853's error / rtol by spin (the same rtol on the body form errs more at faster spin)
  print "## DOP853's error / rtol on the body form, by spin (rtol 1e-5 .. 1e-11)"
  print ""
  print "| body | spin (rad/s) | smallest | largest |"
  print "|---|---|---|---|"
  for (b = 1; b <= nb; b++)
    for (s = 1; s <= ns[bodies[b]]; s++) {
      dk = bodies[b] SUBSEP spins[bodies[b], s] SUBSEP "dop853"; lo = -1; hi = -1
      for (i = 1; i <= count[dk]; i++)
        if (knob[dk, i] <= 1.0001e-5 && knob[dk, i] >= 0.9999e-11) {
          r = err[dk, i] / knob[dk, i]
          if (lo < 0 || r < lo) lo = r
          if (r > hi) hi = r
        }
      printf "| %s | %s | %.3g | %.3g |\n", bodies[b], spins[bodies[b], s], lo, hi
    }
  print ""
}
