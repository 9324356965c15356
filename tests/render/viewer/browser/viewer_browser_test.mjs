#!/usr/bin/env node
// Browser test of the citygen viewer page, in headless Debian Chromium through puppeteer-core.
//
//   node viewer_browser_test.mjs --url http://127.0.0.1:PORT/ [--render BIN --scene FILE --out DIR]
//                                [--screenshot FILE] [--size 960x540] [--chromium PATH]
//
// The server is `render city.scene --serve PORT` or mock_server.py. One line per check
// ("ok - ..." / "not ok - ..."); exit 1 if one failed, 77 if Chromium or puppeteer-core is missing.
// With --render/--scene/--out the picked id and the saved image are compared with the CLI's.

import { spawnSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync } from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const HERE = path.dirname(fileURLToPath(import.meta.url));
const SKIP_EXIT = 77;

function parseArgs(argv) {
  const o = { size: "960x540", chromium: process.env.CHROMIUM || "/usr/bin/chromium" };
  for (let i = 0; i < argv.length; i++) {
    const m = /^--(url|render|scene|out|screenshot|size|chromium)$/.exec(argv[i]);
    if (!m || i + 1 >= argv.length) {
      console.error(`usage: node viewer_browser_test.mjs --url URL [--render BIN --scene FILE --out DIR] [--screenshot FILE]` +
        ` [--size WxH] [--chromium PATH]\nunexpected: ${argv[i]}`);
      process.exit(2);
    }
    o[m[1]] = argv[++i];
  }
  if (!o.url) { console.error("--url is required"); process.exit(2); }
  const [w, h] = o.size.split("x").map(Number);
  o.width = w || 960;
  o.height = h || 540;
  if (o.out) mkdirSync(o.out, { recursive: true });
  return o;
}

const opts = parseArgs(process.argv.slice(2));
const cli = opts.render && opts.scene && opts.out ? { bin: opts.render, scene: opts.scene, out: opts.out } : null;

// ---------------------------------------------------------------------------------- checks
let failures = 0, passes = 0;
async function check(name, fn) {
  try {
    const detail = await fn();
    passes++;
    console.log(`ok - ${name}${detail ? ` (${detail})` : ""}`);
    return true;
  } catch (e) {
    failures++;
    console.log(`not ok - ${name}: ${e && e.message ? e.message.split("\n")[0] : e}`);
    return false;
  }
}
const assert = (cond, message) => { if (!cond) throw new Error(message); };
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// A hung server or page must not hang the test.
const watchdog = setTimeout(() => {
  console.log("not ok - the test timed out after 10 minutes");
  process.exit(1);
}, 10 * 60 * 1000);

// --------------------------------------------------------------------------- the browser
let puppeteer;
try {
  puppeteer = (await import("puppeteer-core")).default;
} catch (e) {
  console.log(`SKIP: puppeteer-core is not available (${e.message.split("\n")[0]}); run npm ci in ${HERE}`);
  process.exit(SKIP_EXIT);
}
if (!existsSync(opts.chromium)) {
  console.log(`SKIP: no Chromium at ${opts.chromium} (apt-get install chromium, or --chromium PATH)`);
  process.exit(SKIP_EXIT);
}
let browser;
try {
  browser = await puppeteer.launch({
    executablePath: opts.chromium,
    headless: true,
    args: ["--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu", `--window-size=${opts.width},${opts.height}`],
  });
} catch (e) {
  console.log(`SKIP: Chromium at ${opts.chromium} does not start: ${e.message.split("\n")[0]}`);
  process.exit(SKIP_EXIT);
}

const page = await browser.newPage();
await page.setViewport({ width: opts.width, height: opts.height, deviceScaleFactor: 1 });
const pageErrors = [];
page.on("pageerror", (e) => pageErrors.push(e.message));

// Mean, spread and distinct colours of the canvas, and a coarse grid of luminances to tell
// two frames apart.
async function canvasSummary() {
  return page.evaluate(() => {
    const c = document.getElementById("view");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const GW = 48, GH = 27, grid = new Array(GW * GH).fill(0), count = new Array(GW * GH).fill(0);
    const colours = new Set();
    let n = 0, sum = 0, sum2 = 0;
    for (let y = 0; y < c.height; y += 3) {
      for (let x = 0; x < c.width; x += 3) {
        const i = 4 * (y * c.width + x);
        const l = 0.2126 * d[i] + 0.7152 * d[i + 1] + 0.0722 * d[i + 2];
        n++; sum += l; sum2 += l * l;
        if (colours.size < 5000) colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
        const g = Math.floor((y * GH) / c.height) * GW + Math.floor((x * GW) / c.width);
        grid[g] += l; count[g]++;
      }
    }
    const mean = sum / n;
    return { mean, std: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), distinct: colours.size,
      grid: grid.map((v, i) => v / Math.max(1, count[i])) };
  });
}
const gridDiff = (a, b) => a.grid.reduce((s, v, i) => s + Math.abs(v - b.grid[i]), 0) / a.grid.length;
const citygen = (expr) => page.evaluate(expr);

// Waits until the newest /api/view answer has a full-resolution frame drawn, then (up to
// `finalMs`) until that frame reached its target samples.
async function settle(generationAbove, finalMs = 20000) {
  await page.waitForFunction((g) => {
    const s = window.citygen.state, f = window.citygen.lastFrame;
    return !s.moving && s.generation > g && f && f.generation >= s.generation && f.width >= s.size.width;
  }, { timeout: 90000, polling: 50 }, generationAbove);
  try {
    await page.waitForFunction(() => window.citygen.lastFrame.final ||
      window.citygen.lastFrame.generation < window.citygen.state.generation, { timeout: finalMs, polling: 100 });
  } catch (e) { /* a slow renderer: the first full pass will do */ }
  await sleep(100);  // the frame is drawn before lastFrame is set; let a paint happen
}
const generation = () => citygen(() => window.citygen.state.generation);

// Opens the collapsed panel section of an element, as a user would before clicking in it.
async function reveal(selector) {
  await page.$eval(selector, (e) => {
    const d = e.closest("details");
    if (d && !d.open) d.querySelector("summary").click();
    document.body.classList.remove("panel-closed");
  });
  await sleep(250);  // the panel slides in
}

// Waits for the answer to a new /api/view (a newer generation) or for an error line.
async function viewAnswered(g0) {
  await page.waitForFunction((g) => window.citygen.state.generation > g || window.citygen.state.error,
    { timeout: 30000, polling: 50 }, g0);
  const error = await citygen(() => window.citygen.state.error);
  if (error) throw new Error(`the page shows the error "${error}"`);
  await settle(g0, 2000);
}

// Splits a shell command line as the server quotes it (POSIX single/double quotes, backslashes).
function shellSplit(line) {
  const out = [];
  let cur = null, i = 0;
  while (i < line.length) {
    const ch = line[i];
    if (/\s/.test(ch)) { if (cur !== null) { out.push(cur); cur = null; } i++; continue; }
    cur = cur ?? "";
    if (ch === "'") { const j = line.indexOf("'", i + 1); cur += line.slice(i + 1, j < 0 ? undefined : j); i = j < 0 ? line.length : j + 1; }
    else if (ch === '"') {
      i++;
      while (i < line.length && line[i] !== '"') { if (line[i] === "\\" && i + 1 < line.length) i++; cur += line[i++]; }
      i++;
    } else if (ch === "\\" && i + 1 < line.length) { cur += line[i + 1]; i += 2; }
    else { cur += ch; i++; }
  }
  if (cur !== null) out.push(cur);
  return out;
}

function run(argv, what) {
  const r = spawnSync(argv[0], argv.slice(1), { encoding: "utf8", timeout: 600000, maxBuffer: 64 << 20 });
  if (r.error) throw new Error(`${what}: ${r.error.message}`);
  if (r.status !== 0) throw new Error(`${what} exited ${r.status}: ${(r.stderr || "").trim().split("\n").pop()}`);
  return r.stdout;
}

// ----------------------------------------------------------------------------------------
// The id AOV of the CLI at pixel (x, y) of a view: {kind, index}, or null without --render.
// Kept apart so that the C++ side can change how the CLI is run or the EXR is read.
function cliIdAt(view, x, y) {
  if (!cli) return null;
  const exr = path.join(cli.out, "pick.exr");
  run([cli.bin, cli.scene, ...view.args, "--aovs", "id", "-o", exr, "-q"], "render --aovs id");
  // oiiotool (OpenImageIO, which the renderer links) cuts out the pixel and prints it.
  const px = path.join(cli.out, "pick_pixel.exr");
  run(["oiiotool", exr, "--ch", "id.kind,id.index", "--cut", `1x1+${x}+${y}`, "-o", px], "oiiotool --cut");
  const info = run(["oiiotool", "--info", "-v", "--dumpdata", px], "oiiotool --dumpdata");
  const names = /channel list:\s*(.*)/.exec(info)[1].split(",").map((s) => s.trim());
  const values = /Pixel \(0, 0\):\s*(.*)/.exec(info)[1].trim().split(/\s+/).map(Number);
  const at = (name) => values[names.indexOf(name)];
  return { kind: Math.round(at("id.kind")), index: Math.round(at("id.index")) };
}

// ------------------------------------------------------------------------------- the run
const cx = Math.floor(opts.width / 2), cy = Math.floor(opts.height / 2);

const loaded = await check("page loads and draws a first frame", async () => {
  await page.goto(opts.url, { waitUntil: "domcontentloaded", timeout: 30000 });
  await page.waitForSelector('body[data-ready="1"]', { timeout: 60000 });
  const f = await citygen(() => window.citygen.lastFrame);
  return `frame ${f.width}x${f.height}, seq ${f.seq}`;
});
if (!loaded) {
  const err = await page.$eval("#error", (e) => e.textContent).catch(() => "");
  console.log(`# the page shows: ${err || "(no error line)"}`);
  await browser.close();
  console.log(`${passes} passed, ${failures} failed`);
  process.exit(1);
}
await settle(0);

await check("the canvas is not blank", async () => {
  const s = await canvasSummary();
  assert(s.std > 5 && s.distinct > 16, `std ${s.std.toFixed(1)}, ${s.distinct} colours`);
  return `mean ${s.mean.toFixed(1)}, std ${s.std.toFixed(1)}, ${s.distinct}+ colours`;
});

await check("a mouse drag orbits the camera and a new frame shows it", async () => {
  const before = await citygen(() => ({ camera: window.citygen.state.camera.slice(), seq: window.citygen.lastFrame.seq }));
  const g0 = await generation();
  const pixels0 = await canvasSummary();
  await page.mouse.move(cx, cy);
  await page.mouse.down();
  for (let i = 1; i <= 12; i++) { await page.mouse.move(cx + i * 18, cy + i * 3); await sleep(16); }
  await page.mouse.up();
  const camera = await citygen(() => window.citygen.state.camera.slice());
  const moved = Math.hypot(...camera.map((c, i) => c - before.camera[i]));
  assert(moved > 1, `the camera moved ${moved.toFixed(2)} m`);
  await settle(g0);
  const seq = await citygen(() => window.citygen.lastFrame.seq);
  assert(seq > before.seq, "no newer frame");
  const diff = gridDiff(pixels0, await canvasSummary());
  assert(diff > 2, `the image barely changed (mean difference ${diff.toFixed(2)})`);
  return `camera moved ${moved.toFixed(1)} m, image difference ${diff.toFixed(1)}`;
});

await check("night is darker than day", async () => {
  const day = await canvasSummary();
  const g0 = await generation();
  await page.select("#opt-time", "night");
  await settle(g0);
  const args = await citygen(() => window.citygen.state.lastBody.args.join(" "));
  assert(args.includes("--time night"), `the view sent has no --time night: ${args}`);
  const night = await canvasSummary();
  assert(night.mean < day.mean * 0.7 && day.mean - night.mean > 10,
    `mean brightness ${day.mean.toFixed(1)} -> ${night.mean.toFixed(1)}`);
  return `mean brightness ${day.mean.toFixed(1)} -> ${night.mean.toFixed(1)}`;
});
{
  const g0 = await generation();
  await page.select("#opt-time", "day");
  await settle(g0);
}

let pickAnswer = null;
await check("a click picks what is under the cursor", async () => {
  await page.evaluate(() => { window.citygen.lastPick = null; });
  await page.mouse.click(cx, cy);
  await page.waitForFunction(() => window.citygen.lastPick && document.getElementById("pick-kind").textContent !== "",
    { timeout: 15000 });
  const shown = await page.evaluate(() => ({
    visible: !document.getElementById("pick-info").hidden,
    kind: document.getElementById("pick-kind").textContent,
    osm: document.getElementById("pick-osm").textContent,
    pick: window.citygen.lastPick,
    size: window.citygen.state.size,
  }));
  assert(shown.visible, "the pick box is hidden");
  pickAnswer = { ...shown.pick, size: shown.size };
  const ex = Math.floor(shown.size.width / 2), ey = Math.floor(shown.size.height / 2);
  assert(Math.abs(shown.pick.x - ex) <= 2 && Math.abs(shown.pick.y - ey) <= 2,
    `picked pixel (${shown.pick.x}, ${shown.pick.y}), expected about (${ex}, ${ey})`);
  return `${shown.kind} ${shown.osm} at (${shown.pick.x}, ${shown.pick.y})`;
});

if (!cli) console.log("SKIP: no --render (the picked id against the CLI's id AOV)");
else if (pickAnswer) {
  await check("the pick agrees with the CLI's id AOV", async () => {
    const view = await citygen(() => ({ args: window.citygen.state.lastBody.args }));
    const id = cliIdAt(view, pickAnswer.x, pickAnswer.y);
    const a = pickAnswer.answer;
    if (a.kind === "sky") assert(id.kind === 0, `the page says sky, the CLI id.kind is ${id.kind}`);
    else assert(a.index === id.index, `the page says index ${a.index} (${a.kind}), the CLI ${id.index} (kind ${id.kind})`);
    return `${a.kind} ${a.index ?? ""} = id.kind ${id.kind}, id.index ${id.index}`;
  });
}

if (pickAnswer && pickAnswer.answer.osm) {
  await check("go to the picked OSM id looks at it", async () => {
    const before = await citygen(() => window.citygen.state.lookAt.slice());
    const g0 = await generation();
    await reveal("#goto-input");
    await page.$eval("#goto-input", (e, v) => { e.value = v; }, pickAnswer.answer.osm);
    await page.click("#goto-button");
    await viewAnswered(g0);
    const s = await citygen(() => ({ lookAt: window.citygen.state.lookAt, camera: window.citygen.state.camera,
      error: window.citygen.state.error }));
    assert(!s.error, s.error);
    const dist = Math.hypot(...s.camera.map((c, i) => c - s.lookAt[i]));
    assert(dist >= 79, `camera ${dist.toFixed(1)} m from the target`);
    return `look-at ${before.map(Math.round)} -> ${s.lookAt.map(Math.round)}, distance ${dist.toFixed(0)} m`;
  });
}

await check("a click on the minimap moves the look-at point there", async () => {
  const box = await page.$eval("#minimap", (e) => { const b = e.getBoundingClientRect(); return [b.left, b.top, b.width, b.height]; });
  const s0 = await citygen(() => ({ camera: window.citygen.state.camera.slice(), lookAt: window.citygen.state.lookAt.slice() }));
  const g0 = await generation();
  await page.mouse.click(box[0] + box[2] * 0.5, box[1] + box[3] * 0.5);
  await viewAnswered(g0);
  const s = await citygen(() => ({ camera: window.citygen.state.camera, lookAt: window.citygen.state.lookAt,
    ground: window.citygen.state.info.ground_z || 0 }));
  const off0 = s0.camera.map((c, i) => c - s0.lookAt[i]), off = s.camera.map((c, i) => c - s.lookAt[i]);
  assert(Math.abs(s.lookAt[2] - s.ground) < 1e-6, `look-at z ${s.lookAt[2]}, ground ${s.ground}`);
  assert(off.every((v, i) => Math.abs(v - off0[i]) < 1e-3 || i === 2), "the camera offset changed");
  return `look-at ${s.lookAt.map((v) => v.toFixed(0)).join(",")}`;
});

await check("keyframes make a camera path CSV", async () => {
  await reveal("#add-key");
  await page.click("#add-key");
  await page.keyboard.down("KeyW");
  await sleep(300);
  await page.keyboard.up("KeyW");
  await sleep(50);
  await page.click("#add-key");
  const s = await page.evaluate(() => ({ csv: window.citygen.cameraPathCsv(), count: document.getElementById("key-count").textContent,
    disabled: document.getElementById("download-path").disabled }));
  const lines = s.csv.trim().split("\n");
  assert(lines.length === 2, `${lines.length} lines`);
  for (const l of lines) assert(l.split(",").length === 8 && l.split(",").every((v) => Number.isFinite(+v)), `bad line ${l}`);
  assert(+lines[1].split(",")[0] > +lines[0].split(",")[0], "times do not increase");
  assert(lines[0].split(",")[1] !== lines[1].split(",")[1] || lines[0].split(",")[2] !== lines[1].split(",")[2],
    "flying with W did not move the camera");
  assert(!s.disabled && /2 keyframes/.test(s.count), `count "${s.count}"`);
  return lines.join(" | ");
});

let saved = null;
await check("Save image writes a small image and shows its command", async () => {
  await settle(0, 1000);
  await reveal("#save-button");
  for (const [id, v] of [["save-width", 160], ["save-height", 90], ["save-spp", 2]])
    await page.$eval(`#${id}`, (e, v) => { e.value = v; e.dispatchEvent(new Event("input")); }, String(v));
  await page.$eval("#save-command", (e) => { e.textContent = ""; });
  await page.click("#save-button");
  await page.waitForFunction(() => document.getElementById("save-command").textContent !== "" &&
    !document.getElementById("save-link").hidden, { timeout: 300000 });
  const s = await page.evaluate(() => ({ command: document.getElementById("save-command").textContent,
    href: document.getElementById("save-link").href, name: document.getElementById("save-link").textContent }));
  assert(/--width 160\b/.test(s.command) && /--height 90\b/.test(s.command) && /--spp 2\b/.test(s.command),
    `the command lacks the size or spp: ${s.command}`);
  const r = await fetch(s.href);
  assert(r.ok, `GET ${s.href}: HTTP ${r.status}`);
  const bytes = Buffer.from(await r.arrayBuffer());
  if (bytes.subarray(1, 4).toString() === "PNG") {
    const w = bytes.readUInt32BE(16), h = bytes.readUInt32BE(20);
    assert(w === 160 && h === 90, `the saved PNG is ${w}x${h}`);
  }
  saved = { ...s, bytes };
  return `${s.name}, ${bytes.length} bytes`;
});

if (!cli) console.log("SKIP: no --render (the saved image against the CLI's)");
else if (saved) {
  await check("the saved image equals the CLI's run of its command", async () => {
    const argv = shellSplit(saved.command);
    argv[0] = cli.bin;
    argv[1] = cli.scene;
    const target = path.join(cli.out, "cli.png");
    const o = argv.findIndex((a) => a === "-o" || a === "--output");
    assert(o > 0 && o + 1 < argv.length, `no -o in ${saved.command}`);
    argv[o + 1] = target;
    run([...argv, "-q"], "the saved command");
    const mine = readFileSync(target);
    assert(Buffer.compare(mine, saved.bytes) === 0, `${target} (${mine.length} bytes) differs from ${saved.name} (${saved.bytes.length} bytes)`);
    return `${mine.length} bytes`;
  });
}

await check("a bad option shows the server's error", async () => {
  await reveal("#opt-extra");
  await page.$eval("#opt-extra", (e) => { e.value = "--no-such-option 1"; e.dispatchEvent(new Event("change")); });
  await page.waitForFunction(() => !document.getElementById("error").hidden, { timeout: 10000 });
  const text = await page.$eval("#error", (e) => e.textContent);
  await page.$eval("#opt-extra", (e) => { e.value = ""; e.dispatchEvent(new Event("change")); });
  await page.waitForFunction(() => document.getElementById("error").hidden, { timeout: 10000 });
  return `"${text}"`;
});

await check("Copy command shows the command of the view", async () => {
  await reveal("#copy-command");
  await page.click("#copy-command");
  const s = await page.evaluate(() => ({ shown: document.getElementById("command").textContent, command: window.citygen.state.command }));
  assert(s.command && s.shown === s.command, `shown "${s.shown}"`);
  assert(/--camera /.test(s.shown) && /--look-at /.test(s.shown), s.shown);
  return s.shown.length > 70 ? s.shown.slice(0, 70) + "…" : s.shown;
});

await check("the settings panel folds away and back", async () => {
  const inView = () => page.$eval("#panel", (e) => e.getBoundingClientRect().left < window.innerWidth - 1);
  assert(await inView(), "the panel is not open at the start");
  await page.click("#panel-toggle");
  await sleep(400);
  assert(!(await inView()), "the panel is still in view");
  await page.click("#panel-toggle");
  await sleep(400);
  assert(await inView(), "the panel did not come back");
});

if (opts.screenshot) {
  await check(`screenshot to ${opts.screenshot}`, async () => {
    await settle(0, 5000);
    await page.screenshot({ path: opts.screenshot });
  });
}

await check("no uncaught errors on the page", async () => {
  assert(pageErrors.length === 0, pageErrors.join("; "));
});

await browser.close();
clearTimeout(watchdog);
console.log(`${passes} passed, ${failures} failed`);
process.exit(failures ? 1 : 0);
