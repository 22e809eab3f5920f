//! The egui sidebar: scene, solver, effects, drawing, and the cost of accuracy: the scene's
//! measured front with the demo's setting on it, and the live step cost.

use crate::accuracy_panel::{self, AccuracyPanel, Marker, Source};
use crate::demo::{Demo, HINTS, Key};
use crate::metrics::{Metrics, STAGES};
use carom::draw::DrawFlags;
use carom::{Effect, SolverKind};
use carom_bench::sweep::{Engine, Point};
use egui_plot::{GridMark, HoverPosition, Legend, Line, MarkerShape, Plot, PlotPoint, PlotPoints};
use egui_plot::{Points, Text};
use std::ops::RangeInclusive;

/// Sidebar width, points.
pub const SIDEBAR_WIDTH: f32 = 300.0;

/// What the sidebar asks of the window's surroundings, which alone can write files (natively)
/// or offer downloads (on the web).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ask {
    /// Save the run so far as a recording.
    SaveRecording,
}

/// Draws the sidebar and applies what the user changed. Errors (a scene that fails to load)
/// come back as text for the sidebar to show; what only the host can do comes back as an
/// [`Ask`].
pub fn sidebar(ui: &mut egui::Ui, demo: &mut Demo, error: &mut Option<String>) -> Option<Ask> {
    let mut ask = None;
    egui::ScrollArea::vertical().show(ui, |ui| {
        scene_section(ui, demo, error);
        ui.separator();
        timeline_section(ui, demo, error, &mut ask);
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
        if let Some(notice) = &demo.notice {
            ui.small(notice.as_str());
        }
        if let Some(message) = error {
            ui.colored_label(egui::Color32::from_rgb(255, 120, 100), message.as_str());
        }
    });
    ask
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

/// The run so far: a scrubber over every step, buttons to go back and forth, and the memory
/// its keyframes take.
fn timeline_section(
    ui: &mut egui::Ui,
    demo: &mut Demo,
    error: &mut Option<String>,
    ask: &mut Option<Ask>,
) {
    ui.heading("Timeline");
    let (at, end) = (demo.timeline().at(), demo.timeline().end());
    let mut chosen = at;
    let scrubbed = ui
        .scope(|ui| {
            ui.spacing_mut().slider_width = SIDEBAR_WIDTH - 100.0;
            ui.add(egui::Slider::new(&mut chosen, 0..=end).text("step"))
        })
        .inner
        .on_hover_text("Drag back to any step of the run; playing on replays it exactly");
    let mut go = scrubbed.changed().then_some(chosen);
    ui.horizontal(|ui| {
        if ui
            .button("|<")
            .on_hover_text("The run's first step")
            .clicked()
        {
            go = Some(0);
        }
        if ui.button("<").on_hover_text("One step back (,)").clicked() {
            *error = demo.key(Key::StepBack).err();
        }
        if ui
            .button(">")
            .on_hover_text("One step forward (S or .)")
            .clicked()
        {
            *error = demo.key(Key::Step).err();
        }
        if ui
            .button(">|")
            .on_hover_text("The run's newest step")
            .clicked()
        {
            go = Some(end);
        }
        if ui
            .button("Save recording")
            .on_hover_text("The run as a file `carom replay` plays back")
            .clicked()
        {
            *ask = Some(Ask::SaveRecording);
        }
    });
    if let Some(step) = go {
        *error = demo.go_to(step).err();
    }
    let timeline = demo.timeline();
    ui.label(format!(
        "step {at} of {end} · {} keyframes, {:.1} MB",
        timeline.keyframe_count(),
        timeline.bytes() as f64 / (1 << 20) as f64
    ))
    .on_hover_text(
        "Keyframes keep the scene's state every few steps to go back to; past their memory \
         budget the older ones are thinned",
    );
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
                        // Each solver starts from its own iteration count.
                        params.kind = kind;
                        params.iterations = None;
                    }
                }
            });
    });
    let mut iterations = params.effective_iterations();
    if ui
        .add(egui::Slider::new(&mut iterations, 1..=64).text("iterations"))
        .changed()
    {
        params.iterations = Some(iterations);
    }
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
    ui.add_enabled(
        soft,
        egui::Checkbox::new(&mut params.direct_joints, "direct joints"),
    )
    .on_hover_text(
        "Solve each tree of hinges at once: a light chain holds a heavy load without stretching",
    );
    ui.add_enabled(
        soft,
        egui::Checkbox::new(&mut params.shock_propagation, "shock propagation"),
    )
    .on_hover_text(
        "Solve each body resting on another once more, from the ground up, with the lower one \
         immovable: a heavy body on light ones does not push them into the ground",
    );
    if soft {
        ui.add(egui::Slider::new(&mut params.contact_hertz, 5.0..=120.0).text("contact Hz"));
        ui.add(egui::Slider::new(&mut params.damping_ratio, 0.1..=20.0).text("damping ratio"));
    }
    if params != before
        && let Err(e) = demo.input(carom_scene::Input::Solver(params))
    {
        *error = Some(e);
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
                demo.input(carom_scene::Input::Effect { effect, on })
                    .expect("switching an effect keeps the settings valid");
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
    front_section(ui, demo);
    let metrics = &demo.metrics;
    let step = metrics.typical(|s| s.step_ms);
    ui.label(format!(
        "step {step:.3} ms ({} of the last {})",
        Metrics::TYPICAL,
        Metrics::WINDOW
    ));
    let split: Vec<String> = STAGES
        .iter()
        .enumerate()
        .map(|(i, name)| format!("{name} {:.3}", metrics.typical(|s| s.stage_ms[i])))
        .collect();
    ui.small(split.join(" · "));
    if let Some(latest) = metrics.latest() {
        ui.label(format!(
            "penetration {:.2} mm · rest drift {:.2} mm/s",
            latest.max_penetration * 1e3,
            latest.rest_drift * 1e3,
        ));
        ui.label(energy_label(latest.energy_change)).on_hover_text(
            "Kinetic plus gravitational energy against the last reset. Landings, \
                 friction and drag take energy away; a gain means the solver added some.",
        );
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

/// The mechanical energy the scene has lost (or, a warning sign, gained) since the last
/// reset, said as such: a drop of 160 J once a box has landed is physics, not an error.
pub fn energy_label(change: f32) -> String {
    if change <= 0.0 {
        format!("energy lost since reset {:.2} J", change.abs())
    } else {
        format!("energy gained since reset {change:.2} J")
    }
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

/// The colour of "you are here": unlike any engine's.
const MARKER_COLOR: egui::Color32 = egui::Color32::from_rgb(255, 210, 60);

/// The scene's measured front with the demo's setting on it, or what to do when nothing is
/// measured: the report's points if one has the scene, else a button to measure them.
fn front_section(ui: &mut egui::Ui, demo: &mut Demo) {
    let params = *demo.scene.world.solver();
    let panel = &mut demo.accuracy;
    panel.update(&demo.scene_path, &params);
    if panel.points().is_empty() {
        let without_answer = panel.scene().is_some_and(|s| !s.has_accuracy);
        ui.label(if without_answer {
            "Nothing measured for this scene yet. It has no exact answer, so its error is \
             the deepest overlap."
        } else {
            "Nothing measured for this scene yet."
        });
    } else {
        front_plot(ui, panel.points(), panel.marker());
        match panel.marker() {
            Some(marker) => {
                ui.colored_label(MARKER_COLOR, marker.title());
                ui.label(marker.numbers());
            }
            None => {
                ui.label(format!(
                    "{} was not measured on this scene.",
                    label_of(params.effective_kind())
                ));
            }
        }
        let changed = panel.unmeasured_changes(&params);
        if !changed.is_empty() {
            ui.small(format!(
                "Measured at the scene's {}, which you changed.",
                changed.join(", ")
            ));
        }
        let lost = panel
            .points()
            .iter()
            .filter(|p| !p.error.is_finite())
            .count();
        let mut source = match panel.source() {
            Some(Source::Report(path)) => format!("From {}.", path.display()),
            Some(Source::Sweep) => "Measured here, one run each, beside the app: times are \
                                    rough."
                .into(),
            _ => String::new(),
        };
        if lost > 0 {
            source.push_str(&format!(" {lost} settings went NaN (not drawn)."));
        }
        if !source.is_empty() {
            ui.small(source.trim_start());
        }
    }
    measure_controls(ui, panel);
    if let Some(notice) = panel.notice() {
        ui.colored_label(egui::Color32::from_rgb(255, 120, 100), notice);
    }
}

/// The button that measures the scene's front in the background, or its progress bar while
/// it runs.
fn measure_controls(ui: &mut egui::Ui, panel: &mut AccuracyPanel) {
    if let Some((progress, scene)) = panel.progress() {
        ui.add(
            egui::ProgressBar::new(progress.fraction())
                .show_percentage()
                .text(format!("{}/{} points", progress.done, progress.total)),
        );
        ui.small(format!("measuring {}: {}", scene.display(), progress.what));
        // The thread reports progress between frames; keep drawing it.
        ui.ctx().request_repaint();
        return;
    }
    if !accuracy_panel::CAN_MEASURE {
        ui.small(
            "The desktop app measures scenes here, and `carom-bench sweep` writes the report.",
        );
        return;
    }
    let label = if panel.points().is_empty() {
        "Measure this scene's front"
    } else {
        "Measure it again here"
    };
    // Wrapped: the button and the checkbox are wider together than the sidebar.
    ui.horizontal_wrapped(|ui| {
        if ui
            .button(label)
            .on_hover_text(
                "Runs every solver setting once on this scene in the background, as \
                 `carom bench` does; the app keeps running meanwhile",
            )
            .clicked()
        {
            panel.start_sweep();
        }
        if accuracy_panel::CAN_MEASURE_PEERS {
            ui.checkbox(&mut panel.with_peers, "with Box2D, Rapier");
        }
    });
}

/// Each engine's front as a line in its colour, its other settings faint, and the marker:
/// error against ms/step on log-log axes (log10 values plotted, real values labelled).
fn front_plot(ui: &mut egui::Ui, points: &[Point], marker: Option<&Marker>) {
    let kind = points[0].error_kind;
    // Errors of 0 (exact) sit a decade under the smallest error measured.
    let floor = points
        .iter()
        .map(|p| p.error)
        .filter(|e| e.is_finite() && *e > 0.0)
        .fold(f64::INFINITY, f64::min);
    let floor = if floor.is_finite() {
        floor / 10.0
    } else {
        1e-9
    };
    let at = move |p: &Point| [p.ms_per_step.max(1e-6).log10(), p.error.max(floor).log10()];
    let fronts = accuracy_panel::fronts(points);
    // The settings by where they are drawn, for the hover label.
    let names: Vec<([f64; 2], String)> = points
        .iter()
        .filter(|p| p.error.is_finite())
        .map(|p| (at(p), carom_bench::sweep::report::setting_name(&p.setting)))
        .collect();
    let unit = kind.unit();
    let xs = points
        .iter()
        .filter(|p| p.error.is_finite())
        .map(|p| at(p)[0]);
    let (x_min, x_max) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    Plot::new("accuracy_front")
        .height(200.0)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .allow_boxed_zoom(false)
        .allow_double_click_reset(false)
        .x_axis_label("ms per step")
        .y_axis_label(format!("error ({unit})"))
        .x_axis_formatter(decade_label)
        .y_axis_formatter(decade_label)
        .label_formatter(move |position| {
            let (HoverPosition::NearDataPoint { position, .. }
            | HoverPosition::Elsewhere { position }) = *position;
            let name = names
                .iter()
                .find(|(xy, _)| *xy == [position.x, position.y])
                .map(|(_, name)| format!("{name}\n"))
                .unwrap_or_default();
            Some(format!(
                "{name}{} ms/step\nerror {} {unit}",
                accuracy_panel::format_ms(10f64.powf(position.x)),
                accuracy_panel::format_error(10f64.powf(position.y))
            ))
        })
        .show(ui, |plot| {
            for (engine, front, rest) in &fronts {
                let color = engine_color(*engine);
                let along = |ps: &[&Point]| ps.iter().map(|p| at(p)).collect::<Vec<[f64; 2]>>();
                plot.points(
                    Points::new("", along(rest))
                        .color(color.gamma_multiply(0.4))
                        .radius(2.0),
                );
                plot.line(
                    Line::new(engine.name(), PlotPoints::from(along(front)))
                        .color(color)
                        .width(2.0),
                );
                plot.points(
                    Points::new(engine.name(), along(front))
                        .color(color)
                        .radius(3.0)
                        .filled(true),
                );
            }
            if let Some(marker) = marker {
                let [x, y] = at(&marker.point);
                plot.points(
                    Points::new("you are here", vec![[x, y]])
                        .shape(MarkerShape::Diamond)
                        .color(MARKER_COLOR)
                        .radius(7.0)
                        .filled(true),
                );
                // The label on the side with room for it.
                let right_half = x > 0.5 * (x_min + x_max);
                let (anchor, text) = match (right_half, marker.exact) {
                    (false, true) => (egui::Align2::LEFT_BOTTOM, "   you are here"),
                    (false, false) => (egui::Align2::LEFT_BOTTOM, "   nearest measured"),
                    (true, true) => (egui::Align2::RIGHT_BOTTOM, "you are here   "),
                    (true, false) => (egui::Align2::RIGHT_BOTTOM, "nearest measured   "),
                };
                plot.text(
                    Text::new("", PlotPoint::new(x, y), text)
                        .anchor(anchor)
                        .color(MARKER_COLOR),
                );
            }
        });
    // The legend under the plot, not on it: in 300 points of width it would hide points.
    ui.horizontal_wrapped(|ui| {
        for (engine, _, _) in &fronts {
            ui.colored_label(engine_color(*engine), format!("— {}", engine.name()));
        }
        ui.weak("faint: the other settings");
    });
}

/// An engine's colour in the chart, for egui.
fn engine_color(engine: Engine) -> egui::Color32 {
    let [r, g, b] = engine.color();
    egui::Color32::from_rgb(r, g, b)
}

/// An axis label for a log10 value: the real value at whole decades (at every mark when the
/// axis spans less than a decade), nothing between them.
fn decade_label(mark: GridMark, range: &RangeInclusive<f64>) -> String {
    let decade = (mark.value - mark.value.round()).abs() < 1e-6;
    if !decade && range.end() - range.start() >= 1.0 {
        return String::new();
    }
    let value = 10f64.powf(mark.value);
    if decade {
        if (1e-3..=1e4).contains(&value) {
            // 0.001 … 10000 as plain numbers.
            let text = format!("{value:.3}");
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            format!("{value:.0e}")
        }
    } else {
        format!("{value:.2e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_is_said_as_lost_or_gained_since_the_reset() {
        assert_eq!(energy_label(-160.487), "energy lost since reset 160.49 J");
        assert_eq!(energy_label(0.0), "energy lost since reset 0.00 J");
        assert_eq!(energy_label(2.5), "energy gained since reset 2.50 J");
    }
}
