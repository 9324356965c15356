// citygen viewer page: shows the frames of `render city.scene --serve PORT` and steers its view.
// Plain JavaScript, no libraries. The HTTP API is described in viewer-api.md.
"use strict";

(function () {
  const $ = (id) => document.getElementById(id);
  const canvas = $("view");
  const ctx = canvas.getContext("2d");
  const token = new URLSearchParams(location.search).get("token") || "";

  // Built-in defaults of the CLI (main.cpp); /api/info `defaults` overrides them where given.
  const CLI_DEFAULTS = {
    width: 1280, height: 720, spp: 16, seed: 1, fov: 50, time: "day", "max-depth": 8,
    "lamp-power": 6000, "lamp-kelvin": 4000, "lit-windows": 0.3, "shop-probability": 0.3,
    fog: 0, visibility: 20, "light-sampler": "tree",
  };

  // The panel's render options. `key` is the CLI option without "--"; `auto` adds a checkbox
  // that, when ticked, leaves the option out (the renderer then picks it, e.g. from --time).
  const CONTROLS = [
    { sec: "view", key: "scale", label: "Resolution", kind: "select", values: ["1", "0.75", "0.5"],
      names: ["full", "3/4", "1/2"], def: "1", local: true },
    { sec: "view", key: "fov", label: "Field of view °", kind: "range", min: 10, max: 120, step: 1, local: true },
    { sec: "view", key: "aov", label: "Show", kind: "select", values: ["image", "albedo", "normal", "depth", "id"],
      def: "image", local: true },
    { sec: "light", key: "time", label: "Time of day", kind: "select", values: ["day", "sunset", "dusk", "night"] },
    { sec: "light", key: "sun-elevation", label: "Sun elevation °", kind: "range", min: -20, max: 90, step: 1, def: 30, auto: true },
    { sec: "light", key: "sun-azimuth", label: "Sun azimuth °", kind: "range", min: 0, max: 360, step: 1, def: 180, auto: true },
    { sec: "light", key: "moon", label: "Full moon", kind: "flag" },
    { sec: "light", key: "exposure", label: "Exposure EV", kind: "range", min: -5, max: 20, step: 0.5, def: 12, auto: true },
    { sec: "light", key: "lamp-power", label: "Lamp power lm", kind: "range", min: 0, max: 30000, step: 250 },
    { sec: "light", key: "lamp-kelvin", label: "Lamp colour K", kind: "range", min: 1800, max: 6500, step: 100 },
    { sec: "light", key: "lit-windows", label: "Lit windows", kind: "range", min: 0, max: 1, step: 0.05 },
    { sec: "light", key: "shop-probability", label: "Shop fronts", kind: "range", min: 0, max: 1, step: 0.05 },
    { sec: "light", key: "fog", label: "Fog /m", kind: "range", min: 0, max: 0.1, step: 0.002 },
    { sec: "light", key: "visibility", label: "Visibility km", kind: "range", min: 0, max: 100, step: 1 },
    { sec: "render", key: "spp", label: "Samples target", kind: "number", min: 1, max: 1048576, always: true },
    { sec: "render", key: "max-depth", label: "Bounces", kind: "range", min: 0, max: 16, step: 1 },
    { sec: "render", key: "light-sampler", label: "Light sampler", kind: "select", values: ["tree", "power", "uniform"] },
    { sec: "render", key: "seed", label: "Seed", kind: "number", min: 0 },
    { sec: "render", key: "denoise", label: "Denoise", kind: "flag" },
  ];

  const state = {
    info: null,
    camera: [0, -300, 150], lookAt: [0, 0, 0], fov: 50,
    size: { width: 1280, height: 720 },  // the --width/--height last sent
    moving: false,
    generation: 0,       // of the newest /api/view answer
    command: "",         // of the newest /api/view answer
    lastBody: null,      // the newest /api/view body sent
    keyframes: [],
    error: "",
  };
  const citygen = {
    state, frames: 0, lastFrame: null, lastPick: null,
    setTime: (t) => { setControl("time", t); settingsChanged(true); },
    setView: (camera, lookAt, fov) => {
      state.camera = camera.slice();
      state.lookAt = lookAt.slice();
      if (fov) { state.fov = +fov; setControl("fov", state.fov); }
      viewChanged(false);
    },
    buildArgs: () => buildArgs(),
    pick: (x, y) => pick(x, y),
    cameraPathCsv: () => cameraPathCsv(),
    postView: (moving) => postView(!!moving),
  };
  window.citygen = citygen;

  // ---------------------------------------------------------------------------------- helpers
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const len = (a) => Math.hypot(a[0], a[1], a[2]);
  const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));
  const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
  // Short, locale-free numbers for the CLI: 3 decimals at most, no exponent, no "-0".
  const num = (v, digits = 3) => String(+(+v).toFixed(digits) || 0);
  const vec = (v) => v.map((c) => num(c)).join(",");
  const groundZ = () => (state.info && Number.isFinite(state.info.ground_z) ? state.info.ground_z : 0);

  // An API URL relative to the page, with the page's token (the server checks it on every call).
  function api(path, params = {}) {
    const u = new URL(path, location.href);
    for (const [k, v] of Object.entries(params)) u.searchParams.set(k, v);
    if (token) u.searchParams.set("token", token);
    return u.pathname + u.search;
  }

  async function readJson(response) {
    try { return await response.json(); } catch (e) { return { error: `HTTP ${response.status}` }; }
  }

  // One visible error line; `source` lets a later success of the same kind clear it.
  let errorSource = "";
  function showError(message, source = "view") {
    state.error = message; errorSource = source;
    $("error").textContent = message;
    $("error").hidden = false;
  }
  function clearError(source) {
    if (errorSource !== source) return;
    state.error = ""; errorSource = "";
    $("error").hidden = true;
  }

  // ------------------------------------------------------------------------------- the panel
  function defaultOf(c) {
    const d = (state.info && state.info.defaults) || {};
    for (const k of [c.key, c.key.replace(/-/g, "_")]) if (d[k] !== undefined) return d[k];
    if (c.def !== undefined) return c.def;
    return CLI_DEFAULTS[c.key];
  }

  function buildControls() {
    for (const c of CONTROLS) {
      const row = document.createElement("div");
      row.className = "row";
      const id = "opt-" + c.key;
      const label = document.createElement("label");
      label.htmlFor = id;
      label.textContent = c.label;
      let input;
      if (c.kind === "select") {
        input = document.createElement("select");
        c.values.forEach((v, i) => input.add(new Option(c.names ? c.names[i] : v, v)));
      } else {
        input = document.createElement("input");
        input.type = { range: "range", number: "number", flag: "checkbox" }[c.kind];
        for (const k of ["min", "max", "step"]) if (c[k] !== undefined) input[k] = c[k];
      }
      input.id = id;
      row.append(label);
      const cell = document.createElement("span");
      cell.className = "inline";
      cell.append(input);
      if (c.kind === "range") {  // the number beside a slider
        const out = document.createElement("output");
        out.id = id + "-value";
        cell.append(out);
        input.addEventListener("input", () => { out.textContent = input.value; });
      }
      if (c.auto) {  // "auto" = leave the option to the renderer
        const auto = document.createElement("label");
        auto.className = "auto";
        auto.innerHTML = `<input type="checkbox" id="${id}-auto" checked> auto`;
        cell.append(auto);
        auto.firstChild.addEventListener("change", () => { input.disabled = auto.firstChild.checked; settingsChanged(true); });
        input.disabled = true;
      }
      row.append(cell);
      $("sec-" + c.sec).append(row);
      input.addEventListener(c.kind === "range" || c.kind === "number" ? "input" : "change",
        () => onControl(c, input));
    }
  }

  function onControl(c, input) {
    if (c.key === "fov") { state.fov = +input.value; lastMoveAt = performance.now(); viewChanged(true); return; }
    if (c.key === "scale") updateSize();
    if (c.key === "spp" && !sppEdited) $("save-spp").value = sppTarget();
    settingsChanged(c.kind === "select" || c.kind === "flag");
  }

  function setControl(key, value) {
    const input = $("opt-" + key);
    if (input.type === "checkbox") input.checked = !!value; else input.value = value;
    const out = $("opt-" + key + "-value");
    if (out) out.textContent = input.value;
  }

  // Geometry modes: one select per class the scene has.
  function buildGeometryControls(classes) {
    const sec = $("sec-geometry");
    sec.textContent = "";
    for (const name of classes) {
      const row = document.createElement("div");
      row.className = "row";
      row.innerHTML = `<label for="opt-geometry-${name}">${name}</label>`;
      const sel = document.createElement("select");
      sel.id = "opt-geometry-" + name;
      ["stored", "procedural"].forEach((v) => sel.add(new Option(v, v)));
      sel.value = defaultOf({ key: "geometry-" + name, def: "stored" });
      sel.addEventListener("change", () => settingsChanged(true));
      row.append(sel);
      sec.append(row);
    }
  }

  function applyDefaults() {
    for (const c of CONTROLS) {
      if (c.kind === "flag") { setControl(c.key, !!defaultOf(c)); continue; }
      const d = c.key === "fov" ? state.fov : defaultOf(c);
      if (d !== undefined) setControl(c.key, d);
    }
  }

  // The CLI options of the current view and panel. Always the view, size and spp; the rest
  // only where they differ from the defaults, so the copied command stays short.
  function buildArgs(size = state.size, spp = sppTarget()) {
    const args = ["--camera", vec(state.camera), "--look-at", vec(state.lookAt), "--fov", num(state.fov, 2),
      "--width", String(size.width), "--height", String(size.height), "--spp", String(spp)];
    for (const c of CONTROLS) {
      if (c.local || c.always) continue;
      const input = $("opt-" + c.key);
      if (c.kind === "flag") { if (input.checked) args.push("--" + c.key); continue; }
      if (c.auto) {
        if (!$("opt-" + c.key + "-auto").checked) args.push("--" + c.key, input.value);
        continue;
      }
      if (input.value === "") continue;
      // Against the CLI's own defaults (not the server's start options): the command line
      // must say everything that differs from a plain `render` run.
      const d = c.key in CLI_DEFAULTS ? CLI_DEFAULTS[c.key] : c.def;
      const same = c.kind === "select" ? input.value === String(d) : Math.abs(+input.value - +d) < 1e-9;
      if (!same) args.push("--" + c.key, input.value);
    }
    const classes = (state.info && state.info.classes) || [];
    const modes = classes.map((name) => $("opt-geometry-" + name).value);
    if (classes.length && modes.every((v) => v === "procedural")) args.push("--procedural");
    else classes.forEach((name, i) => { if (modes[i] !== "stored") args.push("--geometry-" + name, modes[i]); });
    args.push(...$("opt-extra").value.trim().split(/\s+/).filter(Boolean));
    return args;
  }

  function sppTarget() {
    const v = parseInt($("opt-spp").value, 10);
    return v >= 1 ? v : defaultOf({ key: "spp" }) || 16;
  }

  // The full-resolution size: the canvas in device pixels times the resolution scale, capped
  // by the server's limits (keeping the aspect ratio).
  function frameSize() {
    const dpr = window.devicePixelRatio || 1;
    const s = +$("opt-scale").value || 1;
    let w = Math.max(1, Math.round(canvas.clientWidth * dpr * s));
    let h = Math.max(1, Math.round(canvas.clientHeight * dpr * s));
    const lim = (state.info && state.info.limits) || {};
    const f = Math.min(1, (lim.max_width || Infinity) / w, (lim.max_height || Infinity) / h,
      Math.sqrt((lim.max_pixels || Infinity) / (w * h)));
    return { width: Math.max(1, Math.floor(w * f)), height: Math.max(1, Math.floor(h * f)) };
  }

  function updateSize() {
    state.size = frameSize();
    if (!saveEdited) {
      $("save-width").value = state.size.width;
      $("save-height").value = state.size.height;
    }
  }

  // ------------------------------------------------------------------------- sending the view
  const MOVE_INTERVAL_MS = 30, IDLE_MS = 150;
  let moveTimer = 0, idleTimer = 0, settingsTimer = 0, lastPostAt = 0;

  // The camera moved: moving frames at most every 30 ms, a still one 150 ms after the last input.
  function viewChanged(moving = true) {
    keepAboveGround();
    drawMinimap();
    if (!moving) { clearTimeout(moveTimer); moveTimer = 0; postView(false); return; }
    state.moving = true;
    if (!moveTimer) {
      moveTimer = setTimeout(() => { moveTimer = 0; postView(true); },
        Math.max(0, lastPostAt + MOVE_INTERVAL_MS - performance.now()));
    }
    clearTimeout(idleTimer);
    idleTimer = setTimeout(() => {
      clearTimeout(moveTimer); moveTimer = 0;
      state.moving = false;
      postView(false);
    }, IDLE_MS);
  }

  // A panel setting changed: sliders are debounced, the rest is sent at once.
  function settingsChanged(now) {
    clearTimeout(settingsTimer);
    settingsTimer = setTimeout(() => postView(false), now ? 0 : 120);
  }

  // One request at a time, in order: a still view sent while a moving one is under way must
  // not overtake it at the server (which takes the newest arrival). Only the newest waits.
  let sending = false, queued = null;
  function postView(moving) {
    lastPostAt = performance.now();
    queued = { moving };
    if (!sending) pumpViews();
  }
  async function pumpViews() {
    sending = true;
    while (queued) {
      const { moving } = queued;
      queued = null;
      await sendView(moving);
    }
    sending = false;
  }

  // The body: the CLI args, moving, and the page-only fields aov and boxes when not default.
  function viewBody(moving) {
    const body = { args: buildArgs(), moving };
    const aov = $("opt-aov").value;
    if (aov !== "image") body.aov = aov;
    const boxes = [];
    if ($("opt-box-buildings").checked) boxes.push("buildings");
    if ($("opt-box-roads").checked) boxes.push("roads");
    if (boxes.length) body.boxes = boxes;
    return body;
  }

  async function sendView(moving) {
    const body = viewBody(moving);
    state.lastBody = body;
    try {
      const r = await fetch(api("api/view"), {
        method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
      const j = await readJson(r);
      if (!r.ok) { showError(j.error || `view: HTTP ${r.status}`, "view"); return; }
      clearError("view");
      state.generation = j.generation;
      state.command = j.command || "";
    } catch (e) {
      showError("view: " + e.message, "view");
    }
  }

  // ----------------------------------------------------------------------------------- frames
  let lastBitmap = null;
  const frameTimes = [];  // when frames were drawn, for the fps
  let lastMoveAt = 0;

  function resizeCanvas() {
    const dpr = window.devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(canvas.clientWidth * dpr));
    canvas.height = Math.max(1, Math.round(canvas.clientHeight * dpr));
    drawFrame();
  }

  // Where a w x h image sits in the canvas (fitted whole, centred), in canvas-relative units.
  function fitRect(w, h, boxW, boxH) {
    const s = Math.min(boxW / w, boxH / h);
    return { x: (boxW - w * s) / 2, y: (boxH - h * s) / 2, w: w * s, h: h * s, s };
  }

  function drawFrame() {
    ctx.fillStyle = "#111";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    if (!lastBitmap) return;
    const r = fitRect(lastBitmap.width, lastBitmap.height, canvas.width, canvas.height);
    ctx.imageSmoothingEnabled = true;
    ctx.imageSmoothingQuality = lastBitmap.width < state.size.width ? "low" : "high";
    ctx.drawImage(lastBitmap, r.x, r.y, r.w, r.h);
  }

  // Long poll: each answer is the newest frame after `seq`, 204 when none came within a second.
  async function frameLoop() {
    let seq = 0;
    for (;;) {
      try {
        seq = await nextFrame(seq);
      } catch (e) {
        showError("no connection to the server; retrying…", "frame");
        await sleep(1000);
      }
    }
  }

  async function nextFrame(seq) {
    const r = await fetch(api("api/frame", { after: seq }), { cache: "no-store" });
    if (r.status === 204) { clearError("frame"); return seq; }
    if (!r.ok) {
      const j = await readJson(r);
      showError(j.error || `frame: HTTP ${r.status}`, "frame");
      await sleep(1000);
      return seq;
    }
    const h = (name) => r.headers.get("X-Frame-" + name);
    const blob = await r.blob();
    const t0 = performance.now();
    const bitmap = await createImageBitmap(blob);
    if (lastBitmap) lastBitmap.close();
    lastBitmap = bitmap;
    drawFrame();
    const now = performance.now();
    clearError("frame");
    frameTimes.push(now);
    while (frameTimes.length && frameTimes[0] < now - 1000) frameTimes.shift();
    citygen.frames += 1;
    citygen.lastFrame = {
      seq: +h("Seq") || seq + 1, generation: +h("Generation"), spp: +h("Spp"), targetSpp: +h("Target-Spp"),
      final: h("Final") === "1", width: +h("Width") || bitmap.width, height: +h("Height") || bitmap.height,
      renderMs: +h("Render-Ms"), encodeMs: +h("Encode-Ms"), raysPerSecond: +h("Rays-Per-Second"),
      displayMs: now - t0, bytes: blob.size,
    };
    showStats();
    if (document.body.dataset.ready !== "1") document.body.dataset.ready = "1";
    return citygen.lastFrame.seq;
  }

  // ------------------------------------------------------------------------------------ stats
  let serverStats = null;
  const fmtRate = (v) => (!v ? "–" : v >= 1e9 ? (v / 1e9).toFixed(2) + " G" : v >= 1e6 ? (v / 1e6).toFixed(1) + " M" : (v / 1e3).toFixed(0) + " k");

  function showStats() {
    const f = citygen.lastFrame;
    const lines = [];
    if (f) {
      const moving = state.moving || performance.now() - lastMoveAt < 1000;
      lines.push(`frame   ${f.width}×${f.height}  #${f.seq}${f.final ? "  final" : ""}`);
      lines.push(`samples ${f.spp} / ${f.targetSpp || sppTarget()}   gen ${f.generation}`);
      lines.push(`render  ${num(f.renderMs, 1)} ms   encode ${num(f.encodeMs, 1)} ms`);
      lines.push(`display ${num(f.displayMs, 1)} ms   fps ${moving ? frameTimes.length : "–"}`);
      lines.push(`rays/s  ${fmtRate(f.raysPerSecond || (serverStats && serverStats.rays_per_second))}`);
    } else {
      lines.push("waiting for the first frame…");
    }
    if (serverStats) lines.push(`memory  ${num(serverStats.memory_mb, 0)} MB   frames ${serverStats.frames}`);
    $("stats").textContent = lines.join("\n");
  }

  async function statsLoop() {
    for (;;) {
      try {
        const r = await fetch(api("api/stats"), { cache: "no-store" });
        if (r.ok) { serverStats = await r.json(); showStats(); }
      } catch (e) { /* the frame loop reports a lost connection */ }
      await sleep(2000);
    }
  }

  // ------------------------------------------------------------------------------- navigation
  // The camera is an orbit around the look-at point: offset = distance, yaw, elevation.
  function orbitParams() {
    const off = sub(state.camera, state.lookAt);
    const r = Math.max(len(off), 1e-3);
    return { r, yaw: Math.atan2(off[1], off[0]), pitch: Math.asin(clamp(off[2] / r, -1, 1)) };
  }
  function setOrbit(r, yaw, pitch) {
    const c = Math.cos(pitch);
    state.camera = add(state.lookAt, [r * c * Math.cos(yaw), r * c * Math.sin(yaw), r * Math.sin(pitch)]);
  }

  // The camera stays 2 m above the ground (and off the look-at point).
  function keepAboveGround() {
    const minZ = groundZ() + 2;
    if (state.camera[2] < minZ) state.camera[2] = minZ;
    if (len(sub(state.camera, state.lookAt)) < 0.5) state.camera = add(state.lookAt, [0, -0.5, 0.5]);
  }

  function orbit(dx, dy) {
    const o = orbitParams();
    let pitch = clamp(o.pitch + dy * 0.005, -1.4, 1.55);
    const minPitch = Math.asin(clamp((groundZ() + 2 - state.lookAt[2]) / o.r, -1, 1));
    pitch = Math.max(pitch, minPitch);
    setOrbit(o.r, o.yaw - dx * 0.005, pitch);
  }

  // Horizontal unit vectors: towards the look-at point, and to the right of the view.
  function groundAxes() {
    const { yaw } = orbitParams();
    return { fwd: [-Math.cos(yaw), -Math.sin(yaw), 0], right: [-Math.sin(yaw), Math.cos(yaw), 0] };
  }

  function translate(d) {
    state.camera = add(state.camera, d);
    state.lookAt = add(state.lookAt, d);
  }

  // Pan: the ground under the cursor follows it (roughly: ground foreshortening is capped).
  function pan(dx, dy) {
    const o = orbitParams();
    const mpp = (2 * o.r * Math.tan((state.fov * Math.PI) / 360)) / Math.max(1, canvas.clientHeight);
    const { fwd, right } = groundAxes();
    const fore = Math.min(4, 1 / Math.max(0.25, Math.sin(Math.abs(o.pitch))));
    translate(add(mul(right, -dx * mpp), mul(fwd, dy * mpp * fore)));
  }

  // Zoom: the distance to the look-at point changes exponentially.
  function zoom(factor) {
    const o = orbitParams();
    setOrbit(clamp(o.r * factor, 2, 100000), o.yaw, o.pitch);
  }

  // Mouse and touch through pointer events. A press that moves less than 4 px is a click (pick).
  const pointers = new Map();
  let gesture = null;
  const CLICK_PX = 4;

  function twoFinger() {
    const [a, b] = [...pointers.values()];
    return { mid: [(a.x + b.x) / 2, (a.y + b.y) / 2], dist: Math.hypot(a.x - b.x, a.y - b.y) };
  }

  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("pointerdown", (e) => {
    canvas.focus();
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
    if (pointers.size === 1) {
      const panMode = e.button === 2 || e.button === 1 || e.shiftKey;
      gesture = { mode: panMode ? "pan" : "orbit", start: [e.clientX, e.clientY], last: [e.clientX, e.clientY], moved: false };
    } else if (gesture) {
      gesture.mode = "pinch";
      gesture.moved = true;  // no pick after a two-finger gesture
      gesture.pinch = twoFinger();
    }
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!gesture || !pointers.has(e.pointerId)) return;
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
    if (gesture.mode === "pinch" && pointers.size >= 2) {
      const now = twoFinger();
      if (now.dist > 0 && gesture.pinch.dist > 0) zoom(gesture.pinch.dist / now.dist);
      pan(now.mid[0] - gesture.pinch.mid[0], now.mid[1] - gesture.pinch.mid[1]);
      gesture.pinch = now;
    } else {
      if (!gesture.moved && Math.hypot(e.clientX - gesture.start[0], e.clientY - gesture.start[1]) < CLICK_PX) return;
      gesture.moved = true;
      const dx = e.clientX - gesture.last[0], dy = e.clientY - gesture.last[1];
      gesture.last = [e.clientX, e.clientY];
      if (gesture.mode === "pan") pan(dx, dy); else orbit(dx, dy);
    }
    lastMoveAt = performance.now();
    viewChanged(true);
  });
  function pointerEnd(e) {
    if (!pointers.delete(e.pointerId) || !gesture) return;
    if (pointers.size === 1) {  // one finger left of a pinch: it orbits on from here
      const p = [...pointers.values()][0];
      gesture.mode = "orbit";
      gesture.last = [p.x, p.y];
      return;
    }
    if (pointers.size === 0) {
      if (!gesture.moved && e.type === "pointerup") pickAtClient(e.clientX, e.clientY);
      gesture = null;
    }
  }
  canvas.addEventListener("pointerup", pointerEnd);
  canvas.addEventListener("pointercancel", pointerEnd);

  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const lines = e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1;
    zoom(Math.exp(clamp(e.deltaY * lines, -500, 500) * 0.0015));
    lastMoveAt = performance.now();
    viewChanged(true);
  }, { passive: false });

  // Keys fly the camera and its look-at point together, at a speed that grows with the distance.
  const FLY_KEYS = {
    KeyW: [1, 0, 0], ArrowUp: [1, 0, 0], KeyS: [-1, 0, 0], ArrowDown: [-1, 0, 0],
    KeyD: [0, 1, 0], ArrowRight: [0, 1, 0], KeyA: [0, -1, 0], ArrowLeft: [0, -1, 0],
    KeyE: [0, 0, 1], KeyQ: [0, 0, -1],
  };
  const held = new Set();
  let flyLast = 0, flyFast = false;
  const typing = (t) => t && (t.tagName === "INPUT" || t.tagName === "SELECT" || t.tagName === "TEXTAREA");

  window.addEventListener("keydown", (e) => {
    if (typing(e.target) || e.ctrlKey || e.metaKey || e.altKey || !FLY_KEYS[e.code]) return;
    e.preventDefault();
    flyFast = e.shiftKey;
    if (!held.size) { flyLast = performance.now(); requestAnimationFrame(flyStep); }
    held.add(e.code);
  });
  window.addEventListener("keyup", (e) => { held.delete(e.code); flyFast = e.shiftKey; });
  window.addEventListener("blur", () => held.clear());

  function flyStep(now) {
    if (!held.size) return;
    const dt = Math.min(0.1, (now - flyLast) / 1000);
    flyLast = now;
    const speed = Math.max(5, orbitParams().r * 0.8) * (flyFast ? 4 : 1);
    const { fwd, right } = groundAxes();
    let d = [0, 0, 0];
    for (const code of held) {
      const [f, r, u] = FLY_KEYS[code];
      d = add(d, add(add(mul(fwd, f), mul(right, r)), [0, 0, u]));
    }
    d = mul(d, speed * dt);
    d[2] = Math.max(d[2], groundZ() + 2 - state.camera[2]);  // not below the ground
    translate(d);
    lastMoveAt = performance.now();
    viewChanged(true);
    requestAnimationFrame(flyStep);
  }

  // ---------------------------------------------------------------------------------- picking
  // A click in CSS pixels -> the pixel of the full-resolution frame (the size sent).
  function pickAtClient(clientX, clientY) {
    const b = canvas.getBoundingClientRect();
    const r = fitRect(state.size.width, state.size.height, b.width, b.height);
    const x = Math.floor((clientX - b.left - r.x) / r.s), y = Math.floor((clientY - b.top - r.y) / r.s);
    if (x < 0 || y < 0 || x >= state.size.width || y >= state.size.height) return;
    pick(x, y);
  }

  async function pick(x, y) {
    try {
      const r = await fetch(api("api/pick", { x, y }));
      const j = await readJson(r);
      if (!r.ok) { showError(j.error || `pick: HTTP ${r.status}`, "pick"); return null; }
      clearError("pick");
      citygen.lastPick = { x, y, answer: j };
      showPick(j);
      return j;
    } catch (e) {
      showError("pick: " + e.message, "pick");
      return null;
    }
  }

  function showPick(j) {
    $("pick-kind").textContent = j.kind || "?";
    $("pick-osm").textContent = j.osm || "";
    const link = $("pick-link");
    if (j.osm_type && j.osm_id !== undefined) {
      link.textContent = `${j.osm_type} ${j.osm_id}`;
      link.href = `https://www.openstreetmap.org/${encodeURIComponent(j.osm_type)}/${encodeURIComponent(j.osm_id)}`;
      link.hidden = false;
    } else {
      link.hidden = true;
    }
    const table = $("pick-fields");
    table.textContent = "";
    const rows = Object.entries(j.fields || {});
    if (j.index !== undefined) rows.unshift(["index", j.index]);
    for (const [k, v] of rows) {
      const tr = table.insertRow();
      tr.insertCell().textContent = k;
      tr.insertCell().textContent = typeof v === "object" ? JSON.stringify(v) : String(v);
    }
    $("pick-info").hidden = false;
  }
  $("pick-close").addEventListener("click", () => { $("pick-info").hidden = true; });

  // ---------------------------------------------------------------------------------- minimap
  const mini = $("minimap");
  const miniCtx = mini.getContext("2d");
  let mapLayer = null;   // the static map, drawn once
  let mapXf = null;      // scene metres <-> minimap CSS pixels

  async function loadMap() {
    let m;
    try {
      const r = await fetch(api("api/map"));
      if (!r.ok) { mini.hidden = true; return; }
      m = await r.json();
    } catch (e) { mini.hidden = true; return; }
    const b = m.bounds || state.info.bounds;
    const spanX = Math.max(1, b.max[0] - b.min[0]), spanY = Math.max(1, b.max[1] - b.min[1]);
    const cssW = 220, cssH = Math.round(clamp((220 * spanY) / spanX, 120, 220));
    const dpr = window.devicePixelRatio || 1;
    mini.style.width = cssW + "px";
    mini.style.height = cssH + "px";
    mini.width = cssW * dpr;
    mini.height = cssH * dpr;
    const pad = 6, s = Math.min((cssW - 2 * pad) / spanX, (cssH - 2 * pad) / spanY);
    const ox = (cssW - spanX * s) / 2, oy = (cssH - spanY * s) / 2;
    mapXf = {  // north (+y) up
      toPx: (x, y) => [ox + (x - b.min[0]) * s, cssH - oy - (y - b.min[1]) * s],
      toWorld: (px, py) => [b.min[0] + (px - ox) / s, b.min[1] + (cssH - oy - py) / s],
      dpr,
    };
    mapLayer = document.createElement("canvas");
    mapLayer.width = mini.width;
    mapLayer.height = mini.height;
    const c = mapLayer.getContext("2d");
    c.scale(dpr, dpr);
    c.fillStyle = "#d8d6cf";
    c.fillRect(0, 0, cssW, cssH);
    const path = (flat, close) => {
      c.beginPath();
      for (let i = 0; i + 1 < flat.length; i += 2) {
        const [px, py] = mapXf.toPx(flat[i], flat[i + 1]);
        if (i === 0) c.moveTo(px, py); else c.lineTo(px, py);
      }
      if (close) c.closePath();
    };
    c.fillStyle = "#6aa3d8";
    for (const w of m.water || []) { path(w, true); c.fill(); }
    c.strokeStyle = "#8a8a8a";
    c.lineWidth = 1;
    for (const r of m.roads || []) { path(r, false); c.stroke(); }
    c.fillStyle = "#3b3b40";
    for (const p of m.buildings || []) { path(p, true); c.fill(); }
    drawMinimap();
  }

  function drawMinimap() {
    if (!mapLayer) return;
    const { dpr } = mapXf;
    miniCtx.setTransform(1, 0, 0, 1, 0, 0);
    miniCtx.drawImage(mapLayer, 0, 0);
    miniCtx.setTransform(dpr, 0, 0, dpr, 0, 0);
    const [cx, cy] = mapXf.toPx(state.camera[0], state.camera[1]);
    const [lx, ly] = mapXf.toPx(state.lookAt[0], state.lookAt[1]);
    // The horizontal field of view as a wedge from the camera through the look-at point.
    const dir = Math.atan2(ly - cy, lx - cx);
    const aspect = state.size.width / state.size.height;
    const half = Math.atan(Math.tan((state.fov * Math.PI) / 360) * aspect);
    const reach = Math.max(18, Math.hypot(lx - cx, ly - cy));
    miniCtx.fillStyle = "rgba(255, 200, 40, 0.35)";
    miniCtx.beginPath();
    miniCtx.moveTo(cx, cy);
    miniCtx.arc(cx, cy, reach, dir - half, dir + half);
    miniCtx.closePath();
    miniCtx.fill();
    miniCtx.strokeStyle = "#e0302a";
    miniCtx.lineWidth = 1.5;
    miniCtx.beginPath();
    miniCtx.moveTo(cx, cy);
    miniCtx.lineTo(lx, ly);
    miniCtx.stroke();
    miniCtx.fillStyle = "#e0302a";
    miniCtx.beginPath();
    miniCtx.arc(cx, cy, 4, 0, 2 * Math.PI);
    miniCtx.fill();
  }

  // A click on the map moves the look-at point there, at ground height, keeping the offset.
  mini.addEventListener("click", (e) => {
    if (!mapXf) return;
    const b = mini.getBoundingClientRect();
    const [x, y] = mapXf.toWorld(e.clientX - b.left, e.clientY - b.top);
    const offset = sub(state.camera, state.lookAt);
    state.lookAt = [x, y, groundZ()];
    state.camera = add(state.lookAt, offset);
    viewChanged(false);
  });

  // -------------------------------------------------------------------------------- go to
  async function goTo() {
    const q = $("goto-input").value.trim();
    if (!q) return;
    try {
      const r = await fetch(api("api/goto", { q }));
      const j = await readJson(r);
      if (!r.ok) { showError(j.error || `go to: HTTP ${r.status}`, "goto"); return; }
      clearError("goto");
      const dir = sub(state.camera, state.lookAt);
      const d = Math.max(80, 2.5 * (+j.radius || 0));
      state.lookAt = [+j.x, +j.y, +j.z];
      state.camera = add(state.lookAt, mul(dir, d / Math.max(len(dir), 1e-6)));
      viewChanged(false);
    } catch (e) {
      showError("go to: " + e.message, "goto");
    }
  }
  $("goto-button").addEventListener("click", goTo);
  $("goto-input").addEventListener("keydown", (e) => { if (e.key === "Enter") goTo(); });

  // ------------------------------------------------------------------------- save and command
  let saveEdited = false, sppEdited = false;  // once the user types a size, resizing keeps it
  for (const id of ["save-width", "save-height"]) $(id).addEventListener("input", () => { saveEdited = true; });
  $("save-spp").addEventListener("input", () => { sppEdited = true; });

  async function saveImage() {
    const w = parseInt($("save-width").value, 10), h = parseInt($("save-height").value, 10);
    const spp = parseInt($("save-spp").value, 10);
    if (!(w >= 1 && h >= 1 && spp >= 1)) { showError("save: width, height and samples must be positive", "save"); return; }
    const button = $("save-button");
    button.disabled = true;
    button.textContent = "Saving…";
    try {
      const r = await fetch(api("api/save"), {
        method: "POST", headers: { "Content-Type": "application/json" },
        body: JSON.stringify({ args: buildArgs({ width: w, height: h }, spp) }) });
      const j = await readJson(r);
      if (!r.ok) { showError(j.error || `save: HTTP ${r.status}`, "save"); return; }
      clearError("save");
      $("save-command").textContent = j.command;
      const link = $("save-link");
      link.href = api("api/saved/" + encodeURIComponent(j.file));
      link.download = j.file;
      link.textContent = j.file;
      link.hidden = false;
    } catch (e) {
      showError("save: " + e.message, "save");
    } finally {
      button.disabled = false;
      button.textContent = "Save image";
    }
  }
  $("save-button").addEventListener("click", saveImage);

  async function copyCommand() {
    const text = state.command;
    $("command").textContent = text || "(no view answered yet)";
    if (!text) return;
    let ok = false;
    try {
      await navigator.clipboard.writeText(text);
      ok = true;
    } catch (e) {  // no clipboard API (insecure context, no permission): a selected textarea
      const ta = document.createElement("textarea");
      ta.value = text;
      ta.style.position = "fixed";
      ta.style.opacity = "0";
      document.body.append(ta);
      ta.select();
      try { ok = document.execCommand("copy"); } catch (e2) { ok = false; }
      ta.remove();
    }
    $("copy-note").textContent = ok ? "copied" : "select and copy it below";
  }
  $("copy-command").addEventListener("click", copyCommand);

  // ---------------------------------------------------------------------------- camera path
  let firstKeyAt = 0;
  function addKeyframe() {
    const now = performance.now();
    if (!state.keyframes.length) firstKeyAt = now;
    let t = (now - firstKeyAt) / 1000;
    const prev = state.keyframes[state.keyframes.length - 1];
    if (prev && t <= prev.time) t = prev.time + 0.001;  // the CLI wants increasing times
    state.keyframes.push({ time: +t.toFixed(3), camera: state.camera.slice(), look_at: state.lookAt.slice(), fov: state.fov });
    showKeyCount();
  }
  function showKeyCount() {
    const n = state.keyframes.length;
    $("key-count").textContent = `${n} keyframe${n === 1 ? "" : "s"}` + (n === 1 ? " (2 needed)" : "");
    $("download-path").disabled = n < 2;
  }
  // One line per keyframe, numbers only: time,x,y,z,look_x,look_y,look_z,fov.
  function cameraPathCsv() {
    return state.keyframes.map((k) => [k.time, ...k.camera, ...k.look_at, k.fov].map((v) => num(v)).join(",")).join("\n") + "\n";
  }
  $("add-key").addEventListener("click", addKeyframe);
  $("clear-keys").addEventListener("click", () => { state.keyframes = []; showKeyCount(); });
  $("download-path").addEventListener("click", () => {
    const url = URL.createObjectURL(new Blob([cameraPathCsv()], { type: "text/csv" }));
    const a = document.createElement("a");
    a.href = url;
    a.download = "camera_path.csv";
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  });

  // ------------------------------------------------------------------------------ the rest
  function setPanelOpen(open) {
    document.body.classList.toggle("panel-closed", !open);
    $("panel-toggle").setAttribute("aria-expanded", String(open));
  }
  $("panel-toggle").addEventListener("click", () => setPanelOpen(document.body.classList.contains("panel-closed")));

  for (const id of ["opt-box-buildings", "opt-box-roads"]) $(id).addEventListener("change", () => settingsChanged(true));
  $("opt-extra").addEventListener("change", () => settingsChanged(true));
  $("reset-view").addEventListener("click", () => {
    const v = state.info && state.info.view;
    if (v) citygen.setView(v.camera, v.look_at, v.fov);
  });

  let resizeTimer = 0;
  window.addEventListener("resize", () => {
    resizeCanvas();
    drawMinimap();
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(() => {
      const before = state.size;
      updateSize();
      if (before.width !== state.size.width || before.height !== state.size.height) postView(false);
    }, 250);
  });

  async function start() {
    buildControls();
    setPanelOpen(window.innerWidth >= 700);
    resizeCanvas();
    showKeyCount();
    for (;;) {  // the server may still be loading the scene
      try {
        const r = await fetch(api("api/info"));
        const j = await readJson(r);
        if (!r.ok) throw new Error(j.error || `HTTP ${r.status}`);
        state.info = j;
        break;
      } catch (e) {
        showError("info: " + e.message + "; retrying…", "info");
        await sleep(2000);
      }
    }
    clearError("info");
    const v = state.info.view || {};
    if (v.camera && v.look_at) { state.camera = v.camera.slice(); state.lookAt = v.look_at.slice(); }
    state.fov = +v.fov || +defaultOf({ key: "fov" }) || 50;
    document.title = `${state.info.scene || "citygen"} – citygen viewer`;
    applyDefaults();
    buildGeometryControls(state.info.classes || []);
    updateSize();
    $("save-spp").value = sppTarget();
    keepAboveGround();
    postView(false);
    frameLoop();
    statsLoop();
    loadMap();
  }
  start();
})();
