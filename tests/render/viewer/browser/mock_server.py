#!/usr/bin/env python3
"""A stand-in for `render city.scene --serve PORT` (the API of viewer-api.md) with fake data.

Python 3 standard library only. It serves the viewer page from render/viewer/page/ and answers
the JSON API with a made-up grid city, so the page and its browser test can be developed
without the C++ server. Frames are PNGs drawn in pure Python whose picture follows the camera
(orbiting turns the skyline, looking down moves the horizon), the time of day (night is dark
with lit windows), the AOV and the boxes, so a test can see that a change of view changes it.

    python3 mock_server.py --port 8765 [--host 127.0.0.1] [--token HEX] [--out DIR]
"""

import argparse
import hashlib
import json
import math
import os
import pathlib
import resource
import shlex
import struct
import sys
import tempfile
import threading
import time
import zlib
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from urllib.parse import parse_qs, urlparse

HERE = pathlib.Path(__file__).resolve().parent
DEFAULT_PAGE_DIR = HERE.parents[3] / "render" / "viewer" / "page"

CLASSES = ["buildings", "roads", "joints", "sidewalks", "terrain", "land-cover", "trees", "paths", "lamps"]
ORIGIN = {"lat": 43.7384, "lon": 7.4246}
BOUNDS = {"min": [-600.0, -400.0], "max": [600.0, 400.0]}
LIMITS = {"max_width": 4096, "max_height": 4096}
DEFAULTS = {"width": 1280, "height": 720, "spp": 16, "time": "day", "seed": 1, "fov": 50, "max-depth": 8,
            "lamp-power": 6000, "lamp-kelvin": 4000, "lit-windows": 0.3, "shop-probability": 0.3, "fog": 0,
            "visibility": 20, "light-sampler": "tree"}
FIRST_VIEW = {"camera": [-260.0, -330.0, 140.0], "look_at": [0.0, 0.0, 0.0], "fov": 50}


class BadRequest(Exception):
    pass


# ---------------------------------------------------------------------------------------------
# The options the viewer accepts: a small copy of the CLI's parser (names, arity, ranges).

def _number(lo, hi, integer=False):
    def check(name, text):
        try:
            v = int(text) if integer else float(text)
        except ValueError:
            raise BadRequest(f"{name}: '{text}' is not a{'n integer' if integer else ' number'}")
        if not (lo <= v <= hi) or (not integer and not math.isfinite(v)):
            raise BadRequest(f"{name}: {text} not in [{lo} - {hi}]")
        return v
    return check


def _choice(*values):
    def check(name, text):
        if text not in values:
            raise BadRequest(f"{name}: '{text}' is not one of {', '.join(values)}")
        return text
    return check


def _point(name, text):
    parts = text.split(",")
    try:
        v = [float(p) for p in parts]
    except ValueError:
        v = []
    if len(v) != 3 or not all(math.isfinite(c) and abs(c) < 1e6 for c in v):
        raise BadRequest(f"{name}: expected X,Y,Z in metres, got '{text}'")
    return v


OPTIONS = {
    "--width": _number(1, LIMITS["max_width"], True),
    "--height": _number(1, LIMITS["max_height"], True),
    "--spp": _number(1, 1 << 20, True),
    "--seed": _number(0, 2**64 - 1, True),
    "--camera": _point,
    "--look-at": _point,
    "--fov": _number(1, 170),
    "--time": _choice("day", "sunset", "dusk", "night"),
    "--sun-elevation": _number(-90, 90),
    "--sun-azimuth": _number(-360, 360),
    "--exposure": _number(-20, 30),
    "--lamp-power": _number(0, 1e7),
    "--lamp-kelvin": _number(1667, 25000),
    "--lit-windows": _number(0, 1),
    "--fog": _number(0, 10),
    "--fog-height": _number(0, 10000),
    "--visibility": _number(0, 1000),
    "--light-sampler": _choice("tree", "power", "uniform"),
    "--max-depth": _number(0, 1000, True),
    "--rr-depth": _number(0, 1000, True),
    "--rr-prob": _number(0.01, 1),
    "--shop-probability": _number(0, 1),
    "--time-limit": _number(0, 1e9),
}
for _c in CLASSES:
    OPTIONS["--geometry-" + _c] = _choice("stored", "procedural")
FLAGS = {"--denoise", "--moon", "--procedural", "--no-gather-panes"}
FILE_OPTIONS = {"-o", "--output", "--camera-path", "--texture-dir", "--export-ply", "--export-gltf", "--aovs"}


def parse_args(args):
    """The args list of a /api/view or /api/save body -> dict of values (BadRequest if wrong)."""
    if not isinstance(args, list) or not all(isinstance(a, str) for a in args):
        raise BadRequest("args: expected a list of strings")
    out = {"--width": DEFAULTS["width"], "--height": DEFAULTS["height"], "--spp": DEFAULTS["spp"],
           "--time": "day", "--fov": 50.0}
    i = 0
    while i < len(args):
        name = args[i]
        value = None
        if "=" in name and name.startswith("--"):
            name, value = name.split("=", 1)
        if name in FILE_OPTIONS:
            raise BadRequest(f"{name}: not accepted by the viewer (no file paths)")
        if name in FLAGS:
            out[name] = True
            i += 1
            continue
        if name not in OPTIONS:
            raise BadRequest(f"{name}: unknown option" if name.startswith("-") else f"'{name}': unexpected argument")
        if value is None:
            if i + 1 >= len(args):
                raise BadRequest(f"{name}: needs a value")
            value = args[i + 1]
            i += 1
        out[name] = OPTIONS[name](name, value)
        i += 1
    if ("--camera" in out) != ("--look-at" in out):
        raise BadRequest("--camera and --look-at go together")
    if "--camera" not in out:
        out["--camera"], out["--look-at"] = FIRST_VIEW["camera"], FIRST_VIEW["look_at"]
    if math.dist(out["--camera"], out["--look-at"]) < 1e-6:
        raise BadRequest("--camera and --look-at coincide")
    return out


# ---------------------------------------------------------------------------------------------
# The fake city: a grid of blocks with buildings, streets between them and the sea to the south.

def _hash(*parts):
    return int.from_bytes(hashlib.blake2b(repr(parts).encode(), digest_size=8).digest(), "little")


def _h01(*parts):
    return (_hash(*parts) & 0xFFFFFF) / float(0x1000000)


def make_city():
    buildings, roads, water = [], [], []
    block, street = 70.0, 14.0
    x0, y0 = BOUNDS["min"]
    x1, y1 = BOUNDS["max"]
    shore = y0 + 90.0
    water.append([x0, y0, x1, y0, x1, shore - 10, 200.0, shore + 5, -250.0, shore - 5, x0, shore - 15])
    next_id = 100000
    y = shore + street
    while y + block <= y1:
        x = x0 + street
        while x + block <= x1:
            for k in range(4):  # four houses per block, of random size
                bx = x + (k % 2) * block / 2 + 3
                by = y + (k // 2) * block / 2 + 3
                w = block / 2 - 6 - 10 * _h01("w", next_id)
                d = block / 2 - 6 - 10 * _h01("d", next_id)
                buildings.append({"id": next_id, "poly": [bx, by, bx + w, by, bx + w, by + d, bx, by + d],
                                  "height": round(9 + 45 * _h01("h", next_id) ** 2, 1)})
                next_id += 7
            x += block + street
        y += block + street
    gx = x0 + street / 2
    while gx < x1:
        roads.append([gx, shore, gx, y1])
        gx += block + street
    gy = shore + street / 2
    while gy < y1:
        roads.append([x0, gy, x1, gy])
        gy += block + street
    return buildings, roads, water


BUILDINGS, ROADS, WATER = make_city()
BUILDING_BY_ID = {b["id"]: b for b in BUILDINGS}
ROAD_ID0 = 500000  # road k is way ROAD_ID0 + k


def rounded(poly):
    return [round(v, 1) for v in poly]


MAP_JSON = json.dumps({"bounds": BOUNDS, "buildings": [rounded(b["poly"]) for b in BUILDINGS],
                       "roads": [rounded(r) for r in ROADS], "water": [rounded(w) for w in WATER]}).encode()


# ---------------------------------------------------------------------------------------------
# The picture: a skyline of blocks of columns, worked out per column so it costs little.

SKIES = {  # top colour, horizon colour, light on walls, lamps and windows on
    "day": ((80, 135, 215), (185, 212, 240), 1.0, False),
    "sunset": ((55, 60, 120), (245, 150, 85), 0.65, False),
    "dusk": ((18, 22, 55), (85, 65, 105), 0.3, True),
    "night": ((4, 5, 12), (16, 18, 34), 0.1, True),
}
AUTO_EV = {"day": 15, "sunset": 12, "dusk": 9, "night": 3}


def kelvin_rgb(k):
    """A rough lamp colour for a colour temperature (orange sodium .. white LED)."""
    t = max(0.0, min(1.0, (k - 1800) / 4700))
    return (255, int(150 + 90 * t), int(60 + 180 * t))


class Layout:
    """Where the sky, the buildings and the ground are in a w x h frame of a view."""

    def __init__(self, view, w, h):
        cam, look = view["--camera"], view["--look-at"]
        dx, dy, dz = (look[i] - cam[i] for i in range(3))
        horiz = max(math.hypot(dx, dy), 1e-6)
        self.w, self.h = w, h
        self.yaw = math.atan2(dy, dx)
        self.pitch = math.atan2(dz, horiz)
        self.focal = (h / 2) / math.tan(math.radians(view["--fov"]) / 2)
        self.horizon = h / 2 + self.focal * math.tan(self.pitch)
        self.bw = max(2, round(16 * w / 1280))
        self.cols = []
        cam_z = max(cam[2], 0.5)
        reach = math.hypot(horiz, dz)
        for c in range((w + self.bw - 1) // self.bw):
            az = self.yaw - math.atan(((c + 0.5) * self.bw - w / 2) / self.focal)
            sector = math.floor(math.degrees(az) / 5.0)  # one building per 5 degrees of view
            key = _hash("b", sector, round(cam[0] / 40), round(cam[1] / 40))
            b = BUILDINGS[key % len(BUILDINGS)]
            dist = reach * (0.55 + 0.9 * _h01("dist", key))
            top = self._screen_y(math.atan2(b["height"] - cam_z, dist))
            base = self._screen_y(math.atan2(-cam_z, dist))
            self.cols.append((b, top, base, key))

    def _screen_y(self, elevation):
        a = max(-1.5, min(1.5, elevation - self.pitch))
        return self.h / 2 - self.focal * math.tan(a)

    def at(self, x, y):
        """'sky', 'building' or 'road' and the column's building at pixel (x, y)."""
        b, top, base, _ = self.cols[min(len(self.cols) - 1, max(0, int(x) // self.bw))]
        if top <= y < base:
            return "building", b
        if y < self.horizon:
            return "sky", None
        return "road", b


def render_png(view, w, h, spp, aov=None, boxes=()):
    lay = Layout(view, w, h)
    time_name = view["--time"]
    sky_top, sky_low, light, lit = SKIES[time_name]
    if "--sun-elevation" in view:
        el = view["--sun-elevation"]
        light = max(0.08, min(1.0, (el + 8) / 35))
        lit = el < 1
    gain = 1.0
    if "--exposure" in view:
        gain = 2 ** ((AUTO_EV[time_name] - view["--exposure"]) / 2)
    fog = min(0.8, view.get("--fog", 0) * 12)
    share = view.get("--lit-windows", DEFAULTS["lit-windows"])
    lamp = kelvin_rgb(view.get("--lamp-kelvin", DEFAULTS["lamp-kelvin"]))
    noise_amp = 48 / math.sqrt(max(spp, 1))

    def shade(rgb, mult=1.0):
        f = gain * mult
        return bytes(min(255, max(0, int((c * (1 - fog) + 150 * fog) * f))) for c in rgb)

    sky_rows = []
    for y in range(h):
        t = max(0.0, min(1.0, y / max(1.0, lay.horizon))) if lay.horizon > 0 else 1.0
        sky_rows.append(shade(tuple(a + (b - a) * t for a, b in zip(sky_top, sky_low))))
    ground_day = (95, 98, 104)
    wall_cache = {}

    def wall(b, key, floor):
        k = (b["id"], floor, aov)
        if k not in wall_cache:
            hue = _h01("hue", b["id"])
            base = (int(150 + 70 * hue), int(130 + 40 * hue), int(110 + 20 * (1 - hue)))
            if aov == "albedo":
                wall_cache[k] = bytes(base)
            elif aov == "normal":
                wall_cache[k] = bytes((int(128 + 120 * math.cos(hue * 6.28)), int(128 + 120 * math.sin(hue * 6.28)), 128))
            elif aov == "id":
                wall_cache[k] = bytes((_hash(b["id"]) >> s) & 255 for s in (0, 8, 16))
            elif aov == "depth":
                wall_cache[k] = bytes([int(255 * _h01("dist", key))] * 3)
            else:
                window = floor % 2 == 1 and lit and _h01("lit", b["id"], floor) < share * 1.5
                wall_cache[k] = bytes(lamp) if window else shade(base, light * (0.8 if floor % 2 else 1.0))
        return wall_cache[k]

    bw = lay.bw
    gap = max(1, bw // 6)
    rows = []
    for y in range(h):
        sky = sky_rows[y]
        ground = shade(ground_day, light * (0.7 + 0.3 * y / h)) if aov is None else bytes([40 + int(160 * y / h)] * 3)
        parts = []
        for c, (b, top, base, key) in enumerate(lay.cols):
            if top <= y < base:
                if "buildings" in boxes and (y - top < 2 or base - y <= 2):
                    px = b"\xff\x30\x30"
                else:
                    px = wall(b, key, int((y - top) // max(3, bw * 0.6)))
                edge = b"\x28\x28\x2c" if aov is None else px
                parts.append(px * (bw - gap) + edge * gap)
            elif y < lay.horizon:
                parts.append(sky * bw)
            elif "roads" in boxes and int(y) % 40 < 2:
                parts.append(b"\x30\xff\x30" * bw)
            else:
                parts.append(ground * bw)
        row = bytearray(b"".join(parts)[: 3 * w])
        if aov is None and noise_amp > 4:  # fewer samples: noisier, as a path tracer is
            n = int(noise_amp * (_h01("n", y, spp) - 0.5))
            if n:
                step = 3 * bw * 5
                for i in range(3 * ((y * 7) % (bw * 5)), len(row), step):
                    row[i] = max(0, min(255, row[i] + n))
        rows.append(bytes(row))
    return encode_png(w, h, rows)


def encode_png(w, h, rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 1)) + chunk(b"IEND", b""))


# ---------------------------------------------------------------------------------------------
# The server's state: the newest view and the newest frame, and a thread that renders.

class Viewer:
    def __init__(self, out_dir, delay):
        self.cond = threading.Condition()
        self.out_dir = pathlib.Path(out_dir)
        self.delay = delay
        self.view = parse_args([])
        self.args = []
        self.aov, self.boxes = None, ()
        self.moving = False
        self.generation = 0
        self.spp_done = 0
        self.rendered_generation = -1
        self.frame = None  # (seq, headers, body)
        self.seq = 0
        self.frames = 0
        self.saved = {}
        self.save_count = 0
        self.rays_per_second = 0.0
        threading.Thread(target=self._render_loop, daemon=True).start()

    def set_view(self, body):
        view = parse_args(body.get("args"))
        aov = body.get("aov")
        if aov in (None, "image"):
            aov = None
        elif aov not in ("albedo", "normal", "depth", "id"):
            raise BadRequest(f"aov: '{aov}' is not one of image, albedo, normal, depth, id")
        boxes = body.get("boxes") or []
        if not isinstance(boxes, list) or any(b not in ("buildings", "roads") for b in boxes):
            raise BadRequest("boxes: expected a list of 'buildings' and 'roads'")
        with self.cond:
            self.view, self.args, self.aov, self.boxes = view, list(body["args"]), aov, tuple(boxes)
            self.moving = bool(body.get("moving", False))
            self.generation += 1
            self.spp_done = 0
            self.cond.notify_all()
            return {"generation": self.generation, "command": command_line(self.args, "out.png")}

    def _render_loop(self):
        while True:
            with self.cond:
                while not self._has_work():
                    self.cond.wait()
                view, gen, moving, aov, boxes = self.view, self.generation, self.moving, self.aov, self.boxes
                w, h, target = view["--width"], view["--height"], view["--spp"]
                if moving:  # cheap low-resolution frames while the camera moves
                    s = min(1.0, max(240 / w, 135 / h, 0.25))
                    w, h, spp = max(1, round(w * s)), max(1, round(h * s)), 1
                else:  # passes at full size: 1, 2, 4, ... samples up to the target
                    spp = min(target, max(1, self.spp_done * 2))
            start = time.perf_counter()
            if self.delay:
                time.sleep(self.delay)
            body = render_png(view, w, h, spp, aov, boxes)
            render_ms = (time.perf_counter() - start) * 1000
            with self.cond:
                if gen != self.generation:
                    continue  # a newer view came in meanwhile: this frame is stale
                self.rendered_generation = gen
                self.spp_done = target if moving else spp
                self.seq += 1
                self.frames += 1
                self.rays_per_second = w * h * spp * 3 / max(render_ms / 1000, 1e-3)
                final = not moving and spp >= target
                headers = {"X-Frame-Seq": self.seq, "X-Frame-Generation": gen, "X-Frame-Spp": spp,
                           "X-Frame-Target-Spp": target, "X-Frame-Width": w, "X-Frame-Height": h,
                           "X-Frame-Render-Ms": f"{render_ms:.1f}", "X-Frame-Encode-Ms": "0.0",
                           "X-Frame-Rays-Per-Second": f"{self.rays_per_second:.0f}",
                           "X-Frame-Final": "1" if final else "0"}
                self.frame = (self.seq, headers, body)
                self.cond.notify_all()

    def _has_work(self):
        if self.rendered_generation != self.generation:
            return True
        return not self.moving and self.spp_done < self.view["--spp"]

    def wait_frame(self, after, timeout=1.0):
        deadline = time.monotonic() + timeout
        with self.cond:
            while self.frame is None or self.frame[0] <= after:
                left = deadline - time.monotonic()
                if left <= 0:
                    return None
                self.cond.wait(left)
            return self.frame

    def pick(self, x, y):
        with self.cond:
            view = self.view
        w, h = view["--width"], view["--height"]
        if not (0 <= x < w and 0 <= y < h):
            raise BadRequest(f"x, y: ({x}, {y}) is outside the {w}x{h} frame")
        kind, b = Layout(view, w, h).at(x, y)
        if kind == "sky":
            return {"kind": "sky"}
        if kind == "road":
            k = b["id"] % len(ROADS)
            rid = ROAD_ID0 + k
            return {"kind": "road", "osm": f"w{rid}", "osm_type": "way", "osm_id": rid, "index": k,
                    "fields": {"highway": "residential", "width": "7.0 m", "lanes": "2", "surface": "asphalt"}}
        levels = max(1, int(b["height"] / 3))
        return {"kind": "building", "osm": f"w{b['id']}", "osm_type": "way", "osm_id": b["id"],
                "index": BUILDINGS.index(b),
                "fields": {"height": f"{b['height']:.1f} m", "height_rule": "levels", "levels": str(levels),
                           "type": ["apartments", "office", "retail", "house"][b["id"] % 4],
                           "roof": "flat", "material": ["plaster", "brick", "concrete"][b["id"] % 3]}}

    def save(self, body):
        view = parse_args(body.get("args"))
        with self.cond:
            self.save_count += 1
            name = f"citygen-{self.save_count:04d}.png"
        data = render_png(view, view["--width"], view["--height"], view["--spp"])
        self.out_dir.mkdir(parents=True, exist_ok=True)
        (self.out_dir / name).write_bytes(data)
        with self.cond:
            self.saved[name] = self.out_dir / name
        return {"file": name, "command": command_line(body["args"], name)}


def command_line(args, output):
    return "render mock.scene " + " ".join(shlex.quote(a) for a in args) + " -o " + shlex.quote(output)


def goto(q):
    q = q.strip()
    if not q:
        raise BadRequest("q: empty")
    if q[0] in "nwr" and q[1:].isdigit():
        osm_id = int(q[1:])
        if q[0] == "w" and osm_id in BUILDING_BY_ID:
            p = BUILDING_BY_ID[osm_id]["poly"]
            xs, ys = p[0::2], p[1::2]
            cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
            return {"x": cx, "y": cy, "z": BUILDING_BY_ID[osm_id]["height"] / 2,
                    "radius": math.hypot(max(xs) - min(xs), max(ys) - min(ys)) / 2}
        if q[0] == "w" and 0 <= osm_id - ROAD_ID0 < len(ROADS):
            r = ROADS[osm_id - ROAD_ID0]
            return {"x": (r[0] + r[-2]) / 2, "y": (r[1] + r[-1]) / 2, "z": 0.0,
                    "radius": math.hypot(r[-2] - r[0], r[-1] - r[1]) / 2}
        if q[0] == "n" and osm_id < 10**6:  # nodes: somewhere in the city, a point
            x = BOUNDS["min"][0] + (osm_id * 37 % 1000) / 1000 * (BOUNDS["max"][0] - BOUNDS["min"][0])
            y = BOUNDS["min"][1] + (osm_id * 91 % 1000) / 1000 * (BOUNDS["max"][1] - BOUNDS["min"][1])
            return {"x": x, "y": y, "z": 0.0, "radius": 0.0}
        raise LookupError(f"{q}: no such object in the scene")
    try:
        lat, lon = (float(v) for v in q.split(","))
    except ValueError:
        raise BadRequest(f"q: '{q}' is neither lat,lon nor an OSM id like w123")
    x = (lon - ORIGIN["lon"]) * 111320.0 * math.cos(math.radians(ORIGIN["lat"]))
    y = (lat - ORIGIN["lat"]) * 110540.0
    if not (BOUNDS["min"][0] <= x <= BOUNDS["max"][0] and BOUNDS["min"][1] <= y <= BOUNDS["max"][1]):
        raise LookupError(f"{q}: outside the scene")
    return {"x": x, "y": y, "z": 0.0, "radius": 0.0}


def info():
    return {"scene": "mock.scene", "bounds": BOUNDS, "ground_z": 0, "origin": ORIGIN,
            "counts": {"buildings": len(BUILDINGS), "roads": len(ROADS), "water": len(WATER)},
            "view": FIRST_VIEW, "defaults": DEFAULTS, "classes": CLASSES, "limits": LIMITS}


# ---------------------------------------------------------------------------------------------
# HTTP

STATIC = {"/": ("index.html", "text/html; charset=utf-8"), "/viewer.js": ("viewer.js", "text/javascript"),
          "/viewer.css": ("viewer.css", "text/css")}


class Handler(BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"  # keep-alive: the page polls a lot
    server_version = "citygen-mock/1"

    def log_message(self, fmt, *args):
        if self.server.verbose:
            sys.stderr.write("%s %s\n" % (self.address_string(), fmt % args))

    def _send(self, status, body=b"", content_type="application/json", headers=None):
        self.send_response(status)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        for k, v in (headers or {}).items():
            self.send_header(k, str(v))
        self.end_headers()
        if self.command != "HEAD":
            self.wfile.write(body)

    def _json(self, status, obj):
        self._send(status, json.dumps(obj).encode())

    def _error(self, status, message):
        self._json(status, {"error": message})

    def _authorised(self, query):
        token = self.server.token
        if token and query.get("token", [""])[0] != token:
            self._error(403, "wrong or missing token")
            return False
        return True

    def _body(self):
        length = int(self.headers.get("Content-Length") or 0)
        if length > 1 << 20:
            raise BadRequest("body too large")
        try:
            body = json.loads(self.rfile.read(length) or b"{}")
        except ValueError as e:
            raise BadRequest(f"body: not JSON ({e})")
        if not isinstance(body, dict):
            raise BadRequest("body: expected a JSON object")
        return body

    def do_GET(self):
        self._dispatch("GET")

    def do_POST(self):
        self._dispatch("POST")

    def _dispatch(self, method):
        url = urlparse(self.path)
        query = parse_qs(url.query)
        if not self._authorised(query):
            return
        viewer = self.server.viewer
        try:
            if method == "GET" and url.path in STATIC:
                name, ctype = STATIC[url.path]
                path = self.server.page_dir / name
                if not path.is_file():
                    return self._error(404, f"{path} is missing")
                return self._send(200, path.read_bytes(), ctype)
            if not url.path.startswith("/api/"):
                return self._error(404, "not found")
            route = (method, url.path)
            if route == ("GET", "/api/info"):
                return self._json(200, info())
            if route == ("POST", "/api/view"):
                return self._json(200, viewer.set_view(self._body()))
            if route == ("GET", "/api/frame"):
                after = int(query.get("after", ["0"])[0])
                frame = viewer.wait_frame(after)
                if frame is None:
                    return self._send(204, b"", "text/plain")
                _, headers, body = frame
                return self._send(200, body, "image/png", headers)
            if route == ("GET", "/api/stats"):
                mem = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
                return self._json(200, {"memory_mb": round(mem, 1), "frames": viewer.frames,
                                        "rays_per_second": round(viewer.rays_per_second),
                                        "spp": viewer.spp_done})
            if route == ("GET", "/api/pick"):
                try:
                    x, y = int(float(query["x"][0])), int(float(query["y"][0]))
                except (KeyError, ValueError):
                    raise BadRequest("pick needs x and y pixel numbers")
                return self._json(200, viewer.pick(x, y))
            if route == ("GET", "/api/map"):
                return self._send(200, MAP_JSON)
            if route == ("GET", "/api/goto"):
                try:
                    return self._json(200, goto(query.get("q", [""])[0]))
                except LookupError as e:
                    return self._error(404, str(e))
            if route == ("POST", "/api/save"):
                return self._json(200, viewer.save(self._body()))
            if method == "GET" and url.path.startswith("/api/saved/"):
                name = url.path[len("/api/saved/"):]
                path = viewer.saved.get(name)
                if path is None:
                    return self._error(404, f"{name}: not a file this server saved")
                return self._send(200, path.read_bytes(), "image/png")
            return self._error(404 if method == "GET" else 405, f"{method} {url.path}: no such call")
        except BadRequest as e:
            self._error(400, str(e))
        except (BrokenPipeError, ConnectionResetError):
            pass


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--port", type=int, default=8765)
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--token", default="", help="require ?token=TOKEN on every request")
    ap.add_argument("--out", default="", help="folder for /api/save images (default: a temporary one)")
    ap.add_argument("--page-dir", default=str(DEFAULT_PAGE_DIR))
    ap.add_argument("--delay", type=float, default=0.0, help="extra seconds per frame (a slow renderer)")
    ap.add_argument("--verbose", action="store_true", help="log every request")
    a = ap.parse_args()
    out = a.out or tempfile.mkdtemp(prefix="citygen-mock-")
    server = ThreadingHTTPServer((a.host, a.port), Handler)
    server.daemon_threads = True
    server.viewer = Viewer(out, a.delay)
    server.token = a.token
    server.page_dir = pathlib.Path(a.page_dir)
    server.verbose = a.verbose
    print(f"mock viewer on http://{a.host}:{server.server_address[1]}/"
          + (f"?token={a.token}" if a.token else "") + f" (saves to {out})", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
