"""The summary table of bench/sensitivities/run.sh: for each key set and each target accuracy of
S, the fastest run of each route whose error reaches it, and the variational route's time against
the others'. Reads the rows `| keys | route | rtol | ms | error |` the bench prints."""
import sys

ROUTES = ("variational", "differences", "cvodes fixed-point", "cvodes newton")
TARGETS = (1e-4, 1e-6, 1e-8, 1e-10)


def main(path):
    runs = {}
    for line in open(path):
        keys, route, _rtol, ms, error = [c.strip() for c in line.strip().strip("|").split("|")]
        runs.setdefault(keys, []).append((route, float(ms), float(error)))
    print("| keys | error ≤ | variational ms | differences ms | CVODES fixed-point ms "
          "| CVODES Newton ms | variational ÷ differences | variational ÷ faster CVODES |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for keys, rows in runs.items():
        for target in TARGETS:
            best = {r: min((ms for route, ms, e in rows if route == r and e <= target),
                           default=None) for r in ROUTES}
            cells = [f"{best[r]:.2f}" if best[r] is not None else "not reached" for r in ROUTES]
            cvodes = [best[r] for r in ROUTES[2:] if best[r] is not None]
            peers = (best["differences"], min(cvodes) if cvodes else None)
            ratios = [f"{best['variational'] / p:.2f}"
                      if best["variational"] is not None and p is not None else "—"
                      for p in peers]
            print(f"| {keys} | {target:.0e} | " + " | ".join(cells + ratios) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
