//! How each engine's cost grows with the work: the same kind of scene at several sizes (rows
//! of Box2D's base-10 pyramids, 55 boxes each, twenty to a ground strip as in its
//! `many_pyramids`), timed in every engine, and drawn as ms per step against bodies on log-log
//! axes.

use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// The sizes measured: (rows of pyramids, pyramids per row), about 1k, 5k, 20k and 100k boxes.
pub const SIZES: [(usize, usize); 4] = [(1, 18), (5, 20), (18, 20), (91, 20)];

/// A scene of `rows` ground strips, each with `columns` base-10 pyramids of one-metre boxes
/// (Box2D's `many_pyramids` layout, sleeping off), as scene-file text.
pub fn pyramid_rows(rows: usize, columns: usize) -> String {
    let width = 11.0 * columns as f64;
    let first = -0.5 * width + 5.5;
    format!(
        "(name: \"pyramids_{rows}x{columns}\", \
         description: \"{rows} rows of {columns} base-10 pyramids\", \
         world: (effects: [gravity, friction, restitution, continuous]), \
         generators: [\
           Grid(origin: (0.0, -0.05), columns: 1, rows: {rows}, spacing: (0.0, 11.0), \
                shape: Box(width: {width:.1}, height: 0.1), kind: static), \
           Repeat(columns: {columns}, rows: {rows}, spacing: (11.0, 11.0), \
                  of: Pyramid(base: ({first:.1}, 0.0), count: 10, size: 1.0)),\
         ])"
    )
}

/// One engine's time at one size.
#[derive(Debug, Clone)]
pub struct Point {
    /// The engine and its thread count, as the chart's legend says it.
    pub engine: String,
    /// Bodies in the scene (static ones included).
    pub bodies: usize,
    /// Milliseconds per step.
    pub ms_per_step: f64,
}

/// The points as CSV: `engine,bodies,ms_per_step`.
pub fn csv(points: &[Point]) -> String {
    let mut s = String::from("engine,bodies,ms_per_step\n");
    for p in points {
        let _ = writeln!(s, "{},{},{:.4}", p.engine, p.bodies, p.ms_per_step);
    }
    s
}

/// The engines in the order they were first measured.
fn engines(points: &[Point]) -> Vec<&str> {
    let mut engines: Vec<&str> = Vec::new();
    for p in points {
        if !engines.contains(&p.engine.as_str()) {
            engines.push(&p.engine);
        }
    }
    engines
}

/// The points as a markdown table: a row per size, a column per engine.
pub fn markdown(points: &[Point]) -> String {
    let engines = engines(points);
    let mut sizes: Vec<usize> = points.iter().map(|p| p.bodies).collect();
    sizes.sort_unstable();
    sizes.dedup();
    let mut s = format!("| bodies | {} |\n", engines.join(" | "));
    let _ = writeln!(s, "|---|{}", "---|".repeat(engines.len()));
    for bodies in sizes {
        let _ = write!(s, "| {bodies} |");
        for engine in &engines {
            match points
                .iter()
                .find(|p| p.bodies == bodies && p.engine == *engine)
            {
                Some(p) => {
                    let _ = write!(s, " {:.3} |", p.ms_per_step);
                }
                None => s.push_str(" |"),
            }
        }
        s.push('\n');
    }
    s
}

/// The lines' colours, in the order the engines were measured (carom's reds, Box2D's blues,
/// then Rapier's orange).
const COLORS: [RGBColor; 5] = [
    RGBColor(200, 30, 40),
    RGBColor(240, 120, 130),
    RGBColor(20, 60, 200),
    RGBColor(110, 170, 250),
    RGBColor(230, 140, 0),
];

/// Size of the chart, pixels.
const SIZE: (u32, u32) = (900, 600);

/// Draws ms per step against bodies, log-log, a line per engine, to a PNG at `path`.
///
/// # Errors
/// No points, or the picture cannot be drawn or written.
pub fn write_chart(points: &[Point], path: &Path) -> Result<(), String> {
    if points.is_empty() {
        return Err("no points to draw".into());
    }
    crate::register_fonts();
    let (width, height) = SIZE;
    let mut pixels = vec![0u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let bound = |f: fn(f64, f64) -> f64, of: fn(&Point) -> f64| {
            points.iter().map(of).fold(of(&points[0]), f)
        };
        let bodies = |p: &Point| p.bodies as f64;
        let ms = |p: &Point| p.ms_per_step;
        let x = (0.8 * bound(f64::min, bodies))..(1.25 * bound(f64::max, bodies));
        let y = (0.7 * bound(f64::min, ms))..(1.4 * bound(f64::max, ms));
        let mut chart = ChartBuilder::on(&root)
            .caption("ms per step against bodies (pyramids)", ("sans-serif", 24))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(x.log_scale(), y.log_scale())
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .x_labels(6)
            .y_labels(8)
            .x_desc("bodies")
            .y_desc("ms per step")
            .axis_desc_style(("sans-serif", 16))
            .label_style(("sans-serif", 14))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y}"))
            .draw()
            .map_err(draw_error)?;
        for (i, engine) in engines(points).into_iter().enumerate() {
            let color = COLORS[i % COLORS.len()].to_rgba();
            let series: Vec<(f64, f64)> = points
                .iter()
                .filter(|p| p.engine == engine)
                .map(|p| (p.bodies as f64, p.ms_per_step))
                .collect();
            let style = ShapeStyle::from(color).stroke_width(2);
            chart
                .draw_series(LineSeries::new(series.clone(), style))
                .map_err(draw_error)?
                .label(engine)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
            chart
                .draw_series(
                    series
                        .into_iter()
                        .map(|p| Circle::new(p, 4, color.filled())),
                )
                .map_err(draw_error)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .draw()
            .map_err(draw_error)?;
        root.present().map_err(draw_error)?;
    }
    let image = image::RgbImage::from_raw(width, height, pixels).ok_or("chart buffer size")?;
    image
        .save(path)
        .map_err(|e| format!("{}: {e}", path.display()))
}

fn draw_error(error: impl std::fmt::Display) -> String {
    format!("drawing the chart: {error}")
}
