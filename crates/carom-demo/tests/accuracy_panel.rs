//! The sidebar's measured front, driven headless: egui runs the real sidebar on a `Demo`
//! without a window or GPU, and the test reads what it drew.

use carom::SolverKind;
use carom_bench::sweep::report;
use carom_demo::accuracy_panel::{Marker, Source};
use carom_demo::demo::Demo;
use carom_demo::ui::{SIDEBAR_WIDTH, sidebar};
use std::path::PathBuf;

const VIEWPORT: [u32; 2] = [980, 720];

fn demos() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../demos")
}

/// A CSV of the pendulum's points as `carom bench` writes them: soft step at 4 substeps over
/// 1, 2 and 4 iterations, a slower 8-substep setting, sequential impulse, and Box2D.
const PENDULUM: &str = "\
engine,scene,error_kind,solver,iterations,substeps,ms_per_step,error,error_unit,max_penetration_m,joint_hertz,contact_hertz,stabilization,joints
carom,pendulum,Period,sequential impulse,8,1,0.004000,9.000e-1,%,0.000000,,,,true
carom,pendulum,Period,soft step,1,4,0.010000,4.000e-1,%,0.000000,,,,true
carom,pendulum,Period,soft step,2,4,0.020000,2.000e-1,%,0.000000,,,,true
carom,pendulum,Period,soft step,4,4,0.040000,5.000e-2,%,0.000000,,,,true
carom,pendulum,Period,soft step,1,8,0.080000,1.000e-2,%,0.000000,,,,true
Box2D,pendulum,Period,soft step,1,4,0.012000,4.000e-1,%,,,30,,true
";

/// What one frame of the sidebar showed.
struct Frame {
    /// Every text drawn, with where.
    texts: Vec<(String, egui::Pos2)>,
}

impl Frame {
    fn has(&self, text: &str) -> bool {
        self.texts.iter().any(|(t, _)| t.contains(text))
    }

    /// Where the text that is exactly `text` (trimmed) was drawn.
    fn position_of(&self, text: &str) -> Option<egui::Pos2> {
        self.texts
            .iter()
            .find(|(t, _)| t.trim() == text)
            .map(|(_, pos)| *pos)
    }

    fn all(&self) -> String {
        let texts: Vec<&str> = self.texts.iter().map(|(t, _)| t.as_str()).collect();
        texts.join(" | ")
    }
}

/// Runs the sidebar once, as the window does, on a screen tall enough to hold all of it.
fn frame(ctx: &egui::Context, demo: &mut Demo, events: Vec<egui::Event>) -> Frame {
    let input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(1280.0, 2400.0),
        )),
        events,
        ..Default::default()
    };
    let mut error = None;
    let mut output = ctx.run_ui(input, |ui| {
        egui::Panel::left("sidebar")
            .exact_size(SIDEBAR_WIDTH)
            .resizable(false)
            .show(ui, |ui| sidebar(ui, demo, &mut error));
    });
    assert_eq!(error, None);
    // No renderer takes the font atlas: dropped on purpose (egui checks in debug builds).
    output.textures_delta.clear();
    let mut texts = Vec::new();
    for clipped in &output.shapes {
        collect_texts(&clipped.shape, &mut texts);
    }
    Frame { texts }
}

fn collect_texts(shape: &egui::Shape, out: &mut Vec<(String, egui::Pos2)>) {
    match shape {
        egui::Shape::Text(text) => out.push((text.galley.text().to_string(), text.pos)),
        egui::Shape::Vec(shapes) => shapes.iter().for_each(|s| collect_texts(s, out)),
        _ => {}
    }
}

/// Sets the demo's solver as the sidebar's controls do.
fn set_solver(demo: &mut Demo, kind: SolverKind, iterations: u32, substeps: u32) {
    let mut params = *demo.scene.world.solver();
    params.kind = kind;
    params.iterations = Some(iterations);
    params.substeps = substeps;
    demo.scene
        .world
        .update_settings(|s| s.solver = params)
        .unwrap();
}

fn marker_of(demo: &Demo) -> Marker {
    demo.accuracy.marker().cloned().expect("a marker")
}

#[test]
fn the_marker_moves_when_the_iteration_count_changes() {
    let mut demo = Demo::open(&demos(), &demos().join("pendulum.ron"), VIEWPORT).unwrap();
    let path = demo.scene_path.clone();
    demo.accuracy
        .set_points(&path, report::parse_csv(PENDULUM).unwrap());
    set_solver(&mut demo, SolverKind::SoftStep, 1, 4);
    let ctx = egui::Context::default();

    let first = frame(&ctx, &mut demo, Vec::new());
    let before = marker_of(&demo);
    assert!(before.exact);
    assert_eq!(
        (
            before.point.setting.iterations,
            before.point.setting.substeps
        ),
        (1, 4)
    );
    assert_eq!((before.point.ms_per_step, before.point.error), (0.01, 0.4));
    assert!(
        first.has("you are here: soft step, 4 substeps, 1 iteration"),
        "{}",
        first.all()
    );
    assert!(first.has("0.010 ms/step, error 0.400 %"), "{}", first.all());
    // The plot's own label at the marker, and a legend with both engines.
    let drawn_before = first
        .position_of("you are here")
        .unwrap_or_else(|| panic!("{}", first.all()));
    assert!(first.has("carom") && first.has("Box2D"), "{}", first.all());
    assert!(
        first.has("ms per step") && first.has("error (%)"),
        "{}",
        first.all()
    );

    // The sidebar's iteration slider to 4.
    set_solver(&mut demo, SolverKind::SoftStep, 4, 4);
    let second = frame(&ctx, &mut demo, Vec::new());
    let after = marker_of(&demo);
    assert!(after.exact);
    assert_ne!(after.point.setting, before.point.setting);
    assert_eq!(after.point.setting.iterations, 4);
    assert_eq!((after.point.ms_per_step, after.point.error), (0.04, 0.05));
    assert!(
        second.has("you are here: soft step, 4 substeps, 4 iterations"),
        "{}",
        second.all()
    );
    assert!(
        second.has("0.040 ms/step, error 0.0500 %"),
        "{}",
        second.all()
    );
    assert!(!second.has("0.010 ms/step"), "{}", second.all());
    // Slower and more accurate: the label moved right and down the plot.
    let drawn_after = second
        .position_of("you are here")
        .unwrap_or_else(|| panic!("{}", second.all()));
    assert!(
        drawn_after.x > drawn_before.x && drawn_after.y > drawn_before.y,
        "{drawn_before:?} to {drawn_after:?}"
    );

    // 3 iterations were not measured: the nearest measured setting is marked, and said so.
    set_solver(&mut demo, SolverKind::SoftStep, 3, 4);
    let third = frame(&ctx, &mut demo, Vec::new());
    let near = marker_of(&demo);
    assert!(!near.exact);
    assert_eq!(near.point.setting.iterations, 4);
    assert!(
        third.has("nearest measured: soft step, 4 substeps, 4 iterations (you: soft step, 4 substeps, 3 iterations, 30 Hz contacts)"),
        "{}",
        third.all()
    );
    assert!(
        third.position_of("nearest measured").is_some(),
        "{}",
        third.all()
    );

    // Another solver: its own point, never the peer's.
    set_solver(&mut demo, SolverKind::SequentialImpulse, 8, 4);
    frame(&ctx, &mut demo, Vec::new());
    let classic = marker_of(&demo);
    assert!(classic.exact);
    assert_eq!(classic.point.error, 0.9);
}

#[test]
fn the_checked_in_report_is_found_beside_the_scene_folder() {
    let mut demo = Demo::open(&demos(), &demos().join("pyramid.ron"), VIEWPORT).unwrap();
    let ctx = egui::Context::default();
    let shown = frame(&ctx, &mut demo, Vec::new());
    let source = demo.accuracy.source().cloned();
    let Some(Source::Report(path)) = source else {
        panic!("no report found: {source:?}, {}", shown.all());
    };
    assert!(path.ends_with("docs/accuracy/accuracy.csv"), "{path:?}");
    assert!(demo.accuracy.points().iter().all(|p| p.scene == "pyramid"));
    assert!(demo.accuracy.points().len() >= 20);
    // The scene's own setting (soft step, 4 substeps, 1 iteration) was swept.
    assert!(marker_of(&demo).exact, "{}", shown.all());
    assert!(shown.has("you are here: soft step"), "{}", shown.all());
}

/// A folder of its own with `scenes` copied or written into `demos/`, and no report.
fn scratch(name: &str, scenes: &[(&str, String)]) -> PathBuf {
    let root = std::env::temp_dir().join(format!("carom-accuracy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(root.join("demos")).unwrap();
    for (file, text) in scenes {
        std::fs::write(root.join("demos").join(file), text).unwrap();
    }
    root
}

/// Clicks at `at` through egui's input: pressed in one frame, released in the next.
fn click(ctx: &egui::Context, demo: &mut Demo, at: egui::Pos2) -> Frame {
    let button = |pressed| egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: egui::Modifiers::default(),
    };
    frame(ctx, demo, vec![egui::Event::PointerMoved(at), button(true)]);
    frame(ctx, demo, vec![button(false)])
}

#[test]
fn a_scene_with_nothing_measured_offers_the_button_and_no_marker() {
    let stack = std::fs::read_to_string(demos().join("vertical_stack.ron")).unwrap();
    let root = scratch("unmeasured", &[("vertical_stack.ron", stack)]);
    let scene = root.join("demos/vertical_stack.ron");
    let mut demo = Demo::open(&root.join("demos"), &scene, VIEWPORT).unwrap();
    let ctx = egui::Context::default();
    let shown = frame(&ctx, &mut demo, Vec::new());
    assert!(demo.accuracy.points().is_empty());
    assert!(demo.accuracy.marker().is_none());
    assert!(
        shown.has("Nothing measured for this scene yet."),
        "{}",
        shown.all()
    );
    assert!(shown.has("Measure this scene's front"), "{}", shown.all());
    assert!(!shown.has("you are here"), "{}", shown.all());
    assert!(!shown.has("nearest measured"), "{}", shown.all());
    let _ = std::fs::remove_dir_all(&root);
}

/// Two boxes dropped on a floor: no exact answer, so the sweep's error is the deepest overlap.
const DROP: &str = r#"(
    name: "drop",
    description: "Two boxes fall on a floor.",
    world: (effects: [gravity]),
    bodies: [
        (kind: static, shape: Box(width: 10.0, height: 1.0), position: (0.0, -0.5)),
        (shape: Box(width: 1.0, height: 1.0), position: (0.0, 0.6)),
        (shape: Box(width: 1.0, height: 1.0), position: (0.2, 1.7)),
    ],
)"#;

#[test]
fn the_button_measures_a_scene_without_an_answer_in_the_background() {
    let root = scratch("sweep", &[("drop.ron", DROP.to_string())]);
    let scene = root.join("demos/drop.ron");
    let mut demo = Demo::open(&root.join("demos"), &scene, VIEWPORT).unwrap();
    let ctx = egui::Context::default();
    let shown = frame(&ctx, &mut demo, Vec::new());
    assert!(shown.has("no exact answer"), "{}", shown.all());
    let button = shown
        .position_of("Measure this scene's front")
        .unwrap_or_else(|| panic!("{}", shown.all()));
    // Click a little inside the button's text.
    click(&ctx, &mut demo, button + egui::vec2(8.0, 6.0));
    let (progress, measuring) = demo.accuracy.progress().expect("a sweep runs");
    assert_eq!(measuring, scene.as_path());
    assert!(progress.done <= progress.total);
    // The button gives way to the progress bar while it runs, from the next frame on (the
    // frame that took the click had drawn the button already).
    let running = frame(&ctx, &mut demo, Vec::new());
    // Still running after the frame means the frame found it running (a sweep that ended
    // first would have been collected by the frame): it drew the bar.
    if demo.accuracy.progress().is_some() {
        assert!(running.has("points"), "{}", running.all());
        assert!(running.has("measuring"), "{}", running.all());
        assert!(
            !running.has("Measure this scene's front"),
            "{}",
            running.all()
        );
    }

    demo.accuracy.wait_for_sweep();
    let measured = frame(&ctx, &mut demo, Vec::new());
    assert!(demo.accuracy.progress().is_none());
    assert_eq!(demo.accuracy.source(), Some(&Source::Sweep));
    assert_eq!(demo.accuracy.notice(), None);
    let points = demo.accuracy.points();
    // Every solver at 7 iteration counts; soft step at 5 substep counts and 2 contact
    // stiffnesses, with the iterations that keep it within 64 passes a step (7, 6, 5, 4 and
    // 3 of them at 1, 2, 4, 8 and 16 substeps).
    assert_eq!(
        points.len(),
        3 * 7 + 2 * (7 + 6 + 5 + 4 + 3),
        "{}",
        points.len()
    );
    assert!(points.iter().all(|p| p.error_kind.unit() == "m"));
    // The scene's own setting, soft step at 4 substeps and 1 iteration, is marked.
    let here = marker_of(&demo);
    assert!(here.exact);
    assert_eq!(here.point.setting.solver, SolverKind::SoftStep);
    assert!(
        measured.has("you are here: soft step, 4 substeps, 1 iteration"),
        "{}",
        measured.all()
    );
    assert!(measured.has("error (m)"), "{}", measured.all());
    assert!(measured.has("Measured here"), "{}", measured.all());
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_malformed_report_is_said_and_the_button_still_offered() {
    let stack = std::fs::read_to_string(demos().join("vertical_stack.ron")).unwrap();
    let root = scratch("malformed", &[("vertical_stack.ron", stack)]);
    std::fs::create_dir_all(root.join("docs/accuracy")).unwrap();
    let broken = PENDULUM.replace(
        "pendulum,Period,soft step,2,4",
        "vertical_stack,Period,soft step,two,4",
    );
    std::fs::write(root.join("docs/accuracy/accuracy.csv"), broken).unwrap();
    let scene = root.join("demos/vertical_stack.ron");
    let mut demo = Demo::open(&root.join("demos"), &scene, VIEWPORT).unwrap();
    let ctx = egui::Context::default();
    let shown = frame(&ctx, &mut demo, Vec::new());
    let notice = demo.accuracy.notice().unwrap_or_default().to_string();
    assert!(
        notice.contains("line 4: column `iterations`: `two`"),
        "{notice}"
    );
    assert!(shown.has("line 4"), "{}", shown.all());
    assert!(shown.has("Measure this scene's front"), "{}", shown.all());
    let _ = std::fs::remove_dir_all(&root);
}
