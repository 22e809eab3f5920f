//! The sweep as a picture: per scene, error against ms/step on log-log axes, each engine's
//! Pareto front (the settings no other of its settings beats in both time and error) as a
//! line in the engine's colour, every other setting a faint dot.

use super::{Engine, Point, pareto_front};
use plotters::prelude::*;
use std::path::Path;

/// Size of one scene's panel, pixels.
const PANEL: (u32, u32) = (640, 420);

/// Draws the chart of `points` to a PNG at `path`.
pub fn write_chart(points: &[Point], path: &Path) -> Result<(), String> {
    let image = draw_chart(points)?;
    image
        .save(path)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Draws the chart of `points`: a panel per scene and one for the legend, two columns.
pub fn draw_chart(points: &[Point]) -> Result<image::RgbImage, String> {
    crate::register_fonts();
    let scenes = super::report::fronts(points);
    let rows = (scenes.len() + 1).div_ceil(2) as u32;
    let (width, height) = (2 * PANEL.0, rows * PANEL.1);
    let mut pixels = vec![0u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let panels = root.split_evenly((rows as usize, 2));
        for (panel, (scene, of_scene)) in panels.iter().zip(&scenes) {
            draw_panel(panel, scene, of_scene)?;
        }
        if let Some(panel) = panels.get(scenes.len()) {
            let mut engines: Vec<Engine> = points.iter().map(|p| p.setting.engine).collect();
            engines.sort_unstable();
            engines.dedup();
            let joints = points.iter().any(|p| p.joints);
            draw_legend(panel, &engines, joints)?;
        }
        root.present().map_err(draw_error)?;
    }
    image::RgbImage::from_raw(width, height, pixels).ok_or_else(|| "chart buffer size".into())
}

fn draw_panel<DB: DrawingBackend>(
    panel: &DrawingArea<DB, plotters::coord::Shift>,
    scene: &str,
    points: &[&Point],
) -> Result<(), String> {
    let kind = points[0].error_kind;
    let (x_range, y_range, floor) = ranges(points);
    let mut chart = ChartBuilder::on(panel)
        .caption(scene, ("sans-serif", 24))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.log_scale(), y_range.clone().log_scale())
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .x_desc("ms per step")
        .y_desc(format!("{} ({})", kind.description(), kind.unit()))
        .axis_desc_style(("sans-serif", 15))
        .label_style(("sans-serif", 13))
        .x_label_formatter(&|x| format_tick(*x))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()
        .map_err(draw_error)?;
    // Zero errors sit on the floor; NaN worlds at the top of the panel.
    let at = |p: &Point| {
        let error = if p.error.is_finite() {
            p.error.max(floor)
        } else {
            y_range.end
        };
        (p.ms_per_step.max(1e-6), error)
    };
    let mut engines: Vec<Engine> = points.iter().map(|p| p.setting.engine).collect();
    engines.sort_unstable();
    engines.dedup();
    // Every engine's faint points first, so no front is drawn over by another's dots.
    for &engine in &engines {
        let faint = faint_color_of(engine);
        chart
            .draw_series(
                points
                    .iter()
                    .filter(|p| p.setting.engine == engine)
                    .map(|p| Circle::new(at(p), 3, faint.filled())),
            )
            .map_err(draw_error)?;
    }
    for &engine in &engines {
        let of_engine: Vec<&Point> = points
            .iter()
            .copied()
            .filter(|p| p.setting.engine == engine)
            .collect();
        let front = pareto_front(&of_engine);
        let color = color_of(engine);
        chart
            .draw_series(LineSeries::new(
                front.iter().map(|p| at(p)),
                color.stroke_width(2),
            ))
            .map_err(draw_error)?;
        chart
            .draw_series(front.iter().map(|p| Circle::new(at(p), 4, color.filled())))
            .map_err(draw_error)?;
    }
    Ok(())
}

/// The legend: how to read a front, what a setting has no counterpart in a peer (when peers
/// ran), what joint scenes leave out (if `joints`), each engine's colour.
fn draw_legend<DB: DrawingBackend>(
    panel: &DrawingArea<DB, plotters::coord::Shift>,
    engines: &[Engine],
    joints: bool,
) -> Result<(), String> {
    let style = ("sans-serif", 18).into_font();
    let mut notes = vec![
        "line: the settings nothing beats in both time and error",
        "faint: every other setting",
    ];
    if engines.len() > 1 {
        // Said here, as no dot can say why it is missing.
        notes.push("push-out, tutorial and sequential impulse: carom only;");
        notes.push("Box2D has no iteration count, Rapier no joint stiffness");
    }
    if joints && engines.contains(&Engine::Carom) {
        notes.push("joint scenes: push-out and tutorial impulse leave joints out");
    }
    for (index, note) in notes.iter().enumerate() {
        let y = 30 + 26 * index as i32;
        panel
            .draw(&Text::new(*note, (30, y), style.clone()))
            .map_err(draw_error)?;
    }
    let top = 44 + 26 * notes.len() as i32;
    for (index, &engine) in engines.iter().enumerate() {
        let y = top + 32 * index as i32;
        panel
            .draw(&PathElement::new(
                vec![(30, y), (80, y)],
                color_of(engine).stroke_width(3),
            ))
            .map_err(draw_error)?;
        panel
            .draw(&Text::new(engine.name(), (95, y - 9), style.clone()))
            .map_err(draw_error)?;
    }
    Ok(())
}

/// Axis ranges around the finite, positive values, and the floor zero errors are drawn at.
fn ranges(points: &[&Point]) -> (std::ops::Range<f64>, std::ops::Range<f64>, f64) {
    let positive = |v: f64| v.is_finite() && v > 0.0;
    let (mut x_low, mut x_high) = (f64::MAX, f64::MIN);
    let (mut y_low, mut y_high) = (f64::MAX, f64::MIN);
    for p in points {
        if positive(p.ms_per_step) {
            x_low = x_low.min(p.ms_per_step);
            x_high = x_high.max(p.ms_per_step);
        }
        if positive(p.error) {
            y_low = y_low.min(p.error);
            y_high = y_high.max(p.error);
        }
    }
    if x_low > x_high {
        (x_low, x_high) = (1e-3, 1.0);
    }
    if y_low > y_high {
        (y_low, y_high) = (1e-6, 1.0);
    }
    let floor = y_low / 2.0;
    (
        x_low / 1.3..x_high * 1.3,
        floor / 1.3..(y_high * 2.0).max(floor * 10.0),
        floor,
    )
}

/// Each engine's colour ([`Engine::color`]): its front and its legend line.
pub fn color_of(engine: Engine) -> RGBColor {
    let [r, g, b] = engine.color();
    RGBColor(r, g, b)
}

/// The engine's colour faded three quarters of the way to white: its dominated settings.
fn faint_color_of(engine: Engine) -> RGBColor {
    let RGBColor(r, g, b) = color_of(engine);
    let fade = |c: u8| (c as u16 + 3 * 255).div_ceil(4) as u8;
    RGBColor(fade(r), fade(g), fade(b))
}

fn format_tick(x: f64) -> String {
    if x >= 10.0 {
        format!("{x:.0}")
    } else if x >= 0.1 {
        format!("{x:.1}")
    } else {
        format!("{x:.3}")
    }
}

/// Plotters draws text with a font registered by name; egui's default font serves.
fn draw_error(error: impl std::fmt::Display) -> String {
    format!("drawing the chart: {error}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::{ErrorKind, Setting};
    use carom::SolverKind;

    fn point(engine: Engine, iterations: u32, ms: f64, error: f64) -> Point {
        Point {
            scene: "stack".into(),
            error_kind: ErrorKind::Rest,
            setting: Setting {
                engine,
                ..Setting::carom(SolverKind::SoftStep, iterations, 4)
            },
            ms_per_step: ms,
            error,
            max_penetration: 0.0,
            joints: false,
        }
    }

    fn has(image: &image::RgbImage, color: RGBColor) -> bool {
        image.pixels().any(|p| p.0 == [color.0, color.1, color.2])
    }

    #[test]
    fn each_engine_draws_its_front_in_its_colour_and_the_rest_faint() {
        let points = vec![
            point(Engine::Carom, 1, 0.01, 0.5),
            point(Engine::Carom, 8, 0.05, 0.01),
            point(Engine::Carom, 16, 0.09, 0.02), // dominated: faint
            point(Engine::Box2d, 1, 0.005, f64::INFINITY),
            point(Engine::Box2d, 4, 0.02, 0.0),
        ];
        let image = draw_chart(&points).unwrap();
        assert_eq!(image.dimensions(), (2 * PANEL.0, PANEL.1));
        assert!(has(&image, color_of(Engine::Carom)), "no carom front");
        assert!(has(&image, color_of(Engine::Box2d)), "no Box2D front");
        assert!(
            has(&image, faint_color_of(Engine::Carom)),
            "no faint carom point"
        );
        assert!(
            !has(&image, color_of(Engine::Rapier)),
            "a Rapier line with no points"
        );
    }

    #[test]
    fn faint_colours_are_lighter_and_engines_differ() {
        for engine in Engine::ALL {
            let (RGBColor(r, g, b), RGBColor(fr, fg, fb)) =
                (color_of(engine), faint_color_of(engine));
            assert!(fr >= r && fg >= g && fb >= b && (fr, fg, fb) != (r, g, b));
        }
        assert_ne!(color_of(Engine::Carom), color_of(Engine::Box2d));
        assert_ne!(color_of(Engine::Box2d), color_of(Engine::Rapier));
    }
}
