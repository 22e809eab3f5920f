//! Real pixels: draw lists rendered offscreen and read back. These need a wgpu adapter (Mesa's
//! GL or Vulkan will do); without one they fail and say what to install.

use carom::{Real, vec2};

use carom::draw::{Color, DebugDraw, DrawList};
use carom_render::{Camera, Offscreen};
use image::RgbaImage;

fn offscreen(width: u32, height: u32) -> Offscreen {
    Offscreen::new(width, height).unwrap_or_else(|e| panic!("{e}"))
}

fn close(image: &RgbaImage, x: u32, y: u32, color: Color) {
    let pixel = image.get_pixel(x, y);
    let expected = [color.r, color.g, color.b].map(|c| (c * 255.0).round() as i32);
    for (got, want) in pixel.0[..3].iter().zip(expected) {
        assert!(
            (*got as i32 - want).abs() <= 3,
            "pixel ({x}, {y}) is {pixel:?}, expected {expected:?}"
        );
    }
}

#[test]
fn shapes_land_where_the_camera_puts_them_in_their_colours() {
    // 101 x 80 pixels: rows of 404 bytes are padded to 512 for the copy.
    let mut renderer = offscreen(101, 80);
    // 10 pixels per metre, world origin in the middle.
    let camera = Camera {
        center: vec2(0.0, 0.0),
        zoom: 10.0,
    };
    let red = Color::rgb(0.9, 0.1, 0.1);
    let green = Color::rgb(0.1, 0.8, 0.2);
    let white = Color::rgb(1.0, 1.0, 1.0);
    let blue = Color::rgb(0.2, 0.3, 1.0);
    let mut list = DrawList::new();
    // A 2 m square around the origin: 20 pixels, centred on pixel (50.5, 40).
    let square = [
        vec2(-1.0, -1.0),
        vec2(1.0, -1.0),
        vec2(1.0, 1.0),
        vec2(-1.0, 1.0),
    ];
    list.polygon(&square, red, red);
    // A circle of 1 m radius at (-3, 2): centre pixel (20.5, 20).
    list.circle(vec2(-3.0, 2.0), 1.0, green, green);
    // A point at (3, 2): pixel (80.5, 20).
    list.point(vec2(3.0, 2.0), 6.0, white);
    // A horizontal line 3 px thick at y = -3: row 70.
    list.segment(vec2(-4.0, -3.0), vec2(4.0, -3.0), 3.0, blue);
    let image = renderer.render(&list, &camera, Color::BACKGROUND).unwrap();
    assert_eq!(image.dimensions(), (101, 80));
    close(&image, 50, 40, red);
    close(&image, 20, 20, green);
    close(&image, 80, 20, white);
    close(&image, 50, 70, blue);
    close(&image, 2, 2, Color::BACKGROUND);
    close(&image, 98, 77, Color::BACKGROUND);
    // Just outside the square, the background.
    close(&image, 50, 52, Color::BACKGROUND);
}

#[test]
fn an_empty_list_is_the_background_and_buffers_are_reused() {
    let mut renderer = offscreen(64, 48);
    let camera = Camera {
        center: vec2(0.0, 0.0),
        zoom: 20.0,
    };
    let empty = renderer
        .render(&DrawList::new(), &camera, Color::BACKGROUND)
        .unwrap();
    assert!(empty.pixels().all(|p| {
        let expected = [23u8, 26, 31];
        p.0[..3]
            .iter()
            .zip(expected)
            .all(|(a, b)| a.abs_diff(b) <= 2)
    }));
    let mut list = DrawList::new();
    for i in 0..200 {
        let x = i as Real * 0.01;
        list.polygon(
            &[vec2(x, 0.0), vec2(x + 0.1, 0.0), vec2(x, 0.1)],
            Color::rgb(0.5, 0.5, 0.5),
            Color::rgb(1.0, 1.0, 1.0),
        );
    }
    renderer.render(&list, &camera, Color::BACKGROUND).unwrap();
    let capacity = renderer.renderer().buffer_capacity();
    for _ in 0..3 {
        renderer.render(&list, &camera, Color::BACKGROUND).unwrap();
    }
    assert_eq!(renderer.renderer().buffer_capacity(), capacity);
}

#[test]
fn polygons_have_their_outline_on_the_edge_whatever_their_vertex_count() {
    // 10 pixels per metre. A square, a hexagon and a 20-gon (more corners than one batch
    // holds) side by side, plus a degenerate polygon that must be skipped, not drawn wrong.
    let mut renderer = offscreen(160, 60);
    let camera = Camera {
        center: vec2(0.0, 0.0),
        zoom: 10.0,
    };
    let fill = Color::rgb(0.2, 0.4, 0.9);
    let outline = Color::rgb(1.0, 0.9, 0.2);
    let mut list = DrawList::new();
    let ngon = |center: carom::Vec2, sides: usize, radius: Real| -> Vec<carom::Vec2> {
        (0..sides)
            .map(|i| {
                let angle = carom::consts::TAU * (i as Real + 0.5) / sides as Real;
                center + vec2(angle.cos(), angle.sin()) * radius
            })
            .collect()
    };
    // The square spans x -7..-3 m, pixels 10..50; its left edge is at pixel 10.
    list.polygon(
        &[
            vec2(-7.0, -2.0),
            vec2(-3.0, -2.0),
            vec2(-3.0, 2.0),
            vec2(-7.0, 2.0),
        ],
        fill,
        outline,
    );
    list.polygon(&ngon(vec2(0.0, 0.0), 6, 2.0), fill, outline);
    list.polygon(&ngon(vec2(5.0, 0.0), 20, 2.0), fill, outline);
    // A polygon whose vertices coincide, and one with a repeated vertex.
    list.polygon(&[vec2(-5.0, -2.5); 4], outline, outline);
    list.polygon(
        &[
            vec2(-7.5, -2.8),
            vec2(-7.5, -2.8),
            vec2(-6.5, -2.8),
            vec2(-7.0, -2.6),
        ],
        fill,
        outline,
    );
    let image = renderer.render(&list, &camera, Color::BACKGROUND).unwrap();
    // Inside each shape: the fill.
    close(&image, 30, 30, fill);
    close(&image, 80, 30, fill);
    close(&image, 130, 30, fill);
    // On the square's left edge (x = 10 px, between pixel columns 9 and 10): the outline.
    let edge = image.get_pixel(10, 30);
    assert!(
        edge[0] > 150 && edge[2] < 150,
        "the square's edge should be outline-yellow, got {edge:?}"
    );
    // Three pixels outside it: the background.
    close(&image, 6, 30, Color::BACKGROUND);
    // The 20-gon's rightmost edge is near x = 7 m (pixel 150); past it, the background.
    close(&image, 154, 30, Color::BACKGROUND);
    // No stray fill colour anywhere the degenerate polygons were.
    close(&image, 30, 55, Color::BACKGROUND);
}

#[test]
fn a_scene_far_from_the_origin_draws_as_it_does_at_the_origin() {
    // The same shapes drawn at the origin and far away, the camera on them each time. In the
    // double-precision build they sit 100 km out, their corners at tenths of a metre, which no
    // `f32` out there holds. The single-precision build cannot place them there at all: it
    // moves them by a power of two, their corners on eighths of a metre, which `f32` holds.
    let (far, unit): (carom::Vec2, Real) = if std::mem::size_of::<Real>() == 8 {
        (vec2(100_000.3, -70_000.7), 0.1)
    } else {
        (vec2(65_536.0, -32_768.0), 0.125)
    };
    let fill = Color::rgb(0.2, 0.4, 0.9);
    let outline = Color::rgb(1.0, 0.9, 0.2);
    let draw = |at: carom::Vec2| {
        let p = |x: Real, y: Real| at + vec2(x, y) * unit;
        let mut list = DrawList::new();
        list.polygon(
            &[p(-9.0, -8.0), p(8.0, -9.0), p(11.0, 7.0), p(-8.0, 9.0)],
            fill,
            outline,
        );
        list.circle(p(-21.0, 9.0), 7.0 * unit, fill, outline);
        list.segment(p(-25.0, -17.0), p(23.0, -13.0), 2.0, outline);
        list.arrow(p(16.0, 1.0), p(27.0, 11.0), outline);
        list.point(p(3.0, 17.0), 5.0, outline);
        list
    };
    let mut renderer = offscreen(160, 100);
    let mut image_at = |at| {
        let camera = Camera {
            center: at + vec2(3.0, 1.0) * unit,
            zoom: 20.0,
        };
        renderer
            .render(&draw(at), &camera, Color::BACKGROUND)
            .unwrap()
    };
    let near = image_at(vec2(0.0, 0.0));
    let away = image_at(far);
    assert!(
        near.pixels().any(|p| p.0[..3] != [23, 26, 31]),
        "the shapes were drawn"
    );
    let worst = near
        .pixels()
        .zip(away.pixels())
        .flat_map(|(a, b)| (0..3).map(move |c| a.0[c].abs_diff(b.0[c])))
        .max()
        .unwrap_or(0);
    assert!(worst <= 2, "a channel differs by {worst} levels 100 km out");
}
