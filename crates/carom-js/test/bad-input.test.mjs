// What a user gets wrong: each mistake is an Error with a message that says what, never a
// trap, and the world goes on working after it.
import { test } from "node:test";
import assert from "node:assert/strict";
import { carom, withGround, box } from "./load.mjs";

const { World } = carom;

/** Asserts that `f` throws an Error whose message matches `pattern`. */
function throwsWith(f, pattern) {
    assert.throws(f, (e) => {
        assert.ok(e instanceof Error, `not an Error: ${e}`);
        assert.match(e.message, pattern);
        return true;
    });
}

test("bad definitions are errors that name the field", () => {
    const { world } = withGround();
    throwsWith(() => world.createBody({ shape: box(), desnity: 2 }), /unknown field `desnity`/);
    throwsWith(() => world.createBody({ shape: box(), position: { x: NaN, y: 0 } }), /position\.x: expected a finite number, got NaN/);
    throwsWith(() => world.createBody({ shape: box(), position: [1, 2] }), /position: expected a vector/);
    throwsWith(() => world.createBody({ shape: { kind: "triangle" } }), /unknown shape "triangle"/);
    throwsWith(() => world.createBody({ shape: { kind: "circle", radius: -1 } }), /radius/);
    throwsWith(() => world.createBody({ shape: { kind: "circle" } }), /shape\.radius: missing/);
    throwsWith(() => world.createBody({ shape: { kind: "circle", radius: 1, halfWidth: 2 } }), /halfWidth: not a field of a circle/);
    throwsWith(() => world.createBody({ type: "floating", shape: box() }), /unknown body type "floating"/);
    throwsWith(() => world.createBody({ shape: box(), colliders: [] }), /not both/);
    throwsWith(() => world.createBody("a box"), /expected an object, got the string "a box"/);
    throwsWith(() => world.createBody({ shape: box(), filter: { mask: -1 } }), /filter\.mask/);
    throwsWith(() => world.createBody({ shape: { kind: "polygon", points: [{ x: 0, y: 0 }, { x: 1, y: 0 }] } }), /points/);
    throwsWith(() => new World({ gravity: { x: 0, y: Infinity } }), /gravity\.y/);
    throwsWith(() => new World({ substeps: 0 }), /substeps/);
    const a = world.createBody({ shape: box(), position: { x: 0, y: 2 } });
    throwsWith(() => world.createJoint(a, a, { kind: "hinge" }), /unknown joint kind "hinge"/);
    throwsWith(() => world.createJoint(a, a, { anchor: { x: 0, y: 0 } }), /needs its kind/);
    throwsWith(() => world.createJoint(a, a, { kind: "weld", anchor: { x: 0, y: 0 }, axis: { x: 1, y: 0 } }), /unknown field `axis`/);
    throwsWith(() => world.createJoint(a, a, { kind: "revolute", anchor: { x: 0, y: 0 }, breakForce: -1 }), /breakForce/);
    throwsWith(() => world.step(NaN), /time step: expected a finite number/);
    throwsWith(() => a.setPosition({ x: 1 }), /position\.y/);
    throwsWith(() => a.applyForce({ x: 1, y: 1 }, { x: "1", y: 0 }), /point\.x.*string/);
    throwsWith(() => world.castRay({ x: 0, y: 0 }, { x: 1, y: 0 }, { excludeBody: "me" }), /excludeBody: expected a Body/);
    throwsWith(() => World.fromScene("(not a scene", "broken.ron"), /broken\.ron/);
    throwsWith(() => World.load("World(format: 1)"), /saved world/);
    world.step();
    assert.equal(world.stepCount(), 1, "the world still steps after every mistake");
    world.free();
});

test("a removed body's handle, a freed world's handles and another world's handles are errors", () => {
    const { world, ground } = withGround();
    const body = world.createBody({ shape: box(), position: { x: 0, y: 2 } });
    const collider = body.colliders()[0];
    world.removeBody(body);
    assert.equal(body.isValid(), false);
    throwsWith(() => body.position(), /this body was removed from its world/);
    throwsWith(() => collider.friction(), /this collider was removed from its world/);
    throwsWith(() => world.removeBody(body), /body/);
    const again = world.createBody({ shape: box(), position: { x: 0, y: 2 } });
    assert.equal(again.id, body.id, "the slot is reused");
    assert.equal(body.isValid(), false, "and the old handle does not reach the new body");
    assert.equal(again.equals(body), false);

    const other = new World();
    const stranger = other.createBody({ shape: box() });
    throwsWith(() => world.removeBody(stranger), /the body belongs to another world/);
    throwsWith(() => world.createJoint(ground, stranger, { kind: "weld", anchor: { x: 0, y: 0 } }), /body B belongs to another world/);
    throwsWith(() => world.castRay({ x: 0, y: 0 }, { x: 1, y: 0 }, { excludeBody: stranger }), /another world/);
    const snapshot = other.snapshot();
    throwsWith(() => world.restore(snapshot), /another world/);

    other.free();
    throwsWith(() => stranger.position(), /this body's world was freed/);
    throwsWith(() => other.step(), /null pointer|freed|destroyed/i);
    const newer = new World();
    assert.equal(stranger.isValid(), false, "a world made in the freed one's slot is not the old one");
    newer.free();
    snapshot.free();

    const freedHandle = world.createBody({ shape: box() });
    freedHandle.free();
    assert.throws(() => freedHandle.position(), "a freed handle object throws");
    assert.throws(() => world.removeBody(collider), "a collider is not a body");
    world.step();
    world.free();
});

test("freed and collected worlds release their memory", async () => {
    const before = World.liveCount();
    const worlds = Array.from({ length: 5 }, () => new World());
    assert.equal(World.liveCount(), before + 5);
    for (const w of worlds) w.free();
    assert.equal(World.liveCount(), before, "free() releases at once");
    assert.equal(typeof globalThis.gc, "function", "run the suite with node --expose-gc");
    (() => {
        for (let i = 0; i < 5; i++) new World().createBody({ shape: box() });
    })();
    assert.equal(World.liveCount(), before + 5);
    for (let i = 0; i < 50 && World.liveCount() > before; i++) {
        globalThis.gc();
        await new Promise((resolve) => setTimeout(resolve, 20));
    }
    assert.equal(World.liveCount(), before, "the garbage collector's finaliser releases them");
});
