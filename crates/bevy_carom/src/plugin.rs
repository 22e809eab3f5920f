//! [`CaromPlugin`]: where in Bevy's schedules the world is kept in step and stepped.

use crate::interpolation::interpolate;
use crate::messages::{
    ContactEnded, ContactStarted, Hit, JointBroken, PhysicsError, SensorEntered, SensorExited,
    write_messages,
};
use crate::scene::SceneLoaded;
use crate::step::{step, write_back};
use crate::sync::create::{
    create_bodies, create_colliders, create_joints, give_lone_colliders_bodies, retry_refused,
};
use crate::sync::remove::{body_removed, collider_removed, joint_removed, remove_gone};
use crate::sync::update::{
    apply_forces, collider_flag_added, collider_flag_removed, update_bodies, update_colliders,
    update_joints,
};
use crate::world::CaromWorld;
use bevy::app::{App, FixedPostUpdate, Plugin, RunFixedMainLoop, RunFixedMainLoopSystems};
use bevy::ecs::schedule::{IntoScheduleConfigs, SystemSet};

/// carom in a Bevy app: add it beside Bevy's `MinimalPlugins` or `DefaultPlugins` (it needs
/// `TransformPlugin` and the time plugin, which both have).
///
/// On each of Bevy's fixed steps (`Time<Fixed>`, 64 Hz unless set), in `FixedPostUpdate`,
/// after the game's `FixedUpdate`:
/// 1. [`CaromSystems::Prepare`]: what was despawned or removed leaves the world; new bodies
///    (with their colliders), colliders and joints are made, in entity order; changed
///    components reach their objects; forces and impulses are applied.
/// 2. [`CaromSystems::Step`]: the world steps by the fixed timestep.
/// 3. [`CaromSystems::Writeback`]: poses, velocities and sleep go back to the components; the
///    step's events go out as messages.
///
/// After the frame's fixed steps, [`crate::Interpolated`] bodies are placed between their
/// last two poses for drawing.
#[derive(Debug, Default, Clone, Copy)]
pub struct CaromPlugin;

/// The plugin's stages in `FixedPostUpdate`, to order the game's systems around them.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CaromSystems {
    /// Removals, new objects, changes, forces.
    Prepare,
    /// The step.
    Step,
    /// Components and messages from the step.
    Writeback,
}

impl Plugin for CaromPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<CaromWorld>()
            .add_message::<ContactStarted>()
            .add_message::<ContactEnded>()
            .add_message::<SensorEntered>()
            .add_message::<SensorExited>()
            .add_message::<Hit>()
            .add_message::<JointBroken>()
            .add_message::<PhysicsError>()
            .add_message::<SceneLoaded>()
            .add_observer(body_removed)
            .add_observer(collider_removed)
            .add_observer(joint_removed)
            .add_observer(collider_flag_added)
            .add_observer(collider_flag_removed)
            .configure_sets(
                FixedPostUpdate,
                (
                    CaromSystems::Prepare,
                    CaromSystems::Step,
                    CaromSystems::Writeback,
                )
                    .chain(),
            )
            .add_systems(
                FixedPostUpdate,
                (
                    remove_gone,
                    give_lone_colliders_bodies,
                    retry_refused,
                    create_bodies,
                    create_colliders,
                    create_joints,
                    update_bodies,
                    update_colliders,
                    update_joints,
                    apply_forces,
                )
                    .chain()
                    .in_set(CaromSystems::Prepare),
            )
            .add_systems(FixedPostUpdate, step.in_set(CaromSystems::Step))
            .add_systems(
                FixedPostUpdate,
                (write_back, write_messages)
                    .chain()
                    .in_set(CaromSystems::Writeback),
            )
            .add_systems(
                RunFixedMainLoop,
                interpolate.in_set(RunFixedMainLoopSystems::AfterFixedMainLoop),
            );
    }
}
