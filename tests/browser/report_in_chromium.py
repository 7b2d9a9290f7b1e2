#!/usr/bin/env python3
"""The eval report in a real browser: Debian's chromium, headless, driven through chromedriver's
WebDriver HTTP API (standard library only, no network). Asserts that the page logs no console
errors, that the viewer's controls change the displayed image, that its error views open at a
scale from the data (not the old fixed 0.5) where the error shows, that its play button and the
space key play and pause and that taking the frame slider stops playback, and that screenshots of
the plots, the viewer and the pictures have real content. Leaves report_screenshot.png in
--out."""
import argparse
import base64
import io
import json
import math
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
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
        try:
            self.session = self.call("POST", "/session",
                                     {"capabilities": {"alwaysMatch": caps}})["sessionId"]
        except BaseException:  # no session, no quit(): chromedriver would outlive the test
            self.proc.terminate()
            self.proc.wait(10)
            raise

    def call(self, method, path, body=None):
        data = json.dumps(body).encode() if body is not None else None
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=60) as r:
                return json.loads(r.read().decode())["value"]
        except urllib.error.HTTPError as e:  # chromedriver says why in the body
            fail("%s %s: %s %s" % (method, path, e.code, e.read().decode()[:500]))

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

    def drag(self, css, dx):
        """Presses the mouse at the element's centre, moves it dx pixels and releases it."""
        x, y = self.run("const r = document.querySelector(arguments[0]);"
                        "r.scrollIntoView({block: 'center'});"
                        "const b = r.getBoundingClientRect();"
                        "return [Math.round(b.left + b.width / 2),"
                        " Math.round(b.top + b.height / 2)];", css)
        actions = [{"type": "pointerMove", "duration": 0, "origin": "viewport", "x": x, "y": y},
                   {"type": "pointerDown", "button": 0},
                   {"type": "pointerMove", "duration": 150, "origin": "viewport", "x": x + dx,
                    "y": y},
                   {"type": "pointerUp", "button": 0}]
        self.s("POST", "/actions", {"actions": [{"type": "pointer", "id": "mouse",
                                                 "parameters": {"pointerType": "mouse"},
                                                 "actions": actions}]})

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


# The share of the canvas near the top of the error colour map (magma's light end).
BRIGHT_SHARE = """
const c = document.getElementById('v-canvas');
const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
let n = 0;
for (let i = 0; i < d.length; i += 4) n += d[i] >= 250 && d[i + 1] >= 180;
return n / (d.length / 4);
"""


def waited(driver, what, condition, seconds=5):
    """Polls a script until it returns true."""
    for _ in range(int(seconds / 0.05)):
        if driver.run(condition):
            return
        time.sleep(0.05)
    fail(what)


def check_error_scale(driver):
    """The error views open at the data's scale: the best non-noisy method's 99th percentile."""
    abs_scale, state_scale, slider = driver.run(
        "const d = JSON.parse(document.getElementById('viewer-data').textContent);"
        "return [d.errorScale.abs, window.bmfrViewer.state.vmax.abs,"
        " +document.getElementById('v-vmax').value];")
    print("opening error scale: %.4f (slider %.1f)" % (abs_scale, slider))
    if abs(state_scale - abs_scale) > 1e-12:
        fail("the viewer opens at error scale %g, the data says %g" % (state_scale, abs_scale))
    if abs(abs_scale - 0.5) < 1e-9 or abs(slider + 0.3) < 1e-9:
        fail("the error scale is still the old fixed 0.5")
    if abs(slider - math.log10(abs_scale)) > 0.051:
        fail("the error scale slider shows %g for a scale of %g" % (slider, abs_scale))


def check_playback(driver):
    """Play advances the frame; space pauses and plays; taking the frame slider stops it."""
    viewer = "window.bmfrViewer.state"

    def frame():
        return driver.run("return %s.frame" % viewer)

    if driver.run("return document.getElementById('v-play') === null"):
        fail("the viewer has no play button")
    start = frame()
    driver.click("#v-play")
    waited(driver, "the play button did not advance the frame",
           "return %s.frame !== %d" % (viewer, start))
    if driver.run("return document.getElementById('v-play').textContent") != "pause":
        fail("the play button does not offer to pause while playing")
    driver.keys(" ")
    waited(driver, "space did not pause", "return !%s.playing" % viewer)
    paused = frame()
    time.sleep(0.4)
    if frame() != paused:
        fail("the frame still moves after space paused")
    driver.keys(" ")
    waited(driver, "space did not play again",
           "return %s.playing && %s.frame !== %d" % (viewer, viewer, paused))
    driver.drag("#v-frame", -30)
    waited(driver, "taking the frame slider did not stop playback", "return !%s.playing" % viewer)
    held = frame()
    time.sleep(0.4)
    if frame() != held or driver.run("return +document.getElementById('v-frame').value") != held:
        fail("the frame moves after the slider was dragged")
    print("play: advances, space pauses and plays, the frame slider stops it at frame %d" % held)


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
            changed("key f: flip to B (reference)", lambda: driver.keys("f"))
            check_error_scale(driver)
            changed("view select: absolute error", lambda: driver.click("#v-mode option[value=abs]"))
            if not driver.run("return getComputedStyle(document.getElementById('v-bar-box'))"
                              ".visibility === 'visible'"):
                fail("the error view shows no colour bar")
            # At the opening scale the best method's 99th percentile is full brightness: bmfr's
            # error shows (at the old fixed 0.5 it was all but black).
            bright = driver.run(BRIGHT_SHARE)
            print("absolute error of bmfr: %.2f%% of the canvas near full brightness"
                  % (100 * bright))
            if bright < 0.005:
                fail("the absolute error view opens nearly black")
            changed("A select: noisy", lambda: driver.click("#v-a option[value='1']"))
            changed("key e: relative error", lambda: driver.keys("e"))
            changed("key a: show A", lambda: driver.keys("a"))
            changed("exposure slider +0.5 EV", lambda: driver.keys("\ue014", "#v-ev"))
            changed("zoom button +", lambda: driver.click("#v-zoom-in"))
            changed("key s, click: slider compare", lambda: (driver.keys("s"), driver.click("#v-canvas")))
            check_playback(driver)
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
