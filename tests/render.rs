//! The preview renderer: pictures that are not blank, motion where the ripples are and
//! stillness where they are not, an undistorted bottom through flat water, the wireframe,
//! the balls and the facets of solids, which the water hides where it is in front.
#![cfg(feature = "render")]

use glam::Vec3;
use springwater::render::{Ball, Camera, Facet, Frame, Look, RenderParams, Renderer, Texture};
use springwater::{Params, Surface};

fn luminance(frame: &Frame) -> Vec<f32> {
    frame
        .rgb()
        .chunks_exact(3)
        .map(|p| 0.2126 * p[0] as f32 + 0.7152 * p[1] as f32 + 0.0722 * p[2] as f32)
        .collect()
}

#[test]
fn a_render_is_neither_blank_nor_uniform() {
    let mut water = Surface::new(Params::with_size(64, 64)).unwrap();
    water.drop_at(30.0, 34.0, -2.0, 3.0).unwrap();
    for _ in 0..15 {
        water.step().unwrap();
    }
    let camera = Camera::framing(64, 64, 1.0, 160, 120);
    let mut renderer = Renderer::new(RenderParams::default(), Texture::pool_tiles(256)).unwrap();
    let frame = renderer.render(&water.mesh_view(), &camera).unwrap();
    assert_eq!((frame.width(), frame.height()), (160, 120));
    let lum = luminance(frame);
    let mean = lum.iter().sum::<f32>() / lum.len() as f32;
    let var = lum.iter().map(|l| (l - mean).powi(2)).sum::<f32>() / lum.len() as f32;
    assert!(mean > 20.0 && mean < 240.0, "mean luminance {mean}");
    assert!(var.sqrt() > 10.0, "standard deviation {}", var.sqrt());
    let mut colours: Vec<[u8; 3]> = frame
        .rgb()
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 500, "only {} colours", colours.len());
    // The middle of the image is water: bluish.
    let [r, _, b] = frame.pixel(80, 60);
    assert!(b > r, "middle pixel is not water-coloured");
}

#[test]
fn frames_change_where_ripples_travel_and_agree_where_the_water_is_calm() {
    // One drop near a corner of a 96×96 pool, seen from straight above. In 8 steps the
    // disturbance reaches at most ~30 cells from the drop (its Gaussian's non-zero reach
    // plus one cell per step); the opposite corner stays exactly at rest.
    let mut water = Surface::new(Params::with_size(96, 96)).unwrap();
    water.drop_at(14.0, 14.0, -1.5, 2.0).unwrap();
    let camera = Camera::top_down(96, 96, 1.0, 192, 192);
    let mut renderer = Renderer::new(RenderParams::default(), Texture::pool_tiles(512)).unwrap();
    for _ in 0..4 {
        water.step().unwrap();
    }
    let a = renderer
        .render(&water.mesh_view(), &camera)
        .unwrap()
        .clone();
    for _ in 0..4 {
        water.step().unwrap();
    }
    let b = renderer
        .render(&water.mesh_view(), &camera)
        .unwrap()
        .clone();
    // Pixels per cell: 192 / 95 ≈ 2. The drop is near pixel (28, 28).
    let differs = |x0: usize, x1: usize| {
        (x0..x1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| a.pixel(x, y) != b.pixel(x, y))
            .count()
    };
    assert!(
        differs(10, 50) > 200,
        "the ripple near the drop did not change the picture"
    );
    assert_eq!(differs(120, 190), 0, "calm water far from the drop changed");
}

#[test]
fn a_flat_surface_seen_from_above_shows_the_bottom_undistorted() {
    let (cols, rows) = (65, 65);
    let water = Surface::new(Params::with_size(cols, rows)).unwrap();
    let (w, h) = (240u32, 240u32);
    let camera = Camera::top_down(cols, rows, 1.0, w, h);
    // Nothing but the bottom: no tint, no caustics, a black sky (the Fresnel reflection of
    // a black sky only darkens by the reflectance, about 2% looking straight down).
    let look = Look {
        sky_zenith: [0.0; 3],
        sky_horizon: [0.0; 3],
        glint: 0.0,
        absorption: [0.0; 3],
        caustics: 0.0,
        surroundings: false,
        ..Look::default()
    };
    let mut params = RenderParams {
        look,
        ..RenderParams::default()
    };
    params.refraction.depth = 6.0;
    let ior = params.refraction.ior;
    let texture = Texture::pool_tiles(512);
    let mut renderer = Renderer::new(params, texture.clone()).unwrap();
    let frame = renderer.render(&water.mesh_view(), &camera).unwrap();

    // The same picture traced directly: each pixel's ray meets the flat water at y = 0,
    // bends by Snell's law, meets the bottom, and reads the texture there.
    let footprint = ((cols - 1) as f32, (rows - 1) as f32);
    let expected = |px: f32, py: f32, shift: f32| -> Option<[u8; 3]> {
        let d = camera.ray(px, py);
        let s = -camera.eye.y / d.y;
        let p = camera.eye + d * s;
        if p.x < 0.0 || p.z < 0.0 || p.x > footprint.0 || p.z > footprint.1 {
            return None;
        }
        let (sin_i, eta) = ((1.0 - d.y * d.y).max(0.0).sqrt(), 1.0 / ior);
        let sin_t = eta * sin_i;
        let tan_t = sin_t / (1.0 - sin_t * sin_t).sqrt();
        let horizontal = Vec3::new(d.x, 0.0, d.z).normalize_or_zero();
        let q = p + horizontal * (tan_t * params.refraction.depth);
        let c = texture.sample(q.x / footprint.0 + shift, q.z / footprint.1);
        let r0 = ((1.0 - ior) / (1.0 + ior)).powi(2);
        Some(c.map(|v| {
            let s = v * (1.0 - r0);
            let s = if s <= 0.003_130_8 {
                s * 12.92
            } else {
                1.055 * s.powf(1.0 / 2.4) - 0.055
            };
            (s * 255.0 + 0.5).clamp(0.0, 255.0) as u8
        }))
    };
    let error = |shift: f32| {
        let (mut sum, mut n) = (0.0f64, 0usize);
        for y in 0..h as usize {
            for x in 0..w as usize {
                if let Some(e) = expected(x as f32 + 0.5, y as f32 + 0.5, shift) {
                    let got = frame.pixel(x, y);
                    sum += (0..3)
                        .map(|k| (got[k] as f64 - e[k] as f64).abs())
                        .sum::<f64>()
                        / 3.0;
                    n += 1;
                }
            }
        }
        assert!(
            n > (w * h) as usize / 2,
            "the water covers too little of the image"
        );
        sum / n as f64
    };
    let exact = error(0.0);
    // The bottom moved by 1% of the pool (a quarter of a tile) is far off: the test is sharp.
    let shifted = error(0.01);
    assert!(
        exact < 1.0,
        "mean error {exact:.2} levels against the directly sampled bottom"
    );
    assert!(
        shifted > 4.0 * exact.max(0.5),
        "a shifted bottom is not detected ({shifted:.2} vs {exact:.2})"
    );
}

#[test]
fn the_wireframe_overlay_colours_edges_by_level() {
    let water = Surface::new(Params::with_size(48, 48)).unwrap();
    let camera = Camera::framing(48, 48, 1.0, 200, 150);
    let plain = Renderer::new(RenderParams::default(), Texture::pool_tiles(256))
        .unwrap()
        .render(&water.mesh_view(), &camera)
        .unwrap()
        .clone();
    let mut wire = Renderer::new(
        RenderParams {
            wireframe: true,
            ..RenderParams::default()
        },
        Texture::pool_tiles(256),
    )
    .unwrap();
    let framed = wire.render(&water.mesh_view(), &camera).unwrap();
    let changed = (0..150)
        .flat_map(|y| (0..200).map(move |x| (x, y)))
        .filter(|&(x, y)| plain.pixel(x, y) != framed.pixel(x, y))
        .count();
    assert!(changed > 2000, "only {changed} pixels show edges");
    // The finest level's edges are yellow: strong red and green, little blue.
    let yellow = framed
        .rgb()
        .chunks_exact(3)
        .filter(|p| p[0] > 200 && p[1] > 150 && p[2] < 100)
        .count();
    assert!(yellow > 100, "only {yellow} yellow pixels");
}

#[test]
fn balls_are_drawn_over_the_water_and_bad_ones_refused() {
    let water = Surface::new(Params::with_size(48, 48)).unwrap();
    let camera = Camera::framing(48, 48, 1.0, 160, 120);
    let mut renderer = Renderer::new(RenderParams::default(), Texture::pool_tiles(256)).unwrap();
    let centre = Vec3::new(24.0, 1.0, 24.0);
    let red = [[0.9, 0.0, 0.0], [0.9, 0.0, 0.0]];
    renderer
        .set_balls(&[Ball {
            centre,
            radius: 3.0,
            colours: red,
        }])
        .unwrap();
    let frame = renderer.render(&water.mesh_view(), &camera).unwrap();
    let (x, y, _) = camera.project(centre).unwrap();
    let [r, g, b] = frame.pixel(x as usize, y as usize);
    assert!(
        r > 150 && g < 80 && b < 80,
        "the ball's middle is {r},{g},{b}"
    );
    let bad = Ball {
        centre: Vec3::new(f32::NAN, 0.0, 0.0),
        radius: 1.0,
        colours: red,
    };
    assert!(renderer.set_balls(&[bad]).is_err());
    let bad = Ball {
        centre,
        radius: 0.0,
        colours: red,
    };
    assert!(renderer.set_balls(&[bad]).is_err());
}

/// A square of two facets lying flat at height `y` over the middle of a 48 × 48 pool.
fn square(y: f32, colour: [f32; 3]) -> [Facet; 2] {
    let (lo, hi) = (16.0, 32.0);
    let p = |x: f32, z: f32| Vec3::new(x, y, z);
    [
        Facet {
            corners: [p(lo, lo), p(lo, hi), p(hi, hi)],
            colour,
        },
        Facet {
            corners: [p(lo, lo), p(hi, hi), p(hi, lo)],
            colour,
        },
    ]
}

#[test]
fn facets_above_the_water_are_drawn_and_under_it_hidden() {
    let water = Surface::new(Params::with_size(48, 48)).unwrap();
    let camera = Camera::framing(48, 48, 1.0, 160, 120);
    let mut renderer = Renderer::new(RenderParams::default(), Texture::pool_tiles(256)).unwrap();
    let middle = Vec3::new(24.0, 0.0, 24.0);
    let (x, y, _) = camera.project(middle).unwrap();
    let red = [0.9, 0.0, 0.0];
    let redness = |renderer: &mut Renderer| {
        let frame = renderer.render(&water.mesh_view(), &camera).unwrap();
        let [r, g, b] = frame.pixel(x as usize, y as usize);
        (r, g, b)
    };
    let water_alone = redness(&mut renderer);
    renderer.set_facets(&square(0.5, red)).unwrap();
    let (r, g, b) = redness(&mut renderer);
    assert!(
        r > 150 && g < 60 && b < 60,
        "a facet over the water is {r},{g},{b}"
    );
    // Half a unit under the flat water: the water is in front of it everywhere.
    renderer.set_facets(&square(-0.5, red)).unwrap();
    assert_eq!(redness(&mut renderer), water_alone);
    // Refused, and the facets drawn before stay.
    let mut bad = square(0.5, red);
    bad[1].corners[2].x = f32::INFINITY;
    assert!(renderer.set_facets(&bad).is_err());
    let negative = square(0.5, [-0.1, 0.0, 0.0]);
    assert!(renderer.set_facets(&negative).is_err());
    assert_eq!(redness(&mut renderer), water_alone);
}
