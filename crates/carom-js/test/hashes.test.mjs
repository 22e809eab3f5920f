// Determinism across platforms: every scene of demos/ stepped in the package ends in the same
// state hash as carom's native build. CAROM_SCENE_HASHES names the native hashes (the
// scene_hashes example's `name hash steps` lines); without it the suite skips this check.
import { test } from "node:test";
import assert from "node:assert/strict";
import fs from "node:fs";
import { carom } from "./load.mjs";

const file = process.env.CAROM_SCENE_HASHES;

test("every scene ends in the native hash", { skip: !file && "CAROM_SCENE_HASHES is not set" }, () => {
    const lines = fs.readFileSync(file, "utf8").trim().split("\n");
    const scenes = fs.readdirSync("demos").filter((f) => f.endsWith(".ron") && !f.endsWith("-saved.ron"));
    assert.equal(lines.length, scenes.length, `${file} lists every scene of demos/`);
    for (const line of lines) {
        const [name, native, count] = line.split(" ");
        const world = carom.World.fromScene(fs.readFileSync(`demos/${name}.ron`, "utf8"), `${name}.ron`);
        const steps = Number(count);
        assert.ok(steps > 0, `${file}: ${line}`);
        for (let i = 0; i < steps; i++) world.step();
        assert.equal(world.stateHash().toString(16).padStart(16, "0"), native, `${name} after ${steps} steps`);
        world.free();
    }
});
