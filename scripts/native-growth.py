#!/usr/bin/env python3
"""Where a native viewer's resident memory grows, on a served run left running.

Runs what `scripts/native-soak.sh SECONDS both` runs (`rope run --duration inf --realtime
--serve-grpc`, and a headless `rerun` 0.36.3 joined to both of its endpoints), and besides
the viewer's resident memory it records where the memory went:

* every SAMPLE seconds, the resident size of each of the viewer's memory mappings
  (/proc/PID/smaps);
* throughout, the viewer's page faults (`perf record -e page-faults`, one in 64, with call
  stacks): which code touched pages for the first time, and at which address.

At the end it names the mapping that the renderer's staging buffers live in (the one most
faults under `wgpu_core::device::map_buffer` land in: on a software renderer, GPU buffers
are ordinary memory), writes SECONDS,viewer_mb,staging_mb,rest_mb to CSV, and prints the
code that faulted pages in after the first minute, grouped by the first Rerun function on
each stack.

    scripts/native-growth.py [SECONDS] [--csv PATH] [--port PORT] [--sample S]

Needs `perf` (Debian: linux-perf), `pip install rerun-sdk==0.36.3` and Vulkan
(apt-get install mesa-vulkan-drivers libvulkan1). Run as root or with
kernel.perf_event_paranoid ≤ 1.
"""

import argparse
import collections
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
PERIOD = 64  # page faults per perf sample
PAGE = os.sysconf("SC_PAGE_SIZE")  # bytes a page fault brings in


def smaps_rss(pid: int) -> dict:
    """(end address, resident kB) of each mapping, keyed by its start address (an arena may
    grow at its end)."""
    rss, start, end = {}, None, None
    with open(f"/proc/{pid}/smaps") as f:
        for line in f:
            head = re.match(r"^([0-9a-f]+)-([0-9a-f]+) ", line)
            if head:
                start, end = int(head.group(1), 16), int(head.group(2), 16)
            elif line.startswith("Rss:") and start is not None:
                rss[start] = (end, int(line.split()[1]))
    return rss


def vm_rss_mb(pid: int) -> float:
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1000
    return float("nan")


def owner(frames: list) -> str:
    """The first Rerun function on a stack (innermost first), else the innermost named one."""
    for frame in frames:
        name = re.sub(r"::h[0-9a-f]{16}$", "", frame)
        if name.startswith(("re_", "<re_")):
            while re.search(r"(?<=\w)<[^<>]*>", name):  # generic arguments, not <T as Trait>
                name = re.sub(r"(?<=\w)<[^<>]*>", "", name)
            return name[:110]
    return frames[0][:110] if frames else "?"


def faults(data: pathlib.Path):
    """(time, address, frames) of each perf sample."""
    out = subprocess.run(
        ["perf", "script", "-i", str(data), "-F", "time,addr,ip,sym"],
        capture_output=True, text=True, check=True,
    ).stdout
    for block in out.split("\n\n"):
        lines = block.strip("\n").splitlines()
        if not lines:
            continue
        head = lines[0].split()
        try:
            t, addr = float(head[0].rstrip(":")), int(head[1], 16)
        except (IndexError, ValueError):
            continue
        frames = [m.group(1) for m in (re.match(r"\s*[0-9a-f]+\s+(.*)$", l) for l in lines[1:]) if m]
        yield t, addr, frames


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("seconds", nargs="?", type=float, default=3600)
    ap.add_argument("--csv", default=str(ROOT / "assets/live-soak/native-growth.csv"))
    ap.add_argument("--port", type=int, default=9961)
    ap.add_argument("--sample", type=float, default=60)
    args = ap.parse_args()
    for tool in ("perf", "rerun"):
        if not shutil.which(tool):
            sys.exit(f"native-growth: {tool} is not installed (see the script's help)")
    rope_bin = ROOT / "target/release/rope"
    if not rope_bin.exists():
        sys.exit("native-growth: build first: cargo build --release")
    work = pathlib.Path(tempfile.mkdtemp(prefix="native-growth."))
    port, viewer_port = args.port, args.port + 9
    rope = subprocess.Popen(
        [str(rope_bin), "run", "--duration", "inf", "--realtime", "--serve-grpc", f"127.0.0.1:{port}"],
        stderr=open(work / "rope.txt", "w"),
    )
    time.sleep(3)
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    launcher = subprocess.Popen(
        ["rerun", "--headless", "--port", str(viewer_port),
         f"rerun+http://127.0.0.1:{port}/proxy", f"rerun+http://127.0.0.1:{port + 1}/proxy"],
        stdout=open(work / "viewer.txt", "w"), stderr=subprocess.STDOUT, env=env,
    )
    perf = None
    try:
        viewer = None
        for _ in range(100):  # the viewer itself, below pip's launcher
            found = subprocess.run(["pgrep", "-f", f"rerun_cli/rerun --headless --port {viewer_port}"],
                                   capture_output=True, text=True).stdout.split()
            if found:
                viewer = int(found[0])
                break
            time.sleep(0.1)
        if viewer is None:
            sys.exit("native-growth: the viewer did not start; see " + str(work / "viewer.txt"))
        data = work / "faults.data"
        perf = subprocess.Popen(
            ["perf", "record", "-q", "-e", "page-faults", "-c", str(PERIOD), "-d",
             "--call-graph", "dwarf,4096", "-p", str(viewer), "-o", str(data)],
            stdout=subprocess.DEVNULL, stderr=open(work / "perf.txt", "w"),
        )
        time.sleep(5)  # the viewer loads its fonts and shaders
        start = time.time()
        samples = []  # (seconds, viewer MB, {mapping: kB})
        while True:
            samples.append((time.time() - start, vm_rss_mb(viewer), smaps_rss(viewer)))
            print(f"native-growth: {samples[-1][0]:.0f} s, viewer {samples[-1][1]:.1f} MB", flush=True)
            if samples[-1][0] >= args.seconds:
                break
            time.sleep(min(args.sample, args.seconds - samples[-1][0]))
        perf.send_signal(signal.SIGINT)
        perf.wait(timeout=120)
    finally:
        for p in (perf, launcher, rope):
            if p and p.poll() is None:
                p.terminate()
        subprocess.run(["pkill", "-f", f"rerun --headless --port {viewer_port}"])

    if not data.exists() or data.stat().st_size == 0:
        sys.exit("native-growth: perf recorded nothing: " + (work / "perf.txt").read_text().strip()
                 + " (perf needs root or kernel.perf_event_paranoid <= 1)")
    all_faults = list(faults(data))
    t0 = all_faults[0][0] if all_faults else 0.0
    spans = {start: end for _, _, rss in samples for start, (end, _) in rss.items()}
    home = lambda addr: next((start for start, end in spans.items() if start <= addr < end), None)
    staging = collections.Counter(
        home(a) for _, a, fr in all_faults if any("wgpu_core::device::map_buffer" in f for f in fr))
    staging.pop(None, None)
    region = staging.most_common(1)[0][0] if staging else None
    stage = lambda sample: sample[2].get(region, (0, 0))[1] / 1000  # MB in the staging mapping
    with open(args.csv, "w") as f:
        f.write("seconds,viewer_mb,staging_mb,rest_mb\n")
        for sample in samples:
            s, mb = sample[0], sample[1]
            f.write(f"{s:.0f},{mb:.1f},{stage(sample):.1f},{mb - stage(sample):.1f}\n")
    first, last = samples[0], samples[-1]
    print(f"native-growth: {last[0]:.0f} s; viewer {first[1]:.1f} → {last[1]:.1f} MB; "
          f"the renderer's staging buffers {stage(first):.1f} → {stage(last):.1f} MB; "
          f"the rest {first[1] - stage(first):.1f} → {last[1] - stage(last):.1f} MB ({args.csv})")
    grown = collections.Counter()
    for t, a, fr in all_faults:
        if t - t0 >= 60:
            grown[owner(fr)] += PERIOD * PAGE / 1e6
    lost = re.findall(r"lost [^\n]*", (work / "perf.txt").read_text())
    print("native-growth: pages faulted in after the first minute, by the first Rerun function on the stack"
          + (f" (perf: {'; '.join(lost)})" if lost else "") + ":")
    for name, mb in grown.most_common(12):
        print(f"  {mb:8.1f} MB  {name}")
    shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
