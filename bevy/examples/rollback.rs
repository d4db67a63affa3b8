//! Rollback netcode on one machine: a bevy_ggrs `SyncTestSession` (it loads the frame
//! `check distance` back every frame, simulates the frames since again and compares their
//! checksums, springwater's state hashes, with the first run's) with two local players,
//! one dropping water and one pushing a floating ball. Headless: one session frame per
//! update, as fast as the CPU goes; every 60 frames it prints the water's hash, the
//! rollbacks and mismatches so far and the time a frame took.
//!
//! ```sh
//! cargo run -p springwater-bevy --release --features ggrs --example rollback
//! cargo run -p springwater-bevy --release --features ggrs --example rollback -- --size 128 --frames 1200 --check-distance 7
//! ```

#[path = "../tests/rollback_game/mod.rs"]
mod rollback_game;

use std::time::Instant;

use bevy::prelude::*;
use rollback_game::Counts;
use springwater_bevy::prelude::*;
use springwater_bevy::rollback::WaterSnapshots;

struct Args {
    size: usize,
    frames: usize,
    check_distance: usize,
}

fn args() -> Result<Args, String> {
    let mut args = Args {
        size: 256,
        frames: 600,
        check_distance: 7,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let slot = match flag.as_str() {
            "--size" => &mut args.size,
            "--frames" => &mut args.frames,
            "--check-distance" => &mut args.check_distance,
            _ => {
                return Err(format!(
                    "unknown argument {flag}: use --size, --frames or --check-distance"
                ))
            }
        };
        let value = it.next().ok_or(format!("{flag} needs a number"))?;
        *slot = value
            .parse()
            .map_err(|_| format!("{flag} {value}: not a whole number"))?;
    }
    if args.size < 16 {
        return Err(format!("--size {}: at least 16", args.size));
    }
    Ok(args)
}

fn main() {
    let args = match args() {
        Ok(args) => args,
        Err(e) => {
            eprintln!("rollback: {e}");
            std::process::exit(2);
        }
    };
    let mut app = rollback_game::app(args.size, args.check_distance, |app| {
        app.add_plugins(SpringwaterPlugin::default().with_rollback());
    });
    println!(
        "{0}×{0} pool, sync test of check distance {1}, {2} frames",
        args.size, args.check_distance, args.frames
    );
    println!("frame  water hash        rollbacks  mismatches  ms/frame");
    let (mut since, mut printed) = (Instant::now(), 0);
    for frame in 1..=args.frames {
        app.update();
        if frame % 60 == 0 || frame == args.frames {
            let ms = since.elapsed().as_secs_f64() * 1e3 / (frame - printed) as f64;
            (since, printed) = (Instant::now(), frame);
            let world = app.world_mut();
            let hash = world
                .query::<&WaterSurface>()
                .single(world)
                .map(|ws| ws.surface().state_hash())
                .unwrap_or_default();
            let counts = world.resource::<Counts>();
            println!(
                "{frame:>5}  {hash:016x}  {:>9}  {:>10}  {ms:>8.2}",
                counts.loads, counts.mismatches
            );
        }
    }
    let snapshots = app.world().resource::<WaterSnapshots>();
    println!(
        "saves kept: {}; save buffers allocated or grown: {}",
        snapshots.frames(),
        snapshots.buffers_grown()
    );
    let counts = app.world().resource::<Counts>();
    if counts.mismatches > 0 {
        eprintln!("rollback: {} checksum mismatches", counts.mismatches);
        std::process::exit(1);
    }
}
