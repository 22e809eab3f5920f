//! The bodies and joints a scene's generators make (stacks, pyramids, grids, rooms, rain,
//! chains, groups), as batches added to a world together.

use crate::defs::{body_def, checked, shape, with_material};
use crate::pending_joint::{PendingJoint, Target, point};
use crate::scene::{BodySpec, Cells, Generator, JointKindSpec, JointSpec, Material, RevoluteSpec};
use carom::{
    BodyDef, BodyHandle, BodyKind, CaromError, ColliderDef, Real, Shape, Vec2, World, vec2,
};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

pub(crate) fn generator_name(generator: &Generator) -> &'static str {
    match generator {
        Generator::Stack { .. } => "stack",
        Generator::Pyramid { .. } => "pyramid",
        Generator::Grid { .. } => "grid",
        Generator::JointGrid { .. } => "joint grid",
        Generator::Room { .. } => "room",
        Generator::Rain { .. } => "rain",
        Generator::Repeat { .. } => "repeat",
        Generator::Chain { .. } => "chain",
        Generator::Group { .. } => "group",
    }
}

/// A batch's colours and copies that keep apart, body by body.
pub(crate) type BatchParts<'a> = (&'a [Option<(f32, f32, f32)>], &'a [Option<u32>]);

/// Adds a batch's bodies (`defs`, with their colours and the copies that keep apart, from
/// `parts`) to `world`: the bodies of copy `k` of a group that does not collide with itself
/// take collision group `-(1 + first_group + k)`. Returns their handles, in order.
pub(crate) fn add_bodies(
    world: &mut World,
    defs: impl IntoIterator<Item = BodyDef>,
    (batch_colors, apart): BatchParts<'_>,
    first_group: i32,
    colors: &mut HashMap<BodyHandle, (f32, f32, f32)>,
) -> Result<Vec<BodyHandle>, CaromError> {
    let mut handles = Vec::with_capacity(apart.len());
    for ((mut def, color), apart) in defs.into_iter().zip(batch_colors).zip(apart) {
        if let Some(copy) = apart {
            let group = -(1 + first_group + *copy as i32);
            for collider in &mut def.colliders {
                collider.filter.group = group;
            }
        }
        let handle = world.add_body(def)?;
        if let Some(color) = color {
            colors.insert(handle, *color);
        }
        handles.push(handle);
    }
    Ok(handles)
}

/// The bodies a generator makes, their colours, and the joints between them.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct Batch {
    pub defs: Vec<BodyDef>,
    pub colors: Vec<Option<(f32, f32, f32)>>,
    pub joints: Vec<PendingJoint>,
    /// Per body, the copy of a group that must not collide with itself it belongs to.
    pub apart: Vec<Option<u32>>,
}

impl Batch {
    /// How many copies of groups that keep apart it holds (each takes a collision group).
    pub fn copies_apart(&self) -> u32 {
        self.apart.iter().flatten().max().map_or(0, |&k| k + 1)
    }

    /// Bodies all of one material.
    fn of(defs: Vec<BodyDef>, material: &Material) -> Self {
        Batch {
            colors: vec![material.color; defs.len()],
            apart: vec![None; defs.len()],
            defs,
            joints: Vec::new(),
        }
    }
}

/// The bodies and joints a generator makes.
pub(crate) fn generate(generator: &Generator) -> Result<Batch, String> {
    let square =
        |size: Real| checked(Shape::rect(0.5 * size, 0.5 * size)).map_err(|e| e.to_string());
    let (defs, material) = match generator {
        Generator::Stack {
            base,
            count,
            size,
            offset,
            material,
        } => {
            let shape = square(*size)?;
            let defs = (0..*count)
                .map(|i| {
                    let shift = if i % 2 == 0 { *offset } else { -*offset };
                    let at = vec2(base.0 + shift, base.1 + (i as Real + 0.5) * size);
                    with_material(BodyDef::dynamic(shape.clone()).position(at), material)
                })
                .collect();
            (defs, *material)
        }
        Generator::Pyramid {
            base,
            count,
            size,
            rows,
            overlap,
            material,
        } => {
            if !(0.0..1.0).contains(overlap) {
                return Err(format!("overlap must be in [0, 1), got {overlap}"));
            }
            let shape = square(*size)?;
            // Centre to centre: a box, less the overlap.
            let pitch = size * (1.0 - overlap);
            let mut defs = Vec::new();
            for row in 0..rows.unwrap_or(*count).min(*count) {
                let in_row = count - row;
                for column in 0..in_row {
                    let x = base.0 + (column as Real - 0.5 * (in_row as Real - 1.0)) * pitch;
                    let y = base.1 + 0.5 * size + row as Real * pitch;
                    defs.push(with_material(
                        BodyDef::dynamic(shape.clone()).position(vec2(x, y)),
                        material,
                    ));
                }
            }
            (defs, *material)
        }
        Generator::Grid {
            origin,
            columns,
            rows,
            spacing,
            shape: one,
            shapes: cycle,
            count,
            kind: kind_name,
            material,
            awake,
            compound,
        } => {
            let shapes = match (one, cycle.is_empty()) {
                (Some(spec), true) => vec![shape(spec)?],
                (None, false) => cycle.iter().map(shape).collect::<Result<Vec<_>, _>>()?,
                (Some(_), false) => return Err("give `shape` or `shapes`, not both".into()),
                (None, true) => return Err("a grid needs a `shape` or `shapes`".into()),
            };
            let cells = columns.saturating_mul(*rows);
            let count = count.unwrap_or(cells);
            if count > cells {
                return Err(format!(
                    "count {count} is more than the {columns} x {rows} cells"
                ));
            }
            let cells = (0..count).map(|i| {
                let (row, column) = (i / columns, i % columns);
                let at = vec2(
                    origin.0 + column as Real * spacing.0,
                    origin.1 + row as Real * spacing.1,
                );
                (at, shapes[i as usize % shapes.len()].clone())
            });
            let defs = if *compound {
                let colliders: Vec<ColliderDef> = cells
                    .map(|(at, shape)| ColliderDef::new(shape).offset(at))
                    .collect();
                let Some(first) = colliders.first() else {
                    return Err("a compound grid needs at least one cell".into());
                };
                let mut def = BodyDef::new(*kind_name, first.shape.clone()).awake(*awake);
                def.colliders = colliders;
                vec![with_material(def, material)]
            } else {
                cells
                    .map(|(at, shape)| {
                        with_material(
                            BodyDef::new(*kind_name, shape).position(at).awake(*awake),
                            material,
                        )
                    })
                    .collect()
            };
            (defs, *material)
        }
        Generator::JointGrid {
            origin,
            columns,
            rows,
            spacing,
            shape: spec,
            material,
            fixed,
            joint,
        } => {
            let shape = shape(spec)?;
            return Ok(joint_grid(
                point(*origin),
                (*columns, *rows),
                point(*spacing),
                &shape,
                material,
                fixed,
                joint,
            ));
        }
        Generator::Rain {
            low,
            high,
            count,
            shape: spec,
            seed,
            material,
        } => {
            let shape = shape(spec)?;
            // xorshift64*: small, deterministic on every machine.
            let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
            let mut unit = move || {
                state ^= state >> 12;
                state ^= state << 25;
                state ^= state >> 27;
                (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as Real / (1u64 << 24) as Real
            };
            let defs = (0..*count)
                .map(|_| {
                    let at = vec2(
                        low.0 + (high.0 - low.0) * unit(),
                        low.1 + (high.1 - low.1) * unit(),
                    );
                    let angle = carom::consts::TAU * unit();
                    with_material(
                        BodyDef::dynamic(shape.clone()).position(at).angle(angle),
                        material,
                    )
                })
                .collect();
            (defs, *material)
        }
        Generator::Repeat {
            columns,
            rows,
            spacing,
            of,
        } => {
            let one = generate(of)?;
            if one.defs.is_empty() {
                // Copies of nothing: no need to walk the cells (which may be billions).
                return Ok(one);
            }
            let copies_apart = one.copies_apart();
            let mut all = Batch::default();
            for row in 0..*rows {
                for column in 0..*columns {
                    let copy = row * columns + column;
                    let apart = one.apart.iter().map(|k| k.map(|k| k + copy * copies_apart));
                    all.apart.extend(apart);
                    let shift = vec2(column as Real * spacing.0, row as Real * spacing.1);
                    let offset = all.defs.len();
                    all.defs.extend(one.defs.iter().cloned().map(|mut def| {
                        def.position += shift;
                        def
                    }));
                    all.colors.extend_from_slice(&one.colors);
                    all.joints
                        .extend(one.joints.iter().map(|j| j.shifted(shift, offset)));
                }
            }
            return Ok(all);
        }
        Generator::Chain {
            from,
            to,
            count,
            thickness,
            start,
            end,
            joint,
            material,
        } => {
            return chain(
                point(*from),
                point(*to),
                *count,
                *thickness,
                (start, end),
                joint,
                material,
            );
        }
        Generator::Group {
            bodies,
            joints,
            self_collide,
        } => return group(bodies, joints, *self_collide),
        Generator::Room {
            center,
            width,
            height,
            thickness,
            material,
        } => {
            let (c, w, h, t) = (vec2(center.0, center.1), *width, *height, *thickness);
            let wall = |half_w: Real, half_h: Real, dx: Real, dy: Real| {
                checked(Shape::rect(half_w, half_h))
                    .map(|s| {
                        with_material(BodyDef::static_body(s).position(c + vec2(dx, dy)), material)
                    })
                    .map_err(|e| e.to_string())
            };
            let defs = vec![
                wall(0.5 * w + t, 0.5 * t, 0.0, -0.5 * (h + t))?,
                wall(0.5 * w + t, 0.5 * t, 0.0, 0.5 * (h + t))?,
                wall(0.5 * t, 0.5 * h, -0.5 * (w + t), 0.0)?,
                wall(0.5 * t, 0.5 * h, 0.5 * (w + t), 0.0)?,
            ];
            (defs, *material)
        }
    };
    Ok(Batch::of(defs, &material))
}

/// A chain of `count` box links from `from` to `to`, each joined to the next at their shared
/// end, the first to `start` and the last to `end` (scene body names) if given.
fn chain(
    from: Vec2,
    to: Vec2,
    count: u32,
    thickness: Real,
    (start, end): (&Option<String>, &Option<String>),
    joint: &RevoluteSpec,
    material: &Material,
) -> Result<Batch, String> {
    if count == 0 {
        return Err("a chain needs at least one link".into());
    }
    let step = (to - from) / count as Real;
    let length = step.norm();
    let link = checked(Shape::rect(0.5 * length, 0.5 * thickness)).map_err(|e| e.to_string())?;
    let angle = carom::atan2(step.y, step.x);
    let defs: Vec<BodyDef> = (0..count)
        .map(|i| {
            let at = from + step * (i as Real + 0.5);
            with_material(
                BodyDef::dynamic(link.clone()).position(at).angle(angle),
                material,
            )
        })
        .collect();
    let spec = JointSpec {
        bodies: (String::new(), String::new()),
        kind: JointKindSpec::Revolute {
            limits: joint.limits,
            motor: joint.motor,
            spring: joint.spring,
            target_angle: joint.target_angle,
        },
        anchor: (0.0, 0.0),
        anchor_b: None,
        collide_connected: false,
        break_force: None,
        break_torque: None,
    };
    let n = count as usize;
    let mut joints = Vec::new();
    for i in 0..=n {
        let before = match i {
            0 => start.clone().map(Target::Named),
            _ => Some(Target::Local(i - 1)),
        };
        let after = match i {
            _ if i == n => end.clone().map(Target::Named),
            _ => Some(Target::Local(i)),
        };
        if let (Some(a), Some(b)) = (before, after) {
            let at = from + step * i as Real;
            joints.push(PendingJoint::with_targets(&spec, [a, b], at));
        }
    }
    Ok(Batch {
        joints,
        ..Batch::of(defs, material)
    })
}

/// `columns × rows` bodies made column by column, each hinged to the one before it in its
/// column and to its neighbour in the column before, at the midpoints (Box2D's joint grid).
fn joint_grid(
    origin: Vec2,
    (columns, rows): (u32, u32),
    spacing: Vec2,
    shape: &Shape,
    material: &Material,
    fixed: &[Cells],
    joint: &RevoluteSpec,
) -> Batch {
    let (n, m) = (columns as usize, rows as usize);
    let mut defs = Vec::with_capacity(n * m);
    let mut joints = Vec::with_capacity(2 * n * m);
    let at =
        |column: u32, row: u32| origin + vec2(column as Real * spacing.x, row as Real * spacing.y);
    for column in 0..columns {
        for row in 0..rows {
            let kind = if fixed.iter().any(|cells| cells.contains(column, row)) {
                BodyKind::Static
            } else {
                BodyKind::Dynamic
            };
            let here = at(column, row);
            let index = defs.len();
            defs.push(with_material(
                BodyDef::new(kind, shape.clone()).position(here),
                material,
            ));
            // Box2D's order: the joint up the column, then the one across from the column
            // before, each right after the body.
            if row > 0 {
                let mid = 0.5 * (at(column, row - 1) + here);
                joints.push(PendingJoint::hinge(joint, index - 1, index, mid));
            }
            if column > 0 {
                let mid = 0.5 * (at(column - 1, row) + here);
                joints.push(PendingJoint::hinge(joint, index - m, index, mid));
            }
        }
    }
    Batch {
        joints,
        ..Batch::of(defs, material)
    }
}

/// Bodies and joints defined together; a joint's names are looked up among the group's
/// bodies first, then the scene's.
fn group(bodies: &[BodySpec], joints: &[JointSpec], self_collide: bool) -> Result<Batch, String> {
    let mut batch = Batch::default();
    let mut local = HashMap::new();
    for (index, spec) in bodies.iter().enumerate() {
        let def = body_def(spec).map_err(|e| format!("body {index}: {e}"))?;
        if let Some(name) = &spec.name
            && local.insert(name.clone(), index).is_some()
        {
            return Err(format!("body {index}: the name {name:?} is used twice"));
        }
        batch.defs.push(def);
        batch.colors.push(spec.material.color);
        batch.apart.push((!self_collide).then_some(0));
    }
    let target = |name: &String| match local.get(name) {
        Some(&index) => Target::Local(index),
        None => Target::Named(name.clone()),
    };
    for spec in joints {
        let bodies = [target(&spec.bodies.0), target(&spec.bodies.1)];
        batch
            .joints
            .push(PendingJoint::with_targets(spec, bodies, Vec2::zeros()));
    }
    Ok(batch)
}
