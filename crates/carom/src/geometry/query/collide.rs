//! The manifold of any two placed shapes: each pair of kinds to the function that builds its
//! points (convex shapes in `manifold`, chain links in `chain_segment`), and, for a pair that
//! touched last step, the reference side kept and the impulses carried over.

use super::chain_segment::{self, ChainLink};
use super::manifold::{
    Core, Manifold, Margins, PairSide, collide_circles, collide_polygon_circle, collide_polygons,
};
use crate::geometry::shape::WorldShape;
use crate::math::Real;

/// The manifold of two placed shapes, with points for every feature closer than `margin`
/// (use 0 for touching points only).
///
/// The reference face is the better of the two polygons' best faces, so swapping the
/// arguments gives the same points with the normal flipped.
pub fn collide(a: &WorldShape, b: &WorldShape, margin: Real) -> Manifold {
    collide_after(a, b, Margins::plain(margin), None)
}

/// [`collide`] for a pair that touched last step: the side that held the reference face keeps
/// it unless the other side's face is better by
/// [`REFERENCE_TOLERANCE`](crate::constants::REFERENCE_TOLERANCE), and impulses carry
/// over to points with the same feature ids. Face points are kept up to `margins.face` apart.
/// Built in place of last step's `manifold`, which keeps only what it hands on.
pub(crate) fn update(a: &WorldShape, b: &WorldShape, margins: Margins, manifold: &mut Manifold) {
    let kept = manifold.warm_start();
    *manifold = collide_after(a, b, margins, manifold.reference_edge.map(|e| e.side));
    manifold.warm_start_from(&kept);
}

/// [`collide`]'s and [`update`]'s work; `previous_reference` is the side that held the
/// reference face last step, if the pair touched then.
fn collide_after(
    a: &WorldShape,
    b: &WorldShape,
    margins: Margins,
    previous_reference: Option<PairSide>,
) -> Manifold {
    let margin = margins.any;
    match (a, b) {
        (
            WorldShape::Circle {
                center: ca,
                radius: ra,
            },
            WorldShape::Circle {
                center: cb,
                radius: rb,
            },
        ) => collide_circles(*ca, *ra, *cb, *rb, margin),
        (
            WorldShape::Polygon {
                vertices,
                normals,
                radius: rounding,
            },
            WorldShape::Circle { center, radius },
        ) => collide_polygon_circle(vertices, normals, *rounding, *center, *radius, margins),
        (
            WorldShape::Circle { center, radius },
            WorldShape::Polygon {
                vertices,
                normals,
                radius: rounding,
            },
        ) => collide_polygon_circle(vertices, normals, *rounding, *center, *radius, margins)
            .flipped(),
        (
            WorldShape::Polygon {
                vertices: va,
                normals: na,
                radius: ra,
            },
            WorldShape::Polygon {
                vertices: vb,
                normals: nb,
                radius: rb,
            },
        ) => collide_polygons(
            Core::new(va, na, *ra),
            Core::new(vb, nb, *rb),
            margins,
            previous_reference,
        ),
        (link @ WorldShape::ChainSegment { .. }, other) => {
            chain_segment::collide(&ChainLink::of(link), other, margins)
        }
        (other, link @ WorldShape::ChainSegment { .. }) => {
            chain_segment::collide(&ChainLink::of(link), other, margins).flipped()
        }
    }
}
