//! Contact manifolds: where two shapes touch, as at most two points.
//!
//! For two polygons the tutorial's construction: the *reference* edge is the face most
//! perpendicular to the contact normal (the separating-axis face), the *incident* edge is the
//! other polygon's edge most anti-parallel to it, and the incident edge is clipped against the
//! two side planes through the reference edge's ends. Each surviving point sits midway between
//! the two surfaces and carries its separation (negative = penetration) and a [`FeatureId`]
//! naming the reference and incident vertices it came from, which stays the same from step to
//! step while the same features touch, so the solver can warm start from last step's impulses.
//!
//! Points are kept up to a speculative margin *apart*: a pair about to touch already has
//! points with positive separation, which lets the solver stop a fast body at the surface.
//! Where a face meets a face (or a circle), the margin may reach further, by how far the pair
//! can close this step: such a point's normal stays the normal while the bodies close, so
//! stopping the approach along it stops a real impact. Facing corners, and an edge beyond the
//! end of the face, keep the plain margin: their normal turns as the bodies pass, and a
//! speculative point there would stop bodies that were only going to graze past (a ghost
//! collision).

use super::distance::{self, PolygonFeature};
use crate::constants::LINEAR_SLOP;
use crate::constants::{REFERENCE_TOLERANCE, SPURIOUS_TOLERANCE};
use crate::geometry::segment::closest_between_segments;
use crate::geometry::shape::WorldShape;
use crate::math::{Real, Vec2};

/// Which features of the two shapes produced a contact point.
///
/// Built from the reference and incident vertex indices (and whether B held the reference
/// face); equal ids on consecutive steps mean the same point, so impulses can carry over.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FeatureId(u32);

impl FeatureId {
    const FLIPPED: u32 = 1 << 31;
    const VERTEX_PAIR: u32 = 1 << 30;
    const INDEX_BITS: u32 = 15;
    const INDEX_MASK: u32 = (1 << Self::INDEX_BITS) - 1;

    /// The id of the single point of a contact involving a circle.
    pub const SINGLE: FeatureId = FeatureId(0);

    /// A clipped point: reference vertex and incident vertex, and whether the reference face
    /// belongs to B.
    pub fn clipped(reference_on_b: bool, reference_vertex: usize, incident_vertex: usize) -> Self {
        let flag = if reference_on_b { Self::FLIPPED } else { 0 };
        FeatureId(
            flag | (reference_vertex as u32 & Self::INDEX_MASK) << Self::INDEX_BITS
                | (incident_vertex as u32 & Self::INDEX_MASK),
        )
    }

    /// Two corners facing each other: A's vertex and B's vertex.
    pub fn vertex_pair(vertex_a: usize, vertex_b: usize) -> Self {
        FeatureId(
            Self::VERTEX_PAIR
                | (vertex_a as u32 & Self::INDEX_MASK) << Self::INDEX_BITS
                | (vertex_b as u32 & Self::INDEX_MASK),
        )
    }

    /// The packed value.
    pub fn raw(self) -> u32 {
        self.0
    }
}

/// One point of contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ManifoldPoint {
    /// World position, midway between the two surfaces.
    pub point: Vec2,
    /// From A's centre of mass to the point, in world axes: the solver's lever arm on A. Set by
    /// the world's contact update (zero from [`collide`](crate::query::collide) alone); a recycled manifold keeps it
    /// as it was when built, as Box2D does, so resting contacts do not shift from step to step.
    pub anchor_a: Vec2,
    /// From B's centre of mass to the point, in world axes: the lever arm on B (see
    /// [`ManifoldPoint::anchor_a`]).
    pub anchor_b: Vec2,
    /// Distance between the surfaces along the normal: negative when they overlap.
    pub separation: Real,
    /// Which features touch here.
    pub id: FeatureId,
    /// Accumulated normal impulse, kept across steps for warm starting.
    pub normal_impulse: Real,
    /// Accumulated friction impulse, kept across steps for warm starting.
    pub tangent_impulse: Real,
    /// Accumulated impulse of shock propagation on the upper body, kept across steps for warm
    /// starting (0 unless [`crate::SolverParams::shock_propagation`] is on).
    #[cfg_attr(feature = "serde", serde(default))]
    pub shock_impulse: Real,
}

/// Which shape of a pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PairSide {
    /// The first shape.
    A,
    /// The second shape.
    B,
}

/// An edge taking part in a contact, for drawing and inspection.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactEdge {
    /// Which shape it belongs to.
    pub side: PairSide,
    /// Its index in that polygon (edge `i` runs from vertex `i` to `i + 1`).
    pub index: usize,
}

impl ContactEdge {
    /// Its end points on `shape`, the world shape on its side (wherever that shape is now), if
    /// `shape` is a polygon with this edge.
    pub fn ends(&self, shape: &WorldShape) -> Option<(Vec2, Vec2)> {
        match shape {
            WorldShape::Polygon { vertices, .. } if self.index < vertices.len() => Some((
                vertices[self.index],
                vertices[(self.index + 1) % vertices.len()],
            )),
            _ => None,
        }
    }
}

/// Where two shapes touch: a normal from A to B and up to two points.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Manifold {
    /// Unit normal from A to B.
    pub normal: Vec2,
    points: [ManifoldPoint; 2],
    point_count: usize,
    /// The reference face, when a polygon face defines the normal.
    pub reference_edge: Option<ContactEdge>,
    /// The incident edge that was clipped, for polygon pairs.
    pub incident_edge: Option<ContactEdge>,
}

impl Manifold {
    /// At most two points: a manifold read from a saved world is checked for it.
    #[cfg(feature = "serde")]
    pub(crate) fn is_sound(&self) -> bool {
        self.point_count <= self.points.len()
    }

    /// The contact points (0, 1 or 2).
    #[inline]
    pub fn points(&self) -> &[ManifoldPoint] {
        &self.points[..self.point_count]
    }

    /// The contact points, mutably (the solver stores its impulses here).
    #[inline]
    pub fn points_mut(&mut self) -> &mut [ManifoldPoint] {
        &mut self.points[..self.point_count]
    }

    /// True when the shapes are farther apart than the speculative margin.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.point_count == 0
    }

    /// The smallest separation among the points (the deepest penetration, negated).
    pub fn min_separation(&self) -> Option<Real> {
        self.points().iter().map(|p| p.separation).reduce(Real::min)
    }

    pub(crate) fn with_normal(normal: Vec2) -> Self {
        Manifold {
            normal,
            ..Manifold::default()
        }
    }

    pub(crate) fn push(&mut self, point: Vec2, separation: Real, id: FeatureId) {
        self.points[self.point_count] = ManifoldPoint {
            point,
            separation,
            id,
            ..ManifoldPoint::default()
        };
        self.point_count += 1;
    }

    /// The same contact described from B's side.
    pub(crate) fn flipped(mut self) -> Self {
        let swap = |edge: Option<ContactEdge>| {
            edge.map(|mut e| {
                e.side = match e.side {
                    PairSide::A => PairSide::B,
                    PairSide::B => PairSide::A,
                };
                e
            })
        };
        self.normal = -self.normal;
        self.reference_edge = swap(self.reference_edge);
        self.incident_edge = swap(self.incident_edge);
        self
    }

    /// Measures each point's lever arms from the bodies' centres of mass.
    pub(crate) fn set_anchors(&mut self, center_a: Vec2, center_b: Vec2) {
        for point in self.points_mut() {
            point.anchor_a = point.point - center_a;
            point.anchor_b = point.point - center_b;
        }
    }

    /// Copies accumulated impulses from last step's points with the same feature ids.
    pub fn carry_impulses_from(&mut self, previous: &Manifold) {
        self.warm_start_from(&previous.warm_start());
    }

    /// What its points hand on to the next step's points of the same features.
    #[inline]
    pub(crate) fn warm_start(&self) -> WarmStart {
        let mut kept = WarmStart {
            points: [(FeatureId::SINGLE, [0.0; 3]); 2],
            count: self.point_count,
        };
        for (slot, point) in kept.points.iter_mut().zip(self.points()) {
            *slot = (
                point.id,
                [
                    point.normal_impulse,
                    point.tangent_impulse,
                    point.shock_impulse,
                ],
            );
        }
        kept
    }

    /// Takes the accumulated impulses `kept` from last step's points with the same feature
    /// ids.
    #[inline]
    pub(crate) fn warm_start_from(&mut self, kept: &WarmStart) {
        let old = &kept.points[..kept.count];
        for point in self.points_mut() {
            if let Some((_, [normal, tangent, shock])) = old.iter().find(|old| old.0 == point.id) {
                point.normal_impulse = *normal;
                point.tangent_impulse = *tangent;
                point.shock_impulse = *shock;
            }
        }
    }
}

/// A manifold's points' feature ids and accumulated impulses (normal, tangent, shock): all a
/// manifold built again in its place takes from it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WarmStart {
    points: [(FeatureId, [Real; 3]); 2],
    count: usize,
}

/// How far apart two shapes' points may be and still be kept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Margins {
    /// For every point, m.
    pub any: Real,
    /// For points where a face meets a face or a circle, m: at least `any`.
    pub face: Real,
}

impl Margins {
    /// The same margin for every point.
    pub(crate) fn plain(margin: Real) -> Self {
        Margins {
            any: margin,
            face: margin,
        }
    }
}

/// A convex core, its outward unit normals and the radius it is grown by: a polygon, rounded
/// or not, or a capsule's or segment's two-vertex core.
#[derive(Clone, Copy)]
pub(crate) struct Core<'a> {
    pub vertices: &'a [Vec2],
    pub normals: &'a [Vec2],
    pub radius: Real,
}

impl<'a> Core<'a> {
    pub(crate) fn new(vertices: &'a [Vec2], normals: &'a [Vec2], radius: Real) -> Self {
        Core {
            vertices,
            normals,
            radius,
        }
    }

    /// A segment's or capsule's core, which has no inside.
    fn is_line(&self) -> bool {
        self.vertices.len() == 2
    }
}

pub(super) fn collide_circles(ca: Vec2, ra: Real, cb: Vec2, rb: Real, margin: Real) -> Manifold {
    let s = distance::circle_circle(ca, ra, cb, rb);
    let mut manifold = Manifold::with_normal(s.normal);
    if s.separation <= margin {
        let offset = s.normal.dot(&(cb - ca));
        let u = middle((-ra, ra), (offset - rb, offset + rb));
        manifold.push(ca + s.normal * u, s.separation, FeatureId::SINGLE);
    }
    manifold
}

/// The stretch `(lo, hi)` of the line `origin + u × direction` inside a convex polygon
/// (empty when `lo > hi`): the slab test over its edges.
fn polygon_chord(
    vertices: &[Vec2],
    normals: &[Vec2],
    origin: Vec2,
    direction: Vec2,
) -> (Real, Real) {
    let (mut lo, mut hi) = (Real::NEG_INFINITY, Real::INFINITY);
    for (v, n) in vertices.iter().zip(normals) {
        let inside_by = n.dot(&(v - origin));
        let rate = n.dot(&direction);
        if rate > 0.0 {
            hi = hi.min(inside_by / rate);
        } else if rate < 0.0 {
            lo = lo.max(inside_by / rate);
        } else if inside_by < 0.0 {
            return (Real::INFINITY, Real::NEG_INFINITY);
        }
    }
    (lo, hi)
}

/// The middle of what two stretches of one line share, or of the gap between them when they
/// share nothing (the stretches must be finite where they face each other).
#[inline]
fn middle(a: (Real, Real), b: (Real, Real)) -> Real {
    0.5 * (a.0.max(b.0) + a.1.min(b.1))
}

pub(super) fn collide_polygon_circle(
    vertices: &[Vec2],
    normals: &[Vec2],
    rounding: Real,
    center: Vec2,
    radius: Real,
    margins: Margins,
) -> Manifold {
    // A rounded polygon against a circle is its core against a circle as much larger.
    let pc = distance::polygon_circle(vertices, normals, center, radius + rounding);
    let s = pc.separation;
    let mut manifold = Manifold::with_normal(s.normal);
    let margin = match pc.feature {
        PolygonFeature::Edge(_) => margins.face,
        PolygonFeature::Vertex(_) => margins.any,
    };
    if s.separation > margin {
        return manifold;
    }
    // Along the normal from the core's nearest point: the polygon from `rounding` behind its
    // core to `rounding` in front of it, the circle from `separation + rounding` to that plus
    // its diameter.
    let mut polygon = polygon_chord(vertices, normals, pc.polygon_point, s.normal);
    if polygon.0 > polygon.1 && polygon.0 == Real::INFINITY {
        // The nearest point is on the boundary, so the line meets the polygon there: it
        // misses only by rounding, running beside an edge square to the normal (a box's
        // corner), and then the chord is that point.
        polygon = (0.0, 0.0);
    }
    let near = s.separation + rounding;
    let u = middle(
        (polygon.0 - rounding, polygon.1.min(0.0) + rounding),
        (near, near + 2.0 * radius),
    );
    manifold.push(
        pc.polygon_point + s.normal * u,
        s.separation,
        FeatureId::SINGLE,
    );
    if let PolygonFeature::Edge(i) = pc.feature {
        manifold.reference_edge = Some(ContactEdge {
            side: PairSide::A,
            index: i,
        });
    }
    manifold
}

/// Two convex cores, each grown by its radius: SAT and clipping on the cores, every
/// separation less both radii, every point midway between the grown surfaces.
pub(super) fn collide_polygons(
    a: Core,
    b: Core,
    margins: Margins,
    previous_reference: Option<PairSide>,
) -> Manifold {
    let margin = margins.any;
    let rounding = a.radius + b.radius;
    let pp = distance::polygon_sat(a.vertices, a.normals, b.vertices, b.normals);
    let (edge_a, separation_a) = pp.edge_a;
    let (edge_b, separation_b) = pp.edge_b;
    if pp.separation.separation - rounding > margins.face {
        return Manifold::with_normal(pp.separation.normal);
    }
    // Two polygons that barely touch (a tenth of the slop, Box2D's rule) keep SAT's axis: the
    // exact answer differs by less than a contact can tell, and resting contacts are nearly
    // all like that. Further apart, the closest points are on the facing edges.
    let mut separation = pp.separation;
    let mut closest = None;
    if separation.separation > 0.1 * LINEAR_SLOP {
        let facing = facing_edges_closest(a, b, pp.edge_a, pp.edge_b);
        // Facing features: the SAT axis is the true normal. Corner to corner: the line
        // between the closest points is.
        if facing.distance > separation.separation * (1.0 + 1e-5) + 1e-7 {
            separation = distance::Separation {
                normal: (facing.point_b - facing.point_a) / facing.distance,
                separation: facing.distance,
            };
        }
        closest = Some(facing);
    }
    if separation.separation - rounding > margins.face {
        return Manifold::with_normal(separation.normal);
    }
    // Apart with two corners facing each other: one point on the line between them.
    if let Some(closest) = closest
        && separation.separation > separation_a.max(separation_b)
    {
        let normal = separation.normal;
        let mut manifold = Manifold::with_normal(normal);
        if closest.distance - rounding > margin {
            return manifold;
        }
        let id =
            FeatureId::vertex_pair(closest.vertex_a.unwrap_or(0), closest.vertex_b.unwrap_or(0));
        let point = if rounding == 0.0 {
            (closest.point_a + closest.point_b) * 0.5
        } else {
            // Midway between the grown surfaces, but within both corners' discs (a large
            // rounding reaching past a sharp corner would put it outside that shape).
            let d = closest.distance;
            let t = (0.5 * (d + a.radius - b.radius)).clamp(-a.radius, d + b.radius);
            closest.point_a + normal * t
        };
        manifold.push(point, closest.distance - rounding, id);
        return manifold;
    }

    let reference_on_b = match previous_reference {
        Some(PairSide::A) => separation_b > separation_a + REFERENCE_TOLERANCE,
        Some(PairSide::B) => separation_b + REFERENCE_TOLERANCE >= separation_a,
        None => separation_b > separation_a,
    };
    let ((reference, i1), incident) = if reference_on_b {
        ((b, edge_b), a)
    } else {
        ((a, edge_a), b)
    };
    let (ref_vertices, ref_normals) = (reference.vertices, reference.normals);
    let (inc_vertices, inc_normals) = (incident.vertices, incident.normals);
    // The grown surfaces lie each its radius out from the core: points move to midway.
    let surface_shift = 0.5 * (reference.radius - incident.radius);
    let i2 = (i1 + 1) % ref_vertices.len();
    let (v11, v12) = (ref_vertices[i1], ref_vertices[i2]);
    let normal = ref_normals[i1];

    // The incident edge: the one facing the reference face most directly.
    let j1 = facing_edge(inc_normals, normal);
    let j2 = (j1 + 1) % inc_vertices.len();
    let (v21, v22) = (inc_vertices[j1], inc_vertices[j2]);

    // Clip the incident edge to the strip between the side planes through v11 and v12,
    // working in distances along the reference edge from v11.
    let edge = v12 - v11;
    let length = edge.norm();
    let tangent = edge / length;
    let (s21, s22) = (tangent.dot(&(v21 - v11)), tangent.dot(&(v22 - v11)));
    // The incident edge normally runs against the reference edge, so v22 is the lower end.
    let ((low, s_low, j_low), (high, s_high, j_high)) = if s22 <= s21 {
        ((v22, s22, j2), (v21, s21, j1))
    } else {
        ((v21, s21, j1), (v22, s22, j2))
    };
    let span = s_high - s_low;
    let at = |s: Real| {
        if span > Real::EPSILON * length {
            low + (high - low) * ((s - s_low) / span)
        } else {
            low
        }
    };

    let mut manifold = Manifold::with_normal(if reference_on_b { -normal } else { normal });
    manifold.reference_edge = Some(ContactEdge {
        side: if reference_on_b {
            PairSide::B
        } else {
            PairSide::A
        },
        index: i1,
    });
    manifold.incident_edge = Some(ContactEdge {
        side: if reference_on_b {
            PairSide::A
        } else {
            PairSide::B
        },
        index: j1,
    });

    // Behind the reference face a clipped end may lie outside the reference polygon: with a
    // corner sharper than a right angle (a triangle's) the side planes leave it there. Slide it
    // along the incident edge, toward `toward`, until it enters the polygon, so a face-to-face
    // overlap keeps both of its points instead of losing one and rotating into the other shape.
    // None when no part of the way is inside: in a deep overlap the incident point can poke out
    // past the reference polygon's other faces, and then it marks no contact at all.
    let into_reference = |end: Vec2, toward: Vec2| {
        // A segment's core has no inside for a point to poke out of.
        if reference.is_line()
            || normal.dot(&(end - v11)) >= 0.0
            || distance_outside(ref_vertices, ref_normals, end) <= SPURIOUS_TOLERANCE
        {
            return Some(end);
        }
        let (enter, leave) = polygon_chord(ref_vertices, ref_normals, end, toward - end);
        (enter <= leave && (0.0..=1.0).contains(&enter)).then(|| end + (toward - end) * enter)
    };
    // Face to face, the points may reach as far as the pair can close; an edge beyond the end
    // of the face only as far as the plain margin.
    let beyond_the_face = s_low > length || s_high < 0.0;
    let point_margin = if beyond_the_face {
        margin
    } else {
        margins.face
    };
    let candidates = if beyond_the_face {
        // The incident edge lies wholly beyond one end of the reference face (possible only
        // for shapes barely within the margin): keep its nearer end.
        if s_low > length {
            [into_reference(low, low).map(|p| (p, i2, j_low)), None]
        } else {
            [into_reference(high, high).map(|p| (p, i1, j_high)), None]
        }
    } else {
        let lower = if s_low < 0.0 { at(0.0) } else { low };
        let upper = if s_high > length { at(length) } else { high };
        [
            into_reference(lower, upper).map(|p| (p, i1, j_low)),
            into_reference(upper, lower).map(|p| (p, i2, j_high)),
        ]
    };
    for (point, reference_vertex, incident_vertex) in candidates.into_iter().flatten() {
        let separation = normal.dot(&(point - v11));
        if separation - rounding > point_margin {
            continue;
        }
        let incident_extent = || polygon_chord(inc_vertices, inc_normals, point, normal).1;
        let u = if separation < 0.0 {
            // Midway to the reference face, unless the incident polygon is thinner than that
            // along the normal (a small shape deep in a large one).
            0.5 * (-separation).min(incident_extent().max(0.0))
        } else {
            -0.5 * separation
        };
        let shift = if surface_shift == 0.0 {
            u
        } else {
            // Out to midway between the grown surfaces, but never through the far side of
            // either shape (a thin one deep in a round one). Where a capsule's core crosses
            // the other shape the two limits can conflict, and the point stays in the
            // incident shape, as it does for sharp shapes.
            let mut shift = u + surface_shift;
            // A point on a side plane through a sharp corner meets that shape in the corner
            // alone, which rounding may miss by a hair.
            let (reference_lo, reference_hi) =
                polygon_chord(ref_vertices, ref_normals, point, normal);
            if reference_lo <= reference_hi + SPURIOUS_TOLERANCE {
                shift = shift.max(reference_lo.min(reference_hi) - reference.radius);
            }
            let (incident_lo, incident_hi) =
                polygon_chord(inc_vertices, inc_normals, point, normal);
            if incident_lo <= incident_hi + SPURIOUS_TOLERANCE {
                shift = shift.min(incident_hi.max(incident_lo).max(0.0) + incident.radius);
            }
            shift
        };
        manifold.push(
            point + normal * shift,
            separation - rounding,
            FeatureId::clipped(reference_on_b, reference_vertex, incident_vertex),
        );
    }
    if manifold.is_empty() && pp.separation.separation < 0.0 {
        // Every clipped point was spurious, yet the shapes overlap: one point in the middle of
        // the overlap keeps the pair in contact.
        if let Some(center) = overlap_center(ref_vertices, ref_normals, inc_vertices) {
            manifold.push(
                center,
                pp.separation.separation - rounding,
                FeatureId::clipped(reference_on_b, i1, j1),
            );
        }
    }
    manifold
}

/// The closest points of SAT's best face (`edge_a` or `edge_b`, each with its separation;
/// B's when it separates more) and the other polygon's edge that faces it most directly:
/// Box2D's two-edge test. For polygons apart these hold the closest points of the two; for
/// two segments' cores, whose edges are the segments, they are exact.
fn facing_edges_closest(
    a: Core,
    b: Core,
    edge_a: (usize, Real),
    edge_b: (usize, Real),
) -> distance::ClosestPoints {
    let b_holds_face = edge_b.1 > edge_a.1;
    let ((reference, i1), incident) = if b_holds_face {
        ((b, edge_b.0), a)
    } else {
        ((a, edge_a.0), b)
    };
    let normal = reference.normals[i1];
    let j1 = facing_edge(incident.normals, normal);
    let ends = |core: Core, i: usize| (i, (i + 1) % core.vertices.len());
    let ((i1, i2), (j1, j2)) = (ends(reference, i1), ends(incident, j1));
    let ((on_reference, f_reference), (on_incident, f_incident)) = closest_between_segments(
        (reference.vertices[i1], reference.vertices[i2]),
        (incident.vertices[j1], incident.vertices[j2]),
    );
    let vertex = |f: Real, start: usize, end: usize| match f {
        0.0 => Some(start),
        1.0 => Some(end),
        _ => None,
    };
    let (reference_vertex, incident_vertex) =
        (vertex(f_reference, i1, i2), vertex(f_incident, j1, j2));
    let (point_a, point_b, vertex_a, vertex_b) = if b_holds_face {
        (on_incident, on_reference, incident_vertex, reference_vertex)
    } else {
        (on_reference, on_incident, reference_vertex, incident_vertex)
    };
    distance::ClosestPoints {
        point_a,
        point_b,
        distance: (point_b - point_a).norm(),
        vertex_a,
        vertex_b,
    }
}

/// The edge whose normal is most nearly opposite `normal`: the one facing a face of that
/// normal most directly.
#[allow(
    clippy::expect_used,
    reason = "a polygon has at least three normals, so the range is not empty"
)]
fn facing_edge(normals: &[Vec2], normal: Vec2) -> usize {
    (0..normals.len())
        .min_by(|&x, &y| normals[x].dot(&normal).total_cmp(&normals[y].dot(&normal)))
        .expect("polygons have edges")
}

/// How far a point lies outside a convex polygon (negative inside).
fn distance_outside(vertices: &[Vec2], normals: &[Vec2], point: Vec2) -> Real {
    vertices
        .iter()
        .zip(normals)
        .map(|(v, n)| n.dot(&(point - v)))
        .fold(Real::NEG_INFINITY, Real::max)
}

/// The centre (vertex average) of the overlap of two convex polygons, by clipping the second
/// against each edge of the first, or `None` when they do not overlap. The clipped outlines
/// live on the stack (a step allocates nothing); only outlines too long for it take the heap.
fn overlap_center(a_vertices: &[Vec2], a_normals: &[Vec2], b_vertices: &[Vec2]) -> Option<Vec2> {
    const ON_STACK: usize = 64;
    let mut stack = [[Vec2::zeros(); ON_STACK]; 2];
    let [front, back] = &mut stack;
    if let Some(center) = clip_overlap(a_vertices, a_normals, b_vertices, front, back) {
        return center;
    }
    // A convex outline gains at most a point per clip; rounding can add a few more.
    let mut room = 2 * (a_vertices.len() + b_vertices.len());
    loop {
        let mut heap = [vec![Vec2::zeros(); room], vec![Vec2::zeros(); room]];
        let [front, back] = &mut heap;
        if let Some(center) = clip_overlap(a_vertices, a_normals, b_vertices, front, back) {
            return center;
        }
        room *= 2;
    }
}

/// [`overlap_center`] in the buffers `front` and `back`: `None` when they are too short.
fn clip_overlap<'a>(
    a_vertices: &[Vec2],
    a_normals: &[Vec2],
    b_vertices: &[Vec2],
    mut front: &'a mut [Vec2],
    mut back: &'a mut [Vec2],
) -> Option<Option<Vec2>> {
    let mut len = b_vertices.len();
    front.get_mut(..len)?.copy_from_slice(b_vertices);
    for (v, n) in a_vertices.iter().zip(a_normals) {
        let mut next = 0;
        for i in 0..len {
            let (p, q) = (front[i], front[(i + 1) % len]);
            let (dp, dq) = (n.dot(&(p - v)), n.dot(&(q - v)));
            if dp <= 0.0 {
                *back.get_mut(next)? = p;
                next += 1;
            }
            if (dp < 0.0) != (dq < 0.0) {
                *back.get_mut(next)? = p + (q - p) * (dp / (dp - dq));
                next += 1;
            }
        }
        std::mem::swap(&mut front, &mut back);
        len = next;
        if len == 0 {
            return Some(None);
        }
    }
    Some(Some(front[..len].iter().sum::<Vec2>() / len as Real))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::query::collide::{self, collide};
    use crate::geometry::shape::Shape;
    use crate::math::vec2;

    /// The manifold [`collide::update`] builds in place of `previous`.
    fn update(a: &WorldShape, b: &WorldShape, margins: Margins, previous: &Manifold) -> Manifold {
        let mut manifold = *previous;
        collide::update(a, b, margins, &mut manifold);
        manifold
    }

    fn placed(shape: Shape, x: Real, y: Real, angle: Real) -> WorldShape {
        WorldShape::at(&shape, vec2(x, y), angle)
    }

    /// Polygons apart, turned every way: the closest points of SAT's face and the edge facing
    /// it are the polygons' closest points (what the all-pairs search finds).
    #[test]
    fn the_facing_edges_hold_the_closest_points_of_polygons_apart() {
        let shapes = [
            Shape::rect(1.0, 0.5),
            Shape::rect(0.1, 2.0),
            Shape::polygon(&[vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.2, 0.7)]).unwrap(),
            Shape::capsule(vec2(-0.5, 0.0), vec2(0.5, 0.0), 0.1),
        ];
        let mut checked = 0;
        for (i, a) in shapes.iter().enumerate() {
            for b in &shapes[i..] {
                for k in 0..400 {
                    let t = k as Real;
                    let wa = placed(a.clone(), 0.0, 0.0, 0.37 * t);
                    let (x, y) = ((0.71 * t).cos() * 3.0, (0.71 * t).sin() * 3.0);
                    let wb = placed(b.clone(), x, y, 1.13 * t);
                    let pair = distance::with_core(&wa, |va, na, ra| {
                        distance::with_core(&wb, |vb, nb, rb| {
                            let sat = distance::polygon_sat(va, na, vb, nb);
                            (sat.separation.separation > 0.1 * LINEAR_SLOP).then(|| {
                                let facing = facing_edges_closest(
                                    Core::new(va, na, ra),
                                    Core::new(vb, nb, rb),
                                    sat.edge_a,
                                    sat.edge_b,
                                );
                                (facing, distance::closest_points(va, vb))
                            })
                        })
                    });
                    let Some((facing, exact)) = pair else {
                        continue;
                    };
                    assert!(
                        (facing.distance - exact.distance).abs() < 1e-5,
                        "{a:?} {b:?} at {k}: {} against {}",
                        facing.distance,
                        exact.distance
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 2000, "{checked}");
    }

    #[test]
    fn a_circle_off_a_turned_box_corner_gets_a_finite_point() {
        // Met in the spinner: the circle's centre projects onto edge 0 a rounding error
        // past its start, so the nearest point is the corner and the normal is edge 0's,
        // exactly square to edge 3's normal; the line from the corner along it runs beside
        // edge 3, a rounding error outside it.
        let vertices = [
            vec2(-30.08221, 33.10679),
            vec2(-30.055412, 32.4073),
            vec2(-29.355927, 32.434097),
            vec2(-29.382725, 33.133587),
        ];
        let normals = [
            vec2(-0.99926686, -0.0382842),
            vec2(0.0382842, -0.99926686),
            vec2(0.99926686, 0.0382842),
            vec2(-0.0382842, 0.99926686),
        ];
        let margins = Margins {
            any: 0.02,
            face: 0.031149585,
        };
        let manifold = collide_polygon_circle(
            &vertices,
            &normals,
            0.0,
            vec2(-30.434263, 33.0933),
            0.35,
            margins,
        );
        assert_eq!(manifold.points().len(), 1);
        let point = manifold.points()[0].point;
        assert!(point.x.is_finite() && point.y.is_finite(), "{manifold:?}");
        // Midway between the corner and the circle, along the normal.
        let expected = vertices[0] + normals[0] * (0.5 * 0.002311021);
        assert!(
            (point - expected).norm() < 1.0e-4,
            "{point:?}, not {expected:?}"
        );
    }

    #[test]
    fn overlap_centres_of_short_and_long_outlines_agree_with_symmetry() {
        // A polygon with a centre of symmetry and a shifted copy: their overlap is symmetric
        // about the point halfway, and so is its outline. 80 sides are more than the stack
        // buffers hold.
        for sides in [6, 8, 80] {
            let polygon = crate::geometry::polygon::Polygon::regular(sides, 1.0).unwrap();
            let shift = vec2(0.31, 0.17);
            let moved: Vec<Vec2> = polygon.vertices().iter().map(|v| v + shift).collect();
            let center = overlap_center(polygon.vertices(), polygon.normals(), &moved).unwrap();
            assert!(
                (center - shift * 0.5).norm() < 1e-3,
                "{sides} sides: {center:?}"
            );
            let far: Vec<Vec2> = moved.iter().map(|v| v + shift * 10.0).collect();
            assert_eq!(
                overlap_center(polygon.vertices(), polygon.normals(), &far),
                None
            );
        }
    }

    #[test]
    fn box_resting_on_ground_gets_two_points() {
        let ground = placed(Shape::rect(5.0, 0.5), 0.0, -0.5, 0.0);
        let crate_box = placed(Shape::rect(0.5, 0.5), 1.0, 0.49, 0.0);
        let m = collide(&ground, &crate_box, 0.0);
        assert_eq!(m.points().len(), 2);
        assert_eq!(m.normal, vec2(0.0, 1.0));
        for p in m.points() {
            assert!((p.separation + 0.01).abs() < 1e-5);
            assert!((p.point.y + 0.005).abs() < 1e-5);
        }
        let xs: Vec<Real> = m.points().iter().map(|p| p.point.x).collect();
        assert!(xs.contains(&0.5) && xs.contains(&1.5), "{xs:?}");
        let reference = m.reference_edge.unwrap();
        assert_eq!(reference.side, PairSide::A);
        assert_eq!(m.incident_edge.unwrap().side, PairSide::B);
        // Ids differ and survive a small move.
        let ids: Vec<FeatureId> = m.points().iter().map(|p| p.id).collect();
        assert_ne!(ids[0], ids[1]);
        let moved = placed(Shape::rect(0.5, 0.5), 1.02, 0.495, 0.001);
        let m2 = collide(&ground, &moved, 0.0);
        let ids2: Vec<FeatureId> = m2.points().iter().map(|p| p.id).collect();
        assert_eq!(ids, ids2);
    }

    #[test]
    fn speculative_points_only_within_the_margin() {
        let ground = placed(Shape::rect(5.0, 0.5), 0.0, -0.5, 0.0);
        let hovering = placed(Shape::rect(0.5, 0.5), 0.0, 0.51, 0.0);
        assert!(collide(&ground, &hovering, 0.0).is_empty());
        let m = collide(&ground, &hovering, 0.02);
        assert_eq!(m.points().len(), 2);
        assert!(
            m.points()
                .iter()
                .all(|p| (p.separation - 0.01).abs() < 1e-5)
        );
        assert!(collide(&ground, &hovering, 0.005).is_empty());
    }

    #[test]
    fn only_facing_features_reach_past_the_plain_margin() {
        let reach = Margins {
            any: 0.02,
            face: 0.5,
        };
        let ground = placed(Shape::rect(5.0, 0.5), 0.0, -0.5, 0.0);
        // A face 30 cm above a face: kept with the reach, not without.
        let above = placed(Shape::rect(0.5, 0.5), 0.0, 0.8, 0.0);
        let no_reach = Margins::plain(0.02);
        assert!(update(&ground, &above, no_reach, &Manifold::default()).is_empty());
        let m = update(&ground, &above, reach, &Manifold::default());
        assert_eq!(m.points().len(), 2);
        assert!(m.points().iter().all(|p| (p.separation - 0.3).abs() < 1e-5));
        // A box off to the side and 1 cm above the ground's top corner, 30 cm away: its face
        // is beyond the end of the ground's side face and its corner faces the ground's
        // corner, so nothing reaches past the plain margin (a box grazing by is no impact).
        let beside = placed(Shape::rect(0.5, 0.5), 5.8, 0.51, 0.0);
        assert!(update(&ground, &beside, reach, &Manifold::default()).is_empty());
        // A ball 30 cm above a face reaches; off a corner it does not.
        let ball = placed(Shape::circle(0.5), 0.0, 0.8, 0.0);
        assert_eq!(
            update(&ground, &ball, reach, &Manifold::default())
                .points()
                .len(),
            1
        );
        let ball_by_corner = placed(Shape::circle(0.5), 5.6, 0.6, 0.0);
        assert!(update(&ground, &ball_by_corner, reach, &Manifold::default()).is_empty());
    }

    #[test]
    fn circle_contacts_have_one_point_midway() {
        let a = placed(Shape::circle(1.0), 0.0, 0.0, 0.0);
        let b = placed(Shape::circle(0.5), 1.4, 0.0, 0.0);
        let m = collide(&a, &b, 0.0);
        assert_eq!(m.points().len(), 1);
        assert!((m.points()[0].point - vec2(0.95, 0.0)).norm() < 1e-6);
        assert!((m.points()[0].separation + 0.1).abs() < 1e-6);
        // Circle against a polygon, both orders: normals opposite, same point.
        let square = placed(Shape::rect(1.0, 1.0), 0.0, 0.0, 0.0);
        let ball = placed(Shape::circle(0.5), 0.0, 1.4, 0.0);
        let ab = collide(&square, &ball, 0.0);
        let ba = collide(&ball, &square, 0.0);
        assert_eq!(ab.normal, -ba.normal);
        assert_eq!(ab.points()[0].point, ba.points()[0].point);
        assert_eq!(ab.reference_edge.unwrap().side, PairSide::A);
        assert_eq!(ba.reference_edge.unwrap().side, PairSide::B);
    }

    #[test]
    fn the_reference_face_holds_through_near_ties() {
        // Two equal boxes, B tilted a hair: B's bottom face is barely better than A's top.
        let a = placed(Shape::rect(0.5, 0.5), 0.0, 0.0, 0.0);
        let tilt = |angle: Real| placed(Shape::rect(0.5, 0.5), 0.1, 0.99, angle);
        let first = collide(&a, &tilt(0.0), 0.0);
        assert_eq!(first.reference_edge.unwrap().side, PairSide::A);
        // Stateless, the tiniest tilt hands the reference to whichever face is better...
        let tilted = tilt(-1e-4);
        let fresh = collide(&a, &tilted, 0.0);
        // ...but a contact that had A's face keeps it, and keeps its feature ids.
        let held = update(&a, &tilted, Margins::plain(0.0), &first);
        assert_eq!(held.reference_edge.unwrap().side, PairSide::A);
        let ids = |m: &Manifold| m.points().iter().map(|p| p.id).collect::<Vec<_>>();
        assert_eq!(ids(&held), ids(&first));
        if fresh.reference_edge.unwrap().side == PairSide::B {
            assert_ne!(ids(&fresh), ids(&first));
        }
        // A clear win still takes over: A tilted, its corner poking into B's flat face.
        let tilted_a = placed(Shape::rect(0.5, 0.5), 0.0, 0.0, 0.3);
        let clear = update(&tilted_a, &tilt(0.0), Margins::plain(0.0), &first);
        assert_eq!(clear.reference_edge.unwrap().side, PairSide::B);
    }

    #[test]
    fn impulses_follow_feature_ids() {
        let ground = placed(Shape::rect(5.0, 0.5), 0.0, -0.5, 0.0);
        let crate_box = placed(Shape::rect(0.5, 0.5), 0.0, 0.49, 0.0);
        let mut old = collide(&ground, &crate_box, 0.0);
        old.points_mut()[0].normal_impulse = 3.0;
        old.points_mut()[1].normal_impulse = 5.0;
        let mut new = collide(&ground, &crate_box, 0.0);
        new.carry_impulses_from(&old);
        assert_eq!(new.points()[0].normal_impulse, 3.0);
        assert_eq!(new.points()[1].normal_impulse, 5.0);
    }
}
