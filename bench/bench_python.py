"""bench/bench_python.py — the overhead of a Python render call over the C call: median ms of
Renderer.render() (render + read into a new numpy array) against bench_render_call (the same two C
calls into a reused image), same scene, technique, size and parameters, 5 warm-up frames each, in
alternating rounds (the machine's load drifts). Not run by ctest.

usage: PYTHONPATH=build/python /usr/bin/python3 bench/bench_python.py [BUILD_DIR] [--frames N] [--rounds R]
Default: scenes/gl_area.json, technique local, shadow maps of 64 texels (a frame of a few ms, so the
per-call overhead is not lost in the frame), at 64x64 and 512x512."""
import argparse
import os
import statistics
import subprocess
import time

import sss

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PARAMS = {"shadow_size": 64, "shadow_cube_size": 64, "area_samples": 1}


def python_times(scene, technique, size, frames):
    with sss.Renderer(scene, technique=technique, params=PARAMS, width=size, height=size) as r:
        for _ in range(5):
            r.render()
        ms = []
        for _ in range(frames):
            t0 = time.perf_counter()
            r.render()
            ms.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(ms), min(ms)


def c_times(build, scene_path, technique, size, frames):
    out = subprocess.run([os.path.join(build, "bench", "bench_render_call"), scene_path, technique, str(size),
                          str(size), str(frames)] + ["%s=%g" % kv for kv in PARAMS.items()],
                         check=True, capture_output=True, text=True).stdout
    return float(out.split("median")[1].split()[0]), float(out.split(" min ")[1].split()[0])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "gl_area.json"))
    ap.add_argument("--technique", default="local")
    ap.add_argument("--frames", type=int, default=200)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args()
    scene = sss.Scene.load(args.scene)
    print("%s, %s, median of %d frames after 5 warm-up, %d alternating rounds" % (
        args.scene, args.technique, args.frames, args.rounds))
    for size in (64, 512):
        c, py = [], []
        for _ in range(args.rounds):
            c.append(c_times(args.build, args.scene, args.technique, size, args.frames))
            py.append(python_times(scene, args.technique, size, args.frames))
        # The median of the rounds' medians; and the fastest frame, which load disturbs least.
        c_ms, py_ms = statistics.median(m for m, _ in c), statistics.median(m for m, _ in py)
        c_min, py_min = min(m for _, m in c), min(m for _, m in py)
        print("%dx%d: median C %.3f ms, Python %.3f ms (%+.3f ms); fastest C %.3f ms, Python %.3f ms (%+.3f ms);"
              " round medians C %s, Python %s" % (
                  size, size, c_ms, py_ms, py_ms - c_ms, c_min, py_min, py_min - c_min,
                  " ".join("%.3f" % m for m, _ in c), " ".join("%.3f" % m for m, _ in py)))


if __name__ == "__main__":
    main()
