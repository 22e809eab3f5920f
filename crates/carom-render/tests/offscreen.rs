//! Real pixels: draw lists rendered offscreen and read back. These need a wgpu adapter (Mesa's
//! GL or Vulkan will do); without one they fail and say what to install.

use carom::{Color, DebugDraw, DrawList, vec2};
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
        let x = i as f32 * 0.01;
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
