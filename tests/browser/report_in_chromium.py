#!/usr/bin/env python3
"""The eval report in a real browser: Debian's chromium, headless, driven through chromedriver's
WebDriver HTTP API (standard library only, no network). Asserts that the page logs no console
errors, that the viewer's controls change the displayed image, and that screenshots of the plots,
the viewer and the pictures have real content. Leaves report_screenshot.png in --out."""
import argparse
import base64
import io
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request

from PIL import Image

HEADLESS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            "--window-size=1400,1100"]


def fail(message):
    print("FAILED: " + message)
    sys.exit(1)


class Driver:
    def __init__(self, chromedriver, chromium, profile):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        self.proc = subprocess.Popen([chromedriver, "--port=%d" % self.port],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.base = "http://127.0.0.1:%d" % self.port
        for _ in range(100):
            try:
                self.call("GET", "/status")
                break
            except OSError:
                time.sleep(0.1)
        caps = {"browserName": "chrome",
                "goog:chromeOptions": {"binary": chromium,
                                       "args": HEADLESS + ["--user-data-dir=" + profile]},
                "goog:loggingPrefs": {"browser": "ALL"}}
        self.session = self.call("POST", "/session", {"capabilities": {"alwaysMatch": caps}})["sessionId"]

    def call(self, method, path, body=None):
        data = json.dumps(body).encode() if body is not None else None
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        with urllib.request.urlopen(req, timeout=60) as r:
            return json.loads(r.read().decode())["value"]

    def s(self, method, path, body=None):
        return self.call(method, "/session/" + self.session + path, body)

    def run(self, script, *args):
        return self.s("POST", "/execute/sync", {"script": script, "args": list(args)})

    def element(self, css):
        found = self.s("POST", "/element", {"using": "css selector", "value": css})
        return next(iter(found.values()))

    def click(self, css):
        self.s("POST", "/element/%s/click" % self.element(css), {})

    def keys(self, text, css=None):
        if css:
            self.s("POST", "/element/%s/value" % self.element(css), {"text": text})
        else:
            actions = [{"type": "keyDown", "value": text}, {"type": "keyUp", "value": text}]
            self.s("POST", "/actions", {"actions": [{"type": "key", "id": "kb", "actions": actions}]})

    def shot(self, css=None):
        path = "/element/%s/screenshot" % self.element(css) if css else "/screenshot"
        return Image.open(io.BytesIO(base64.b64decode(self.s("GET", path)))).convert("RGB")

    def quit(self):
        try:
            self.s("DELETE", "")
        finally:
            self.proc.terminate()
            self.proc.wait(10)


CANVAS_HASH = """
const c = document.getElementById('v-canvas');
const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
let h = 2166136261;
for (let i = 0; i < d.length; i += 1) h = Math.imul(h ^ d[i], 16777619);
return [c.width, c.height, h >>> 0].join(':');
"""


def settled(driver, before_draws):
    """Waits until the viewer has drawn again after a control changed."""
    for _ in range(200):
        draws = driver.run("return window.bmfrViewer ? window.bmfrViewer.draws : -1")
        if draws > before_draws:
            time.sleep(0.05)
            if driver.run("return window.bmfrViewer.draws") == draws:
                return
        time.sleep(0.05)
    fail("the viewer did not redraw after a control changed")


def content(img, what):
    """Non-trivial content: many colours, neither blank nor flat."""
    small = img.resize((max(1, img.width // 2), max(1, img.height // 2)))
    colours = len(set(small.getdata()))
    pixels = list(small.getdata())
    ink = sum(1 for p in pixels if sum(p) < 600) / len(pixels)
    print("%s: %dx%d, %d colours, %.0f%% non-white" % (what, img.width, img.height, colours, 100 * ink))
    if colours < 40 or not 0.01 < ink < 0.995:
        fail(what + " looks empty")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bmfr", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    chromedriver = shutil.which("chromedriver") or "/usr/bin/chromedriver"
    for exe in (chromium, chromedriver):
        if not os.access(exe, os.X_OK):
            fail(exe + " is missing: scripts/install-deps.sh --tests installs chromium and "
                 "chromium-driver")
    os.makedirs(a.out, exist_ok=True)
    work = tempfile.mkdtemp(prefix="bmfr_browser_")
    try:
        seq, den, svgf, rep = (os.path.join(work, n) for n in ("seq", "den", "svgf", "report"))
        for cmd in (["synth", "-o", seq, "--width", "96", "--height", "64", "--frames", "5", "-q"],
                    ["denoise", seq, "-o", den, "-q", "--no-png"],
                    ["denoise", seq, "-o", svgf, "--filter", "svgf", "-q", "--no-png"],
                    ["eval", "-r", seq, "-m", "noisy", "-m", "bmfr=" + den, "-m",
                     "svgf <i>escaped</i>=" + svgf, "-o", rep, "-q"]):
            subprocess.run([a.bmfr] + cmd, check=True)
        driver = Driver(chromedriver, chromium, os.path.join(work, "profile"))
        try:
            driver.s("POST", "/url", {"url": "file://" + os.path.join(rep, "report.html")})
            settled(driver, 0)
            hashes = [driver.run(CANVAS_HASH)]

            def changed(what, action):
                draws = driver.run("return window.bmfrViewer.draws")
                action()
                settled(driver, draws)
                h = driver.run(CANVAS_HASH)
                print("%-34s %s" % (what, h))
                if h == hashes[-1]:
                    fail(what + " did not change the displayed image")
                hashes.append(h)

            print("%-34s %s" % ("loaded (A = bmfr, frame 0)", hashes[0]))
            changed("right arrow: next frame", lambda: driver.keys("\ue014"))
            changed("space: flip to B (reference)", lambda: driver.keys(" "))
            changed("view select: absolute error", lambda: driver.click("#v-mode option[value=abs]"))
            if not driver.run("return getComputedStyle(document.getElementById('v-bar-box'))"
                              ".visibility === 'visible'"):
                fail("the error view shows no colour bar")
            changed("A select: noisy", lambda: driver.click("#v-a option[value='1']"))
            changed("key e: relative error", lambda: driver.keys("e"))
            changed("key a: show A", lambda: driver.keys("a"))
            changed("exposure slider +0.5 EV", lambda: driver.keys("\ue014", "#v-ev"))
            changed("zoom button +", lambda: driver.click("#v-zoom-in"))
            changed("key s, click: slider compare", lambda: (driver.keys("s"), driver.click("#v-canvas")))
            title = driver.run("return document.title")
            if title != "bmfr eval":
                fail("title is " + repr(title))
            if driver.run("return document.body.innerHTML.indexOf('<i>escaped</i>')") != -1:
                fail("a method name reached the page as markup")

            full = driver.shot()
            full.save(os.path.join(a.out, "report_screenshot.png"))
            content(driver.shot(".plots"), "plots")
            content(driver.shot("#v-box"), "viewer")
            content(driver.shot(".pictures"), "pictures")
            errors = [e for e in driver.s("POST", "/se/log", {"type": "browser"})
                      if e.get("level") == "SEVERE"]
            if errors:
                fail("console errors: " + json.dumps(errors))
            print("console: no errors")
        finally:
            driver.quit()
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("report in chromium passed")


if __name__ == "__main__":
    main()
