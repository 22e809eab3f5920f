//! The egui sidebar: scene, solver, effects, drawing, and the live cost of accuracy.

use crate::demo::{Demo, HINTS};
use crate::metrics::{Metrics, STAGES};
use carom::{DrawFlags, Effect, SolverKind, SolverParams};
use egui_plot::{Legend, Line, Plot, PlotPoints};

/// Sidebar width, points.
pub const SIDEBAR_WIDTH: f32 = 300.0;

/// Draws the sidebar and applies what the user changed. Errors (a scene that fails to load)
/// come back as text for the sidebar to show.
pub fn sidebar(ui: &mut egui::Ui, demo: &mut Demo, error: &mut Option<String>) {
    egui::ScrollArea::vertical().show(ui, |ui| {
        scene_section(ui, demo, error);
        ui.separator();
        // The cost of accuracy right under the settings that change it.
        solver_section(ui, demo, error);
        cost_section(ui, demo);
        ui.separator();
        effects_section(ui, demo);
        ui.separator();
        draw_section(ui, demo);
        ui.separator();
        ui.small(HINTS);
        if let Some(message) = error {
            ui.colored_label(egui::Color32::from_rgb(255, 120, 100), message.as_str());
        }
    });
}

fn scene_section(ui: &mut egui::Ui, demo: &mut Demo, error: &mut Option<String>) {
    ui.heading("Scene");
    let current_name = match demo.current {
        Some(index) => demo.scenes[index].name.clone(),
        None => demo.scene_path.display().to_string(),
    };
    let mut chosen = None;
    egui::ComboBox::from_id_salt("scene")
        .selected_text(current_name)
        .width(SIDEBAR_WIDTH - 30.0)
        .show_ui(ui, |ui| {
            for (index, entry) in demo.scenes.iter().enumerate() {
                let label = format!("{} {}", key_label(index), entry.name);
                if ui
                    .selectable_label(demo.current == Some(index), label)
                    .on_hover_text(&entry.description)
                    .clicked()
                {
                    chosen = Some(index);
                }
            }
        });
    if let Some(index) = chosen {
        *error = demo.select(index).err();
    }
    if let Some(entry) = demo.current.and_then(|i| demo.scenes.get(i)) {
        ui.label(&entry.description);
    }
    ui.horizontal(|ui| {
        let play = if demo.paused { "Play" } else { "Pause" };
        if ui.button(play).clicked() {
            demo.paused = !demo.paused;
        }
        if ui.button("Step").clicked() {
            demo.paused = true;
            *error = demo.step().err();
        }
        if ui.button("Reset").clicked() {
            *error = demo.reset().err();
        }
    });
    ui.add(egui::Slider::new(&mut demo.time_scale, 0.05..=2.0).text("time scale"));
    ui.label(format!(
        "t = {:.2} s, {} bodies, {} contacts",
        demo.scene.world.time(),
        demo.scene.world.body_count(),
        demo.scene.world.stats().touching_contacts
    ));
}

fn key_label(index: usize) -> String {
    match index {
        0..=8 => format!("[{}]", index + 1),
        9 => "[0]".into(),
        _ => "   ".into(),
    }
}

fn solver_section(ui: &mut egui::Ui, demo: &mut Demo, error: &mut Option<String>) {
    ui.heading("Solver");
    let mut params = *demo.scene.world.solver();
    let before = params;
    ui.checkbox(&mut params.impulse_resolution, "Impulse resolution")
        .on_hover_text("Off: overlaps are only pushed apart, as in the tutorial's first demo");
    ui.add_enabled_ui(params.impulse_resolution, |ui| {
        egui::ComboBox::from_id_salt("solver")
            .selected_text(label_of(params.kind))
            .width(SIDEBAR_WIDTH - 30.0)
            .show_ui(ui, |ui| {
                for kind in SolverKind::ALL {
                    if ui
                        .selectable_label(params.kind == kind, label_of(kind))
                        .clicked()
                        && kind != params.kind
                    {
                        // Each solver starts from its own defaults (iterations differ).
                        let defaults = SolverParams::for_kind(kind);
                        params.kind = kind;
                        params.iterations = defaults.iterations;
                    }
                }
            });
    });
    ui.add(egui::Slider::new(&mut params.iterations, 1..=64).text("iterations"));
    let soft = params.impulse_resolution && params.kind == SolverKind::SoftStep;
    ui.add_enabled(
        soft,
        egui::Slider::new(&mut params.substeps, 1..=16).text("substeps"),
    );
    let warm = params.impulse_resolution
        && matches!(
            params.kind,
            SolverKind::SoftStep | SolverKind::SequentialImpulse
        );
    ui.add_enabled(
        warm,
        egui::Checkbox::new(&mut params.warm_starting, "warm starting"),
    );
    ui.add_enabled(
        soft,
        egui::Checkbox::new(&mut params.graph_coloring, "graph colouring (SIMD)"),
    )
    .on_hover_text(
        "Solve contacts colour by colour, eight (or four) at a time: faster, a little more jitter",
    );
    ui.add_enabled(
        soft,
        egui::Checkbox::new(&mut params.friction_in_bias_pass, "friction in biased pass"),
    )
    .on_hover_text("Solve friction in both passes (Box2D v3.1), not only when relaxing");
    if soft {
        ui.add(egui::Slider::new(&mut params.contact_hertz, 5.0..=120.0).text("contact Hz"));
        ui.add(egui::Slider::new(&mut params.damping_ratio, 0.1..=20.0).text("damping ratio"));
    }
    if params != before
        && let Err(e) = demo.scene.world.set_solver(params)
    {
        *error = Some(e.to_string());
    }
}

/// A solver's name as a menu shows it: capitalised.
fn label_of(kind: SolverKind) -> String {
    let name = kind.name();
    let mut label = name[..1].to_uppercase();
    label.push_str(&name[1..]);
    label
}

fn effects_section(ui: &mut egui::Ui, demo: &mut Demo) {
    ui.heading("Effects");
    ui.horizontal_wrapped(|ui| {
        for effect in Effect::ALL {
            let mut on = demo.scene.world.effects().contains(effect);
            if ui.checkbox(&mut on, effect.name()).changed() {
                demo.scene.world.set_effect(effect, on);
            }
        }
    });
}

fn draw_section(ui: &mut egui::Ui, demo: &mut Demo) {
    ui.heading("Draw");
    ui.horizontal_wrapped(|ui| {
        for (name, flag) in DrawFlags::NAMED {
            let mut on = demo.draw.flags.contains(flag);
            if ui.checkbox(&mut on, name.replace('_', " ")).changed() {
                demo.draw.flags.set(flag, on);
            }
        }
    });
}

fn cost_section(ui: &mut egui::Ui, demo: &mut Demo) {
    ui.heading("Cost of accuracy");
    let metrics = &demo.metrics;
    let step = metrics.median(|s| s.step_ms);
    ui.label(format!(
        "step {step:.3} ms (median of the last {})",
        Metrics::WINDOW
    ));
    let split: Vec<String> = STAGES
        .iter()
        .enumerate()
        .map(|(i, name)| format!("{name} {:.3}", metrics.median(|s| s.stage_ms[i])))
        .collect();
    ui.small(split.join(" · "));
    if let Some(latest) = metrics.latest() {
        ui.label(format!(
            "penetration {:.2} mm · rest drift {:.2} mm/s · energy change {:+.2} J",
            latest.max_penetration * 1e3,
            latest.rest_drift * 1e3,
            latest.energy_change
        ));
    }
    // Two small plots, not one: milliseconds and millimetres share no scale.
    let samples = metrics.samples();
    let step_line: PlotPoints = samples.iter().map(|s| [s.time, s.step_ms]).collect();
    let penetration_line: PlotPoints = samples
        .iter()
        .map(|s| [s.time, s.max_penetration as f64 * 1e3])
        .collect();
    small_plot(ui, "step_ms", Line::new("step ms", step_line));
    small_plot(
        ui,
        "penetration_mm",
        Line::new("penetration mm", penetration_line),
    );
}

/// A fixed plot of one line over the last seconds, with its legend.
fn small_plot(ui: &mut egui::Ui, id: &str, line: Line<'_>) {
    Plot::new(id)
        .height(70.0)
        .legend(Legend::default())
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .show(ui, |plot| plot.line(line));
}
