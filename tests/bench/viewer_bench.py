#!/usr/bin/env python3
"""Times a running `render --serve` viewer as the page drives it (run by viewer_bench.sh).

Moving: a new camera every 30 ms along an orbit, as a drag sends them, for --seconds; prints the
frames per second that arrived, their median size, and the median latency from sending a camera
to the first frame that shows it. Still: then one view with --spp 64, and the seconds until the
frames reach 16 and 64 samples per pixel.
Prints one line of key=value pairs. Python 3 standard library only.
"""
import argparse
import http.client
import json
import math
import statistics
import threading
import time


def post(conn, path, body):
    conn.request("POST", path, json.dumps(body), {"Content-Type": "application/json"})
    r = conn.getresponse()
    data = r.read()
    if r.status != 200:
        raise SystemExit(f"{path}: {r.status} {data[:200]!r}")
    return json.loads(data)


def get_frame(conn, after):
    conn.request("GET", f"/api/frame?after={after}")
    r = conn.getresponse()
    r.read()
    if r.status == 204:
        return None
    h = {k.lower(): v for k, v in r.getheaders()}
    return {"seq": int(h["x-frame-seq"]), "generation": int(h["x-frame-generation"]),
            "spp": int(h["x-frame-spp"]), "width": int(h["x-frame-width"]), "final": h["x-frame-final"] == "1"}


def view_args(info, angle, width, height, spp, extra):
    cam, look = info["view"]["camera"], info["view"]["look_at"]
    dx, dy = cam[0] - look[0], cam[1] - look[1]
    c, s = math.cos(angle), math.sin(angle)
    eye = [look[0] + c * dx - s * dy, look[1] + s * dx + c * dy, cam[2]]
    fmt = lambda v: ",".join(f"{x:.3f}" for x in v)
    return ["--camera", fmt(eye), "--look-at", fmt(look), "--width", str(width), "--height", str(height),
            "--spp", str(spp)] + extra


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--seconds", type=float, default=6)
    p.add_argument("--width", type=int, default=960)
    p.add_argument("--height", type=int, default=540)
    p.add_argument("--extra", default="", help="more render options, e.g. '--time night --procedural'")
    o = p.parse_args()
    extra = o.extra.split()
    sender = http.client.HTTPConnection("127.0.0.1", o.port, timeout=120)
    sender.request("GET", "/api/info")
    info = json.loads(sender.getresponse().read())

    # Moving: the receiver records each frame's arrival; the sender posts a camera every 30 ms.
    sent = {}  # generation -> time sent
    frames = []  # (time, generation, width)
    stop = threading.Event()

    def receive():
        conn = http.client.HTTPConnection("127.0.0.1", o.port, timeout=120)
        after = 0
        while not stop.is_set():
            f = get_frame(conn, after)
            if f:
                after = f["seq"]
                frames.append((time.monotonic(), f["generation"], f["width"]))

    # Warm up: the first moving frame sizes the following ones.
    post(sender, "/api/view", {"args": view_args(info, 0, o.width, o.height, 1, extra), "moving": True})
    time.sleep(1.0)
    receiver = threading.Thread(target=receive)
    receiver.start()
    start = time.monotonic()
    step = 0
    while time.monotonic() - start < o.seconds:
        step += 1
        answer = post(sender, "/api/view",
                      {"args": view_args(info, 0.01 * step, o.width, o.height, 1, extra), "moving": True})
        sent[answer["generation"]] = time.monotonic()
        time.sleep(0.03)
    end = time.monotonic()
    stop.set()
    receiver.join()
    first_generation = min(sent)
    moving = [f for f in frames if f[1] >= first_generation and start <= f[0] <= end]
    fps = len(moving) / (end - start)
    latencies = []
    for g, t in sent.items():
        shown = [f[0] for f in frames if f[1] >= g and f[0] >= t]
        if shown:
            latencies.append(shown[0] - t)
    widths = [f[2] for f in moving]

    # Still: the time to 16 and 64 spp.
    answer = post(sender, "/api/view", {"args": view_args(info, 0, o.width, o.height, 64, extra), "moving": False})
    generation, t0 = answer["generation"], time.monotonic()
    conn = http.client.HTTPConnection("127.0.0.1", o.port, timeout=120)
    after, t16, t64 = 0, None, None
    while t64 is None:
        f = get_frame(conn, after)
        if not f:
            continue
        after = f["seq"]
        if f["generation"] != generation:
            continue
        if f["spp"] >= 16 and t16 is None:
            t16 = time.monotonic() - t0
        if f["final"]:
            t64 = time.monotonic() - t0
    print(f"moving_fps={fps:.1f} moving_width={statistics.median(widths) if widths else 0:.0f} "
          f"latency_ms={1000 * statistics.median(latencies) if latencies else float('nan'):.0f} "
          f"still_16spp_s={t16:.1f} still_64spp_s={t64:.1f}")


if __name__ == "__main__":
    main()
