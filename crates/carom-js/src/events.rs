//! The last step's events as plain objects: contacts beginning and ending, sensors entered and
//! left, hard hits, joints broken.

use crate::convert::{object, vec2_out};
use crate::handles::{Body, Collider, Joint};
use crate::world::World;
use carom::{ContactEvent, JointEvent, SensorEvent};
use js_sys::Array;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
impl World {
    /// The contacts that began or ended in the last step.
    #[wasm_bindgen(js_name = contactEvents, unchecked_return_type = "ContactEvent[]")]
    pub fn contact_events(&self) -> Result<JsValue, JsError> {
        let key = self.key;
        self.with(|sim| {
            Ok(sim
                .world()
                .contact_events()
                .iter()
                .map(|event| {
                    let kind = match event {
                        ContactEvent::Begin(_) => "begin",
                        ContactEvent::End(_) => "end",
                    };
                    let pair = event.pair();
                    object(&[
                        ("type", kind.into()),
                        ("colliderA", Collider::new(key, pair.collider_a).into()),
                        ("colliderB", Collider::new(key, pair.collider_b).into()),
                        ("bodyA", Body::new(key, pair.body_a).into()),
                        ("bodyB", Body::new(key, pair.body_b).into()),
                    ])
                })
                .collect::<Array>()
                .into())
        })
    }

    /// What entered or left a sensor in the last step.
    #[wasm_bindgen(js_name = sensorEvents, unchecked_return_type = "SensorEvent[]")]
    pub fn sensor_events(&self) -> Result<JsValue, JsError> {
        let key = self.key;
        self.with(|sim| {
            Ok(sim
                .world()
                .sensor_events()
                .iter()
                .map(|event| {
                    let kind = match event {
                        SensorEvent::Begin(_) => "begin",
                        SensorEvent::End(_) => "end",
                    };
                    let overlap = event.overlap();
                    object(&[
                        ("type", kind.into()),
                        ("sensor", Collider::new(key, overlap.sensor).into()),
                        ("visitor", Collider::new(key, overlap.visitor).into()),
                    ])
                })
                .collect::<Array>()
                .into())
        })
    }

    /// The hard hits of the last step, on colliders made with `hitEvents: true`.
    #[wasm_bindgen(js_name = hitEvents, unchecked_return_type = "HitEvent[]")]
    pub fn hit_events(&self) -> Result<JsValue, JsError> {
        let key = self.key;
        self.with(|sim| {
            Ok(sim
                .world()
                .hit_events()
                .iter()
                .map(|hit| {
                    object(&[
                        ("colliderA", Collider::new(key, hit.pair.collider_a).into()),
                        ("colliderB", Collider::new(key, hit.pair.collider_b).into()),
                        ("point", vec2_out(hit.point)),
                        ("normal", vec2_out(hit.normal)),
                        ("approachSpeed", (hit.approach_speed as f64).into()),
                    ])
                })
                .collect::<Array>()
                .into())
        })
    }

    /// The joints that broke in the last step (they are no longer in the world).
    #[wasm_bindgen(js_name = jointEvents, unchecked_return_type = "JointEvent[]")]
    pub fn joint_events(&self) -> Result<JsValue, JsError> {
        let key = self.key;
        self.with(|sim| {
            Ok(sim
                .world()
                .joint_events()
                .iter()
                // Events carom adds later are not reported here yet.
                .filter_map(|event| match *event {
                    JointEvent::Broken {
                        joint,
                        bodies,
                        force,
                        torque,
                    } => Some(object(&[
                        ("type", "broken".into()),
                        ("joint", Joint::new(key, joint).into()),
                        ("bodyA", Body::new(key, bodies[0]).into()),
                        ("bodyB", Body::new(key, bodies[1]).into()),
                        ("force", vec2_out(force)),
                        ("torque", (torque as f64).into()),
                    ])),
                    _ => None,
                })
                .collect::<Array>()
                .into())
        })
    }
}
