//! `carom run` as a user calls it: the real binary, its output and its exit status.

use std::path::PathBuf;
use std::process::{Command, Output};

fn carom(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_carom"))
        .args(args)
        .current_dir(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .output()
        .expect("the carom binary runs")
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The value of `key` in the one-line JSON object `json` (a test-sized reader).
fn field<'a>(json: &'a str, key: &str) -> &'a str {
    let start = json
        .find(&format!("\"{key}\": "))
        .unwrap_or_else(|| panic!("no {key} in {json}"))
        + key.len()
        + 4;
    let rest = &json[start..];
    let end = rest.find([',', '}']).unwrap();
    rest[..end].trim_matches('"')
}

#[test]
fn json_has_the_promised_keys_in_order() {
    let output = carom(&["run", "demos/collision.ron", "--steps", "30", "--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json = stdout(&output);
    let keys = [
        "ms_per_step",
        "ms_per_step_median",
        "steps",
        "bodies",
        "contacts",
        "max_penetration",
        "kinetic_energy",
        "max_speed",
        "nan",
        "asleep",
        "hash",
    ];
    let positions: Vec<usize> = keys
        .iter()
        .map(|k| {
            json.find(&format!("\"{k}\""))
                .unwrap_or_else(|| panic!("{k} missing"))
        })
        .collect();
    assert!(
        positions.windows(2).all(|w| w[0] < w[1]),
        "keys out of order: {json}"
    );
    assert_eq!(field(&json, "steps"), "30");
    assert_eq!(field(&json, "nan"), "false");
    assert_eq!(field(&json, "hash").len(), 16);
}

#[test]
fn the_same_run_gives_the_same_hash() {
    let args = [
        "run",
        "demos/pyramid.ron",
        "--steps",
        "120",
        "--json",
        "--solver",
        "sequential-impulse",
    ];
    let (first, second) = (stdout(&carom(&args)), stdout(&carom(&args)));
    assert_eq!(field(&first, "hash"), field(&second, "hash"));
    // Different options, different result.
    let other = stdout(&carom(&[
        "run",
        "demos/pyramid.ron",
        "--steps",
        "120",
        "--json",
    ]));
    assert_ne!(field(&first, "hash"), field(&other, "hash"));
}

/// Every scene through the binary: 600 steps, but 150 for Box2D's four large recipes, which
/// settle or spin up within that and are run at length, optimised, by `carom bench` and the
/// benchmarks (600 steps of them here, unoptimised, took two thirds of this test's time). The
/// runs go two at a time, each on one thread (a scene's bits are the same on any thread count),
/// the largest first, so the two cores stay busy to the end.
#[test]
fn every_demo_runs_through_the_binary_without_nan() {
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos");
    let mut scenes: Vec<String> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".ron"))
        .collect();
    assert!(!scenes.is_empty());
    // Box2D's large recipes take longest.
    let large = [
        "many_pyramids.ron",
        "spinner.ron",
        "joint_grid.ron",
        "large_pyramid.ron",
    ];
    scenes.sort_by_key(|name| (!large.contains(&name.as_str()), name.clone()));
    let next = std::sync::atomic::AtomicUsize::new(0);
    let failures = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..2 {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(scene) = scenes.get(i) else {
                        break;
                    };
                    let steps = if large.contains(&scene.as_str()) {
                        "150"
                    } else {
                        "600"
                    };
                    let output = Command::new(env!("CARGO_BIN_EXE_carom"))
                        .args(["run", &format!("demos/{scene}"), "--steps", steps, "--json"])
                        .env("RAYON_NUM_THREADS", "1")
                        .current_dir(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../.."))
                        .output()
                        .expect("the carom binary runs");
                    if !output.status.success() {
                        failures
                            .lock()
                            .unwrap()
                            .push(format!("{scene}: {}", stderr(&output)));
                    } else if field(&stdout(&output), "nan") != "false" {
                        failures.lock().unwrap().push(format!("{scene}: a NaN"));
                    }
                }
            });
        }
    });
    let failures = failures.into_inner().unwrap();
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn effects_can_be_added_and_removed() {
    let run = |effects: &str| {
        let output = carom(&[
            "run",
            "demos/tunneling.ron",
            "--steps",
            "40",
            "--json",
            effects,
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        stdout(&output)
    };
    // The scene leaves continuous collision out: the ball keeps its 300 m/s through the wall.
    assert_eq!(field(&run("--effects=-drag"), "contacts"), "0");
    // Added, the wall stops it and holds a contact with it.
    assert_eq!(field(&run("--effects=+continuous"), "contacts"), "1");
}

#[test]
fn bad_input_fails_cleanly_with_the_reason() {
    for (args, expected) in [
        (vec!["run", "demos/no_such.ron"], "cannot read"),
        (
            vec!["run", "tests/scenes/bad_syntax.ron"],
            "bad_syntax.ron:3:5",
        ),
        (
            vec!["run", "tests/scenes/bad_event.ron"],
            "no body is named",
        ),
        (
            vec!["run", "demos/pyramid.ron", "--effects=+magic"],
            "unknown effect",
        ),
        (
            vec!["run", "demos/pyramid.ron", "--iterations", "0"],
            "iterations",
        ),
    ] {
        let output = carom(&args);
        let message = stderr(&output);
        assert!(!output.status.success(), "{args:?} succeeded");
        assert!(message.contains(expected), "{args:?}: {message}");
        assert!(
            !message.contains("panicked"),
            "{args:?} panicked: {message}"
        );
    }
}
