//! The carom demo app's library. Most of it knows nothing of windows, so tests can drive it:
//! [`run`] runs a scene headless and measures it; [`recording`] records a run and plays one
//! back; [`demo`] is the interactive demo's state
//! (scene, camera, grab, fixed-step clock) and [`metrics`] what it measures live; [`snapshot`]
//! renders a scene offscreen to an image; [`accuracy_panel`] holds what the sidebar shows of
//! the accuracy sweep (`carom_bench::sweep`, which `carom bench` runs) for the scene running.
//! The window itself is [`window`], its egui sidebar [`ui`], and [`capture`] reads the
//! window's pixels back for screenshots. [`files`] is where
//! scenes and reports are read: the disk, or, in the web build, files built into the program.

// Screen and plot values are `f32`; in the double-precision build the casts from world values
// narrow, in the single-precision build they are no-ops.
#![cfg_attr(feature = "f64", allow(clippy::unnecessary_cast))]

pub mod accuracy_panel;
pub mod capture;
pub mod demo;
pub mod files;
pub mod metrics;
pub mod recording;
pub mod run;
pub mod snapshot;
pub mod ui;
pub mod window;
