//! A scene's shapes, materials and bodies as carom's definitions, each checked.

use crate::scene::{BodySpec, Material, ShapeSpec};
use carom::{BodyDef, CaromError, ChainDef, ColliderDef, Real, Shape, Surface, Vec2, vec2};

/// The shape of a single collider (a chain makes several: [`colliders_of`] builds those), or
/// what is wrong with it.
pub(crate) fn shape(spec: &ShapeSpec) -> Result<Shape, String> {
    if let ShapeSpec::Chain { .. } = spec {
        return Err(
            "a chain can be a body's shape or one of its colliders, not a generator's \
                    shape"
                .into(),
        );
    }
    single_shape(spec).map_err(|e| e.to_string())
}

#[allow(
    clippy::unreachable,
    reason = "its one caller, `shape`, answers chains with an error before calling it"
)]
fn single_shape(spec: &ShapeSpec) -> Result<Shape, CaromError> {
    let points =
        |points: &[(Real, Real)]| points.iter().map(|&(x, y)| vec2(x, y)).collect::<Vec<_>>();
    let rounded = |shape: Shape, radius: Real| match shape {
        Shape::Polygon(p) if radius != 0.0 => checked(Shape::Polygon(p.rounded(radius))),
        shape => Ok(shape),
    };
    match spec {
        ShapeSpec::Circle { radius } => checked(Shape::circle(*radius)),
        ShapeSpec::Box { width, height } => checked(Shape::rect(0.5 * width, 0.5 * height)),
        ShapeSpec::RoundedBox {
            width,
            height,
            radius,
        } => {
            let fits = radius.is_finite() && *radius >= 0.0 && 2.0 * radius < width.min(*height);
            if !fits {
                return Err(CaromError::OutOfRange {
                    name: "rounded box radius",
                    expected: "at least 0 and less than half the width and half the height",
                    value: *radius,
                });
            }
            checked(Shape::rounded_rect(
                0.5 * width - radius,
                0.5 * height - radius,
                *radius,
            ))
        }
        ShapeSpec::Capsule { length, radius } => checked(Shape::capsule(
            vec2(-0.5 * length, 0.0),
            vec2(0.5 * length, 0.0),
            *radius,
        )),
        ShapeSpec::Regular {
            sides,
            radius,
            rounding,
        } => rounded(Shape::regular(*sides as usize, *radius)?, *rounding),
        ShapeSpec::Polygon { points: p, radius } => rounded(Shape::polygon(&points(p))?, *radius),
        ShapeSpec::Hull { points: p, radius } => rounded(Shape::hull(&points(p))?, *radius),
        ShapeSpec::Segment { from, to, radius } => {
            let (from, to) = (vec2(from.0, from.1), vec2(to.0, to.1));
            if *radius == 0.0 {
                checked(Shape::segment(from, to))
            } else {
                checked(Shape::capsule(from, to, *radius))
            }
        }
        ShapeSpec::Chain { .. } => unreachable!("chains are made by `colliders_of`"),
    }
}

/// The colliders a shape makes, with `base`'s placement and material: one, or a chain's links.
fn colliders_of(spec: &ShapeSpec, base: ColliderDef) -> Result<Vec<ColliderDef>, String> {
    match spec {
        ShapeSpec::Chain { points, closed } => {
            let points: Vec<Vec2> = points.iter().map(|&(x, y)| vec2(x, y)).collect();
            let chain = if *closed {
                ChainDef::closed(points)
            } else {
                ChainDef::open(points)
            };
            Ok(chain
                .segments()
                .map_err(|e| e.to_string())?
                .into_iter()
                .map(|link| ColliderDef {
                    shape: Shape::ChainSegment(link),
                    density: 0.0,
                    ..base.clone()
                })
                .collect())
        }
        _ => Ok(vec![ColliderDef {
            shape: shape(spec)?,
            ..base
        }]),
    }
}

/// The shape, if it is valid: checked here so the error can name its place in the file.
pub(crate) fn checked(shape: Shape) -> Result<Shape, CaromError> {
    shape.validate()?;
    Ok(shape)
}

pub(crate) fn with_material(def: BodyDef, material: &Material) -> BodyDef {
    def.filter(material.filter)
        .density(material.density)
        .surface(surface(material))
        .damping(material.damping.0, material.damping.1)
}

/// The surface a material gives.
fn surface(material: &Material) -> Surface {
    Surface {
        friction: material.friction,
        restitution: material.restitution,
        rolling_resistance: material.rolling_resistance,
        tangent_speed: material.tangent_speed,
        material: 0,
    }
}

/// A body's definition; a collider that is both a sensor and one-way is refused.
pub(crate) fn body_def(spec: &BodySpec) -> Result<BodyDef, String> {
    let flags = spec.shape.iter().map(|_| (spec.sensor, spec.one_way));
    let parts = spec.colliders.iter().map(|part| {
        (
            part.sensor.unwrap_or(spec.sensor),
            part.one_way.unwrap_or(spec.one_way),
        )
    });
    if flags
        .chain(parts)
        .any(|(sensor, one_way)| sensor && one_way)
    {
        return Err("a sensor never collides, so it cannot be one_way".into());
    }
    body_def_of(spec)
}

/// [`body_def`], its flags checked. A one-way collider is shown to the pre-solve hook, which
/// [`crate::one_way`] installs.
fn body_def_of(spec: &BodySpec) -> Result<BodyDef, String> {
    let material = &spec.material;
    let mut colliders = Vec::with_capacity(spec.colliders.len() + 1);
    // Placeholder shapes: `colliders` puts each spec's own in.
    let placeholder = || ColliderDef::new(Shape::circle(1.0));
    if let Some(first) = &spec.shape {
        colliders.extend(colliders_of(
            first,
            placeholder()
                .density(material.density)
                .surface(surface(material))
                .filter(material.filter)
                .sensor(spec.sensor)
                .pre_solve(spec.one_way),
        )?);
    }
    for part in &spec.colliders {
        colliders.extend(colliders_of(
            &part.shape,
            placeholder()
                .offset(vec2(part.offset.0, part.offset.1))
                .angle(part.angle)
                .density(part.density.unwrap_or(material.density))
                .surface(surface(material))
                .friction(part.friction.unwrap_or(material.friction))
                .restitution(part.restitution.unwrap_or(material.restitution))
                .filter(part.filter.unwrap_or(material.filter))
                .sensor(part.sensor.unwrap_or(spec.sensor))
                .pre_solve(part.one_way.unwrap_or(spec.one_way)),
        )?);
    }
    let Some(first) = colliders.first() else {
        return Err(CaromError::NoCollider.to_string());
    };
    let mut def = BodyDef::new(spec.kind, first.shape.clone())
        .position(vec2(spec.position.0, spec.position.1))
        .angle(spec.angle)
        .linear_velocity(vec2(spec.linear_velocity.0, spec.linear_velocity.1))
        .angular_velocity(spec.angular_velocity)
        .damping(material.damping.0, material.damping.1)
        .bullet(spec.bullet)
        .look_ahead(spec.look_ahead)
        .fixed_rotation(spec.fixed_rotation)
        .awake(spec.awake)
        .sleep_threshold(spec.sleep_threshold);
    def.colliders = colliders;
    Ok(def)
}
