// The package's API from Node: what a user does with worlds, bodies, colliders, joints,
// queries, events, scenes, saves and snapshots.
import { test } from "node:test";
import assert from "node:assert/strict";
import fs from "node:fs";
import { carom, withGround, box } from "./load.mjs";

const { World } = carom;
const near = (a, b, tolerance, what) =>
    assert.ok(Math.abs(a - b) <= tolerance, `${what}: ${a} is not within ${tolerance} of ${b}`);

test("a box dropped on the ground comes to rest on it", () => {
    const { world } = withGround();
    const body = world.createBody({ shape: box(), position: { x: 0, y: 4 } });
    assert.equal(body.type(), "dynamic");
    near(body.mass(), 1, 1e-6, "a 1 m box of density 1");
    for (let i = 0; i < 180; i++) world.step(1 / 60);
    near(body.position().y, 0.5, 0.02, "resting height");
    near(body.linearVelocity().y, 0, 0.01, "vertical speed at rest");
    near(world.time(), 3, 1e-6, "simulated time (steps of 1/60 s in single precision)");
    assert.equal(world.stepCount(), 180);
    world.free();
});

test("bodies, colliders and transforms list what was made", () => {
    const { world, ground } = withGround({ gravity: { x: 0, y: -9.81 } });
    assert.deepEqual(world.gravity(), { x: 0, y: Math.fround(-9.81) });
    const ball = world.createBody({
        shape: { kind: "circle", radius: 0.25 },
        position: { x: 2, y: 1 },
        angle: 0.5,
        density: 2,
    });
    const extra = world.createCollider(ball, {
        shape: { kind: "capsule", center1: { x: -0.5, y: 0 }, center2: { x: 0.5, y: 0 }, radius: 0.1 },
        offset: { x: 0, y: 0.3 },
        friction: 0.1,
    });
    assert.equal(world.bodyCount(), 2);
    assert.equal(ball.colliders().length, 2);
    assert.ok(extra.body().equals(ball));
    assert.equal(extra.shapeType(), "capsule");
    near(extra.friction(), 0.1, 1e-6, "friction");
    assert.ok(ball.mass() > 2 * Math.PI * 0.25 ** 2, "the capsule adds mass");
    const transforms = world.transforms();
    assert.ok(transforms instanceof Float32Array);
    assert.equal(transforms.length, 3 * world.bodyCount());
    const order = world.bodies();
    assert.ok(order[0].equals(ground) && order[1].equals(ball));
    near(transforms[3], 2, 1e-6, "x");
    near(transforms[5], 0.5, 1e-6, "angle");
    world.removeCollider(extra);
    assert.equal(ball.colliders().length, 1);
    assert.equal(extra.isValid(), false);
    world.free();
});

test("a revolute pendulum keeps its length and a motor turns a wheel", () => {
    const { world, ground } = withGround();
    const bob = world.createBody({ shape: { kind: "circle", radius: 0.2 }, position: { x: 3, y: 5 } });
    const pivot = { x: 0, y: 5 };
    const joint = world.createJoint(ground, bob, { kind: "revolute", anchor: pivot });
    assert.equal(joint.kind(), "revolute");
    for (let i = 0; i < 120; i++) {
        world.step();
        const p = bob.position();
        near(Math.hypot(p.x - pivot.x, p.y - pivot.y), 3, 0.01, `length at step ${i}`);
    }
    assert.ok(joint.reactionForce().y > 0, "the pivot holds the bob up");
    const wheel = world.createBody({ shape: { kind: "circle", radius: 0.5 }, position: { x: -5, y: 5 } });
    world.createJoint(ground, wheel, {
        kind: "revolute",
        anchor: { x: -5, y: 5 },
        motor: { speed: 3, maxForce: 1000 },
    });
    for (let i = 0; i < 30; i++) world.step();
    near(wheel.angularVelocity(), 3, 0.01, "the motor's speed");
    world.removeJoint(joint);
    assert.equal(joint.isValid(), false);
    assert.equal(world.joints().length, 1);
    world.free();
});

test("every joint kind can be made", () => {
    const { world, ground } = withGround();
    const a = world.createBody({ shape: box(), position: { x: 0, y: 2 } });
    const b = world.createBody({ shape: box(), position: { x: 2, y: 2 } });
    const defs = [
        { kind: "distance", anchorA: { x: 0, y: 2 }, anchorB: { x: 2, y: 2 }, spring: { hertz: 2, dampingRatio: 0.5 } },
        { kind: "rope", anchorA: { x: 0, y: 2 }, anchorB: { x: 2, y: 2 }, length: 3 },
        { kind: "revolute", anchor: { x: 1, y: 2 }, limits: { lower: -0.5, upper: 0.5 } },
        { kind: "prismatic", anchor: { x: 1, y: 2 }, axis: { x: 1, y: 0 } },
        { kind: "weld", anchor: { x: 1, y: 2 } },
        { kind: "wheel", anchor: { x: 1, y: 2 }, axis: { x: 0, y: 1 } },
        { kind: "motor", maxForce: 10, maxTorque: 5 },
        { kind: "mover", velocity: { x: 1, y: 0 }, maxForce: { x: 100, y: 100 } },
        { kind: "filter" },
    ];
    for (const def of defs) assert.equal(world.createJoint(a, b, def).kind(), def.kind === "rope" ? "distance" : def.kind);
    const pogo = world.createJoint(ground, a, {
        kind: "pogo", groundPoint: { x: 0, y: 0 }, foot: { x: 0, y: 1.5 }, normal: { x: 0, y: 1 },
        restLength: 1, maxCompression: 100, maxTension: 0,
    });
    assert.equal(pogo.kind(), "pogo");
    const mouse = world.createMouseJoint(b, { x: 2, y: 2 }, 1000);
    mouse.setTarget({ x: 2, y: 3 });
    assert.equal(mouse.kind(), "mouse");
    for (let i = 0; i < 60; i++) world.step();
    assert.equal(world.joints().length, defs.length + 2);
    for (const body of world.bodies()) assert.ok(Number.isFinite(body.position().x));
    world.free();
});

test("contact, sensor, hit and joint-break events report what happened", () => {
    const { world, ground } = withGround();
    const falling = world.createBody({ shape: box(), position: { x: 0, y: 3 }, hitEvents: true });
    const sensor = world.createBody({
        type: "static", shape: box(1), position: { x: 0, y: 1.5 }, sensor: true,
    });
    const seen = { begin: 0, sensor: 0, hits: 0 };
    for (let i = 0; i < 90; i++) {
        world.step();
        for (const e of world.contactEvents()) {
            if (e.type === "begin") {
                seen.begin++;
                assert.ok(
                    (e.bodyA.equals(falling) && e.bodyB.equals(ground)) ||
                    (e.bodyA.equals(ground) && e.bodyB.equals(falling)));
            }
        }
        for (const e of world.sensorEvents()) {
            assert.ok(e.sensor.body().equals(sensor));
            if (e.type === "begin") seen.sensor++;
        }
        for (const hit of world.hitEvents()) {
            seen.hits++;
            assert.ok(hit.approachSpeed > 1);
            near(hit.point.y, 0, 0.05, "where it hit");
        }
    }
    assert.equal(seen.begin, 1, "one contact began");
    assert.equal(seen.sensor, 1, "the box entered the sensor once");
    assert.ok(seen.hits >= 1, "the landing was a hit");

    const weight = world.createBody({ shape: box(), position: { x: 5, y: 5 }, density: 50 });
    const link = world.createJoint(ground, weight, { kind: "weld", anchor: { x: 5, y: 5.5 }, breakForce: 100 });
    let broken = [];
    for (let i = 0; i < 10 && broken.length === 0; i++) {
        world.step();
        broken = world.jointEvents();
    }
    assert.equal(broken.length, 1, "the overloaded weld broke");
    assert.equal(broken[0].type, "broken");
    assert.ok(broken[0].joint.equals(link));
    assert.equal(link.isValid(), false);
    world.free();
});

test("queries find what is there", () => {
    const { world, ground } = withGround();
    const target = world.createBody({ shape: box(), position: { x: 3, y: 0.5 }, awake: false });
    const hit = world.castRay({ x: 3, y: 10 }, { x: 0, y: -20 });
    assert.ok(hit.body.equals(target));
    near(hit.point.y, 1, 1e-4, "the ray meets the top of the box");
    near(hit.normal.y, 1, 1e-6, "normal");
    near(hit.fraction, 0.45, 1e-4, "fraction");
    const past = world.castRay({ x: 3, y: 10 }, { x: 0, y: -20 }, { excludeBody: target });
    assert.ok(past.body.equals(ground), "excluding the box, the ray meets the ground");
    assert.equal(world.castRayAll({ x: 3, y: 10 }, { x: 0, y: -20 }).length, 2);
    assert.equal(world.castRay({ x: 30, y: 10 }, { x: 0, y: -20 }), undefined);
    const swept = world.castShape({ kind: "circle", radius: 0.5 }, { x: 3, y: 10 }, 0, { x: 0, y: -20 });
    assert.ok(swept.body.equals(target));
    near(swept.fraction, 0.425, 1e-3, "a ball of radius 0.5 touches the box's top");
    assert.equal(world.overlapAabb({ x: 2.9, y: 0.4 }, { x: 3.1, y: 0.6 }).length, 1);
    assert.equal(world.overlapShape({ kind: "circle", radius: 0.1 }, { x: 3, y: 0.5 }, 0).length, 1);
    assert.ok(world.bodyAt({ x: 3, y: 0.5 }).equals(target));
    assert.ok(world.bodyAt({ x: 10, y: -0.2 }).equals(ground));
    assert.equal(world.bodyAt({ x: 0, y: 50 }), undefined);
    const pushed = world.explode({ center: { x: 2, y: 0.5 }, radius: 3, impulsePerLength: 5 });
    assert.equal(pushed, 1);
    assert.ok(target.linearVelocity().x > 0, "the explosion pushes the box away");
    world.free();
});

test("room made ahead of time is reported and changes nothing", () => {
    const run = (reserve) => {
        const { world } = withGround();
        if (reserve) world.reserve({ bodies: 50, colliders: 50, contacts: 200 });
        for (let i = 0; i < 10; i++) {
            world.createBody({ shape: box(), position: { x: 0.1 * i, y: 1 + 1.1 * i } });
        }
        for (let i = 0; i < 60; i++) world.step(1 / 60);
        const result = { hash: world.stateHash(), highWater: world.highWater() };
        world.free();
        return result;
    };
    const plain = run(false);
    const reserved = run(true);
    assert.equal(reserved.hash, plain.hash, "the same bits with room made");
    assert.equal(plain.highWater.bodies, 11, "the ground and ten boxes");
    assert.ok(plain.highWater.contacts >= 10, `a stack's contacts: ${plain.highWater.contacts}`);
    assert.deepEqual(reserved.highWater, { bodies: 50, colliders: 50, contacts: 200, joints: 0 });
    const world = new World();
    assert.throws(() => world.reserve({ bodies: -1 }), /capacity\.bodies/);
    assert.throws(() => world.reserve({ bodys: 1 }), /unknown field `bodys`/);
    assert.throws(() => world.reserve({ joints: 1.5 }), /capacity\.joints/);
    world.free();
});

test("a snapshot restored and a saved world loaded go on bit for bit", () => {
    const { world } = withGround();
    for (let i = 0; i < 5; i++) {
        world.createBody({ shape: box(0.4), position: { x: i * 0.3, y: 1 + i }, angle: i });
    }
    for (let i = 0; i < 30; i++) world.step();
    const snapshot = world.snapshot();
    assert.equal(snapshot.stepCount(), 30);
    assert.ok(snapshot.heapBytes() > 0);
    const saved = world.save();
    for (let i = 0; i < 60; i++) world.step();
    const after = world.stateHash();
    assert.equal(typeof after, "bigint");
    world.restore(snapshot);
    assert.equal(world.stepCount(), 30);
    for (let i = 0; i < 60; i++) world.step();
    assert.equal(world.stateHash(), after, "restored and stepped again: the same state");
    const loaded = World.load(saved);
    for (let i = 0; i < 60; i++) loaded.step();
    assert.equal(loaded.stateHash(), after, "saved, loaded and stepped: the same state");
    snapshot.free();
    loaded.free();
    world.free();
});

test("a scene from its RON text steps with its names and timed events", () => {
    const text = fs.readFileSync("demos/pyramid.ron", "utf8");
    const one = World.fromScene(text, "pyramid.ron");
    const two = World.fromScene(text, "pyramid.ron");
    assert.ok(one.bodyCount() > 10);
    near(one.timeStep(), 1 / 60, 1e-6, "the scene's time step");
    for (let i = 0; i < 50; i++) {
        one.step();
        two.step();
    }
    assert.equal(one.stateHash(), two.stateHash(), "two runs of one scene agree");
    one.free();
    two.free();
    const named = World.fromScene(fs.readFileSync("demos/pendulum.ron", "utf8"), "pendulum.ron");
    const bob = named.bodyNamed("bob");
    assert.equal(bob.type(), "dynamic");
    assert.equal(named.bodyNamed("pivot").type(), "static");
    assert.equal(named.bodyNamed("no such body"), undefined);
    const y = bob.position().y;
    named.step();
    assert.notEqual(bob.position().y, y, "the bob swings");
    named.free();
});

test("the package reports its version", () => {
    const manifest = JSON.parse(fs.readFileSync(new URL("../package/package.json", import.meta.url)));
    assert.equal(carom.version(), manifest.version);
});

test("chains, filters, sensors' overlaps, body types and forces do what they say", () => {
    const world = new World();
    // A chain collides on the right of its direction: right to left, its top is solid.
    const track = world.createChain({
        points: [{ x: 10, y: 0 }, { x: 0, y: -1 }, { x: -10, y: 0 }],
        friction: 0.8,
    });
    assert.equal(track.type(), "static");
    assert.equal(track.colliders().length, 2);
    assert.equal(track.colliders()[0].shapeType(), "chainSegment");
    const ball = world.createBody({ shape: { kind: "circle", radius: 0.5 }, position: { x: -5, y: 3 } });
    for (let i = 0; i < 240; i++) world.step();
    assert.ok(ball.position().y > -1 && ball.position().y < 0.5, "the ball rolls along the chain");

    const ghost = world.createBody({ shape: box(), position: { x: 0, y: 10 }, filter: { category: 2, mask: 0 } });
    assert.deepEqual(ghost.colliders()[0].filter(), { category: 2n, mask: 0n, group: 0 });
    for (let i = 0; i < 120; i++) world.step();
    assert.ok(ghost.position().y < -5, "a collider that collides with nothing falls through the chain");
    ghost.colliders()[0].setFilter({ mask: 2n ** 64n - 1n });
    assert.equal(ghost.colliders()[0].filter().mask, 2n ** 64n - 1n);

    const zone = world.createBody({ type: "static", shape: { kind: "circle", radius: 3 },
        position: { x: 20, y: 0 }, sensor: true });
    const visitor = world.createBody({ shape: box(), position: { x: 20, y: 0 }, gravityScale: 0 });
    world.step();
    const overlaps = zone.colliders()[0].sensorOverlaps();
    assert.equal(overlaps.length, 1);
    assert.ok(overlaps[0].body().equals(visitor));
    assert.equal(zone.colliders()[0].isSensor(), true);

    visitor.setType("kinematic");
    assert.equal(visitor.type(), "kinematic");
    assert.equal(visitor.mass(), 0);
    visitor.setLinearVelocity({ x: 1, y: 0 });
    world.step(0.5);
    near(visitor.position().x, 20.5, 1e-5, "a kinematic body moves at its velocity");
    visitor.setType("dynamic");
    visitor.setLinearVelocity({ x: 0, y: 0 });
    visitor.applyImpulse({ x: 2, y: 0 });
    near(visitor.linearVelocity().x, 2 / visitor.mass(), 1e-5, "an impulse at the centre");
    visitor.applyAngularImpulse(visitor.inertia());
    near(visitor.angularVelocity(), 1, 1e-5, "an angular impulse");
    const local = visitor.localPoint({ x: 21, y: 0.5 });
    const back = visitor.worldPoint(local);
    near(back.x, 21, 1e-5, "local and world points round-trip");
    near(back.y, 0.5, 1e-5, "local and world points round-trip");
    const edge = visitor.velocityAt(visitor.worldPoint({ x: 0, y: 1 }));
    near(Math.hypot(edge.x - visitor.linearVelocity().x, edge.y - visitor.linearVelocity().y), 1, 1e-4,
        "a point 1 m from the centre moves at 1 m/s more");

    world.setGravity({ x: 0, y: 0 });
    assert.deepEqual(world.gravity(), { x: 0, y: 0 });
    world.free();
});

test("bodies at rest fall asleep, and waking one wakes it", () => {
    const { world } = withGround();
    const body = world.createBody({ shape: box(), position: { x: 0, y: 0.5 } });
    for (let i = 0; i < 120 && !body.isSleeping(); i++) world.step();
    assert.equal(body.isSleeping(), true);
    body.wakeUp();
    assert.equal(body.isSleeping(), false);
    for (let i = 0; i < 120 && !body.isSleeping(); i++) world.step();
    world.wakeAll();
    assert.equal(body.isSleeping(), false);
    world.free();
});
