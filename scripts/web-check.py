#!/usr/bin/env python3
"""`rope run --web` in a real browser.

Starts `rope run --web … --no-browser --duration inf --realtime`, loads the page in headless
Chromium (Debian's chromium-headless-shell, driven by Playwright; nothing downloads a
browser) with WebGL forced, and checks that the viewer says it streams from the run's gRPC
endpoint, that no page error and no "Rerun has crashed" appears, and that the canvas is not
blank; saves a screenshot; stops the run with SIGTERM.

    scripts/web-check.py [--screenshot PATH] [--seconds S]

Where the browser or Playwright is missing it says so and exits 0 as SKIPPED (CI installs
both: `apt-get install --no-install-recommends chromium-headless-shell`, `pip install
playwright`). Software rendering on 2 cores lags a live stream by many seconds, so it checks
that data arrived, not that the newest frame is on screen.
"""

import argparse
import pathlib
import shutil
import signal
import socket
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def skip(why: str) -> None:
    print(f"web-check: SKIPPED: {why}")
    sys.exit(0)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--screenshot", default=str(ROOT / "target" / "web-check.png"))
    parser.add_argument("--seconds", type=float, default=90.0, help="how long to wait for data")
    args = parser.parse_args()

    shell = shutil.which("chromium-headless-shell")
    if shell is None:
        skip("no chromium-headless-shell (apt-get install --no-install-recommends chromium-headless-shell)")
    real = pathlib.Path("/usr/lib/chromium/chromium-headless-shell")
    executable = str(real) if real.exists() else shell
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        skip("no Playwright (pip install playwright)")

    rope = ROOT / "target" / "release" / "rope"
    web, grpc = free_port(), free_port()
    run = subprocess.Popen(
        [str(rope), "run", "--web", f"127.0.0.1:{web}", "--serve-grpc", f"127.0.0.1:{grpc}",
         "--no-browser", "--duration", "inf", "--realtime"],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    page_url = None
    for line in run.stderr:
        if "watch it in a browser at" in line:
            page_url = line.split(" at ", 1)[1].strip()
            break
    if page_url is None:
        print("web-check: FAILED: rope printed no page address")
        return 1
    page_url += "&renderer=webgl"
    failures = []
    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path=executable,
            args=["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                  "--disable-background-networking", "--disable-component-update",
                  "--no-first-run", "--disable-sync"])
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        logs, errors = [], []
        page.on("console", lambda m: logs.append(m.text))
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(page_url)
        deadline = time.time() + args.seconds
        stream = f"port: {grpc}"

        def streaming(log: str) -> bool:
            return "Streaming messages from gRPC endpoint" in log and stream in log

        def data_arrived() -> bool:
            # The viewer migrates each record batch it decodes to its current schema.
            return any("record batch" in log for log in logs)

        while time.time() < deadline:
            if any(streaming(log) for log in logs) and data_arrived():
                break
            page.wait_for_timeout(500)
        page.wait_for_timeout(5000)
        shot = page.screenshot(path=args.screenshot)
        crashed = any(el.is_visible() for el in page.get_by_text("Rerun has crashed").all())
        browser.close()
    run.send_signal(signal.SIGTERM)
    try:
        code = run.wait(timeout=10)
    except subprocess.TimeoutExpired:
        run.kill()
        failures.append("rope did not stop within 10 s of SIGTERM")
        code = None
    if not any(streaming(log) for log in logs):
        failures.append(f"the page never said it streams from the gRPC endpoint ({stream})")
    if not data_arrived():
        failures.append("the page decoded no record batch: no data arrived")
    if errors:
        failures.append(f"page errors: {errors[:3]}")
    if crashed:
        failures.append("the page says Rerun has crashed")
    if len(shot) < 50_000:
        failures.append(f"the screenshot is {len(shot)} bytes: a blank canvas")
    console = pathlib.Path(args.screenshot).with_suffix(".console.txt")
    console.write_text("\n".join(log for log in logs if "naga" not in log))
    for log in [log for log in logs if streaming(log)][:1]:
        print(f"web-check: the page logged: {log.strip()[:200]}")
    print(f"web-check: screenshot {args.screenshot} ({len(shot)} bytes), rope exited {code}")
    for failure in failures:
        print(f"web-check: FAILED: {failure}")
    print(f"web-check: {0 if failures else 1} passed, {1 if failures else 0} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
