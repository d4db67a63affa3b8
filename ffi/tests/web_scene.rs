//! The scripted scene of `web/test/scene.json`, run by the Rust API: its state hash must
//! be the file's `stateHash`, which the npm package's Node test (web/test/native.test.mjs)
//! and its browser test reach through the C ABI built for wasm32. So a native server and
//! a browser agree on the bits. `SPRINGWATER_BLESS=1` writes the hash into the file.

use glam::Vec3;
use serde_json::Value;
use springwater::disturb::{Rain, Wake};
use springwater::{Floater, Params, Surface};
use std::path::PathBuf;

fn floats(v: &Value) -> Vec<f32> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap() as f32)
        .collect()
}

fn vec3(v: &Value) -> Vec3 {
    let f = floats(v);
    Vec3::new(f[0], f[1], f[2])
}

/// Runs the scene; its final state hash.
fn run(scene: &Value) -> u64 {
    let size = |k: &str| scene[k].as_u64().unwrap() as usize;
    let mut water = Surface::new(Params::with_size(size("cols"), size("rows"))).unwrap();
    for drop in scene["drops"].as_array().unwrap() {
        let d = floats(drop);
        water.drop_at(d[0], d[1], d[2], d[3]).unwrap();
    }
    let s = &scene["sphere"];
    let mut sphere = Floater::sphere(
        s["radius"].as_f64().unwrap() as f32,
        s["mass"].as_f64().unwrap() as f32,
        vec3(&s["position"]),
    );
    sphere.velocity = vec3(&s["velocity"]);
    water.add_floater(sphere).unwrap();
    let b = &scene["box"];
    let cuboid = Floater::cuboid(
        vec3(&b["halfExtents"]),
        b["mass"].as_f64().unwrap() as f32,
        vec3(&b["position"]),
    );
    water.add_floater(cuboid).unwrap();
    let h = &scene["hull"];
    let vertices: Vec<[f32; 3]> = floats(&h["vertices"])
        .chunks_exact(3)
        .map(|v| [v[0], v[1], v[2]])
        .collect();
    let triangles: Vec<[u32; 3]> = h["triangles"]
        .as_array()
        .unwrap()
        .chunks_exact(3)
        .map(|t| std::array::from_fn(|k| t[k].as_u64().unwrap() as u32))
        .collect();
    let mut hull = Floater::hull(
        &vertices,
        &triangles,
        h["mass"].as_f64().unwrap() as f32,
        vec3(&h["position"]),
    )
    .unwrap();
    hull.angular_velocity = vec3(&h["angularVelocity"]);
    water.add_floater(hull).unwrap();

    let r = &scene["rain"];
    let radius = floats(&r["radius"]);
    let mut rain = Rain::new(
        r["rate"].as_f64().unwrap() as f32,
        r["seed"].as_u64().unwrap(),
    );
    rain.radius = radius[0]..radius[1];
    rain.depth = r["depth"].as_f64().unwrap() as f32;
    let w = &scene["wake"];
    let path = w["path"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let p = floats(p);
            [p[0], p[1]]
        })
        .collect();
    let mut wake = Wake::new(path).unwrap();
    wake.speed = w["speed"].as_f64().unwrap() as f32;
    wake.radius = w["radius"].as_f64().unwrap() as f32;
    wake.strength = w["strength"].as_f64().unwrap() as f32;

    let frame = 1.0 / scene["framesPerSecond"].as_f64().unwrap() as f32;
    for _ in 0..scene["frames"].as_u64().unwrap() {
        water
            .advance_with(frame, &mut (&mut rain, &mut wake))
            .unwrap();
    }
    assert!(
        rain.fallen() > 10,
        "the scene's rain fell {} drops",
        rain.fallen()
    );
    water.state_hash()
}

#[test]
fn the_web_scene_reaches_the_hash_the_npm_package_checks() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../web/test/scene.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut scene: Value = serde_json::from_str(&text).unwrap();
    let hash = run(&scene).to_string();
    if std::env::var_os("SPRINGWATER_BLESS").is_some() {
        let old = format!(
            "\"stateHash\": \"{}\"",
            scene["stateHash"].as_str().unwrap()
        );
        let new = format!("\"stateHash\": \"{hash}\"");
        std::fs::write(&path, text.replace(&old, &new)).unwrap();
        scene["stateHash"] = Value::String(hash.clone());
    }
    assert_eq!(
        scene["stateHash"].as_str().unwrap(),
        hash,
        "the scene's state hash changed: if on purpose, SPRINGWATER_BLESS=1 rewrites {}",
        path.display()
    );
}
