//! The world's queries: rays, shape casts, overlaps and picking.

use crate::convert::{finite, object, vec2, vec2_out};
use crate::defs;
use crate::handles::{Body, Collider, Tag, key_of};
use crate::world::World;
use carom::{Aabb, BodyHandle, CastHit, ColliderHandle, QueryFilter, Ray, WorldShape};
use wasm_bindgen::prelude::*;

impl World {
    /// A query's filter, its excluded body checked to be this world's.
    fn query_filter(&self, filter: &JsValue) -> Result<QueryFilter, JsError> {
        defs::query_filter(filter, |body| {
            let (world, index, generation) = key_of(body, Tag::Body, "query filter.excludeBody")?;
            self.owns(world, "query filter.excludeBody")?;
            Ok(BodyHandle::from_raw_parts(index, generation))
        })
    }

    fn colliders(&self, handles: Vec<ColliderHandle>) -> Vec<Collider> {
        handles
            .into_iter()
            .map(|c| Collider::new(self.key, c))
            .collect()
    }

    fn hit(&self, hit: CastHit) -> JsValue {
        object(&[
            ("body", Body::new(self.key, hit.body).into()),
            ("collider", Collider::new(self.key, hit.collider).into()),
            ("point", vec2_out(hit.point)),
            ("normal", vec2_out(hit.normal)),
            ("fraction", (hit.fraction as f64).into()),
        ])
    }
}

/// A query's shape, placed at `position` and turned by `angle`.
fn placed_shape(shape: &JsValue, position: &JsValue, angle: f64) -> Result<WorldShape, JsError> {
    Ok(WorldShape::at(
        &defs::shape(shape, "shape")?,
        vec2(position, "position")?,
        finite(angle, "angle")?,
    ))
}

#[wasm_bindgen]
impl World {
    /// The first collider the ray from `origin` along `translation` meets, or `undefined`.
    #[wasm_bindgen(js_name = castRay, unchecked_return_type = "CastHit | undefined")]
    pub fn cast_ray(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] origin: JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] translation: JsValue,
        #[wasm_bindgen(unchecked_param_type = "QueryFilter | undefined")] filter: JsValue,
    ) -> Result<JsValue, JsError> {
        let ray = Ray::new(vec2(&origin, "origin")?, vec2(&translation, "translation")?);
        let filter = self.query_filter(&filter)?;
        self.with(|sim| {
            Ok(sim
                .world()
                .cast_ray(&ray, filter)
                .map_or(JsValue::UNDEFINED, |hit| self.hit(hit)))
        })
    }

    /// Every collider the ray meets, nearest first.
    #[wasm_bindgen(js_name = castRayAll, unchecked_return_type = "CastHit[]")]
    pub fn cast_ray_all(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] origin: JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] translation: JsValue,
        #[wasm_bindgen(unchecked_param_type = "QueryFilter | undefined")] filter: JsValue,
    ) -> Result<JsValue, JsError> {
        let ray = Ray::new(vec2(&origin, "origin")?, vec2(&translation, "translation")?);
        let filter = self.query_filter(&filter)?;
        self.with(|sim| {
            let hits = sim.world().cast_ray_all(&ray, filter);
            Ok(hits
                .into_iter()
                .map(|hit| self.hit(hit))
                .collect::<js_sys::Array>()
                .into())
        })
    }

    /// The first collider `shape`, placed at `position` turned by `angle` and moved along
    /// `translation`, meets, or `undefined`.
    #[wasm_bindgen(js_name = castShape, unchecked_return_type = "CastHit | undefined")]
    pub fn cast_shape(
        &self,
        #[wasm_bindgen(unchecked_param_type = "ShapeDef")] shape: JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] position: JsValue,
        angle: f64,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] translation: JsValue,
        #[wasm_bindgen(unchecked_param_type = "QueryFilter | undefined")] filter: JsValue,
    ) -> Result<JsValue, JsError> {
        let shape = placed_shape(&shape, &position, angle)?;
        let translation = vec2(&translation, "translation")?;
        let filter = self.query_filter(&filter)?;
        self.with(|sim| {
            Ok(sim
                .world()
                .cast_shape(&shape, translation, filter)
                .map_or(JsValue::UNDEFINED, |hit| self.hit(hit)))
        })
    }

    /// The colliders whose boxes overlap the box from `min` to `max`.
    #[wasm_bindgen(js_name = overlapAabb)]
    pub fn overlap_aabb(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] min: JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] max: JsValue,
        #[wasm_bindgen(unchecked_param_type = "QueryFilter | undefined")] filter: JsValue,
    ) -> Result<Vec<Collider>, JsError> {
        let aabb = Aabb {
            min: vec2(&min, "min")?,
            max: vec2(&max, "max")?,
        };
        let filter = self.query_filter(&filter)?;
        self.with(|sim| Ok(self.colliders(sim.world().query_aabb(&aabb, filter))))
    }

    /// The colliders that overlap `shape` placed at `position` turned by `angle`.
    #[wasm_bindgen(js_name = overlapShape)]
    pub fn overlap_shape(
        &self,
        #[wasm_bindgen(unchecked_param_type = "ShapeDef")] shape: JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] position: JsValue,
        angle: f64,
        #[wasm_bindgen(unchecked_param_type = "QueryFilter | undefined")] filter: JsValue,
    ) -> Result<Vec<Collider>, JsError> {
        let shape = placed_shape(&shape, &position, angle)?;
        let filter = self.query_filter(&filter)?;
        self.with(|sim| Ok(self.colliders(sim.world().query_shape(&shape, filter))))
    }

    /// The body under `point`, for picking with a mouse: dynamic over kinematic over static.
    #[wasm_bindgen(js_name = bodyAt)]
    pub fn body_at(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec2")] point: JsValue,
    ) -> Result<Option<Body>, JsError> {
        let point = vec2(&point, "point")?;
        self.with(|sim| Ok(sim.world().body_at(point).map(|h| Body::new(self.key, h))))
    }
}
