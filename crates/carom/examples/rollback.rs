//! Rollback netcode over carom: two players push boxes about an arena, each on their own
//! machine, and each player's input reaches the other machine `DELAY` frames late.
//!
//! Each machine runs the game at once on what it knows: its own player's input, and for the
//! other player a prediction (the last input that arrived, as GGRS and its kind predict). It
//! keeps a snapshot of every recent frame. When a late input arrives and differs from what was
//! predicted, it restores the snapshot of that frame and steps again to the present with the
//! input now known. Because a step gives the same bits every time, both machines end exactly
//! where a game with no delay ends: the example checks the three state hashes are equal.
//!
//! `cargo run -p carom --example rollback`

use carom::{BodyDef, BodyHandle, CaromError, Real, Shape, Snapshot, World, vec2};
use std::time::{Duration, Instant};

/// Frames played.
const FRAMES: u64 = 600;
/// Frames an input takes to reach the other machine.
const DELAY: u64 = 6;
const DT: Real = 1.0 / 60.0;

/// One player's input for one frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Input {
    /// -1 pushes left, 1 right.
    push: i8,
    jump: bool,
}

/// What player `player` does at `frame`: a fixed script, changing every 20 frames or so, that
/// neither machine can guess ahead of time.
fn script(player: usize, frame: u64) -> Input {
    let mut x = (frame / 20 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ (player as u64 + 1) << 40;
    x ^= x >> 31;
    x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x ^= x >> 29;
    Input {
        push: (x % 3) as i8 - 1,
        jump: (x >> 8).is_multiple_of(4),
    }
}

/// The arena: a floor and two walls, a pile of boxes in the middle, a player on each side.
fn arena() -> Result<(World, [BodyHandle; 2]), CaromError> {
    let mut world = World::new();
    world.add_body(BodyDef::static_body(Shape::rect(15.0, 0.5)).position(vec2(0.0, -0.5)))?;
    for x in [-15.5, 15.5] {
        world.add_body(BodyDef::static_body(Shape::rect(0.5, 5.0)).position(vec2(x, 5.0)))?;
    }
    for row in 0..6 {
        for column in 0..6 - row {
            let x = column as Real - (5 - row) as Real * 0.5;
            world.add_body(
                BodyDef::dynamic(Shape::rect(0.45, 0.45))
                    .position(vec2(x, 0.5 + row as Real))
                    .friction(0.6),
            )?;
        }
    }
    let mut player = |x: Real| {
        world.add_body(
            BodyDef::dynamic(Shape::capsule(vec2(0.0, -0.4), vec2(0.0, 0.4), 0.35))
                .position(vec2(x, 1.0))
                .density(3.0)
                .fixed_rotation(true),
        )
    };
    let players = [player(-10.0)?, player(10.0)?];
    Ok((world, players))
}

/// Applies both players' inputs for a frame and steps.
fn play(world: &mut World, players: [BodyHandle; 2], inputs: [Input; 2]) -> Result<(), CaromError> {
    for (&player, input) in players.iter().zip(inputs) {
        let standing = world
            .body(player)
            .is_some_and(|body| body.linear_velocity().y.abs() < 0.05);
        let Some(mut body) = world.body_mut(player) else {
            continue;
        };
        body.apply_force_at_center(vec2(input.push as Real * 120.0, 0.0))?;
        if input.jump && standing {
            body.apply_impulse_at_center(vec2(0.0, 18.0))?;
        }
    }
    world.step(DT)
}

/// One player's machine.
struct Machine {
    /// Which player is local: 0 or 1.
    me: usize,
    world: World,
    players: [BodyHandle; 2],
    /// The state before each of the last frames, by frame modulo its length.
    ring: Vec<Snapshot>,
    /// The other player's input each frame was played with: arrived, or predicted.
    used: Vec<Input>,
    /// The other player's inputs that have arrived, in order.
    arrived: Vec<Input>,
    /// Frames played.
    frame: u64,
    rollbacks: u64,
    replayed_frames: u64,
    snapshot_time: Duration,
    step_time: Duration,
}

impl Machine {
    fn new(me: usize) -> Result<Machine, CaromError> {
        let (world, players) = arena()?;
        let ring = (0..=DELAY).map(|_| world.snapshot()).collect();
        Ok(Machine {
            me,
            world,
            players,
            ring,
            used: Vec::new(),
            arrived: Vec::new(),
            frame: 0,
            rollbacks: 0,
            replayed_frames: 0,
            snapshot_time: Duration::ZERO,
            step_time: Duration::ZERO,
        })
    }

    /// Plays `frame` (the state is the one before it), keeping a snapshot of it first.
    fn play_frame(&mut self, frame: u64) -> Result<(), CaromError> {
        let clock = Instant::now();
        let slot = (frame % self.ring.len() as u64) as usize;
        self.world.snapshot_into(&mut self.ring[slot]);
        self.snapshot_time += clock.elapsed();
        let mut inputs = [Input::default(); 2];
        inputs[self.me] = script(self.me, frame);
        inputs[1 - self.me] = self.used[frame as usize];
        let clock = Instant::now();
        play(&mut self.world, self.players, inputs)?;
        self.step_time += clock.elapsed();
        Ok(())
    }

    /// The next frame: the other player's input of frame `frame - DELAY` arrives first, then
    /// this frame is played with a prediction of theirs.
    fn advance(&mut self) -> Result<(), CaromError> {
        if self.frame >= DELAY {
            self.arrive()?;
        }
        let predicted = self.arrived.last().copied().unwrap_or_default();
        self.used.push(predicted);
        let frame = self.frame;
        self.play_frame(frame)?;
        self.frame += 1;
        Ok(())
    }

    /// The other player's next input arrives. If a frame was played with another, the machine
    /// goes back to that frame and plays up to now again: the arrived input at that frame,
    /// and from then on the new prediction, which is that input.
    fn arrive(&mut self) -> Result<(), CaromError> {
        let frame = self.arrived.len() as u64;
        let input = script(1 - self.me, frame);
        self.arrived.push(input);
        if frame >= self.frame || self.used[frame as usize] == input {
            return Ok(());
        }
        for used in &mut self.used[frame as usize..] {
            *used = input;
        }
        let clock = Instant::now();
        let slot = (frame % self.ring.len() as u64) as usize;
        self.world.restore(&self.ring[slot]);
        self.snapshot_time += clock.elapsed();
        self.rollbacks += 1;
        for again in frame..self.frame {
            self.play_frame(again)?;
            self.replayed_frames += 1;
        }
        Ok(())
    }

    /// After the last frame: the other player's last inputs arrive.
    fn finish(&mut self) -> Result<(), CaromError> {
        while (self.arrived.len() as u64) < self.frame {
            self.arrive()?;
        }
        Ok(())
    }
}

fn main() -> Result<(), String> {
    let error = |e: CaromError| e.to_string();
    // The game with no delay: both inputs known at every frame.
    let (mut world, players) = arena().map_err(error)?;
    let clock = Instant::now();
    for frame in 0..FRAMES {
        play(&mut world, players, [script(0, frame), script(1, frame)]).map_err(error)?;
    }
    let plain = clock.elapsed();
    let expected = world.state_hash();

    let mut machines = [
        Machine::new(0).map_err(error)?,
        Machine::new(1).map_err(error)?,
    ];
    for _ in 0..FRAMES {
        for machine in &mut machines {
            machine.advance().map_err(error)?;
        }
    }
    println!(
        "{FRAMES} frames, {} bodies, inputs {DELAY} frames late; with no delay {:.3} ms a frame",
        world.body_count(),
        plain.as_secs_f64() * 1e3 / FRAMES as f64
    );
    for machine in &mut machines {
        machine.finish().map_err(error)?;
        let hash = machine.world.state_hash();
        let snapshots = machine.frame + machine.replayed_frames;
        println!(
            "player {}'s machine: {} rollbacks, {} frames played again; {:.3} ms a step, \
             {:.3} ms a snapshot or restore; hash {hash:016x}",
            machine.me + 1,
            machine.rollbacks,
            machine.replayed_frames,
            machine.step_time.as_secs_f64() * 1e3 / snapshots as f64,
            machine.snapshot_time.as_secs_f64() * 1e3 / (snapshots + machine.rollbacks) as f64,
        );
        if machine.rollbacks == 0 {
            return Err("no prediction was ever wrong: the example shows nothing".into());
        }
        if hash != expected {
            return Err(format!(
                "player {}'s machine ended in {hash:016x}, the game with no delay in \
                 {expected:016x}",
                machine.me + 1
            ));
        }
    }
    println!("both machines end in the hash of the game with no delay: {expected:016x}");
    Ok(())
}
