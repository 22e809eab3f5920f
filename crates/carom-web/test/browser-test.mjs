// The web build in a real browser: Debian's Chromium, headless, drawing in software through
// SwiftShader (WebGPU through Dawn on its Vulkan, and WebGL2 through ANGLE), driven through the
// DevTools protocol by playwright-core.
//
//   node crates/carom-web/test/browser-test.mjs [--site target/web] [--out target/web-test]
//       [--carom target/debug/carom] [--steps 200] [--hashes FILE] [--backends webgpu,gl]
//       [--frame-rates --carom target/release/carom [--csv]]
//       [--physics-speed --carom target/release/carom [--rounds 3] [--csv]]
//
// It serves the site on 127.0.0.1, opens it once for each backend (`?backend=`), and checks that
//   - the demo draws with that backend: frames arrive, the sidebar has text and the scene has
//     shapes;
//   - a body dragged with the mouse, and another with a finger, follows the drag;
// and once, on the last backend (the physics is the renderer's no business), that
//   - every built-in scene run in the page ends in the same state hash as the native `carom run`
//     after --steps steps, or as FILE says (the scene_hashes example's `name hash steps` lines);
//   - the page's run with those drags, recorded, replays natively (`carom replay`) to the same
//     hash at every step, and a native recording (`carom record`) replays so in the page;
//   - the page logs no error.
// Screenshots and results.json go to the output folder. Exits 1 with the reason on the first
// failure.
//
// Two measurements run instead of the checks (give them a release build of carom):
// --frame-rates measures the frame rate of three scenes with each backend (frames 30 to 300)
// and their step times in the page and natively; --physics-speed steps three scenes in the
// page and by the native `carom run` on one thread, alternately for --rounds rounds, the mean
// step time of each. With --csv, the table the docs print goes to standard output as CSV and
// the rest to standard error (`carom-bench measure` keeps the table).

import { chromium } from "playwright-core";
import { execFileSync } from "node:child_process";
import fs from "node:fs";
import http from "node:http";
import path from "node:path";

const options = parseArguments(process.argv.slice(2), {
    site: "target/web",
    out: "target/web-test",
    carom: process.env.CAROM ?? "target/debug/carom",
    hashes: "",
    chromium: process.env.CHROMIUM ?? "/usr/bin/chromium",
    steps: "200",
    "frame-rates": false,
    "physics-speed": false,
    csv: false,
    rounds: "3",
    backends: "webgpu,gl",
});
// With --csv, standard output holds the table alone.
const table = options.csv ? (line) => process.stdout.write(`${line}\n`) : () => {};
if (options.csv) console.log = console.error;

/// What the page says it draws with, by the backend asked for.
const BACKENDS = { webgpu: "BrowserWebGpu", gl: "Gl" };
/// The backends as a table names them.
const BACKENDS_SHOWN = { webgpu: "WebGPU", gl: "WebGL2" };
const VIEW = { width: 1280, height: 720 };

class Failure extends Error {}
const check = (ok, message) => {
    if (!ok) throw new Failure(message);
};

const results = { started: new Date().toISOString(), checks: [] };
const passed = (what) => {
    console.log(`ok   ${what}`);
    results.checks.push(what);
};

fs.mkdirSync(options.out, { recursive: true });
const server = await serve(options.site);
const address = `http://127.0.0.1:${server.address().port}/`;
const browser = await chromium.launch({
    executablePath: options.chromium,
    args: [
        // As root (CI) Chromium needs no sandbox; this machine's network is closed, so
        // nothing may phone home.
        "--no-sandbox",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        // WebGL2 through SwiftShader, the software rasteriser Chromium ships.
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        // WebGPU through Dawn on SwiftShader's Vulkan: Chromium offers a CPU adapter only when
        // WebGPU is "unsafe", and a WebGPU canvas shows (rather than white) only when the
        // compositor runs on Vulkan too, there being no GL interop on SwiftShader.
        "--enable-unsafe-webgpu",
        "--enable-features=Vulkan,CDPScreenshotNewSurface",
        "--use-vulkan=swiftshader",
    ],
});
const errors = [];
let status = 0;
try {
    results.browser = browser.version();
    results.backends = {};
    if (options["physics-speed"]) {
        const page = await open();
        await physicsSpeed(page);
        await page.close();
    } else if (options["frame-rates"]) {
        await frameRates();
    } else {
        const backends = options.backends.split(",");
        for (const [i, backend] of backends.entries()) {
            check(backend in BACKENDS, `no backend ${backend}: ${Object.keys(BACKENDS)}`);
            const page = await open("", backend);
            await drawsTheDemo(page, backend);
            await dragsWithTheMouse(page, backend);
            await dragsWithAFinger(page, backend);
            if (i === backends.length - 1) {
                await recordingsCrossOver(page);
                await sameHashesAsNative(page);
            }
            // One page at a time: a second one drawing beside it would halve its frame rate.
            await page.close();
        }
    }
    check(errors.length === 0, `the page logged errors:\n  ${errors.join("\n  ")}`);
    passed("the page logged no error");
} catch (error) {
    status = 1;
    results.failure = error.message;
    console.error(`FAILED: ${error instanceof Failure ? error.message : error.stack}`);
    if (errors.length) console.error(`the page logged:\n  ${errors.join("\n  ")}`);
} finally {
    fs.writeFileSync(path.join(options.out, "results.json"), JSON.stringify(results, null, 2));
    await browser.close();
    server.close();
}
console.log(status === 0 ? `web build passed; screenshots in ${options.out}` : "web build FAILED");
process.exit(status);

// ---------------------------------------------------------------------------------------------

/// Opens the site (with `query`, drawing with `backend`) in a new page of 1280x720 with touch,
/// collecting its errors in `errors`, and waits for 30 frames.
async function open(query = "", backend = "webgpu") {
    const page = await browser.newPage({ viewport: VIEW, hasTouch: true });
    page.on("console", (message) => {
        if (message.type() === "error") errors.push(`console: ${message.text()}`);
    });
    page.on("pageerror", (error) => errors.push(`uncaught: ${error.message}`));
    page.on("requestfailed", (request) => errors.push(`request failed: ${request.url()}`));
    const params = new URLSearchParams(query);
    params.set("backend", backend);
    await page.goto(`${address}?${params}`);
    await waitForFrames(page, 30, 90_000);
    return page;
}

/// What the demo showed last ({} before the first frame).
async function probe(page) {
    const text = await page.evaluate(() => window.carom?.probe() ?? "");
    return text === "" ? {} : JSON.parse(text);
}

async function waitForFrames(page, count, timeout) {
    const start = (await probe(page)).frames ?? 0;
    const deadline = Date.now() + timeout;
    for (;;) {
        const state = await probe(page);
        if ((state.frames ?? 0) >= start + count) return state;
        if (errors.length) throw new Failure(`the page failed before drawing ${count} frames`);
        check(Date.now() < deadline, `fewer than ${count} frames in ${timeout / 1000} s`);
        await page.waitForTimeout(100);
    }
}

async function drawsTheDemo(page, backend) {
    const state = await probe(page);
    // wgpu names no WebGPU adapter (Chromium leaves its description empty): ask the page.
    const webgpu = await page.evaluate(async () => {
        const info = (await navigator.gpu?.requestAdapter())?.info;
        return info ? `${info.vendor} ${info.architecture}` : "";
    });
    const adapter = backend === "webgpu" ? `${webgpu}${state.adapter}` : state.adapter;
    results.backends[backend] = { adapter };
    console.log(`     ${backend}: drawing with ${adapter}`);
    check(state.adapter.endsWith(` on ${BACKENDS[backend]}`),
        `asked for ${backend}, the page draws with ${state.adapter}`);
    check(state.scene === "demos/grabbing.ron", `opened ${state.scene}, not the grabbing scene`);
    const shot = await screenshot(page, `${backend}-grabbing.png`);
    const sidebar = await pixelStats(page, shot, [0, 0, state.sidebar_css, VIEW.height]);
    const scene = await pixelStats(page, shot, [state.sidebar_css, 0, VIEW.width, VIEW.height]);
    results.backends[backend].pixels = { sidebar, scene };
    // Text is many small light marks on the dark panel; shapes are areas in several colours.
    check(sidebar.light > 0.01, `the sidebar shows no text (${pct(sidebar.light)} light pixels)`);
    check(scene.colors >= 8, `the scene is nearly blank (${scene.colors} colours)`);
    check(scene.changed > 0.02, `the scene is nearly blank (${pct(scene.changed)} drawn)`);
    passed(`${backend} draws: sidebar ${pct(sidebar.light)} text, scene ${scene.colors} colours, ` +
        `${pct(scene.changed)} drawn`);
}

/// Presses on a body, drags it `by` CSS pixels in `moves` steps and holds it there; checks it is
/// held and followed the pointer, then lets go. `pointer` does the pressing and moving.
async function drag(page, body, by, pointer, what) {
    const from = { x: body.x, y: body.y };
    const to = { x: from.x + by.x, y: from.y + by.y };
    await pointer.down(from);
    const moves = 30;
    for (let i = 1; i <= moves; i++) {
        await pointer.move({ x: from.x + (by.x * i) / moves, y: from.y + (by.y * i) / moves });
        await page.waitForTimeout(20);
    }
    // Let the spring pull it to the pointer: a second, and at least 60 frames, since a busy
    // machine draws fewer frames a second.
    await page.waitForTimeout(1000);
    const held = (await waitForFrames(page, 60, 60_000)).held;
    check(held, `${what}: no body is held after pressing on one at ${fmt(from)}`);
    const travelled = { x: held.x - from.x, y: held.y - from.y };
    const along = (travelled.x * by.x + travelled.y * by.y) / Math.hypot(by.x, by.y);
    const miss = Math.hypot(held.x - to.x, held.y - to.y);
    await screenshot(page, `${what.replaceAll(" ", "-")}.png`);
    await pointer.up(to);
    check(along > 0.8 * Math.hypot(by.x, by.y),
        `${what}: the body moved ${along.toFixed(0)} px along a ${Math.hypot(by.x, by.y)} px drag`);
    check(miss < 40, `${what}: the body is ${miss.toFixed(0)} px from the pointer`);
    // The release shows in the first frame drawn after it.
    check(!(await waitForFrames(page, 2, 30_000)).held,
        `${what}: the body is still held two frames after letting go`);
    passed(`${what}: the body followed the drag ${fmt(from)} -> ${fmt(to)} (held ${fmt(held)})`);
}

async function dragsWithTheMouse(page, backend) {
    const state = await probe(page);
    const body = nearest(state.bodies, { x: (state.sidebar_css + VIEW.width) / 2, y: 540 });
    const mouse = {
        down: async (at) => { await page.mouse.move(at.x, at.y); await page.mouse.down(); },
        move: (at) => page.mouse.move(at.x, at.y),
        up: async (at) => { await page.mouse.move(at.x, at.y); await page.mouse.up(); },
    };
    await drag(page, body, { x: 120, y: -220 }, mouse, `${backend} mouse drag`);
}

async function dragsWithAFinger(page, backend) {
    // Wait for the thrown body to come down, then take another one.
    await page.waitForTimeout(1500);
    const state = await probe(page);
    const body = nearest(state.bodies, { x: state.sidebar_css + 300, y: 560 });
    const cdp = await page.context().newCDPSession(page);
    const touch = (type, at) => cdp.send("Input.dispatchTouchEvent", {
        type,
        touchPoints: type === "touchEnd" ? [] : [{ x: at.x, y: at.y, id: 1 }],
    });
    const finger = {
        down: (at) => touch("touchStart", at),
        move: (at) => touch("touchMove", at),
        up: (at) => touch("touchEnd", at),
    };
    await drag(page, body, { x: 150, y: -180 }, finger, `${backend} touch drag`);
}

async function recordingsCrossOver(page) {
    check(fs.existsSync(options.carom), `no native carom at ${options.carom} (build it or pass --carom)`);
    // The page's run so far, with the two drags: replayed natively.
    await page.evaluate(() => window.carom.request_recording());
    await waitForFrames(page, 2, 30_000);
    const text = await page.evaluate(() => window.carom.recording());
    check(text.length > 0, "the page wrote no recording");
    const fromPage = path.join(options.out, "browser.run");
    fs.writeFileSync(fromPage, text);
    const native = JSON.parse(execFileSync(options.carom, ["replay", fromPage, "--json"]).toString());
    check(native.inputs >= 4, `the page's recording holds ${native.inputs} inputs, not the drags'`);
    check(native.parted_at === null,
        `the page's recording parts from its native replay at step ${native.parted_at}`);
    // A native recording of a pile of ragdolls: replayed in the page.
    const fromNative = path.join(options.out, "native.run");
    execFileSync(options.carom, ["record", "demos/ragdolls.ron", "--steps", "200", "--out", fromNative]);
    const web = JSON.parse(await page.evaluate((t) => window.carom.replay_run(t),
        fs.readFileSync(fromNative, "utf8")));
    check(web.parted_at === null, `the native recording parts from its replay in the page at ` +
        `step ${web.parted_at}`);
    results.recordings = { browser_to_native: native, native_to_browser: web };
    passed(`recordings cross over: the page's (${native.steps} steps, ${native.inputs} inputs) ` +
        `replays natively, and a native one (${web.steps} steps) in the page, every step's hash equal`);
}

async function sameHashesAsNative(page) {
    const files = (await page.evaluate(() => window.carom.scene_files())).split("\n");
    check(files.length >= 10, `only ${files.length} built-in scenes`);
    // Each scene's native hash and step count: from the scene_hashes example's lines when
    // given (CI has them already), else from the native `carom run`, --steps steps each.
    const known = new Map();
    if (options.hashes) {
        for (const line of fs.readFileSync(options.hashes, "utf8").trim().split("\n")) {
            const [name, hash, steps] = line.split(" ");
            known.set(`demos/${name}.ron`, { hash, steps: Number(steps) });
        }
    } else {
        check(fs.existsSync(options.carom), `no native carom at ${options.carom} (build it or pass --carom)`);
    }
    const rows = [];
    for (const file of files) {
        let native = known.get(file);
        if (options.hashes) {
            check(native !== undefined, `${options.hashes} has no hash for ${file}`);
        } else {
            const steps = Number(options.steps);
            const report = JSON.parse(execFileSync(options.carom,
                ["run", file, "--steps", String(steps), "--json", "--threads", "1"]).toString());
            native = { hash: report.hash, steps };
        }
        const web = JSON.parse(await page.evaluate(([f, s]) => window.carom.run_scene(f, s),
            [file, native.steps]));
        rows.push({ file, steps: native.steps, web: web.hash, native: native.hash });
    }
    results.hashes = { rows };
    const differ = rows.filter((row) => row.web !== row.native);
    check(differ.length === 0, `${differ.length} of ${rows.length} scenes end differently in the ` +
        `browser:\n  ` +
        differ.map((r) => `${r.file} after ${r.steps} steps: browser ${r.web}, native ${r.native}`)
            .join("\n  "));
    const counts = [...new Set(rows.map((row) => row.steps))].join(" or ");
    passed(`all ${rows.length} built-in scenes end in the native state hash after ${counts} steps`);
}

async function physicsSpeed(page) {
    const steps = Number(options.steps);
    // A round first, not counted: V8 runs a module's functions on a quick baseline compiler
    // until it has optimised the hot ones, several times slower.
    for (const scene of ["pyramid", "mixed_1000", "large_pyramid"]) {
        await page.evaluate(([f, s]) => window.carom.run_scene(f, s), [`demos/${scene}.ron`, steps]);
    }
    const rows = [];
    for (let round = 0; round < Number(options.rounds); round++) {
        for (const scene of ["pyramid", "mixed_1000", "large_pyramid"]) {
            const file = `demos/${scene}.ron`;
            const web = JSON.parse(await page.evaluate(([f, s]) => window.carom.run_scene(f, s),
                [file, steps]));
            const native = JSON.parse(execFileSync(options.carom,
                ["run", file, "--steps", String(steps), "--json", "--threads", "1"]).toString());
            check(web.hash === native.hash, `${scene}: the page ended in ${web.hash}, native in ` +
                `${native.hash}`);
            // The mean after the first step: the page's clock ticks in 0.1 ms, too coarse for
            // a median of steps that take less.
            const row = { round, scene, page_ms: web.ms_per_step, native_ms: native.ms_per_step };
            row.ratio = row.page_ms / row.native_ms;
            rows.push(row);
            console.log(`     round ${round + 1} ${scene}: page ${row.page_ms.toFixed(4)} ms, ` +
                `native ${row.native_ms.toFixed(4)} ms, page / native ${row.ratio.toFixed(2)}`);
        }
    }
    results.physics_speed = { steps, rows };
    table("scene,page ms/step,native ms/step,page / native,median of page / native");
    for (const scene of ["pyramid", "mixed_1000", "large_pyramid"]) {
        const of = rows.filter((row) => row.scene === scene);
        const ratios = of.map((row) => row.ratio).sort((a, b) => a - b);
        const middle = ratios.length >> 1;
        const median = ratios.length % 2 ? ratios[middle] : (ratios[middle - 1] + ratios[middle]) / 2;
        table([`\`${scene}\``, range(of.map((row) => row.page_ms)),
            range(of.map((row) => row.native_ms)), range(ratios), figure(median)].join(","));
    }
}

async function frameRates() {
    results.frame_rates = [];
    table("scene,bodies,backend,frames/s,simulated s / real s,page ms/step,native ms/step");
    for (const scene of ["grabbing", "pyramid", "mixed_1000"]) {
        const file = `demos/${scene}.ron`;
        for (const backend of options.backends.split(",")) {
            // Frames 30 to 300, as the native window's `--frames 300` report spans them.
            const page = await open(`?scene=${scene}`, backend);
            const first = await probe(page);
            const started = Date.now();
            const last = await waitForFrames(page, 300 - first.frames, 180_000);
            const seconds = (Date.now() - started) / 1000;
            const fps = (last.frames - first.frames) / seconds;
            const simulated = last.time - first.time;
            // The physics alone, after the frames: the mean of 120 steps from the scene's start.
            const physics = JSON.parse(await page.evaluate((f) => window.carom.run_scene(f, 120), file));
            await screenshot(page, `${scene}-${backend}.png`);
            await page.close();
            const native = JSON.parse(execFileSync(options.carom,
                ["run", file, "--steps", "120", "--json", "--threads", "1"]).toString());
            check(physics.hash === native.hash, `${scene}: the page ended in ${physics.hash}, ` +
                `native in ${native.hash}`);
            results.frame_rates.push({ scene, backend, fps, simulated_seconds: simulated, seconds,
                ms_per_step: physics.ms_per_step, native_ms_per_step: native.ms_per_step });
            console.log(`     ${scene} (${backend}): ${fps.toFixed(1)} frames/s over ` +
                `${seconds.toFixed(1)} s, ${simulated.toFixed(2)} s simulated, physics ` +
                `${physics.ms_per_step.toFixed(3)} ms/step, native ${native.ms_per_step.toFixed(3)}`);
            table([`\`${scene}\``, native.bodies, BACKENDS_SHOWN[backend], fps.toFixed(1),
                (simulated / seconds).toFixed(2), figure(physics.ms_per_step),
                figure(native.ms_per_step)].join(","));
        }
    }
}

/// A figure to three significant digits, and the range of a few as "low–high".
function figure(x) {
    return String(Number(x.toPrecision(3)));
}
function range(values) {
    const low = figure(Math.min(...values)), high = figure(Math.max(...values));
    return low === high ? low : `${low}–${high}`;
}

// ---------------------------------------------------------------------------------------------

async function screenshot(page, name) {
    const file = path.join(options.out, name);
    const png = await page.screenshot({ path: file });
    return png.toString("base64");
}

/// Of the screenshot's `box` [left, top, right, bottom] (CSS pixels): the share of light
/// pixels (text), of pixels unlike the most common colour (drawn), and how many colours
/// cover at least 20 pixels.
async function pixelStats(page, pngBase64, box) {
    return page.evaluate(async ([png, [left, top, right, bottom]]) => {
        const bytes = Uint8Array.from(atob(png), (c) => c.charCodeAt(0));
        const bitmap = await createImageBitmap(new Blob([bytes], { type: "image/png" }));
        const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
        const context = canvas.getContext("2d");
        context.drawImage(bitmap, 0, 0);
        const width = Math.round(right - left), height = Math.round(bottom - top);
        const data = context.getImageData(Math.round(left), Math.round(top), width, height).data;
        const counts = new Map();
        let light = 0;
        for (let i = 0; i < data.length; i += 4) {
            const key = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
            counts.set(key, (counts.get(key) ?? 0) + 1);
            if (data[i] + data[i + 1] + data[i + 2] > 3 * 150) light++;
        }
        const pixels = width * height;
        const background = Math.max(...counts.values());
        return {
            light: light / pixels,
            changed: 1 - background / pixels,
            colors: [...counts.values()].filter((n) => n >= 20).length,
        };
    }, [pngBase64, box]);
}

function nearest(bodies, to) {
    check(bodies?.length, "the probe lists no body in view");
    return bodies.reduce((best, b) =>
        Math.hypot(b.x - to.x, b.y - to.y) < Math.hypot(best.x - to.x, best.y - to.y) ? b : best);
}

/// A static server for `root` on 127.0.0.1 and a free port, wasm served as wasm.
async function serve(root) {
    check(fs.existsSync(path.join(root, "index.html")),
        `no site in ${root}: build it with crates/carom-web/build-site.sh`);
    const types = { ".html": "text/html", ".js": "text/javascript", ".wasm": "application/wasm" };
    const server = http.createServer((request, response) => {
        const wanted = new URL(request.url, "http://x").pathname.replace(/\/$/, "/index.html");
        const file = path.resolve(root, `.${decodeURIComponent(wanted)}`);
        fs.readFile(file, (error, data) => {
            if (error || !file.startsWith(path.resolve(root) + path.sep)) {
                response.writeHead(404);
                response.end();
                return;
            }
            response.writeHead(200, { "content-type": types[path.extname(file)] ?? "application/octet-stream" });
            response.end(data);
        });
    });
    await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
    return server;
}

function parseArguments(args, defaults) {
    const parsed = { ...defaults };
    for (let i = 0; i < args.length; i++) {
        const name = args[i].replace(/^--/, "");
        if (!(name in defaults)) {
            console.error(`unknown option ${args[i]}; options: ${Object.keys(defaults).join(", ")}`);
            process.exit(2);
        }
        parsed[name] = typeof defaults[name] === "boolean" ? true : args[++i];
    }
    return parsed;
}

function pct(share) {
    return `${(100 * share).toFixed(1)} %`;
}

function fmt(point) {
    return `(${point.x.toFixed(0)}, ${point.y.toFixed(0)})`;
}
