//! A kinematic character: a capsule that walks where it is told, as a game expects, on the
//! mover's collide-solve-cast loop ([`crate::World::collide_mover`], [`solve_planes`],
//! [`crate::World::cast_mover`]).
//!
//! What it adds to the loop is which way each surface pushes. Ground it can stand on (a
//! surface no steeper than its `max_slope`) pushes it straight up, so that walking into a
//! slope climbs it at the same pace across and standing on one does not slide it down. A
//! surface too steep pushes it straight back, level, so that walking into it does not lift
//! it and falling against it slides it down. Walls and ceilings push along their normals.
//! On top of that: steps up to a height, a snap down to the ground when walking downhill or
//! off a low step, a ride on whatever body it stands on (moving or turning, or a conveyor
//! belt's surface), its weight on that body when it is dynamic, and a push, bounded in
//! force, on the dynamic bodies it walks into.
//!
//! The world does not see the character: bodies are not stopped by it, only pushed.

use crate::character::mover::MoverPlane;
use crate::character::planes::{CollisionPlane, PlaneSolution, solve_planes, solve_planes_along};
use crate::collision::query_filter::QueryFilter;
use crate::constants::{
    CHARACTER_GROUND_PROBE, CHARACTER_MOVE_TOLERANCE, LINEAR_SLOP, MAX_CHARACTER_ITERATIONS,
    MAX_POSITION, MAX_SHAPE_EXTENT, TIME_STEP_RANGE,
};
use crate::dynamics::body::{Body, BodyHandle, BodyKind, check_position};
use crate::dynamics::collider::ColliderHandle;
use crate::error::{
    CaromError, check_finite, check_finite_not_negative, check_finite_vec, check_within,
};
use crate::geometry::capsule::Capsule;
use crate::geometry::segment::closest_on_segment;
use crate::math::{Real, Vec2, cross, perp_cw, rotation, vec2};
use crate::world::World;

/// How a character is shaped and how it moves; build one with [`CharacterDef::capsule`] and
/// make it with [`Character::new`].
#[derive(Debug, Clone, PartialEq)]
pub struct CharacterDef {
    capsule: Capsule,
    position: Vec2,
    up: Vec2,
    max_slope: Real,
    step_height: Real,
    step_width: Real,
    snap_distance: Real,
    mass: Real,
    max_push_force: Real,
    filter: QueryFilter,
}

impl CharacterDef {
    /// An upright capsule, its end circles' centres `half_height` above and below the
    /// character's position, of `radius`, at the origin. Defaults: up is +y, slopes up to
    /// 45° are ground, steps up to 0.3 m are climbed (needing a tread of half the radius),
    /// the ground is followed down up to 0.2 m, the character weighs 80 kg and pushes with at
    /// most 1000 N, and it sees every collider.
    pub fn capsule(half_height: Real, radius: Real) -> Self {
        CharacterDef {
            capsule: Capsule::new(vec2(0.0, -half_height), vec2(0.0, half_height), radius),
            position: Vec2::zeros(),
            up: vec2(0.0, 1.0),
            max_slope: crate::math::consts::FRAC_PI_4,
            step_height: 0.3,
            step_width: 0.5 * radius,
            snap_distance: 0.2,
            mass: 80.0,
            max_push_force: 1000.0,
            filter: QueryFilter::ALL,
        }
    }

    /// Where it starts: its capsule's middle, m.
    pub fn position(mut self, position: Vec2) -> Self {
        self.position = position;
        self
    }

    /// Which way is up (any length; it is normalised). Ground is measured against it and
    /// steps are climbed along it; the capsule is not turned to it.
    pub fn up(mut self, up: Vec2) -> Self {
        self.up = up;
        self
    }

    /// The steepest ground it stands on and walks up, radians from level, in `[0, π/2)`.
    pub fn max_slope(mut self, angle: Real) -> Self {
        self.max_slope = angle;
        self
    }

    /// The highest step it climbs, m (0: none), and the least tread it needs on top, m.
    pub fn step(mut self, height: Real, min_width: Real) -> Self {
        self.step_height = height;
        self.step_width = min_width;
        self
    }

    /// How far below it the ground may fall away in a move and still be followed down (when it
    /// was on the ground and is not moving up), m; 0 turns the snap off.
    pub fn snap_distance(mut self, distance: Real) -> Self {
        self.snap_distance = distance;
        self
    }

    /// Its mass, kg: its weight rests on the dynamic bodies it stands on. 0 weighs nothing.
    pub fn mass(mut self, mass: Real) -> Self {
        self.mass = mass;
        self
    }

    /// The most force it pushes a dynamic body with, N. 0 pushes nothing.
    pub fn max_push_force(mut self, force: Real) -> Self {
        self.max_push_force = force;
        self
    }

    /// What it collides with: the colliders this filter sees. Exclude the character's own
    /// body here if it has one.
    pub fn filter(mut self, filter: QueryFilter) -> Self {
        self.filter = filter;
        self
    }

    /// Checks every value: a sound capsule with a radius of more than two
    /// [`crate::LINEAR_SLOP`]s, a position within [`crate::MAX_POSITION`], an up from 1e-6
    /// to 1e18 long, a slope in `[0, π/2)`, step and snap distances from 0 to
    /// [`crate::MAX_SHAPE_EXTENT`] and a finite, non-negative mass and push force.
    ///
    /// # Errors
    /// The first value that is not so.
    pub fn validate(&self) -> Result<(), CaromError> {
        self.capsule.validate()?;
        if self.capsule.radius() <= 2.0 * LINEAR_SLOP {
            return Err(CaromError::OutOfRange {
                name: "character radius",
                expected: "more than 0.01 m",
                value: self.capsule.radius(),
            });
        }
        check_position("character position", self.position)?;
        check_finite_vec("character up", self.up)?;
        // Normalised: too short, its direction is rounding; too long, its square overflows.
        let length = self.up.norm();
        if !(1.0e-6..=1.0e18).contains(&length) {
            return Err(CaromError::OutOfRange {
                name: "character up's length",
                expected: "from 1e-6 to 1e18",
                value: length,
            });
        }
        check_finite("character max slope", self.max_slope)?;
        if !(0.0..crate::math::consts::FRAC_PI_2).contains(&self.max_slope) {
            return Err(CaromError::OutOfRange {
                name: "character max slope",
                expected: "in [0, π/2) radians",
                value: self.max_slope,
            });
        }
        // Distances the character casts its capsule over: a shape's size at most.
        let (distances, expected) = (0.0..=MAX_SHAPE_EXTENT, "from 0 to 1e5 m");
        check_within(
            "character step height",
            self.step_height,
            distances.clone(),
            expected,
        )?;
        check_within(
            "character step width",
            self.step_width,
            distances.clone(),
            expected,
        )?;
        check_within(
            "character snap distance",
            self.snap_distance,
            distances,
            expected,
        )?;
        check_finite_not_negative("character mass", self.mass)?;
        check_finite_not_negative("character push force", self.max_push_force)?;
        Ok(())
    }
}

/// What a character stands on.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Ground {
    /// The body.
    pub body: BodyHandle,
    /// Its collider.
    pub collider: ColliderHandle,
    /// The ground's unit normal there.
    pub normal: Vec2,
    /// Where the character touches it, in world coordinates.
    pub point: Vec2,
    /// The centre of the character's foot (the point of its capsule's core nearest the
    /// ground) in the body's frame: the ride carries it as if fixed to the body, so that on
    /// ground that turns the foot stays where it stands.
    anchor: Vec2,
}

/// What one [`World::move_character`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacterMove {
    /// How far the character moved, m: the translation asked for, less what stopped it,
    /// plus the ride on its ground.
    pub translation: Vec2,
    /// Whether it ends the move on ground it can stand on.
    pub grounded: bool,
    /// Whether a slope too steep to stand on pushed it (it slides down such slopes).
    pub sliding: bool,
    /// Whether it climbed a step.
    pub stepped: bool,
    /// Whether it was snapped down to the ground.
    pub snapped: bool,
    /// How far its ground carries it over this step, m (included in `translation`).
    pub ride: Vec2,
}

/// What a character carries from one move to the next: where it is and what it stands on.
/// Keep it with a game's saved state and give it back with [`Character::restore`], and the
/// character moves on as it would have.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CharacterState {
    /// Its capsule's middle.
    pub position: Vec2,
    /// What it stood on after its last move.
    pub ground: Option<Ground>,
}

/// A kinematic character: a capsule the game moves with [`World::move_character`].
#[derive(Debug, Clone)]
pub struct Character {
    def: CharacterDef,
    up: Vec2,
    min_ground_cos: Real,
    position: Vec2,
    ground: Option<Ground>,
    touching: Vec<MoverPlane>,
    planes: Vec<CollisionPlane>,
    scratch: Vec<MoverPlane>,
    /// The planes of bodies that do not give way, when they must be solved alone.
    unyielding: Vec<CollisionPlane>,
}

impl Character {
    /// A character as `def` says, standing nowhere yet.
    ///
    /// # Errors
    /// What [`CharacterDef::validate`] finds.
    pub fn new(def: CharacterDef) -> Result<Self, CaromError> {
        def.validate()?;
        Ok(Character {
            up: def.up.normalize(),
            min_ground_cos: crate::math::sin_cos(def.max_slope).1,
            position: def.position,
            def,
            ground: None,
            touching: Vec::new(),
            planes: Vec::new(),
            scratch: Vec::new(),
            unyielding: Vec::new(),
        })
    }

    /// Where it is: its capsule's middle.
    pub fn position(&self) -> Vec2 {
        self.position
    }

    /// Puts it at `position`, off whatever it stood on.
    ///
    /// # Errors
    /// [`CaromError::NonFinite`] for a position that is not finite, and
    /// [`CaromError::OutOfRange`] for one beyond [`crate::MAX_POSITION`].
    pub fn set_position(&mut self, position: Vec2) -> Result<(), CaromError> {
        self.position = check_position("character position", position)?;
        self.ground = None;
        self.touching.clear();
        Ok(())
    }

    /// Where it is and what it stands on, to save ([`CharacterState`]).
    pub fn state(&self) -> CharacterState {
        CharacterState {
            position: self.position,
            ground: self.ground,
        }
    }

    /// Puts it back as `state` left it: where it was, on what it stood on.
    ///
    /// # Errors
    /// [`CaromError::NonFinite`] for a position or ground that is not finite, and
    /// [`CaromError::OutOfRange`] for a position beyond [`crate::MAX_POSITION`]; the character
    /// is then left as it was.
    pub fn restore(&mut self, state: CharacterState) -> Result<(), CaromError> {
        check_position("character position", state.position)?;
        if let Some(ground) = &state.ground {
            check_finite_vec("character ground normal", ground.normal)?;
            check_finite_vec("character ground point", ground.point)?;
            check_finite_vec("character ground anchor", ground.anchor)?;
        }
        self.position = state.position;
        self.ground = state.ground;
        self.touching.clear();
        Ok(())
    }

    /// Its capsule where it stands, in world coordinates.
    pub fn capsule(&self) -> Capsule {
        self.capsule_at(self.position)
    }

    /// Its unit up.
    pub fn up(&self) -> Vec2 {
        self.up
    }

    /// What it stands on, if anything, as of its last move.
    pub fn ground(&self) -> Option<&Ground> {
        self.ground.as_ref()
    }

    /// Whether it stood on ground after its last move.
    pub fn is_grounded(&self) -> bool {
        self.ground.is_some()
    }

    /// Every collider it touched after its last move, with its plane.
    pub fn touching(&self) -> &[MoverPlane] {
        &self.touching
    }

    /// `velocity` without its part into what the character touches: a game keeps its
    /// character's velocity with this, so that a fall ends on the ground, a jump at a ceiling
    /// and a run at a wall. Ground takes away only vertical speed (walking up a slope keeps
    /// the pace across); a slope too steep to stand on turns a fall into a slide along it
    /// but gives no lift to a walk into it.
    pub fn clip_velocity(&self, velocity: Vec2) -> Vec2 {
        self.touching.iter().fold(velocity, |v, plane| {
            let into = v.dot(&plane.normal);
            if into >= 0.0 {
                return v;
            }
            let direction = self.push_direction(plane.normal);
            let slid = v - plane.normal * into;
            if direction == plane.normal
                || (direction != self.up && slid.dot(&self.up) <= v.dot(&self.up).max(0.0))
            {
                slid
            } else {
                v - direction * (into / plane.normal.dot(&direction))
            }
        })
    }

    fn capsule_at(&self, position: Vec2) -> Capsule {
        let c = &self.def.capsule;
        Capsule::new(c.center1() + position, c.center2() + position, c.radius())
    }

    /// Whether a surface with unit normal `normal` is ground it stands on.
    fn is_ground(&self, normal: Vec2) -> bool {
        normal.dot(&self.up) >= self.min_ground_cos
    }

    /// The way a surface with unit normal `normal` pushes it; see the module documentation.
    fn push_direction(&self, normal: Vec2) -> Vec2 {
        let rise = normal.dot(&self.up);
        if rise >= self.min_ground_cos {
            self.up
        } else if rise > 0.0 {
            let level = normal - self.up * rise;
            let length = level.norm();
            if length > Real::EPSILON {
                level / length
            } else {
                normal
            }
        } else {
            normal
        }
    }
}

impl World {
    /// Moves `character` by `translation` (what the game wants this step: its walk plus its
    /// fall or jump, velocity times `dt`) as far as the world lets it, after first carrying
    /// it along with what it stood on. Pushes the dynamic bodies it walks into and rests its
    /// weight on the one it stands on, both through impulses over `dt` seconds; the bodies
    /// move when the world steps. Call it once a step, before [`World::step`].
    ///
    /// # Errors
    /// [`CaromError::NonFinite`] for a translation that is not finite, and
    /// [`CaromError::OutOfRange`] for one beyond [`crate::MAX_POSITION`] on either axis or
    /// a `dt` outside [`crate::TIME_STEP_RANGE`].
    pub fn move_character(
        &mut self,
        character: &mut Character,
        translation: Vec2,
        dt: Real,
    ) -> Result<CharacterMove, CaromError> {
        check_finite_vec("character translation", translation)?;
        for value in [translation.x, translation.y] {
            let bound = MAX_POSITION;
            check_within(
                "character translation",
                value,
                -bound..=bound,
                "within 1e6 m either way",
            )?;
        }
        check_within(
            "character time step",
            dt,
            TIME_STEP_RANGE,
            "from 1e-6 s to 10 s, as a world step's",
        )?;
        let start = character.position;
        let up = character.up;
        let was_grounded = character.ground.is_some();
        let rising = translation.dot(&up) > 0.0;

        // Ride: where the ground's motion over the coming step carries the character's foot,
        // the character goes too, so that the two move together; and a conveyor belt's
        // surface (its tangent speed, clockwise around its shape) carries it along.
        let ride = character
            .ground
            .map(|ground| {
                let moved = self
                    .body(ground.body)
                    .filter(|body| body.moves())
                    .map_or_else(Vec2::zeros, |body| carried(body, ground.anchor, dt));
                let belt = self
                    .collider(ground.collider)
                    .map_or(0.0, |c| c.surface().tangent_speed);
                moved + perp_cw(ground.normal) * (belt * dt)
            })
            .unwrap_or_else(Vec2::zeros);

        let slid = self.slide_character(character, start, start + ride + translation, dt);
        let mut position = slid.position;
        let mut sliding = slid.sliding;

        // A step: the walk was cut short by something too steep, on the ground.
        let level = |v: Vec2| v - up * v.dot(&up);
        let wanted = level(translation);
        let gone = level(position - start - ride);
        let short = wanted.norm() - gone.dot(&wanted) / wanted.norm().max(Real::EPSILON);
        let mut stepped = false;
        if was_grounded
            && slid.blocked
            && character.def.step_height > 0.0
            && short > LINEAR_SLOP
            && let Some(top) = self.climb_step(character, position, wanted.normalize(), short, dt)
        {
            position = top;
            stepped = true;
            sliding = false;
        }

        // Snap: it walked off a low step or down a slope, and was not jumping.
        let reach = ride.norm();
        let mut ground = self.find_ground(character, position, dt, reach);
        let mut snapped = false;
        if ground.is_none() && was_grounded && !rising && character.def.snap_distance > 0.0 {
            let down = -up * character.def.snap_distance;
            let capsule = character.capsule_at(position);
            let fraction = self.cast_mover(&capsule, down, character.def.filter);
            if fraction < 1.0 {
                let landed = position + down * fraction;
                if let Some(found) = self.find_ground(character, landed, dt, reach) {
                    position = landed;
                    ground = Some(found);
                    snapped = true;
                }
            }
        }

        character.position = position;
        character.ground = ground;
        let capsule = character.capsule_at(position);
        let mut touching = std::mem::take(&mut character.touching);
        self.collide_mover_into(&capsule, character.def.filter, &mut touching);
        character.touching = touching;
        if character.ground.is_some() {
            sliding = false;
        }
        self.push_bodies(character, translation / dt, dt);

        Ok(CharacterMove {
            translation: position - start,
            grounded: character.ground.is_some(),
            sliding,
            stepped,
            snapped,
            ride,
        })
    }

    /// The mover loop toward `target` from `from`: collide, solve with the character's push
    /// directions, cast along the answer, move, and again from there.
    fn slide_character(
        &self,
        character: &mut Character,
        from: Vec2,
        target: Vec2,
        dt: Real,
    ) -> Slide {
        let mut position = from;
        let mut slide = Slide {
            position,
            blocked: false,
            sliding: false,
        };
        let mut found = std::mem::take(&mut character.scratch);
        let mut planes = std::mem::take(&mut character.planes);
        let mut held = std::mem::take(&mut character.unyielding);
        for _ in 0..MAX_CHARACTER_ITERATIONS {
            let capsule = character.capsule_at(position);
            self.collide_mover_into(&capsule, character.def.filter, &mut found);
            planes.clear();
            planes.extend(found.iter().map(|plane| self.predicted_plane(plane, dt)));
            let mut solution =
                self.solve_character_planes(character, target - position, &mut planes);
            self.keep_out_of_unyielding(character, &found, &mut planes, &mut held, &mut solution);
            for plane in planes.iter().filter(|plane| plane.push > 0.0) {
                if !character.is_ground(plane.normal) && plane.normal.dot(&character.up) >= 0.0 {
                    slide.blocked = true;
                    slide.sliding |= plane.normal.dot(&character.up) > 0.0;
                }
            }
            let fraction = self.cast_mover(&capsule, solution.delta, character.def.filter);
            let step = solution.delta * fraction;
            position += step;
            if step.norm() < CHARACTER_MOVE_TOLERANCE {
                break;
            }
        }
        character.scratch = found;
        character.planes = planes;
        character.unyielding = held;
        slide.position = position;
        slide
    }

    /// `plane` as the solver takes it, where its body will be after the coming step: a
    /// platform rising under the character lifts it in the same step, and a body it pushes
    /// makes way as it goes, so that it neither sinks into the one nor lags behind the other.
    fn predicted_plane(&self, plane: &MoverPlane, dt: Real) -> CollisionPlane {
        let mut predicted = plane.rigid();
        if let Some(body) = self.body(plane.body).filter(|body| body.moves()) {
            let anchor = body.local_point(plane.point);
            predicted.offset += plane.normal.dot(&carried(body, anchor, dt));
        }
        predicted
    }

    /// Where bodies that give way (dynamic ones) and bodies that do not (static and
    /// kinematic ones) push the character opposite ways (a pile fallen on it, pressing it
    /// into the floor), the planes cannot all hold, and a solve that ends on a dynamic body's
    /// plane leaves the character in the floor; the cast along it then does not stop it,
    /// since the character already rests in the floor by the slop. So when `solution` goes
    /// into an unyielding body's plane, it is solved again, from where it ended, with those
    /// planes alone: they hold, and the dynamic bodies are left overlapping the character,
    /// which pushes them away. `found[i]` is the plane `planes[i]` was made from; `held` is
    /// room for the unyielding planes.
    fn keep_out_of_unyielding(
        &self,
        character: &Character,
        found: &[MoverPlane],
        planes: &mut [CollisionPlane],
        held: &mut Vec<CollisionPlane>,
        solution: &mut PlaneSolution,
    ) {
        let unyielding = |plane: &MoverPlane| {
            self.body(plane.body)
                .is_some_and(|body| body.kind() != BodyKind::Dynamic)
        };
        let into = |plane: &CollisionPlane| {
            plane.normal.dot(&solution.delta) - plane.offset + LINEAR_SLOP < -LINEAR_SLOP
        };
        let violated = found
            .iter()
            .zip(planes.iter())
            .any(|(from, plane)| unyielding(from) && into(plane));
        if !violated {
            return;
        }
        held.clear();
        held.extend(
            found
                .iter()
                .zip(planes.iter())
                .filter(|(from, _)| unyielding(from))
                .map(|(_, plane)| *plane),
        );
        let again = self.solve_character_planes(character, solution.delta, held);
        let mut pushes = held.iter();
        for (from, plane) in found.iter().zip(planes.iter_mut()) {
            if unyielding(from) {
                plane.push = pushes.next().map_or(0.0, |held| held.push);
            }
        }
        *solution = again;
    }

    /// [`solve_planes`] with the character's push directions, or with plain normals when
    /// those do not settle (a crevice between two steep slopes, whose level pushes meet head
    /// on).
    fn solve_character_planes(
        &self,
        character: &Character,
        target: Vec2,
        planes: &mut [CollisionPlane],
    ) -> PlaneSolution {
        let solution = solve_planes_along(target, planes, |plane| {
            character.push_direction(plane.normal)
        });
        if solution.converged {
            solution
        } else {
            solve_planes(target, planes)
        }
    }

    /// Up a step from `from`, where a walk along unit `ahead` stopped `short` of its length:
    /// up by the step height (less any ceiling), ahead by the walk's rest (at least the
    /// tread, and then at least the radius, which brings a rounded foot over the edge), and
    /// down onto ground no higher than the step height. `None` when any part fails.
    fn climb_step(
        &self,
        character: &Character,
        from: Vec2,
        ahead: Vec2,
        short: Real,
        dt: Real,
    ) -> Option<Vec2> {
        let filter = character.def.filter;
        let up = character.up * character.def.step_height;
        let lifted = from + up * self.cast_mover(&character.capsule_at(from), up, filter);
        let rise = (lifted - from).dot(&character.up);
        let tries = [
            short.max(character.def.step_width),
            short.max(character.def.capsule.radius()),
        ];
        for forward in tries {
            let across = ahead * forward;
            if self.cast_mover(&character.capsule_at(lifted), across, filter) < 1.0 {
                return None;
            }
            let over = lifted + across;
            let down = -character.up * (rise + character.def.snap_distance);
            let fraction = self.cast_mover(&character.capsule_at(over), down, filter);
            if fraction >= 1.0 {
                return None;
            }
            let landed = over + down * fraction;
            if self.find_ground(character, landed, dt, 0.0).is_some()
                && (landed - from).dot(&character.up) > LINEAR_SLOP
            {
                return Some(landed);
            }
        }
        None
    }

    /// The ground under a character at `position` after the coming step of `dt`: of the
    /// surfaces it would stand on within [`CHARACTER_GROUND_PROBE`] below, where their bodies
    /// will be, the most level. `reach` is how much farther to look for them now (as far as
    /// its ground moves in the step).
    fn find_ground(
        &self,
        character: &Character,
        position: Vec2,
        dt: Real,
        reach: Real,
    ) -> Option<Ground> {
        let lowered = CHARACTER_GROUND_PROBE + reach;
        let probe = character.capsule_at(position - character.up * lowered);
        let planes = self.collide_mover(&probe, character.def.filter);
        let best = planes
            .iter()
            .filter(|plane| {
                let predicted = self.predicted_plane(plane, dt).offset;
                character.is_ground(plane.normal)
                    && predicted
                        - (lowered - CHARACTER_GROUND_PROBE) * plane.normal.dot(&character.up)
                        >= 0.0
            })
            .max_by(|a, b| {
                a.normal
                    .dot(&character.up)
                    .total_cmp(&b.normal.dot(&character.up))
            })?;
        let body = self.body(best.body)?;
        let capsule = character.capsule_at(position);
        let (foot, _) = closest_on_segment(best.point, capsule.center1(), capsule.center2());
        Some(Ground {
            body: best.body,
            collider: best.collider,
            normal: best.normal,
            point: best.point,
            anchor: body.local_point(foot),
        })
    }

    /// Pushes the dynamic bodies a character moving at `velocity` walks into, each at most
    /// its push force over `dt`, toward the character's velocity along the contact normal (no
    /// faster); and rests its weight on dynamic ground.
    fn push_bodies(&mut self, character: &Character, velocity: Vec2, dt: Real) {
        let max_impulse = character.def.max_push_force * dt;
        for plane in &character.touching {
            if character.is_ground(plane.normal) {
                continue;
            }
            let Some(body) = self.body(plane.body) else {
                continue;
            };
            if !body.is_dynamic() || max_impulse <= 0.0 {
                continue;
            }
            let into = -plane.normal;
            let point = plane.patch_point_nearest(body.center_of_mass());
            let arm = point - body.center_of_mass();
            let closing = (velocity - body.velocity_at(point)).dot(&into);
            if closing <= 0.0 {
                continue;
            }
            let turn = cross(arm, into);
            let mass = 1.0 / (body.inv_mass() + turn * turn * body.inv_inertia());
            let impulse = (mass * closing).min(max_impulse);
            if let Some(mut pushed) = self.body_mut(plane.body) {
                let _ = pushed.apply_impulse(into * impulse, point);
            }
        }
        if let Some(ground) = character.ground
            && character.def.mass > 0.0
            && self.body(ground.body).is_some_and(|b| b.is_dynamic())
        {
            let weight = self.gravity() * character.def.mass * dt;
            if let Some(mut below) = self.body_mut(ground.body) {
                let _ = below.apply_impulse(weight, ground.point);
            }
        }
    }
}

/// How far the point at `anchor` (in `body`'s frame) moves in the next `dt` seconds at the
/// body's velocities, as the world's step moves it: its centre of mass along, the rest
/// turned about that centre.
fn carried(body: &Body, anchor: Vec2, dt: Real) -> Vec2 {
    let now = body.world_point(anchor);
    let center = body.center_of_mass();
    let turned = rotation(body.angular_velocity() * dt) * (now - center);
    center + body.linear_velocity() * dt + turned - now
}

/// Where the mover loop ended, and what stopped it.
struct Slide {
    position: Vec2,
    /// A surface too steep to stand on (or a wall) pushed it.
    blocked: bool,
    /// A slope too steep to stand on pushed it.
    sliding: bool,
}
