//! Definitions read from JavaScript objects: shapes, colliders, bodies, chains, joints, world
//! settings, filters. Field names are the TypeScript types' (`types.d.ts`); what carom itself
//! checks (a shape's size, a joint's settings) it checks again when the object is added.

use crate::convert::{Fields, array, error, string_field, vec2};
use carom::{
    BodyDef, BodyHandle, BodyKind, Capacity, ChainDef, ColliderDef, CollisionFilter, ExplosionDef,
    JointDef, JointKind, QueryFilter, Real, Shape, Surface, Vec2, WorldSettings,
};
use wasm_bindgen::prelude::*;

/// A shape: `{ kind: "circle" | "box" | "capsule" | "segment" | "polygon", ... }`.
pub(crate) fn shape(value: &JsValue, what: &str) -> Result<Shape, JsError> {
    const KNOWN: &[&str] = &[
        "kind",
        "radius",
        "halfWidth",
        "halfHeight",
        "center1",
        "center2",
        "point1",
        "point2",
        "points",
    ];
    let f = Fields::new(value, what, KNOWN, false)?;
    let kind = f
        .string("kind")?
        .ok_or_else(|| error(&f.path("kind"), "missing"))?;
    // Each kind takes only its own fields.
    let only = |fields: &[&str]| -> Result<(), JsError> {
        match KNOWN
            .iter()
            .find(|k| **k != "kind" && !fields.contains(k) && f.value(k).is_some())
        {
            Some(k) => Err(error(&f.path(k), format!("not a field of a {kind}"))),
            None => Ok(()),
        }
    };
    let shape = match kind.as_str() {
        "circle" => {
            only(&["radius"])?;
            Shape::circle(f.required_real("radius")?)
        }
        "box" => {
            only(&["halfWidth", "halfHeight", "radius"])?;
            let (w, h) = (
                f.required_real("halfWidth")?,
                f.required_real("halfHeight")?,
            );
            match f.real("radius")? {
                Some(r) => Shape::rounded_rect(w, h, r),
                None => Shape::rect(w, h),
            }
        }
        "capsule" => {
            only(&["center1", "center2", "radius"])?;
            Shape::capsule(
                f.required_vec2("center1")?,
                f.required_vec2("center2")?,
                f.required_real("radius")?,
            )
        }
        "segment" => {
            only(&["point1", "point2"])?;
            Shape::segment(f.required_vec2("point1")?, f.required_vec2("point2")?)
        }
        "polygon" => {
            only(&["points", "radius"])?;
            let points = points(&f.required("points")?, &f.path("points"))?;
            let shape = Shape::hull(&points).map_err(|e| error(&f.path("points"), e))?;
            match (shape, f.real("radius")?) {
                (Shape::Polygon(polygon), Some(r)) => Shape::Polygon(polygon.rounded(r)),
                (shape, _) => shape,
            }
        }
        other => {
            return Err(error(
                &f.path("kind"),
                format!("unknown shape {other:?} (known: circle, box, capsule, segment, polygon)"),
            ));
        }
    };
    shape.validate().map_err(|e| error(what, e))?;
    Ok(shape)
}

/// An array of points.
fn points(value: &JsValue, what: &str) -> Result<Vec<Vec2>, JsError> {
    array(value, what)?
        .iter()
        .enumerate()
        .map(|(i, p)| vec2(p, &format!("{what}[{i}]")))
        .collect()
}

/// The fields of a collider besides its shape, shared with a body of one shape.
const COLLIDER_FIELDS: &[&str] = &[
    "offset",
    "angle",
    "density",
    "friction",
    "restitution",
    "rollingResistance",
    "tangentSpeed",
    "filter",
    "sensor",
    "hitEvents",
];

/// A collider: `{ shape, offset?, angle?, density?, friction?, ... }`.
pub(crate) fn collider(value: &JsValue, what: &str) -> Result<ColliderDef, JsError> {
    let known: Vec<&str> = COLLIDER_FIELDS.iter().copied().chain(["shape"]).collect();
    let f = Fields::new(value, what, &known, false)?;
    let shape = shape(&f.required("shape")?, &f.path("shape"))?;
    collider_fields(&f, ColliderDef::new(shape))
}

/// `def` with the collider fields `f` has.
fn collider_fields(f: &Fields, mut def: ColliderDef) -> Result<ColliderDef, JsError> {
    if let Some(offset) = f.vec2("offset")? {
        def = def.offset(offset);
    }
    if let Some(angle) = f.real("angle")? {
        def = def.angle(angle);
    }
    if let Some(density) = f.real("density")? {
        def = def.density(density);
    }
    let mut surface = Surface {
        friction: def.friction,
        restitution: def.restitution,
        rolling_resistance: def.rolling_resistance,
        tangent_speed: def.tangent_speed,
        material: def.material,
    };
    surface.friction = f.real("friction")?.unwrap_or(surface.friction);
    surface.restitution = f.real("restitution")?.unwrap_or(surface.restitution);
    surface.rolling_resistance = f
        .real("rollingResistance")?
        .unwrap_or(surface.rolling_resistance);
    surface.tangent_speed = f.real("tangentSpeed")?.unwrap_or(surface.tangent_speed);
    def = def.surface(surface);
    if let Some(value) = f.value("filter") {
        def = def.filter(collision_filter(&value, &f.path("filter"))?);
    }
    if let Some(sensor) = f.bool("sensor")? {
        def = def.sensor(sensor);
    }
    if let Some(hits) = f.bool("hitEvents")? {
        def = def.hit_events(hits);
    }
    def.validate().map_err(|e| error(&f.path("shape"), e))?;
    Ok(def)
}

/// A collision filter: `{ category?, mask?, group? }`.
pub(crate) fn collision_filter(value: &JsValue, what: &str) -> Result<CollisionFilter, JsError> {
    let f = Fields::new(value, what, &["category", "mask", "group"], false)?;
    let default = CollisionFilter::DEFAULT;
    Ok(CollisionFilter {
        category: f.bits("category")?.unwrap_or(default.category),
        mask: f.bits("mask")?.unwrap_or(default.mask),
        group: f.int("group")?.unwrap_or(default.group),
    })
}

/// A body's kind by its name.
pub(crate) fn body_kind(name: &str, what: &str) -> Result<BodyKind, JsError> {
    match name {
        "dynamic" => Ok(BodyKind::Dynamic),
        "static" => Ok(BodyKind::Static),
        "kinematic" => Ok(BodyKind::Kinematic),
        other => Err(error(
            what,
            format!("unknown body type {other:?} (known: dynamic, static, kinematic)"),
        )),
    }
}

/// A body kind's name.
pub(crate) fn body_kind_name(kind: BodyKind) -> &'static str {
    match kind {
        BodyKind::Dynamic => "dynamic",
        BodyKind::Static => "static",
        BodyKind::Kinematic => "kinematic",
    }
}

/// A body: `{ type?, position?, ..., shape? (with collider fields) | colliders? }`.
pub(crate) fn body(value: &JsValue) -> Result<BodyDef, JsError> {
    const WHAT: &str = "body definition";
    const BODY_FIELDS: &[&str] = &[
        "type",
        "position",
        "angle",
        "linearVelocity",
        "angularVelocity",
        "gravityScale",
        "linearDamping",
        "angularDamping",
        "bullet",
        "lookAhead",
        "awake",
        "fixedRotation",
        "sleepThreshold",
        "sweepThreshold",
        "shape",
        "colliders",
    ];
    let known: Vec<&str> = BODY_FIELDS.iter().chain(COLLIDER_FIELDS).copied().collect();
    let f = Fields::new(value, WHAT, &known, false)?;
    let kind = match f.string("type")? {
        Some(name) => body_kind(&name, &f.path("type"))?,
        None => BodyKind::Dynamic,
    };
    let colliders = match (f.value("shape"), f.array("colliders")?) {
        (Some(_), Some(_)) => {
            return Err(error(
                WHAT,
                "give either `shape` (one collider) or `colliders`, not both",
            ));
        }
        (Some(shape_value), None) => {
            let one = ColliderDef::new(shape(&shape_value, &f.path("shape"))?);
            vec![collider_fields(&f, one)?]
        }
        (None, colliders) => {
            if let Some(field) = COLLIDER_FIELDS.iter().find(|k| f.value(k).is_some()) {
                return Err(error(
                    &f.path(field),
                    "a collider's field: give it with `shape`, or in each of `colliders`",
                ));
            }
            colliders
                .unwrap_or_default()
                .iter()
                .enumerate()
                .map(|(i, c)| collider(c, &format!("{WHAT}.colliders[{i}]")))
                .collect::<Result<_, _>>()?
        }
    };
    let mut def = BodyDef::new(kind, Shape::circle(1.0));
    def.colliders = colliders;
    def.position = f.vec2("position")?.unwrap_or(def.position);
    def.angle = f.real("angle")?.unwrap_or(def.angle);
    def.linear_velocity = f.vec2("linearVelocity")?.unwrap_or(def.linear_velocity);
    def.angular_velocity = f.real("angularVelocity")?.unwrap_or(def.angular_velocity);
    def.gravity_scale = f.real("gravityScale")?.unwrap_or(def.gravity_scale);
    def.linear_damping = f.real("linearDamping")?.unwrap_or(def.linear_damping);
    def.angular_damping = f.real("angularDamping")?.unwrap_or(def.angular_damping);
    def.bullet = f.bool("bullet")?.unwrap_or(def.bullet);
    def.look_ahead = f.bool("lookAhead")?.unwrap_or(def.look_ahead);
    def.awake = f.bool("awake")?.unwrap_or(def.awake);
    def.fixed_rotation = f.bool("fixedRotation")?.unwrap_or(def.fixed_rotation);
    def.sleep_threshold = f.real("sleepThreshold")?.unwrap_or(def.sleep_threshold);
    // Infinity is a valid sweep threshold (never swept), so it is read as a plain number.
    if let Some(v) = f.value("sweepThreshold") {
        match v.as_f64() {
            Some(n) if !n.is_nan() => def.sweep_threshold = n as Real,
            _ => {
                return Err(error(
                    &f.path("sweepThreshold"),
                    "expected a number (Infinity never sweeps)",
                ));
            }
        }
    }
    Ok(def)
}

/// A static chain: `{ points, closed?, friction?, restitution?, filter? }`.
pub(crate) fn chain(value: &JsValue) -> Result<BodyDef, JsError> {
    const WHAT: &str = "chain definition";
    let f = Fields::new(
        value,
        WHAT,
        &["points", "closed", "friction", "restitution", "filter"],
        false,
    )?;
    let points = points(&f.required("points")?, &f.path("points"))?;
    let mut chain = if f.bool("closed")?.unwrap_or(false) {
        ChainDef::closed(points)
    } else {
        ChainDef::open(points)
    };
    if let Some(friction) = f.real("friction")? {
        chain = chain.friction(friction);
    }
    if let Some(restitution) = f.real("restitution")? {
        chain = chain.restitution(restitution);
    }
    if let Some(value) = f.value("filter") {
        chain = chain.filter(collision_filter(&value, &f.path("filter"))?);
    }
    BodyDef::static_chain(&chain).map_err(|e| error(WHAT, e))
}

/// A joint between `a` and `b`: `{ kind, ...its fields, ...the common ones }`.
pub(crate) fn joint(value: &JsValue, a: BodyHandle, b: BodyHandle) -> Result<JointDef, JsError> {
    const WHAT: &str = "joint definition";
    const COMMON: &[&str] = &[
        "kind",
        "collideConnected",
        "breakForce",
        "breakTorque",
        "limits",
        "motor",
        "spring",
        "springForce",
    ];
    const OWN: &[(&str, &[&str])] = &[
        ("distance", &["anchorA", "anchorB", "length"]),
        ("rope", &["anchorA", "anchorB", "length"]),
        ("revolute", &["anchor"]),
        ("prismatic", &["anchor", "axis"]),
        ("weld", &["anchor"]),
        ("wheel", &["anchor", "axis"]),
        ("motor", &["anchor", "maxForce", "maxTorque"]),
        ("mover", &["velocity", "maxForce"]),
        (
            "pogo",
            &[
                "groundPoint",
                "foot",
                "normal",
                "restLength",
                "maxCompression",
                "maxTension",
            ],
        ),
        ("filter", &[]),
    ];
    let kind = string_field(value, "kind", WHAT)?.ok_or_else(|| {
        error(
            &format!("{WHAT}.kind"),
            "missing: a joint needs its kind (distance, rope, revolute, prismatic, weld, \
             wheel, motor, mover, pogo, filter)",
        )
    })?;
    let own = OWN
        .iter()
        .find(|(name, _)| *name == kind)
        .map(|(_, own)| *own)
        .ok_or_else(|| {
            let known: Vec<&str> = OWN.iter().map(|(name, _)| *name).collect();
            error(
                &format!("{WHAT}.kind"),
                format!(
                    "unknown joint kind {kind:?} (known: {}; a mouse joint is made by \
                     World.createMouseJoint)",
                    known.join(", ")
                ),
            )
        })?;
    let known: Vec<&str> = COMMON.iter().chain(own).copied().collect();
    let f = Fields::new(value, WHAT, &known, false)?;
    let mut def = match kind.as_str() {
        "distance" => {
            let (anchor_a, anchor_b) = (f.required_vec2("anchorA")?, f.required_vec2("anchorB")?);
            let mut def = JointDef::distance(a, b, anchor_a, anchor_b);
            if let (Some(length), JointKind::Distance(joint)) = (f.real("length")?, &mut def.kind) {
                joint.length = length;
            }
            def
        }
        "rope" => JointDef::rope(
            a,
            b,
            f.required_vec2("anchorA")?,
            f.required_vec2("anchorB")?,
            f.required_real("length")?,
        ),
        "revolute" => JointDef::revolute(a, b, f.required_vec2("anchor")?),
        "prismatic" => {
            JointDef::prismatic(a, b, f.required_vec2("anchor")?, f.required_vec2("axis")?)
        }
        "weld" => JointDef::weld(a, b, f.required_vec2("anchor")?),
        "wheel" => JointDef::wheel(a, b, f.required_vec2("anchor")?, f.required_vec2("axis")?),
        "motor" => JointDef::motor(
            a,
            b,
            f.vec2("anchor")?.unwrap_or_else(Vec2::zeros),
            f.required_real("maxForce")?,
            f.required_real("maxTorque")?,
        ),
        "mover" => JointDef::mover(
            a,
            b,
            f.required_vec2("velocity")?,
            f.required_vec2("maxForce")?,
        ),
        "pogo" => JointDef::pogo(
            a,
            b,
            f.required_vec2("groundPoint")?,
            f.required_vec2("foot")?,
            f.required_vec2("normal")?,
            f.required_real("restLength")?,
            (
                f.required_real("maxCompression")?,
                f.required_real("maxTension")?,
            ),
        ),
        _ => JointDef::filter(a, b),
    };
    if let Some(collide) = f.bool("collideConnected")? {
        def = def.collide_connected(collide);
    }
    if let Some(force) = threshold(&f, "breakForce")? {
        def = def.break_force(force);
    }
    if let Some(torque) = threshold(&f, "breakTorque")? {
        def = def.break_torque(torque);
    }
    if let Some(value) = f.value("limits") {
        let limits = Fields::new(&value, &f.path("limits"), &["lower", "upper"], false)?;
        def = def.limits(
            limits.required_real("lower")?,
            limits.required_real("upper")?,
        );
    }
    if let Some(value) = f.value("motor") {
        let motor = Fields::new(&value, &f.path("motor"), &["speed", "maxForce"], false)?;
        def = def.motor_drive(
            motor.required_real("speed")?,
            motor.required_real("maxForce")?,
        );
    }
    if let Some(value) = f.value("spring") {
        let spring = Fields::new(&value, &f.path("spring"), &["hertz", "dampingRatio"], false)?;
        def = def.spring(
            spring.required_real("hertz")?,
            spring.required_real("dampingRatio")?,
        );
    }
    if let Some(value) = f.value("springForce") {
        let force = Fields::new(&value, &f.path("springForce"), &["lower", "upper"], false)?;
        def = def.spring_force(force.required_real("lower")?, force.required_real("upper")?);
    }
    Ok(def)
}

/// A break force or torque: a positive number, or `Infinity` for none.
fn threshold(f: &Fields, key: &str) -> Result<Option<Real>, JsError> {
    f.value(key)
        .map(|v| match v.as_f64() {
            Some(n) if n > 0.0 => Ok(n as Real),
            _ => Err(error(
                &f.path(key),
                "expected a positive number (Infinity: never breaks)",
            )),
        })
        .transpose()
}

/// World settings: `{ gravity?, substeps?, ... }`, `undefined` for the defaults.
pub(crate) fn settings(value: &JsValue) -> Result<WorldSettings, JsError> {
    let f = Fields::new(
        value,
        "world settings",
        &[
            "gravity",
            "substeps",
            "contactHertz",
            "jointHertz",
            "hitEventThreshold",
            "directJoints",
            "shockPropagation",
        ],
        true,
    )?;
    let mut settings = WorldSettings::default();
    settings.gravity = f.vec2("gravity")?.unwrap_or(settings.gravity);
    let solver = &mut settings.solver;
    if let Some(substeps) = f.int("substeps")? {
        solver.substeps = u32::try_from(substeps)
            .map_err(|_| error(&f.path("substeps"), "expected at least 1"))?;
    }
    solver.contact_hertz = f.real("contactHertz")?.unwrap_or(solver.contact_hertz);
    solver.joint_hertz = f.real("jointHertz")?.unwrap_or(solver.joint_hertz);
    solver.direct_joints = f.bool("directJoints")?.unwrap_or(solver.direct_joints);
    solver.shock_propagation = f
        .bool("shockPropagation")?
        .unwrap_or(solver.shock_propagation);
    settings.hit_event_threshold = f
        .real("hitEventThreshold")?
        .unwrap_or(settings.hit_event_threshold);
    Ok(settings)
}

/// A query's filter: `{ mask?, category?, excludeBody? }`, `undefined` for every collider.
/// `exclude` resolves the excluded body (a handle of the same world).
pub(crate) fn query_filter(
    value: &JsValue,
    exclude: impl FnOnce(&JsValue) -> Result<BodyHandle, JsError>,
) -> Result<QueryFilter, JsError> {
    let f = Fields::new(
        value,
        "query filter",
        &["mask", "category", "excludeBody"],
        true,
    )?;
    Ok(QueryFilter {
        mask: f.bits("mask")?.unwrap_or(u64::MAX),
        category: f.bits("category")?.unwrap_or(0),
        exclude_body: f.value("excludeBody").map(|v| exclude(&v)).transpose()?,
    })
}

/// An explosion: `{ center, radius, impulsePerLength, falloff?, mask? }`.
pub(crate) fn explosion(value: &JsValue) -> Result<ExplosionDef, JsError> {
    let f = Fields::new(
        value,
        "explosion",
        &["center", "radius", "impulsePerLength", "falloff", "mask"],
        false,
    )?;
    let mut def = ExplosionDef::new(
        f.required_vec2("center")?,
        f.required_real("radius")?,
        f.required_real("impulsePerLength")?,
    );
    if let Some(falloff) = f.real("falloff")? {
        def = def.falloff(falloff);
    }
    if let Some(mask) = f.bits("mask")? {
        def = def.mask(mask);
    }
    Ok(def)
}

/// Room to make: `{ bodies?, colliders?, contacts?, joints? }`, each a count (0 when left out).
pub(crate) fn capacity(value: &JsValue) -> Result<Capacity, JsError> {
    let f = Fields::new(
        value,
        "capacity",
        &["bodies", "colliders", "contacts", "joints"],
        false,
    )?;
    let count = |key: &str| match f.int(key)? {
        None => Ok(0),
        Some(n) => usize::try_from(n).map_err(|_| {
            error(
                &f.path(key),
                format!("expected a count of 0 or more, got {n}"),
            )
        }),
    };
    Ok(Capacity {
        bodies: count("bodies")?,
        colliders: count("colliders")?,
        contacts: count("contacts")?,
        joints: count("joints")?,
    })
}
