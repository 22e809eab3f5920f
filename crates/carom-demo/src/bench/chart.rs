//! The sweep as a picture: per scene, error against ms/step on log-log axes, one line per
//! solver (per substep count for soft step), the iteration count growing along each line.

use super::Point;
use super::report::series_of;
use carom::SolverKind;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::Path;
use std::sync::Once;

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
    register_fonts();
    let mut scenes: Vec<&str> = points.iter().map(|p| p.scene.as_str()).collect();
    scenes.dedup();
    let rows = (scenes.len() + 1).div_ceil(2) as u32;
    let (width, height) = (2 * PANEL.0, rows * PANEL.1);
    let mut pixels = vec![0u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let panels = root.split_evenly((rows as usize, 2));
        let mut all_series = Vec::new();
        for (panel, scene) in panels.iter().zip(&scenes) {
            let of_scene: Vec<&Point> = points.iter().filter(|p| p.scene == *scene).collect();
            draw_panel(panel, scene, &of_scene)?;
            for (name, members) in series_of(&of_scene) {
                if !all_series.iter().any(|(n, _)| *n == name) {
                    all_series.push((name, color_of(members[0])));
                }
            }
        }
        if let Some(panel) = panels.get(scenes.len()) {
            let joints = points.iter().any(|p| p.joints);
            draw_legend(panel, &all_series, joints)?;
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
    for (_, members) in series_of(points) {
        let color = color_of(members[0]);
        // Zero errors sit on the floor; NaN worlds at the top of the panel.
        let at = |p: &&Point| {
            let error = if p.error.is_finite() {
                p.error.max(floor)
            } else {
                y_range.end
            };
            (p.ms_per_step.max(1e-6), error)
        };
        chart
            .draw_series(LineSeries::new(
                members.iter().map(at),
                color.stroke_width(2),
            ))
            .map_err(draw_error)?;
        chart
            .draw_series(
                members
                    .iter()
                    .map(|p| Circle::new(at(p), 3, color.filled())),
            )
            .map_err(draw_error)?;
    }
    Ok(())
}

/// The legend: how to read a line, what joint scenes leave out (if `joints`), the series.
fn draw_legend<DB: DrawingBackend>(
    panel: &DrawingArea<DB, plotters::coord::Shift>,
    series: &[(String, RGBColor)],
    joints: bool,
) -> Result<(), String> {
    let style = ("sans-serif", 18).into_font();
    let mut notes = vec!["each line: 1, 2, 4 ... 64 iterations, left to right"];
    if joints {
        // Said here, as no line can say why it is missing.
        notes.push("joint scenes: push-out and tutorial impulse leave joints out");
    }
    for (index, note) in notes.iter().enumerate() {
        let y = 30 + 26 * index as i32;
        panel
            .draw(&Text::new(*note, (30, y), style.clone()))
            .map_err(draw_error)?;
    }
    let top = 44 + 26 * notes.len() as i32;
    for (index, (name, color)) in series.iter().enumerate() {
        let y = top + 32 * index as i32;
        panel
            .draw(&PathElement::new(
                vec![(30, y), (80, y)],
                color.stroke_width(3),
            ))
            .map_err(draw_error)?;
        panel
            .draw(&Text::new(name.as_str(), (95, y - 9), style.clone()))
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

/// One colour per solver; soft step darker with more substeps, in reds at the default joint
/// stiffness and purples at another.
fn color_of(point: &Point) -> RGBColor {
    match (point.setting.solver, point.setting.joint_hertz) {
        (SolverKind::PushOut, _) => RGBColor(130, 130, 130),
        (SolverKind::TutorialImpulse, _) => RGBColor(235, 150, 30),
        (SolverKind::SequentialImpulse, _) => RGBColor(40, 100, 220),
        (SolverKind::SoftStep, None) => match point.setting.substeps {
            0..=1 => RGBColor(245, 150, 150),
            2..=3 => RGBColor(225, 90, 90),
            4..=7 => RGBColor(190, 30, 30),
            _ => RGBColor(110, 0, 20),
        },
        (SolverKind::SoftStep, Some(_)) => match point.setting.substeps {
            0..=3 => RGBColor(200, 140, 230),
            4..=7 => RGBColor(150, 70, 200),
            8..=11 => RGBColor(110, 30, 170),
            _ => RGBColor(60, 0, 110),
        },
    }
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
fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is compiled in and known to parse.
        let _ = register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        );
    });
}

fn draw_error(error: impl std::fmt::Display) -> String {
    format!("drawing the chart: {error}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::report::series_name;
    use crate::bench::{ErrorKind, Setting};

    fn point(scene: &str, solver: SolverKind, iterations: u32, ms: f64, error: f64) -> Point {
        Point {
            scene: scene.into(),
            error_kind: ErrorKind::Rest,
            setting: Setting {
                solver,
                iterations,
                substeps: 1,
                joint_hertz: None,
            },
            ms_per_step: ms,
            error,
            max_penetration: 0.0,
            joints: false,
        }
    }

    #[test]
    fn the_chart_draws_every_series_in_its_colour() {
        let points = vec![
            point("stack", SolverKind::SequentialImpulse, 1, 0.01, 0.5),
            point("stack", SolverKind::SequentialImpulse, 8, 0.05, 0.01),
            point("stack", SolverKind::PushOut, 1, 0.005, f64::INFINITY),
            point("stack", SolverKind::PushOut, 8, 0.02, 0.0),
        ];
        let image = draw_chart(&points).unwrap();
        assert_eq!(image.dimensions(), (2 * PANEL.0, PANEL.1));
        let has = |color: RGBColor| image.pixels().any(|p| p.0 == [color.0, color.1, color.2]);
        assert!(has(color_of(&points[0])), "no sequential impulse line");
        assert!(has(color_of(&points[2])), "no push-out line");
        assert!(
            !has(RGBColor(235, 150, 30)),
            "a tutorial line with no points"
        );
        assert_eq!(series_name(&points[0]), "sequential impulse");
    }

    #[test]
    fn a_stiffer_joint_setting_has_a_colour_of_its_own() {
        let mut points = Vec::new();
        for joint_hertz in [None, Some(120.0)] {
            for (iterations, ms) in [(1, 0.02), (8, 0.1)] {
                let mut p = point("chain", SolverKind::SoftStep, iterations, ms, 6.0);
                p.setting.substeps = 8;
                p.setting.joint_hertz = joint_hertz;
                p.joints = true;
                points.push(p);
            }
        }
        assert_ne!(color_of(&points[0]), color_of(&points[2]));
        let image = draw_chart(&points).unwrap();
        let has = |color: RGBColor| image.pixels().any(|p| p.0 == [color.0, color.1, color.2]);
        assert!(has(color_of(&points[0])), "no default joint line");
        assert!(has(color_of(&points[2])), "no stiffer joint line");
    }
}
