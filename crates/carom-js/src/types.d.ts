/** A point or a vector, in metres (or m/s, N...). */
export interface Vec2 { x: number; y: number }

/** An axis-aligned box. */
export interface Aabb { min: Vec2; max: Vec2 }

/** How a body moves: under forces, not at all, or at the velocity it is given. */
export type BodyType = "dynamic" | "static" | "kinematic";

/** A shape, centred on its body's origin unless its collider gives an offset. */
export type ShapeDef =
    | { kind: "circle"; radius: number }
    /** A box of half extents, its corners rounded by `radius` when given. */
    | { kind: "box"; halfWidth: number; halfHeight: number; radius?: number }
    | { kind: "capsule"; center1: Vec2; center2: Vec2; radius: number }
    | { kind: "segment"; point1: Vec2; point2: Vec2 }
    /** The convex hull of the points (at most 8 corners), rounded by `radius` when given. */
    | { kind: "polygon"; points: Vec2[]; radius?: number };

/**
 * Which colliders collide: each one's category must be in the other's mask, unless they
 * share a group (a positive group always collides within itself, a negative one never).
 * Bits as numbers up to 2^53 or bigints.
 */
export interface CollisionFilter { category?: number | bigint; mask?: number | bigint; group?: number }

/** A collider's filter as read back: its bits as bigints. */
export interface CollisionFilterOut { category: bigint; mask: bigint; group: number }

/** A collider's material, placement and flags (everything but its shape). */
export interface ColliderFields {
    /** Where the shape's centre sits in the body's frame. Default (0, 0). */
    offset?: Vec2;
    /** How the shape is turned in the body's frame, radians. Default 0. */
    angle?: number;
    /** kg/m². Default 1. */
    density?: number;
    /** Default 0.6. */
    friction?: number;
    /** Default 0. */
    restitution?: number;
    rollingResistance?: number;
    /** A conveyor belt's speed along its surface, m/s. */
    tangentSpeed?: number;
    filter?: CollisionFilter;
    /** Reports overlaps (`World.sensorEvents`) and never collides. */
    sensor?: boolean;
    /** Reports hard hits (`World.hitEvents`). */
    hitEvents?: boolean;
}

/** A collider: a shape with its material. */
export interface ColliderDef extends ColliderFields { shape: ShapeDef }

/**
 * A body. Give it one shape (`shape`, with the collider fields beside it) or several
 * (`colliders`). Everything else is optional.
 */
export interface BodyDef extends ColliderFields {
    /** Default "dynamic". */
    type?: BodyType;
    position?: Vec2;
    angle?: number;
    linearVelocity?: Vec2;
    angularVelocity?: number;
    gravityScale?: number;
    linearDamping?: number;
    angularDamping?: number;
    /** Swept against moving bodies too (fast projectiles). */
    bullet?: boolean;
    /** Start asleep with `false` (a pile at rest costs nothing until touched). */
    awake?: boolean;
    fixedRotation?: boolean;
    sleepThreshold?: number;
    /** Infinity: never swept by continuous collision. */
    sweepThreshold?: number;
    shape?: ShapeDef;
    colliders?: ColliderDef[];
}

/**
 * A static chain of segments for ground and tracks. Its links collide on their right side,
 * seen walking along the points: ground runs from right to left, a counter-clockwise loop is
 * solid outside.
 */
export interface ChainDef {
    points: Vec2[];
    /** A loop (the last point joins the first). Default false. */
    closed?: boolean;
    friction?: number;
    restitution?: number;
    filter?: CollisionFilter;
}

/** What every joint takes besides its kind's own fields; each applies to the kinds that have it. */
export interface JointCommon {
    /** Whether the two bodies still collide with each other. Default false. */
    collideConnected?: boolean;
    /** The force that breaks it, N (it is then removed: `World.jointEvents`). */
    breakForce?: number;
    breakTorque?: number;
    limits?: { lower: number; upper: number };
    motor?: { speed: number; maxForce: number };
    spring?: { hertz: number; dampingRatio: number };
    /** A distance joint's spring force bounds, N. */
    springForce?: { lower: number; upper: number };
}

/** A joint; anchors and axes in world coordinates. */
export type JointDef = JointCommon & (
    | { kind: "distance"; anchorA: Vec2; anchorB: Vec2; length?: number }
    | { kind: "rope"; anchorA: Vec2; anchorB: Vec2; length: number }
    | { kind: "revolute"; anchor: Vec2 }
    | { kind: "prismatic"; anchor: Vec2; axis: Vec2 }
    | { kind: "weld"; anchor: Vec2 }
    | { kind: "wheel"; anchor: Vec2; axis: Vec2 }
    | { kind: "motor"; anchor?: Vec2; maxForce: number; maxTorque: number }
    | { kind: "mover"; velocity: Vec2; maxForce: Vec2 }
    | { kind: "pogo"; groundPoint: Vec2; foot: Vec2; normal: Vec2; restLength: number; maxCompression: number; maxTension: number }
    | { kind: "filter" }
);

/** A world's settings, all optional. */
export interface WorldSettings {
    /** m/s². Default (0, -10). */
    gravity?: Vec2;
    /** Solver substeps per step. Default 4. */
    substeps?: number;
    /** Contact stiffness, Hz. Default 30. */
    contactHertz?: number;
    /** Joint stiffness, Hz. Default 60. */
    jointHertz?: number;
    /** The approach speed above which hits are reported, m/s. Default 1. */
    hitEventThreshold?: number;
    /** Solve joint trees directly (stiff chains and ragdolls). Default false. */
    directJoints?: boolean;
    /** Solve stacks from the ground up (tall stacks, heavy on light). Default false. */
    shockPropagation?: boolean;
}

/** Which colliders a query sees. Default: every one. */
export interface QueryFilter {
    /** The categories seen. */
    mask?: number | bigint;
    /** The query's own category, for colliders whose mask chooses what finds them. */
    category?: number | bigint;
    /** A body whose colliders are not seen (the caster's own). */
    excludeBody?: Body;
}

/** Where a ray or a cast shape meets a collider. */
export interface CastHit {
    body: Body;
    collider: Collider;
    point: Vec2;
    /** The collider's outward normal there. */
    normal: Vec2;
    /** How far along the translation, 0 to 1. */
    fraction: number;
}

/** An explosion's centre, reach and strength. */
/** Counts of what a world holds: what `World.reserve` makes room for, `World.highWater` reports. */
export interface Capacity {
    /** Bodies of every kind. Default 0. */
    bodies?: number;
    /** Colliders, sensors included. Default 0. */
    colliders?: number;
    /** Contacts: pairs of colliders whose enlarged boxes overlap, touching or not. Default 0. */
    contacts?: number;
    /** Joints. Default 0. */
    joints?: number;
}

export interface ExplosionDef {
    center: Vec2;
    radius: number;
    /** N·s per metre of a body's outline facing the centre. */
    impulsePerLength: number;
    /** How far beyond `radius` the push fades to nothing, m. Default 0. */
    falloff?: number;
    /** Which categories it pushes. Default all. */
    mask?: number | bigint;
}

/** Two colliders began or stopped touching. */
export interface ContactEvent { type: "begin" | "end"; colliderA: Collider; colliderB: Collider; bodyA: Body; bodyB: Body }

/** A collider began or stopped overlapping a sensor. */
export interface SensorEvent { type: "begin" | "end"; sensor: Collider; visitor: Collider }

/** Two colliders struck each other faster than the world's hit threshold. */
export interface HitEvent { colliderA: Collider; colliderB: Collider; point: Vec2; normal: Vec2; approachSpeed: number }

/** A joint broke (pulled harder than its break force or torque) and was removed. */
export interface JointEvent { type: "broken"; joint: Joint; bodyA: Body; bodyB: Body; force: Vec2; torque: number }
