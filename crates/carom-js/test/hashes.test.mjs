// Determinism across platforms: every scene of demos/ stepped in the package ends in the same
// state hash as carom's native build. CAROM_SCENE_HASHES names the native hashes (the
// scene_hashes example's output, as .ci/run writes it: 40 steps, 8 for the four largest
// scenes); without it the suite skips this check.
import { test } from "node:test";
import assert from "node:assert/strict";
import fs from "node:fs";
import { carom } from "./load.mjs";

const file = process.env.CAROM_SCENE_HASHES;
const LARGE = new Set(["many_pyramids", "spinner", "large_pyramid", "joint_grid"]);

test("every scene ends in the native hash", { skip: !file && "CAROM_SCENE_HASHES is not set" }, () => {
    const lines = fs.readFileSync(file, "utf8").trim().split("\n");
    assert.ok(lines.length >= 30, `${file} lists ${lines.length} scenes`);
    for (const line of lines) {
        const [name, native] = line.split(" ");
        const world = carom.World.fromScene(fs.readFileSync(`demos/${name}.ron`, "utf8"), `${name}.ron`);
        const steps = LARGE.has(name) ? 8 : 40;
        for (let i = 0; i < steps; i++) world.step();
        assert.equal(world.stateHash().toString(16).padStart(16, "0"), native, `${name} after ${steps} steps`);
        world.free();
    }
});
