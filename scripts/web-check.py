#!/usr/bin/env python3
"""`rope run --web` in a real browser.

Starts `rope run --web … --no-browser` with RUN_ARGS (by default two methods side by side,
`--method seed,chain --duration inf --realtime`: the seed scheme blows up after some tens of
seconds and the chain goes on), loads the page in headless
Chromium (Debian's chromium-headless-shell, driven by Playwright; nothing downloads a
browser) with WebGL forced, and checks that the viewer says it streams from the run's two
gRPC endpoints (the history's, and the live picture's one port above it), that no page error and no "Rerun has crashed" appears, and that the canvas is not
blank; saves a screenshot; stops the run with SIGTERM.

    scripts/web-check.py [--screenshot PATH] [--seconds S] [--run-args "ARGS"]
                         [--soak S [--soak-csv PATH] [--sample-every S]] [--shot-at T]

With --shot-at T (a finite run, its --duration in RUN_ARGS) the screenshot is taken near
time T: the script waits until the page has caught up with the run (its time panel
unchanged for 6 s), then clicks the time panel at T's share of its width, and takes the
picture there. The click is approximate (asked 10 of a 20-unit run, the cursor landed at
11.08: the panel pads its ends); the time readout in the picture says where it is. The
"then" rope shows that time; the live rope, the run's end. The scrub check is skipped.

With --soak S the page stays open S seconds more, and every --sample-every seconds (30) the
script records whether the page still answers, whether the time panel's strip changed since
the last sample (its time readout follows a live stream: still streaming), the browser's resident memory (all
its processes) and the page's JS heap, and rope's resident memory: the browser soaks of
docs/measurements.md.

Where the browser or Playwright is missing it says so and exits 0 as SKIPPED (CI installs
both: `apt-get install --no-install-recommends chromium-headless-shell`, `pip install
playwright`). Software rendering on 2 cores lags a live stream by many seconds, so it checks
that data arrived, not that the newest frame is on screen.
"""

import argparse
import hashlib
import os
import pathlib
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def free_pair() -> int:
    """A free port whose next port is free too: the history's endpoint and the live picture's."""
    for _ in range(100):
        port = free_port()
        try:
            with socket.socket() as s:
                s.bind(("127.0.0.1", port + 1))
            return port
        except OSError:
            continue
    raise RuntimeError("no two free ports in a row")


def skip(why: str) -> None:
    print(f"web-check: SKIPPED: {why}")
    sys.exit(0)


def resident_mb(pids) -> float:
    """The resident memory of processes `pids`, in MB (10⁶ bytes)."""
    total = 0
    for pid in pids:
        try:
            for line in pathlib.Path(f"/proc/{pid}/status").read_text().splitlines():
                if line.startswith("VmRSS:"):
                    total += int(line.split()[1]) * 1024
        except (FileNotFoundError, ProcessLookupError):
            pass
    return total / 1e6


def browser_pids(kind: str = ""):
    """The pids of every chromium-headless-shell process, or of those of one `--type=`."""
    pids = []
    for entry in pathlib.Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                cmdline = (entry / "cmdline").read_text()
                if "chromium-headless-shell" in cmdline and (not kind or f"--type={kind}" in cmdline):
                    pids.append(int(entry.name))
            except (FileNotFoundError, ProcessLookupError, PermissionError):
                pass
    return pids


# How many frames the page draws in one second: a viewer whose every frame costs more as its
# history grows draws fewer, and falls behind the stream once it draws too few.
FRAMES_IN_A_SECOND = """new Promise(done => {
    let frames = 0;
    const start = performance.now();
    const tick = now => { frames += 1; if (now - start < 1000) requestAnimationFrame(tick); else done(frames); };
    requestAnimationFrame(tick);
})"""


def simulated_time(said: list) -> str:
    """The time rope last said it had simulated to (its progress line, "rope: t = 754.5 of
    inf", every 30 s or so), or "" before the first."""
    for line in reversed(said):
        if line.startswith("rope: t = "):
            return line.split()[3]
    return ""


def soak(page, rope_pid: int, said: list, seconds: float, every: float, csv: pathlib.Path) -> list:
    """Keeps the page open, sampling every `every` s; returns the failures seen."""
    rows = ["seconds,page_alive,picture_changed,browser_mb,js_heap_mb,rope_mb,page_fps,wasm_mb,renderer_mb,gpu_mb,rope_t"]
    failures = []
    started = time.time()
    last_picture = None
    sample = 0
    while time.time() - started < seconds:
        sample += 1  # on a grid of `every` seconds, whatever a sample itself takes
        page.wait_for_timeout(max(0.0, started + sample * every - time.time()) * 1000)
        try:
            # The time panel's strip (its time readout follows the live stream): a small
            # picture, cheap to take from a renderer that is busy drawing. A renderer that
            # cannot give one within 20 s has fallen behind: the sample says so, and goes on.
            height = page.viewport_size["height"]
            strip = page.screenshot(clip={"x": 0, "y": height - 160, "width": 640, "height": 40},
                                    timeout=20_000)
            picture = hashlib.sha256(strip).hexdigest()
        except Exception:  # a crashed or stalled renderer raises here; said below
            picture = None
        changed = int(picture is not None and picture != last_picture)
        last_picture = picture
        try:
            page.wait_for_function("true", timeout=20_000)  # the page's JS still runs
            heap = page.evaluate("performance.memory ? performance.memory.usedJSHeapSize : 0")
            fps = page.evaluate(FRAMES_IN_A_SECOND)
            # The viewer's own memory: its WebAssembly memory, which grows and never shrinks.
            wasm = page.evaluate("wasm_bindgen().then(w => w.memory.buffer.byteLength)")
            alive = True
        except Exception as err:  # a crashed renderer raises here
            heap, fps, wasm, alive = 0, 0, 0, False
            failures.append(f"the page stopped answering after {time.time() - started:.0f} s: {err}")
        rows.append(f"{time.time() - started:.0f},{int(alive)},{changed},"
                    f"{resident_mb(browser_pids()):.1f},{heap / 1e6:.1f},{resident_mb([rope_pid]):.1f},{fps},{wasm / 1e6:.1f},"
                    f"{resident_mb(browser_pids('renderer')):.1f},{resident_mb(browser_pids('gpu-process')):.1f},"
                    f"{simulated_time(said)}")
        print(f"web-check: soak {rows[-1]}", flush=True)
        csv.parent.mkdir(parents=True, exist_ok=True)
        csv.write_text("\n".join(rows) + "\n")  # kept as it goes: a crash leaves the samples
        if not alive:
            break
    tail = [int(row.split(",")[2]) for row in rows[-3:] if row[0].isdigit()]
    if len(tail) == 3 and not any(tail):
        failures.append("the page's picture did not change over its last 3 samples: no longer streaming")
    return failures


# Where the live layout puts things in a 1280×800 page: the live rope's view, the "then"
# rope's view, and the time bar (the time panel starts collapsed to it).
LIVE_VIEW = {"x": 10, "y": 60, "width": 450, "height": 580}
THEN_VIEW = {"x": 470, "y": 60, "width": 340, "height": 260}
TIME_BAR = (258, 1068, 785)


def scrub(page) -> list:
    """Scrubs back to early in the run: the "then" rope must change (the past one), and the
    live rope go on moving. Returns the failures seen."""
    def picture(clip):
        return hashlib.sha256(page.screenshot(clip=clip, timeout=30_000)).hexdigest()
    def then_after_click(fraction, before):
        """Clicks `fraction` along the time bar and waits up to 8 s for the "then" rope to
        change: a page still catching up may take seconds to draw the cursor's new time
        (software rendering). Returns the "then" view's picture."""
        left, right, y = TIME_BAR
        page.mouse.click(left + fraction * (right - left), y)
        for _ in range(4):
            page.wait_for_timeout(2000)
            after = picture(THEN_VIEW)
            if after != before:
                break
        return after
    failures = []
    try:
        then_before = picture(THEN_VIEW)
        # Early in the run; where the cursor already was there (the page plays the history
        # from its start) the kept shape can be the same one, so then half way along.
        for clicked in (0.1, 0.5):
            then_after = then_after_click(clicked, then_before)
            if then_after != then_before:
                break
        live = [picture(LIVE_VIEW)]
        for _ in range(3):
            page.wait_for_timeout(2000)
            live.append(picture(LIVE_VIEW))
        page.screenshot(path=str(ROOT / "target" / "web-check-scrubbed.png"), timeout=30_000)
    except Exception as err:
        return [f"scrubbing could not be checked: {str(err).splitlines()[0]}"]
    if then_before == then_after:
        failures.append("scrubbing back did not change the 'then' rope")
    if len(set(live)) < 2:
        failures.append("the live rope did not move while the time cursor was scrubbed back")
    print(f"web-check: scrubbed back: the 'then' rope changed (clicked {clicked:.0%} along the time bar), "
          f"the live rope moved in {len(set(live)) - 1} of 3 intervals")
    return failures


def caught_up(page, most_seconds: float = 180.0) -> bool:
    """Waits until the time panel stops changing (the page has drawn all it was sent)."""
    left, right, y = TIME_BAR
    strip = {"x": left, "y": y - 25, "width": right - left, "height": 50}
    last, still, deadline = None, 0, time.time() + most_seconds
    while time.time() < deadline:
        now = hashlib.sha256(page.screenshot(clip=strip, timeout=30_000)).hexdigest()
        still = still + 1 if now == last else 0
        if still >= 2:
            return True
        last = now
        page.wait_for_timeout(3000)
    return False


def shoot_at(page, at: float, duration: float, path: str) -> list:
    """Puts the time cursor at `at` of a run of `duration` and takes the screenshot there."""
    try:
        if not caught_up(page):
            return [f"the page did not catch up with the run within 180 s: no picture at t = {at}"]
        left, right, y = TIME_BAR
        page.mouse.click(left + (right - left) * min(max(at / duration, 0.0), 1.0), y)
        page.wait_for_timeout(4000)
        page.screenshot(path=path, timeout=60_000)
        print(f"web-check: the time cursor put at t = {at} of {duration}: {path}")
        return []
    except Exception as err:
        return [f"no picture at t = {at}: {str(err).splitlines()[0]}"]


def descendants(root: int):
    """The pids of every process below `root`."""
    parents = {}
    for entry in pathlib.Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
                parents[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
            except (FileNotFoundError, ProcessLookupError, IndexError, ValueError):
                pass
    found, frontier = [], [root]
    while frontier:
        parent = frontier.pop()
        children = [pid for pid, ppid in parents.items() if ppid == parent]
        found += children
        frontier += children
    return found


def stall(page, rope_pid: int, seconds: float, every: float, csv: pathlib.Path) -> list:
    """Stops every browser process for `seconds` (a page that reads nothing), sampling rope's
    resident memory every `every` s; resumes them and checks that the page answers and that
    its picture moves again. Returns the failures seen."""
    rows = ["seconds,stopped,rope_mb"]
    # This script's own browser only (another check may be running beside it).
    mine = set(descendants(os.getpid()))
    pids = [pid for pid in browser_pids() if pid in mine]
    for pid in pids:
        subprocess.run(["kill", "-STOP", str(pid)], check=False)
    started = time.time()
    while time.time() - started < seconds:
        rows.append(f"{time.time() - started:.0f},1,{resident_mb([rope_pid]):.1f}")
        print(f"web-check: stalled {rows[-1]}", flush=True)
        time.sleep(min(every, max(0.0, seconds - (time.time() - started))))
    for pid in pids:
        subprocess.run(["kill", "-CONT", str(pid)], check=False)
    failures = []
    shots = []
    for _ in range(6):  # a minute to catch up
        time.sleep(10)
        rows.append(f"{time.time() - started:.0f},0,{resident_mb([rope_pid]):.1f}")
        print(f"web-check: resumed {rows[-1]}", flush=True)
        try:
            shots.append(hashlib.sha256(page.screenshot(timeout=20_000)).hexdigest())
        except Exception as err:
            failures.append(f"the page did not answer after the stall: {str(err).splitlines()[0]}")
            break
    if len(set(shots)) < 2:
        failures.append("the page's picture did not move after the stall")
    csv.parent.mkdir(parents=True, exist_ok=True)
    csv.write_text("\n".join(rows) + "\n")
    return failures


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--screenshot", default=str(ROOT / "target" / "web-check.png"))
    parser.add_argument("--seconds", type=float, default=90.0, help="how long to wait for data")
    parser.add_argument("--soak", type=float, default=0.0, help="seconds to keep the page open")
    parser.add_argument("--soak-csv", default=str(ROOT / "target" / "web-soak.csv"))
    parser.add_argument("--sample-every", type=float, default=30.0, help="seconds between soak samples")
    parser.add_argument("--viewport", default="1280x800",
                        help="the page's size, WIDTHxHEIGHT (a smaller page draws faster in software)")
    parser.add_argument("--stall", type=float, default=0.0,
                        help="seconds to stop the browser (SIGSTOP) once data arrived, rope's memory sampled, then resume it")
    parser.add_argument("--shot-at", type=float, default=None,
                        help="take the screenshot near this time of a finite run (its --duration in --run-args), once the page caught up; approximate, see above")
    parser.add_argument("--pin", action="store_true",
                        help="run rope on the last CPU and the browser on the others, so that a soak's simulation "
                             "keeps its pace beside the software renderer (what it sends per time unit does not change)")
    parser.add_argument("--run-args", default="--method seed,chain --duration inf --realtime",
                        help="the arguments of `rope run` besides --web, --serve-grpc and --no-browser")
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
    cpus = sorted(os.sched_getaffinity(0))
    rope_cpu = cpus[-1] if args.pin and len(cpus) > 1 else None
    web, grpc = free_port(), free_pair()
    run = subprocess.Popen(
        [str(rope), "run", "--web", f"127.0.0.1:{web}", "--serve-grpc", f"127.0.0.1:{grpc}",
         "--no-browser", *args.run_args.split()],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        preexec_fn=(lambda: os.sched_setaffinity(0, {rope_cpu})) if rope_cpu is not None else None)
    if rope_cpu is not None:
        # The browser, launched from here, inherits the other CPUs.
        os.sched_setaffinity(0, set(os.sched_getaffinity(0)) - {rope_cpu})
    page_url = None
    for line in run.stderr:
        if "watch it in a browser at" in line:
            page_url = line.split(" at ", 1)[1].strip()
            break
    if page_url is None:
        print("web-check: FAILED: rope printed no page address")
        return 1
    # Keep reading what rope says (each run's summary in a loop): a full pipe would stall it.
    said: list = []
    threading.Thread(target=lambda: said.extend(run.stderr), daemon=True).start()
    page_url += "&renderer=webgl"
    failures: list = []
    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path=executable,
            args=["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                  "--disable-background-networking", "--disable-component-update",
                  "--no-first-run", "--disable-sync"])
        width, height = (int(x) for x in args.viewport.split("x"))
        page = browser.new_page(viewport={"width": width, "height": height})
        logs, errors = [], []
        page.on("console", lambda m: logs.append(m.text))
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(page_url)
        deadline = time.time() + args.seconds
        stream, live_stream = f"port: {grpc}", f"port: {grpc + 1}"

        def streaming(log: str, port: str = stream) -> bool:
            return "Streaming messages from gRPC endpoint" in log and port in log

        def data_arrived() -> bool:
            # The viewer migrates each record batch it decodes to its current schema.
            return any("record batch" in log for log in logs)

        while time.time() < deadline:
            if any(streaming(log) for log in logs) and data_arrived():
                break
            page.wait_for_timeout(500)
        page.wait_for_timeout(5000)
        if args.viewport == "1280x800" and args.soak == 0 and args.stall == 0 and args.shot_at is None:
            failures += scrub(page)
        if args.stall > 0:
            failures += stall(page, run.pid, args.stall, args.sample_every, pathlib.Path(args.soak_csv))
        if args.soak > 0:
            failures += soak(page, run.pid, said, args.soak, args.sample_every, pathlib.Path(args.soak_csv))
        if args.shot_at is not None:
            words = args.run_args.split()
            duration = float(words[words.index("--duration") + 1]) if "--duration" in words else 3.0
            failures += shoot_at(page, args.shot_at, duration, args.screenshot)
        try:
            # With --shot-at the picture at T is already saved; this one only checks the canvas.
            shot = page.screenshot(path=None if args.shot_at is not None else args.screenshot,
                                   timeout=60_000)
            crashed = any(el.is_visible() for el in page.get_by_text("Rerun has crashed").all())
        except Exception as err:  # a page that stopped answering cannot be drawn either
            shot, crashed = b"", False
            failures.append(f"no screenshot: {str(err).splitlines()[0]}")
        browser.close()
    run.send_signal(signal.SIGTERM)
    try:
        code = run.wait(timeout=10)
    except subprocess.TimeoutExpired:
        run.kill()
        failures.append("rope did not stop within 10 s of SIGTERM")
        code = None
    if not any(streaming(log) for log in logs):
        failures.append(f"the page never said it streams from the history's endpoint ({stream})")
    if not any(streaming(log, live_stream) for log in logs):
        failures.append(f"the page never said it streams from the live picture's endpoint ({live_stream})")
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
    # How far the run went: its summary's first line per method ("… steps to t = …").
    for line in [line for line in said if " steps to t = " in line]:
        print(f"web-check: rope said: {line.strip()[:200]}")
    for failure in failures:
        print(f"web-check: FAILED: {failure}")
    print(f"web-check: {0 if failures else 1} passed, {1 if failures else 0} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
