//! The carom demo app's library: everything the `carom` binary does that is not a window, so
//! tests can drive it. [`run`] runs a scene headless and measures it; [`demo`] is the
//! interactive demo's state (scene, camera, grab, fixed-step clock) without its window, and
//! [`metrics`] what it measures live; [`snapshot`] renders a scene offscreen to an image.

pub mod demo;
pub mod metrics;
pub mod run;
pub mod snapshot;
