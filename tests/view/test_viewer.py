#!/usr/bin/env python3
"""The 3D viewer page in a real browser (headless Chromium, WebGL through SwiftShader).

    test_viewer.py --rotgen BUILD/rotgen --source SOURCE_DIR --chromium /usr/bin/chromium

Simulates a heavy top recording its attitude, writes the page with `rotgen view`, and checks:
the page makes no request to another host (no src/href/url()/import/fetch of one); Chromium loads
it without a console error; the attitude it reports at three times (two samples and a time between
samples) equals the CSV's (slerp between samples) to 1e-15, and so does what three.js drew there:
the world matrices of the body, its figure-axis arrow and the tip marker after the render, from
the scene graph (against R(q) computed here); a screenshot is not blank.
Exit status 0 when every check holds; each failure is printed."""
import argparse, json, math, os, re, struct, subprocess, sys, tempfile, zlib

FLAGS = ["--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-gpu-sandbox", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--disable-quic",
         "--host-resolver-rules=MAP * ~NOTFOUND", "--enable-logging=stderr", "--v=0"]

SCENE = """model: {model}
form: lagrangian
initial: {{phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}}
time: {{start: 0, end: 2, samples: 201}}
integrator: {{method: dop853, rtol: 1e-10, atol: 1e-12}}
record: [q0, q1, q2, q3, Lx, Ly, Lz, theta, energy]
"""

failures = []

def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        failures.append(what)

def chromium(args, browser, page, query, workdir, extra=()):
    profile = tempfile.mkdtemp(dir=workdir)
    cmd = [browser, *FLAGS, f"--user-data-dir={profile}", *extra, *args, f"file://{page}{query}"]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120, cwd=workdir)
    return r.stdout.decode(errors="replace"), r.stderr.decode(errors="replace")

def shown_state(dom):
    m = re.search(r'data-rotgen-view="([^"]*)"', dom)
    if not m:
        return None
    return json.loads(m.group(1).replace("&quot;", '"'))

def slerp(a, b, f):
    d = sum(x * y for x, y in zip(a, b))
    s = -1.0 if d < 0 else 1.0
    d = min(1.0, abs(d))
    w = math.acos(d)
    ka, kb = (1 - f, f) if w <= 1e-9 else (math.sin((1 - f) * w) / math.sin(w), math.sin(f * w) / math.sin(w))
    q = [ka * x + s * kb * y for x, y in zip(a, b)]
    n = math.sqrt(sum(v * v for v in q))
    return [v / n for v in q]

def expected_attitude(rows, t):
    for i in range(len(rows) - 1):
        t0, t1 = rows[i][0], rows[i + 1][0]
        if t0 <= t <= t1:
            f = (t - t0) / (t1 - t0)
            return slerp(rows[i][1:5], rows[i + 1][1:5], f) if f > 0 else rows[i][1:5]
    return rows[-1][1:5]

def rotation(q):
    """R(q), body to space, of the unit quaternion q = (w, x, y, z) (scalar first), row by row."""
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]

def drawn_checks(drawn, want, t):
    """What three.js drew (its scene graph's world matrices after the render) against R(q) of the
    CSV's attitude: the body's matrix, the tip of its figure-axis arrow (1.15 along body z) and
    the orange marker (on the unit sphere at the tip of body z)."""
    check(drawn is not None, f"t = {t}: the page reports what the scene graph drew")
    if drawn is None:
        return
    r = rotation(want)
    m = drawn["body"]  # column-major 4x4
    err = max(abs(m[4 * j + i] - r[i][j]) for i in range(3) for j in range(3))
    # observed 4.4e-16
    check(err <= 4e-15, f"t = {t}: the body is drawn at R(q) of the CSV ({err:.2e})")
    axis = [r[i][2] for i in range(3)]
    err = max(abs(p - 1.15 * a) for p, a in zip(drawn["axisTip"], axis))
    # observed 3.3e-16
    check(err <= 3e-15, f"t = {t}: the drawn figure axis ends at 1.15 R(q) e3 ({err:.2e})")
    err = max(abs(p - a) for p, a in zip(drawn["marker"], axis))
    # observed 5.6e-17
    check(err <= 1e-15, f"t = {t}: the tip marker is drawn at R(q) e3 ({err:.2e})")

def png_pixels(path):
    """(width, height, RGBA rows) of an 8-bit RGB(A) non-interlaced PNG, as Chromium writes."""
    data = open(path, "rb").read()
    pos, chunks = 8, {}
    width = height = 0
    idat = b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            chunks["bpp"] = {6: 4, 2: 3}[colour]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, bpp = zlib.decompress(idat), chunks["bpp"]
    stride, rows, prev = width * bpp, [], bytearray(width * bpp)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], prev[x - bpp] if x >= bpp else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, bpp, rows

def refused(rotgen, work, args, line, page):
    r = subprocess.run([os.path.abspath(rotgen), *args], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, cwd=work)
    err = r.stderr.decode()
    check(r.returncode == 2 and err == "rotgen: error: " + line + "\n" and not os.path.exists(page),
          f"refused with exit 2, one line, no page: {line!r} (got {r.returncode}, {err!r})")

def refusals(rotgen, work, scene, csv):
    """Bad input to the viewer: exit 2, one located line, no page written."""
    page = os.path.join(work, "bad.html")
    no_q = os.path.join(work, "no_q.csv")
    rows = [r for r in open(csv).read().splitlines() if not r.startswith("#")]  # provenance
    header = rows[0].split(",")
    keep = [i for i, c in enumerate(header) if c not in ("q0", "q1", "q2", "q3")]
    open(no_q, "w").write("\n".join(",".join(r.split(",")[i] for i in keep) for r in rows[:3]) + "\n")
    refused(rotgen, work, ["view", no_q, "--scene", scene, "-o", page],
            f"{no_q}:1:1: no attitude to show: the view needs the columns q0, q1, q2, q3 or phi, "
            "theta, psi (add them to the scene's record)", page)
    bad = os.path.join(work, "bad.csv")
    open(bad, "w").write("t,q0\n0,1\n0.5,x1\n")
    refused(rotgen, work, ["view", bad, "--scene", scene, "-o", page],
            f"{bad}:3:5: not a number: 'x1'", page)
    reduced = os.path.join(work, "reduced.yaml")
    open(reduced, "w").write(open(scene).read().replace("form: lagrangian", "form: reduced")
                             .replace("record: [q0, q1, q2, q3, Lx, Ly, Lz, theta, energy]",
                                      "record: [theta]"))
    refused(rotgen, work, ["simulate", reduced, "-o", os.path.join(work, "r.csv"), "--view", page],
            "--view: the view needs the attitude, which the reduced form does not keep (its "
            "ignored angles): use another form", page)
    check(not os.path.exists(os.path.join(work, "r.csv")), "simulate --view refused: no CSV")
    refused(rotgen, work, ["view", csv, "-o", page],
            "rotgen view: give the run's scene (--scene FILE) or its model (--model FILE)", page)

WHEELS = """model: {model}
form: body
initial: {{yaw: pi/3, pitch: -pi/6, roll: pi/4, omega1: 0, omega2: 0, omega3: 0}}
time: {{start: 0, end: 5, samples: 51}}
integrator: {{method: dop853, rtol: 1e-10, atol: 1e-12}}
record: [q0, q1, q2, q3, Lx, Ly, Lz]
"""

def wheel_checks(a, work):
    """A gyrostat's page (the reaction-wheel slew): a disc on each wheel's axis, drawn at 0.8 R(q) a
    with a = body x, y, z (models/reaction_wheels.yaml), and no L arrow (L is zero)."""
    scene = os.path.join(work, "wheels.yaml")
    open(scene, "w").write(WHEELS.format(model=os.path.join(a.source, "models",
                                                            "reaction_wheels.yaml")))
    csv, page = os.path.join(work, "wheels.csv"), os.path.join(work, "wheels.html")
    subprocess.run([a.rotgen, "simulate", scene, "-o", csv, "-q", "--view", page], check=True)
    rows = [[float(v) for v in line.split(",")] for line in open(csv).read().splitlines()[2:]]
    for t in (0.0, 2.5):
        dom, _ = chromium(["--dump-dom"], a.chromium, page, f"?t={t}", work)
        state = shown_state(dom)
        drawn = state.get("drawn") if state else None
        wheels = drawn.get("wheels") if drawn else None
        check(wheels is not None and len(wheels) == 3, f"t = {t}: three wheels drawn ({wheels})")
        if not wheels or len(wheels) != 3:
            continue
        r = rotation(expected_attitude(rows, t))
        err = max(abs(wheels[k][i] - 0.8 * r[i][k]) for k in range(3) for i in range(3))
        # observed 0 (exact: a unit axis, 0.8, the body's matrix)
        check(err <= 1e-15, f"t = {t}: each wheel's disc is drawn at 0.8 R(q) a ({err:.2e})")
        check('id="legend-wheels"' in dom and "(L in space is zero)" in dom,
              f"t = {t}: the legend names the wheel axes and says L is zero")

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rotgen", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--chromium", required=True)
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="rotgen-view-")
    scene = os.path.join(work, "scene.yaml")
    open(scene, "w").write(SCENE.format(model=os.path.join(a.source, "models", "heavy_top.yaml")))
    csv, page = os.path.join(work, "run.csv"), os.path.join(work, "run.html")
    subprocess.run([a.rotgen, "simulate", scene, "-o", csv, "-q"], check=True)
    subprocess.run([a.rotgen, "view", csv, "--scene", scene, "-o", page], check=True,
                   stdout=subprocess.DEVNULL)
    refusals(a.rotgen, work, scene, csv)
    rows = [[float(v) for v in line.split(",")] for line in open(csv).read().splitlines()[2:]]
    html = open(page).read()

    external = re.findall(r"""(?:\b(?:src|href)\s*=\s*["']?|url\(\s*["']?|\bimport\s*\(?\s*["']|"""
                          r"""\bfetch\(\s*["'])(?:https?:)?//[^"')\s]+""", html)
    check(not external, f"no request to another host in the page (found {external[:3]})")
    check(len(html) < 5e6, f"the page is {len(html)} bytes")

    for t in (0.0, 0.5, 1.2345):  # a sample, a sample, between samples
        dom, log = chromium(["--dump-dom"], a.chromium, page, f"?t={t}", work)
        errors = [l for l in log.splitlines() if "Uncaught" in l or ("CONSOLE" in l and "ERROR" in l)
                  or "net::ERR" in l]
        check(not errors, f"t = {t}: no console error ({errors[:2]})")
        state = shown_state(dom)
        check(state is not None, f"t = {t}: the page reports what it shows")
        if state is None:
            continue
        want = expected_attitude(rows, t)
        err = max(abs(x - y) for x, y in zip(state["quaternion"], want))
        # observed 1.1e-16
        check(err <= 1e-15, f"t = {t}: the attitude shown equals the CSV's (max error {err:.2e})")
        tip = state["tip"]
        w, x, y, z = want
        want_tip = [2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)]
        err = max(abs(p - q) for p, q in zip(tip, want_tip))
        # observed 5.6e-17
        check(err <= 1e-15, f"t = {t}: the figure axis's tip is the third column of R(q) ({err:.2e})")
        drawn_checks(state.get("drawn"), want, t)
        check(state.get("drawn", {}).get("wheels") == [] and 'id="legend-wheels"' not in dom,
              f"t = {t}: a body without wheels draws none")

    wheel_checks(a, work)

    shot = os.path.join(work, "shot.png")
    chromium([f"--screenshot={shot}", "--window-size=900,650"], a.chromium, page, "?t=1", work,
             extra=["--run-all-compositor-stages-before-draw", "--virtual-time-budget=3000"])
    if os.path.exists(shot):
        width, height, bpp, pixels = png_pixels(shot)
        # The middle of the picture, clear of the HTML panel and bar: WebGL's drawing alone.
        background = bytes([0xf4, 0xf4, 0xf2])
        middle = [row[i:i + 3] for row in pixels[height // 3:2 * height // 3]
                  for i in range(width // 3 * bpp, 2 * width // 3 * bpp, bpp)]
        share = sum(1 for p in middle if p != background) / len(middle)
        check(share > 0.05, f"the screenshot is not blank ({share:.0%} of the middle third is drawn)")
    else:
        check(False, "Chromium wrote a screenshot")
    return 1 if failures else 0

if __name__ == "__main__":
    sys.exit(main())
