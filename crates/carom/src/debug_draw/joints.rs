//! Joints drawn as Box2D draws them: anchors, links to the centres of mass, a slider's axis,
//! limits, and on request the reaction force.

use super::{Color, DebugDraw, DrawFlags, DrawOptions, palette};
use crate::dynamics::body::Body;
use crate::joint::{Joint, JointKind, Limits};
use crate::math::{Real, Rot, Vec2, vec2};
use crate::world::World;

/// Joint link and axis thickness, pixels.
const JOINT_WIDTH: f32 = 1.5;
/// Joint limit line and tick thickness, pixels: thicker than the links they cross.
const JOINT_LIMIT_WIDTH: f32 = 2.5;
/// Joint anchor diameter, pixels.
const JOINT_ANCHOR_SIZE: f32 = 3.0;
/// The longest reaction force arrow, m.
const MAX_FORCE_ARROW: Real = 2.0;

impl World {
    /// Draws every joint whose bodies are both there, and its reaction force if asked.
    pub(super) fn draw_joints(&self, options: &DrawOptions, out: &mut impl DebugDraw) {
        let flags = options.flags;
        for joint in self.joints() {
            let [a, b] = joint.bodies();
            let (Some(a), Some(b)) = (self.body(a), self.body(b)) else {
                continue;
            };
            if flags.contains(DrawFlags::JOINTS) {
                draw_joint(joint, a, b, options.joint_size, out);
            }
            // A filter joint applies no force. A mouse joint's does count: it is a real pull.
            if flags.contains(DrawFlags::JOINT_FORCES) && !matches!(joint.kind(), JointKind::Filter)
            {
                let arrow = joint.reaction_force() * options.force_scale;
                let length = arrow.norm();
                if length > 1e-4 {
                    let arrow = arrow * (MAX_FORCE_ARROW / length).min(1.0);
                    let at = joint.world_anchors(a, b)[1];
                    out.arrow(at, at + arrow, palette::JOINT_FORCE);
                }
            }
        }
    }
}

/// A joint's anchors, links, axis and limits, as Box2D draws them; `size` is
/// [`DrawOptions::joint_size`].
fn draw_joint(joint: &Joint, a: &Body, b: &Body, size: Real, out: &mut impl DebugDraw) {
    let [anchor_a, anchor_b] = joint.world_anchors(a, b);
    // Centre to anchor to anchor to centre: shows which bodies are joined and where.
    let chain = [a.center_of_mass(), anchor_a, anchor_b, b.center_of_mass()];
    let link = |out: &mut _| {
        for pair in chain.windows(2) {
            segment_unless_empty(pair[0], pair[1], JOINT_WIDTH, palette::JOINT, out);
        }
    };
    match joint.kind() {
        JointKind::Mouse(_) | JointKind::Filter => return,
        JointKind::Distance(distance) => {
            out.segment(anchor_a, anchor_b, JOINT_WIDTH, palette::JOINT);
            let apart = anchor_b - anchor_a;
            if let Some(limits) = distance.limits
                && apart.norm() > 1e-6
            {
                let along = apart.normalize();
                // A least length of 0 (a rope's) would put a tick on anchor A: nothing to say.
                if limits.lower > 0.0 {
                    let at = anchor_a + along * limits.lower;
                    tick(at, along, size, palette::JOINT_LOWER_LIMIT, out);
                }
                let at = anchor_a + along * limits.upper;
                tick(at, along, size, palette::JOINT_UPPER_LIMIT, out);
            }
        }
        JointKind::Revolute(revolute) => {
            link(out);
            if let Some(limits) = revolute.limits {
                // The joint's zero is A's rotation turned by the reference angle; the limits
                // turn on from there. B's own line meets a limit's when it reaches it, and is
                // drawn first so the limit's colour shows when they meet.
                let zero = a.rotation() * Rot::new(joint.reference_angle());
                let arm = vec2(size, 0.0);
                let b_line = anchor_b + b.rotation() * arm;
                out.segment(anchor_b, b_line, JOINT_WIDTH, palette::JOINT);
                for (angle, color) in [
                    (limits.lower, palette::JOINT_LOWER_LIMIT),
                    (limits.upper, palette::JOINT_UPPER_LIMIT),
                ] {
                    let end = anchor_a + zero * Rot::new(angle) * arm;
                    out.segment(anchor_a, end, JOINT_LIMIT_WIDTH, color);
                }
            }
        }
        JointKind::Prismatic(slider) => {
            draw_axis(a, anchor_a, slider.axis, slider.limits, size, out);
            link(out);
        }
        JointKind::Wheel(wheel) => {
            draw_axis(a, anchor_a, wheel.axis, wheel.limits, size, out);
            link(out);
        }
        JointKind::Weld(_) | JointKind::Motor(_) => link(out),
        // A mover drives B's centre: a dot there. A leg is a line from the ground to the foot.
        JointKind::Mover(_) => {
            out.point(b.center_of_mass(), 2.0 * JOINT_ANCHOR_SIZE, palette::JOINT)
        }
        JointKind::Pogo(_) => out.segment(anchor_a, anchor_b, JOINT_WIDTH, palette::JOINT),
    }
    out.point(anchor_a, JOINT_ANCHOR_SIZE, palette::JOINT_ANCHOR);
    out.point(anchor_b, JOINT_ANCHOR_SIZE, palette::JOINT_ANCHOR);
}

/// A prismatic or wheel joint's axis (`local_axis` in A's frame) through anchor A: from the
/// lower to the upper limit with a tick at each, or `size` either side without limits.
fn draw_axis(
    a: &Body,
    anchor_a: Vec2,
    local_axis: Vec2,
    limits: Option<Limits>,
    size: Real,
    out: &mut impl DebugDraw,
) {
    let axis = a.rotation() * local_axis;
    match limits {
        Some(limits) => {
            let lower = anchor_a + axis * limits.lower;
            let upper = anchor_a + axis * limits.upper;
            out.segment(lower, upper, JOINT_WIDTH, palette::JOINT_AXIS);
            tick(lower, axis, size, palette::JOINT_LOWER_LIMIT, out);
            tick(upper, axis, size, palette::JOINT_UPPER_LIMIT, out);
        }
        None => {
            let reach = axis * size;
            out.segment(
                anchor_a - reach,
                anchor_a + reach,
                JOINT_WIDTH,
                palette::JOINT_AXIS,
            );
        }
    }
}

/// A short line across unit direction `along` at `at`, marking a limit.
fn tick(at: Vec2, along: Vec2, size: Real, color: Color, out: &mut impl DebugDraw) {
    let across = vec2(-along.y, along.x) * (0.2 * size);
    out.segment(at - across, at + across, JOINT_LIMIT_WIDTH, color);
}

/// A segment, unless its ends coincide (a wheel's anchor on its centre): a renderer would
/// draw a stray dot.
fn segment_unless_empty(
    start: Vec2,
    end: Vec2,
    width: f32,
    color: Color,
    out: &mut impl DebugDraw,
) {
    if (end - start).norm_squared() > 1e-12 {
        out.segment(start, end, width, color);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::debug_draw::DrawList;
    use crate::debug_draw::sink::DrawSegment;
    use crate::debug_draw::tests::draw;
    use crate::{BodyDef, JointDef, JointHandle, Shape};

    /// A box hanging from a static bar by a hinge with limits, and a ball tied to the box by
    /// a sprung distance joint with limits; also the joints, to find their anchors.
    fn jointed() -> (World, JointHandle, JointHandle) {
        let mut world = World::new();
        let bar = world
            .add_body(BodyDef::static_body(Shape::rect(1.0, 0.2)).position(vec2(0.0, 5.0)))
            .unwrap();
        let boxed = world
            .add_body(BodyDef::dynamic(Shape::rect(0.25, 0.25)).position(vec2(0.0, 4.0)))
            .unwrap();
        let ball = world
            .add_body(BodyDef::dynamic(Shape::circle(0.2)).position(vec2(1.5, 4.0)))
            .unwrap();
        let hinge = JointDef::revolute(bar, boxed, vec2(0.0, 4.5)).limits(
            -crate::math::consts::FRAC_PI_4,
            crate::math::consts::FRAC_PI_2,
        );
        let hinge = world.add_joint(hinge).unwrap();
        let rod = JointDef::distance(boxed, ball, vec2(0.0, 4.0), vec2(1.5, 4.0))
            .spring(2.0, 0.5)
            .limits(1.0, 2.0);
        let rod = world.add_joint(rod).unwrap();
        (world, hinge, rod)
    }

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).norm() < 1e-5
    }

    #[test]
    fn joints_are_drawn_at_their_anchors() {
        let (world, _, _) = jointed();
        let list = draw(&world, DrawFlags::JOINTS);
        assert!(list.polygons.is_empty() && list.circles.is_empty() && list.arrows.is_empty());
        let hinge_at = vec2(0.0, 4.5);
        let (rod_a, rod_b) = (vec2(0.0, 4.0), vec2(1.5, 4.0));
        for at in [hinge_at, rod_a, rod_b] {
            assert!(
                list.points
                    .iter()
                    .any(|p| close(p.at, at) && p.color == palette::JOINT_ANCHOR),
                "an anchor point at {at:?}: {:?}",
                list.points
            );
        }
        // The hinge: bar's centre to the anchor, the anchor to the box's centre.
        let links: Vec<&DrawSegment> = list
            .segments
            .iter()
            .filter(|s| s.color == palette::JOINT)
            .collect();
        assert!(
            links
                .iter()
                .any(|s| close(s.start, vec2(0.0, 5.0)) && close(s.end, hinge_at))
        );
        assert!(
            links
                .iter()
                .any(|s| close(s.start, hinge_at) && close(s.end, vec2(0.0, 4.0)))
        );
        // The rod: anchor to anchor.
        assert!(
            links
                .iter()
                .any(|s| close(s.start, rod_a) && close(s.end, rod_b))
        );
        // The hinge's limits: from the anchor at -45° and 90° (the bar is level and the
        // reference angle 0).
        let limit = |color: Color| {
            list.segments
                .iter()
                .filter(|s| s.color == color && close(s.start, hinge_at))
                .map(|s| (s.end - s.start).normalize())
                .collect::<Vec<_>>()
        };
        let half = crate::math::consts::FRAC_1_SQRT_2;
        let lower = limit(palette::JOINT_LOWER_LIMIT);
        assert!(
            lower.len() == 1 && close(lower[0], vec2(half, -half)),
            "{lower:?}"
        );
        let upper = limit(palette::JOINT_UPPER_LIMIT);
        assert!(
            upper.len() == 1 && close(upper[0], vec2(0.0, 1.0)),
            "{upper:?}"
        );
        // The rod's limits: ticks across the line, 1 m and 2 m out from anchor A.
        for (color, x) in [
            (palette::JOINT_LOWER_LIMIT, 1.0),
            (palette::JOINT_UPPER_LIMIT, 2.0),
        ] {
            let tick = list
                .segments
                .iter()
                .find(|s| s.color == color && !close(s.start, hinge_at))
                .unwrap_or_else(|| panic!("a tick in {color:?}"));
            assert!(
                close((tick.start + tick.end) * 0.5, vec2(x, 4.0)),
                "{tick:?}"
            );
            assert!((tick.start.x - tick.end.x).abs() < 1e-6, "across the rod");
        }
        // Nothing of it is drawn without the flag, whatever else is.
        assert!(draw(&world, DrawFlags::NONE).is_empty());
        let mut others = DrawFlags::ALL;
        others.set(DrawFlags::JOINTS | DrawFlags::JOINT_FORCES, false);
        let off = draw(&world, others);
        let joint_colors = [
            palette::JOINT,
            palette::JOINT_ANCHOR,
            palette::JOINT_AXIS,
            palette::JOINT_LOWER_LIMIT,
            palette::JOINT_UPPER_LIMIT,
        ];
        assert!(
            off.segments
                .iter()
                .all(|s| !joint_colors.contains(&s.color))
        );
        assert!(off.points.iter().all(|p| !joint_colors.contains(&p.color)));
        assert!(!off.points.iter().any(|p| close(p.at, hinge_at)));
        let on = draw(&world, others | DrawFlags::JOINTS);
        assert_eq!(on.segments.len(), off.segments.len() + list.segments.len());
        assert_eq!(on.points.len(), off.points.len() + list.points.len());
    }

    #[test]
    fn axes_span_their_limits_and_mouse_and_filter_joints_draw_nothing() {
        let mut world = World::new();
        let bar = world
            .add_body(BodyDef::static_body(Shape::rect(1.0, 0.2)).position(vec2(0.0, 0.0)))
            .unwrap();
        let slider = world
            .add_body(BodyDef::dynamic(Shape::rect(0.2, 0.2)).position(vec2(0.0, 1.0)))
            .unwrap();
        world
            .add_joint(
                JointDef::prismatic(bar, slider, vec2(0.0, 1.0), vec2(1.0, 0.0)).limits(-0.5, 1.5),
            )
            .unwrap();
        world.add_joint(JointDef::filter(bar, slider)).unwrap();
        world
            .add_joint(JointDef::mouse(slider, vec2(0.1, 1.0), 100.0))
            .unwrap();
        let list = draw(&world, DrawFlags::JOINTS);
        let axis: Vec<&DrawSegment> = list
            .segments
            .iter()
            .filter(|s| s.color == palette::JOINT_AXIS)
            .collect();
        assert_eq!(axis.len(), 1);
        assert!(close(axis[0].start, vec2(-0.5, 1.0)) && close(axis[0].end, vec2(1.5, 1.0)));
        // Only the prismatic joint's two anchors: the mouse and filter joints add none.
        assert_eq!(list.points.len(), 2);
        assert!(list.points.iter().all(|p| close(p.at, vec2(0.0, 1.0))));
    }

    #[test]
    fn joint_forces_are_arrows_from_anchor_b_only_when_asked() {
        let (mut world, hinge, rod) = jointed();
        for _ in 0..10 {
            world.step(1.0 / 60.0).unwrap();
        }
        let without = draw(&world, DrawFlags::JOINTS);
        assert!(without.arrows.is_empty());
        let with = draw(&world, DrawFlags::JOINTS | DrawFlags::JOINT_FORCES);
        assert_eq!(with.segments, without.segments);
        assert_eq!(with.arrows.len(), 2, "{:?}", with.arrows);
        for (arrow, joint) in with.arrows.iter().zip([hinge, rod]) {
            let joint = world.joint(joint).unwrap();
            let [a, b] = joint.bodies().map(|h| world.body(h).unwrap());
            let at = joint.world_anchors(a, b)[1];
            assert!(close(arrow.start, at), "{arrow:?} from {at:?}");
            assert_eq!(arrow.color, palette::JOINT_FORCE);
            let expected = joint.reaction_force() * DrawOptions::default().force_scale;
            assert!(close(arrow.end - arrow.start, expected), "{arrow:?}");
        }
        // The hinge holds the box and the ball up.
        assert!(with.arrows[0].end.y > with.arrows[0].start.y);
        let forces_only = draw(&world, DrawFlags::JOINT_FORCES);
        assert!(forces_only.segments.is_empty() && forces_only.points.is_empty());
        assert_eq!(forces_only.arrows, with.arrows);
    }

    #[test]
    fn force_arrows_are_capped() {
        let (mut world, _, _) = jointed();
        world.step(1.0 / 60.0).unwrap();
        let mut list = DrawList::new();
        let options = DrawOptions {
            flags: DrawFlags::JOINT_FORCES,
            force_scale: 1e3,
            ..DrawOptions::default()
        };
        world.debug_draw(&options, |_| None, &mut list);
        // The hinge holds about 10 N: 10 km at this scale, without the cap.
        let lengths: Vec<Real> = list
            .arrows
            .iter()
            .map(|a| (a.end - a.start).norm())
            .collect();
        assert!((lengths[0] - MAX_FORCE_ARROW).abs() < 1e-4, "{lengths:?}");
        assert!(
            lengths.iter().all(|&l| l < MAX_FORCE_ARROW + 1e-4),
            "{lengths:?}"
        );
    }
}
