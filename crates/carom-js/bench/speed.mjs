// carom-js's physics speed beside native carom and Rapier's JavaScript packages, one thread:
//   - three scenes of demos/ (pyramid, mixed_1000, large_pyramid) stepped by the package in
//     Node and by the native `carom run --threads 1`, ending in the same state hash;
//   - the two pyramids built from their recipe (one-metre boxes, friction 0.6, density 1, 4
//     substeps or solver iterations at 60 Hz, large_pyramid without sleeping) in Rapier's
//     packages, @dimforge/rapier2d-compat and its SIMD build, beside carom-js.
// Rounds alternate the engines; each figure is the mean step time after the first step. A
// round first, not counted, lets V8 compile the modules' hot functions fully (it starts them
// on a quick baseline compiler, several times slower).
//
//   npm ci --prefix crates/carom-js/bench
//   node crates/carom-js/bench/speed.mjs [--package target/carom-js/package]
//       [--carom target/release/carom] [--steps 200] [--rounds 3] [--csv]
//
// With --csv the table the docs print goes to standard output as CSV, each figure the range
// over the rounds, and the rounds to standard error (`carom-bench measure` keeps the table).
import { execFileSync } from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import { pathToFileURL } from "node:url";
import RAPIER from "@dimforge/rapier2d-compat";
import RAPIER_SIMD from "@dimforge/rapier2d-simd-compat";

const options = { package: "target/carom-js/package", carom: "target/release/carom", steps: "200", rounds: "3" };
let csv = false;
for (let i = 2; i < process.argv.length; i += 2) {
    if (process.argv[i] === "--csv") {
        csv = true;
        i--;
        continue;
    }
    const name = process.argv[i].replace(/^--/, "");
    if (!(name in options)) {
        console.error(`unknown option ${process.argv[i]}; options: ${Object.keys(options).join(", ")}, csv`);
        process.exit(2);
    }
    options[name] = process.argv[i + 1];
}
// With --csv, standard output holds the table alone.
const log = csv ? console.error : console.log;
const steps = Number(options.steps);
const carom = await import(pathToFileURL(path.resolve(options.package, "index.js")).href);
await RAPIER.init();
await RAPIER_SIMD.init();

/** Mean milliseconds per step of `step`, after the first. */
function time(step) {
    step();
    const started = performance.now();
    for (let i = 1; i < steps; i++) step();
    return (performance.now() - started) / (steps - 1);
}

function caromScene(name) {
    const world = carom.World.fromScene(fs.readFileSync(`demos/${name}.ron`, "utf8"), `${name}.ron`);
    const ms = time(() => world.step());
    const hash = world.stateHash().toString(16).padStart(16, "0");
    world.free();
    return { ms, hash };
}

function nativeScene(name) {
    const report = JSON.parse(execFileSync(options.carom,
        ["run", `demos/${name}.ron`, "--steps", String(steps), "--json", "--threads", "1"]).toString());
    return { ms: report.ms_per_step, hash: report.hash };
}

/** The pyramid recipe of demos/pyramid.ron (20 in the base) and large_pyramid.ron (100). */
const PYRAMIDS = { pyramid: { count: 20, ground: 40, sleep: true }, large_pyramid: { count: 100, ground: 100, sleep: false } };

function rapierPyramid(R, name) {
    const { count, ground, sleep } = PYRAMIDS[name];
    const world = new R.World({ x: 0, y: -10 });
    world.timestep = 1 / 60;
    world.integrationParameters.numSolverIterations = 4;
    const floor = world.createRigidBody(R.RigidBodyDesc.fixed().setTranslation(0, -1));
    world.createCollider(R.ColliderDesc.cuboid(ground, 1).setFriction(0.6), floor);
    for (let row = 0; row < count; row++) {
        const inRow = count - row;
        for (let column = 0; column < inRow; column++) {
            const body = world.createRigidBody(R.RigidBodyDesc.dynamic()
                .setTranslation(column - 0.5 * (inRow - 1), 0.5 + row).setCanSleep(sleep));
            world.createCollider(R.ColliderDesc.cuboid(0.5, 0.5).setFriction(0.6).setDensity(1), body);
        }
    }
    const ms = time(() => world.step());
    world.free();
    return { ms };
}

for (const scene of ["pyramid", "mixed_1000", "large_pyramid"]) {
    caromScene(scene);
    if (PYRAMIDS[scene]) {
        rapierPyramid(RAPIER, scene);
        rapierPyramid(RAPIER_SIMD, scene);
    }
}
const rows = [];
for (let round = 0; round < Number(options.rounds); round++) {
    for (const scene of ["pyramid", "mixed_1000", "large_pyramid"]) {
        const js = caromScene(scene);
        const native = nativeScene(scene);
        if (js.hash !== native.hash) {
            console.error(`${scene}: carom-js ended in ${js.hash}, native in ${native.hash}`);
            process.exit(1);
        }
        const row = { round, scene, carom_js: js.ms, native: native.ms };
        if (PYRAMIDS[scene]) {
            row.rapier_js = rapierPyramid(RAPIER, scene).ms;
            row.rapier_js_simd = rapierPyramid(RAPIER_SIMD, scene).ms;
        }
        rows.push(row);
        const f = (ms) => (ms === undefined ? "-" : ms.toFixed(3));
        log(`round ${round + 1} ${scene.padEnd(13)} carom-js ${f(row.carom_js)} ms, native ${f(row.native)} ms ` +
            `(${(row.carom_js / row.native).toFixed(2)}x), Rapier JS ${f(row.rapier_js)} ms, ` +
            `Rapier JS SIMD ${f(row.rapier_js_simd)} ms`);
    }
}
if (csv) {
    printTable(rows);
} else {
    console.log(JSON.stringify({ steps, rows }));
}

/** The installed version of an npm package of the bench. */
function version(name) {
    const manifest = path.join(import.meta.dirname, "node_modules", name, "package.json");
    return JSON.parse(fs.readFileSync(manifest, "utf8")).version;
}

/** The docs' table: per scene, each engine's range of ms per step over the rounds and the
 * range of the per-round ratios. */
function printTable(rows) {
    const figure = (x) => String(Number(x.toPrecision(3)));
    const range = (values) => {
        if (values.some((v) => v === undefined)) return "";
        const low = figure(Math.min(...values)), high = figure(Math.max(...values));
        return low === high ? low : `${low}–${high}`;
    };
    const rapier = `Rapier JS ${version("@dimforge/rapier2d-compat")}`;
    const simd = `Rapier JS SIMD ${version("@dimforge/rapier2d-simd-compat")}`;
    console.log(["scene", "carom-js (ms)", "native carom (ms)", "carom-js / native", `${rapier} (ms)`,
        `${simd} (ms)`, `${rapier} / carom-js`, `${simd} / carom-js`].join(","));
    for (const scene of ["pyramid", "mixed_1000", "large_pyramid"]) {
        const of = rows.filter((row) => row.scene === scene);
        const column = (key) => of.map((row) => row[key]);
        const ratio = (top, bottom) => of.map((row) =>
            row[top] === undefined ? undefined : row[top] / row[bottom]);
        console.log([scene, range(column("carom_js")), range(column("native")),
            range(ratio("carom_js", "native")), range(column("rapier_js")),
            range(column("rapier_js_simd")), range(ratio("rapier_js", "carom_js")),
            range(ratio("rapier_js_simd", "carom_js"))].join(","));
    }
}
