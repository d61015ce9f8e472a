#!/usr/bin/env python3
"""The documentation site in a real browser (headless Chromium).

    test_render.py --html BUILD/docs/html --chromium /usr/bin/chromium

Opens index.html, the Python API page and the C++ API page with JavaScript on, and checks, on the
DOM as Chromium built it: no console error and no file that failed to load (a missing stylesheet
or script); the index links every page of the site's tables of contents; the Python page holds an
entry for every public name of `rotgen` (Model, Scene, simulate, sweep, emit, the results, the
errors, __version__); the C++ page holds entries for the runtime's `rotgen::integrate` and
steppers and for the generated header's contract (params, prepare, rhs, jacobian, energy, ...).
Then a screenshot of the index is not blank. Exit status 0 when every check holds."""
import argparse
import html
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "view"))
from test_viewer import FLAGS, png_pixels  # noqa: E402  (the viewer test's Chromium set-up)

failures = []

# What each page must hold: (what, a regular expression over the DOM).
PAGES = {
    "index.html": [(f"a link to {p}.html", rf'href="{p}\.html"') for p in (
        "getting-started", "tour", "models", "scenes", "cli", "formats", "python", "cpp",
        "integrators", "performance", "sweeps", "limits", "physics", "contributing",
        "architecture", "design-notes")],
    "python.html": [(f"the entry rotgen.{n}", rf'id="rotgen\.{re.escape(n)}"') for n in (
        "Model", "Model.equations", "Model.inertia", "Scene", "Scene.with_", "simulate", "sweep",
        "emit", "SimulateResult", "SweepResult", "InputError", "RunError", "__version__")],
    # Sphinx's C++ ids: _CPPv4 then the mangled qualified name (N6rotgen9integrateE...).
    "cpp.html": [(f"the entry {n}", rf'id="_CPPv4[^"]*{m}') for n, m in (
        # integrate(system, method, t0, y, ...) of integrate.hpp (method.hpp's overloads take an
        # any_method<T>)
        ("rotgen::integrate(sys, const Method&, ...)", "N6rotgen9integrateE[^\"]*RK6Method"),
        ("rotgen::integrate(sys, const any_method<T>&, ...)", "N6rotgen9integrateE[^\"]*10any_method"),
        ("rotgen::dop853", "N6rotgen6dop853"),
        ("rotgen::rk4", "N6rotgen3rk4"),
        ("rotgen::taylor", "N6rotgen6taylor"),
        ("rotgen::event_set", "N6rotgen9event_set"),
        ("rotgen::generated_system", "N6rotgen16generated_system"),
        ("rotgen::models::heavy_top::params", "N6rotgen6models9heavy_top6params"),
        ("rotgen::models::heavy_top::prepare", "N6rotgen6models9heavy_top7prepare"),
        ("rotgen::models::heavy_top::rhs", "N6rotgen6models9heavy_top3rhs"),
        ("rotgen::models::heavy_top::jacobian", "N6rotgen6models9heavy_top8jacobian"),
        ("rotgen::models::heavy_top::energy", "N6rotgen6models9heavy_top6energy"),
        ("rotgen::models::heavy_top::state_size", "N6rotgen6models9heavy_top10state_size"))],
}


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        failures.append(what)


def chromium(browser, args, url, workdir):
    profile = tempfile.mkdtemp(dir=workdir)
    cmd = [browser, *FLAGS, f"--user-data-dir={profile}", *args, url]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120,
                       cwd=workdir)
    return r.stdout.decode(errors="replace"), r.stderr.decode(errors="replace")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--html", required=True)
    ap.add_argument("--chromium", required=True)
    a = ap.parse_args()
    root = os.path.abspath(a.html)
    work = tempfile.mkdtemp(prefix="rotgen-docs-")
    for page, wants in PAGES.items():
        path = os.path.join(root, page)
        if not os.path.isfile(path):
            check(False, f"{page} exists (build the site: cmake --build build --target docs)")
            continue
        dom, log = chromium(a.chromium, ["--dump-dom"], f"file://{path}", work)
        errors = [l for l in log.splitlines()
                  if "Uncaught" in l or ("CONSOLE" in l and "ERROR" in l) or "net::ERR" in l]
        check(not errors, f"{page}: no console error and nothing failed to load ({errors[:2]})")
        check("</body>" in dom and len(dom) > 1000, f"{page}: Chromium built its DOM")
        title = re.search(r"<title>(.*?)</title>", dom, re.S)
        check(bool(title) and "rotgen" in html.unescape(title.group(1)),
              f"{page}: the title names rotgen ({title.group(1).strip() if title else None!r})")
        for what, pattern in wants:
            check(re.search(pattern, dom) is not None, f"{page}: {what}")
    shot = os.path.join(work, "index.png")
    chromium(a.chromium, [f"--screenshot={shot}", "--window-size=1000,700"],
             f"file://{os.path.join(root, 'index.html')}", work)
    if os.path.exists(shot):
        width, height, bpp, rows = png_pixels(shot)
        background = rows[height // 2][:bpp]
        drawn = sum(1 for row in rows[height // 4: 3 * height // 4]
                    for x in range(0, width * bpp, bpp) if row[x:x + bpp] != background)
        share = drawn / (width * (3 * height // 4 - height // 4))
        check(share > 0.01, f"the index's screenshot is not blank ({share:.1%} of the middle drawn)")
    else:
        check(False, "Chromium wrote a screenshot of the index")
    print(f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
