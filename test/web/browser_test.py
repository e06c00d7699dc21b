#!/usr/bin/env python3
"""rangefitd's page in a real browser: headless Chromium, driven over WebDriver (chromium-driver),
loads the page from a rangefitd running on the simulated cell (loopback only), sends a bore
request through the form, sees the result appear with its picture, and checks that the 3D view
drew the cloud: a screenshot of the view has no cloud before and many non-background pixels
around its centre, where the view puts the fitted bore, after.

Exit 0 passed, 1 failed, 77 skipped (no chromium/chromedriver, or a build without the page)."""
import argparse
import base64
import fcntl
import json
import os
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
import zlib

TOKEN = "browser-test-token"
BACKGROUND = (0x18, 0x1A, 0x1F)  # the view's clear colour (web/src/view3d.js)
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync",
                  "--enable-unsafe-swiftshader",  # WebGL on the CPU (no GPU in CI)
                  "--window-size=1280,1000"]


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


_domain_lock = None  # open for the life of this process: the DDS domain reservation


def reserve_dds_domain():
    """A DDS domain id no other test process holds (the same lock files as the C++ tests)."""
    global _domain_lock
    first = int.from_bytes(os.urandom(2), "little") % 200
    for i in range(200):
        domain = 1 + (first + i) % 200
        lock = open(os.path.join(tempfile.gettempdir(), f"rangefit-dds-domain-{domain}.lock"), "a")
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            lock.close()
            continue
        _domain_lock = lock
        return domain
    return 1 + first


def http(method, url, body=None, timeout=60):
    data = None if body is None else json.dumps(body).encode()
    req = urllib.request.Request(url, data=data, method=method,
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:
            return r.status, json.loads(r.read() or b"null")
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read() or b"null")


def decode_png(data):
    """(width, height, rows of RGB tuples) of an 8-bit RGB/RGBA non-interlaced PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            assert depth == 8 and colour in (2, 6) and interlace == 0, "unexpected PNG format"
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    bpp = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(width)])
        prev = line
    return width, height, rows


def drawn_share(png, box=0.5):
    """Share of pixels in the central box (fraction of each side) that are not background."""
    w, h, rows = decode_png(png)
    x0, x1 = int(w * (1 - box) / 2), int(w * (1 + box) / 2)
    y0, y1 = int(h * (1 - box) / 2), int(h * (1 + box) / 2)
    drawn = total = 0
    for y in range(y0, y1, 2):
        for x in range(x0, x1, 2):
            total += 1
            drawn += sum(abs(p - q) for p, q in zip(rows[y][x], BACKGROUND)) > 30
    return drawn / max(1, total)


class WebDriver:
    ELEMENT = "element-6066-11e4-a52e-4f735466cecf"

    def __init__(self, port, profile):
        self.base = f"http://127.0.0.1:{port}"
        caps = {"capabilities": {"alwaysMatch": {"browserName": "chrome", "goog:chromeOptions": {
            "binary": "/usr/bin/chromium",
            "args": CHROMIUM_FLAGS + [f"--user-data-dir={profile}"]}}}}
        code, r = http("POST", self.base + "/session", caps, timeout=120)
        assert code == 200, f"no WebDriver session: {r}"
        self.session = f"{self.base}/session/{r['value']['sessionId']}"

    def call(self, method, path, body=None):
        code, r = http(method, self.session + path, body)
        assert code == 200, f"WebDriver {path}: {r}"
        return r["value"]

    def js(self, script, *args):
        return self.call("POST", "/execute/sync", {"script": script, "args": list(args)})

    def element(self, css):
        return self.call("POST", "/element", {"using": "css selector", "value": css})[self.ELEMENT]

    def type(self, css, text):
        e = self.element(css)
        self.call("POST", f"/element/{e}/clear", {})
        self.call("POST", f"/element/{e}/value", {"text": text})

    def screenshot(self, css):
        return base64.b64decode(self.call("GET", f"/element/{self.element(css)}/screenshot"))

    def quit(self):
        http("DELETE", self.session)


def wait(what, predicate, timeout):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.25)
    raise AssertionError(f"timed out waiting for {what}")


def config(tmp, source, http_port):
    scenes = os.path.join(source, "data", "scenes")
    return f"""[service]
bore_sensor = "css"
object_sensor = "stripe"
[http]
listen = "127.0.0.1:{http_port}"
token = "{TOKEN}"
[dds]
domain_id = {reserve_dds_domain()}
[spool]
directory = "{tmp}/spool"
[sim]
time_scale = 0
seed = 3
[[devices]]
name = "css"
kind = "css"
driver = "sim"
scene = "{scenes}/bore_plate.toml"
[[devices]]
name = "stripe"
kind = "stripe"
driver = "sim"
scene = "{scenes}/table_top_fig5_18.toml"
[[objects]]
name = "sphere"
scale_mm = [50, 50, 50]
shape = [1.0, 1.0]
"""


def run(args, tmp, procs):
    http_port, driver_port = free_port(), free_port()
    with open(os.path.join(tmp, "rangefitd.toml"), "w") as f:
        f.write(config(tmp, args.source, http_port))
    env = dict(os.environ, CYCLONEDDS_URI="file://" + os.path.join(
        args.source, "systemd", "cyclonedds-loopback.xml"))
    log = open(os.path.join(tmp, "rangefitd.log"), "w")
    daemon = subprocess.Popen([args.rangefitd, "--config", os.path.join(tmp, "rangefitd.toml")],
                              env=env, stderr=log)
    procs.append(daemon)
    page = f"http://127.0.0.1:{http_port}/"
    wait("rangefitd's HTTP interface", lambda: daemon.poll() is None and
         http_ok(page + "v1/state"), 30)
    driver = subprocess.Popen([shutil.which("chromedriver"), f"--port={driver_port}"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    procs.append(driver)
    wait("chromedriver", lambda: http_ok(f"http://127.0.0.1:{driver_port}/status"), 30)
    browser = WebDriver(driver_port, os.path.join(tmp, "profile"))
    try:
        browser.call("POST", "/url", {"url": page})
        wait("the page's first state", lambda: browser.js(
            "return document.getElementById('state').className.includes('idle')"), 30)
        webgl = browser.js("return !!document.createElement('canvas').getContext('webgl2')")
        assert webgl, "no WebGL in this Chromium"
        before = drawn_share(browser.screenshot("#view canvas"))
        assert before < 0.01, f"the view shows {before:.1%} drawn before any scan"
        browser.type("#token", TOKEN)  # the form's defaults: the 12 mm bore under the CSS
        browser.call("POST", f"/element/{browser.element('#send')}/click", {})
        status = wait("the result in the page", lambda: browser.js(
            "const s = document.getElementById('request-status').textContent;"
            "return /: (found|not found|\\w+:)/.test(s) && s"), 120)
        print("page says:", status)
        assert status.endswith(": found"), status
        shown = wait("the 3D view of the cloud", lambda: int(browser.js(
            "return document.getElementById('view').dataset.points")), 60)
        assert shown > 10000, f"only {shown} points in the view"
        wait("the result's picture", lambda: browser.js(
            "const i = document.querySelector('#results li img');"
            "return i && i.complete && i.naturalWidth > 500"), 30)
        result = json.loads(browser.js("return document.getElementById('last-result').textContent"))
        assert abs(result["bore_radius_mm"] - 6.0) < 0.1, result
        png = browser.screenshot("#view canvas")
        with open(os.path.join(args.keep or tmp, "view.png"), "wb") as f:
            f.write(png)
        after = drawn_share(png)
        print(f"view: {shown} points; drawn around the centre {before:.1%} before, {after:.1%} after")
        assert after > 0.2, f"the cloud covers only {after:.1%} of the view's centre"

        # Teach a model from the page: kind "learn" on the stripe cell; the page offers the
        # learnt model.toml, which reads as a model of one part.
        browser.js("const k = document.getElementById('kind'); k.value = 'learn';"
                   "k.dispatchEvent(new Event('change'));"
                   "const n = document.getElementById('learn-name'); n.value = 'taught';"
                   "for (const o of document.getElementById('learn-sensors').options)"
                   "  o.selected = o.value === 'stripe';")
        assert browser.js("return document.getElementById('send').textContent") == "Scan and learn"
        browser.call("POST", f"/element/{browser.element('#send')}/click", {})
        bore_status = status
        status = wait("the learnt model in the page", lambda: browser.js(
            "const s = document.getElementById('request-status').textContent;"
            "return s !== arguments[0] && /: (found|not found|\\w+:)/.test(s) && s", bore_status),
            180)
        print("page says:", status)
        assert status.endswith(": found"), status
        href = browser.js("const a = document.querySelector('#result-files a[download=\"model.toml\"]');"
                          "return a && a.href")
        assert href, "no link to the learnt model"
        with urllib.request.urlopen(href, timeout=10) as r:
            model = r.read().decode()
        assert 'name = "taught"' in model and model.count("[[part]]") == 1, model
        print("learnt model:", " ".join(line for line in model.splitlines()
                                        if line.startswith("size")))

        # Calibrate from the page: the CSS at one robot pose (the bore plate's scan pose) is
        # recorded, not yet calibrated (one of at least three poses), and the page offers the
        # recorded samples, the file `rangefit calibrate css` reads.
        browser.js("const k = document.getElementById('kind'); k.value = 'calibrate';"
                   "k.dispatchEvent(new Event('change'));"
                   "const t = document.getElementById('calibrate-target'); t.value = 'css';"
                   "t.dispatchEvent(new Event('change'));"
                   "document.getElementById('calibrate-robot-pose').value = '0, 0, 0, 0, 0, 0';")
        assert browser.js("return document.getElementById('send').textContent") == \
            "Scan and calibrate"
        assert browser.js("return document.getElementById('calibrate-cube').closest('label')"
                          ".hidden"), "the cube's fields show for the CSS"
        assert browser.js("return document.getElementById('calibrate-sensors').closest('label')"
                          ".hidden"), "the stripe cameras' choice shows for the CSS"
        # The page shows the learnt result before it has drawn its cloud; it takes the next
        # request once the button is back.
        wait("the page ready for the next request",
             lambda: browser.js("return !document.getElementById('send').disabled"), 60)
        browser.call("POST", f"/element/{browser.element('#send')}/click", {})
        learn_status = status
        status = wait("the recorded CSS pose in the page", lambda: browser.js(
            "const s = document.getElementById('request-status').textContent;"
            "return s !== arguments[0] && /: (found|not found|\\w+:)/.test(s) && s",
            learn_status), 180)
        print("page says:", status)
        assert ": not found: not calibrated: pose recorded; 1 of at least 3 robot poses" in status, \
            status
        href = browser.js("const a = document.querySelector("
                          "'#result-files a[download=\"css_sphere_scan.txt\"]');"
                          "return a && a.href")
        assert href, "no link to the recorded sphere scan"
        with urllib.request.urlopen(href, timeout=10) as r:
            scan = r.read().decode()
        lines = scan.splitlines()
        assert lines[0] == "rangefit-css-sphere-scans 1", lines[0]
        pose = [float(v) for v in lines[1].split()[1:]]
        assert lines[1].startswith("pose ") and max(map(abs, pose)) < 1e-12, lines[1]
        print("recorded CSS pose:", len(scan.splitlines()) - 2, "samples")
    finally:
        browser.quit()
    daemon.send_signal(signal.SIGTERM)
    assert daemon.wait(30) == 0, "rangefitd did not stop cleanly"


def http_ok(url):
    try:
        with urllib.request.urlopen(url, timeout=2) as r:
            return r.status == 200
    except OSError:
        return False


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rangefitd", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--page-built", default="1")
    p.add_argument("--keep", help="directory to keep the view's screenshot in")
    args = p.parse_args()
    if args.page_built != "1":
        print("skipped: this build has no page (npm was not available at configure time)")
        return 77
    if not os.path.exists("/usr/bin/chromium") or not shutil.which("chromedriver"):
        print("skipped: needs Debian's chromium and chromium-driver (scripts/deps.sh)")
        return 77
    procs = []
    tmp = tempfile.mkdtemp(prefix="rangefit_browser_")
    try:
        run(args, tmp, procs)
        print("passed")
        return 0
    except AssertionError as e:
        print("FAILED:", e)
        with open(os.path.join(tmp, "rangefitd.log")) as f:
            print(f.read()[-3000:])
        return 1
    finally:
        for proc in procs:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
