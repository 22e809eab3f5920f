//! The scaling scenes hold the boxes they say, and the table, CSV and chart show every point.

use carom_bench::scaling::{Point, SIZES, csv, markdown, pyramid_rows, write_chart};

#[test]
fn pyramid_rows_hold_their_boxes_on_their_strips() {
    let (rows, columns) = (2, 3);
    let text = pyramid_rows(rows, columns);
    let scene = carom_scene::parse(&text, "test").unwrap();
    let built = carom_scene::build(&scene, "test").unwrap();
    let world = &built.world;
    assert_eq!(world.body_count(), rows * columns * 55 + rows);
    // Every pyramid sits on its strip, within the strip's width.
    let strip_half_width = 0.5 * 11.0 * columns as carom::Real;
    for body in world
        .bodies()
        .filter(|b| b.kind() == carom::BodyKind::Dynamic)
    {
        let p = body.position();
        assert!(p.x.abs() < strip_half_width, "{p:?}");
        let above_strip = p.y - 11.0 * (p.y / 11.0).floor();
        assert!(above_strip > 0.4 && above_strip < 10.0, "{p:?}");
    }
    // The sizes run from about a thousand boxes to about a hundred thousand.
    let boxes = |(rows, columns): (usize, usize)| rows * columns * 55;
    assert!((900..1100).contains(&boxes(SIZES[0])));
    assert!((95_000..105_000).contains(&boxes(SIZES[3])));
}

#[test]
fn table_csv_and_chart_show_every_point() {
    let point = |engine: &str, bodies, ms_per_step| Point {
        engine: engine.into(),
        bodies,
        ms_per_step,
    };
    let points = [
        point("carom, 1 thread", 1000, 0.5),
        point("Box2D v3, 1 thread", 1000, 0.4),
        point("carom, 1 thread", 5000, 2.5),
        point("Box2D v3, 1 thread", 5000, 2.0),
    ];
    let table = markdown(&points);
    assert!(table.starts_with("| bodies | carom, 1 thread | Box2D v3, 1 thread |"));
    assert!(table.contains("| 5000 | 2.500 | 2.000 |"), "{table}");
    let csv = csv(&points);
    assert_eq!(csv.lines().count(), 5);
    assert!(csv.contains("Box2D v3, 1 thread,1000,0.4000"));
    let dir = std::env::temp_dir().join(format!("carom-scaling-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scaling.png");
    write_chart(&points, &path).unwrap();
    let image = image::open(&path).unwrap().to_rgb8();
    // Not blank: some pixels are neither white nor grey (the lines' colours).
    let coloured = image
        .pixels()
        .filter(|p| p.0.iter().max().unwrap() - p.0.iter().min().unwrap() > 60)
        .count();
    assert!(coloured > 500, "{coloured} coloured pixels");
    assert!(write_chart(&[], &path).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}
