//! Rollback netcode on one machine, headless, with two players, one dropping water and
//! one pushing a floating ball (their inputs a function of the frame number):
//!
//! - by default a bevy_ggrs `SyncTestSession`: every frame it loads the frame `check
//!   distance` back, simulates the frames since again and compares their checksums
//!   (springwater's state hashes) with the first run's;
//! - with `--p2p`, two peers of a P2P session in this process, talking over UDP on
//!   127.0.0.1 (ports 7731 and 7732, or `--port N` and N + 1), each predicting the
//!   other's input, rolling back when the prediction was wrong, and comparing checksums
//!   with the other every 10 frames (a difference is a desync).
//!
//! One session frame per update, as fast as the CPU goes; every 60 frames it prints each
//! session's frame, the water's hash, the rollbacks and mismatches (or desyncs) so far
//! and the time a frame took.
//!
//! ```sh
//! cargo run -p springwater-bevy --release --features ggrs --example rollback
//! cargo run -p springwater-bevy --release --features ggrs --example rollback -- --size 128 --frames 1200 --check-distance 7
//! cargo run -p springwater-bevy --release --features ggrs --example rollback -- --p2p
//! ```

#[path = "../tests/rollback_game/mod.rs"]
mod rollback_game;

use std::net::SocketAddr;
use std::time::Instant;

use bevy::prelude::*;
use bevy_ggrs::ggrs::{DesyncDetection, UdpNonBlockingSocket};
use bevy_ggrs::prelude::*;
use bevy_ggrs::RollbackFrameCount;
use rollback_game::{Config, Counts};
use springwater_bevy::prelude::*;
use springwater_bevy::rollback::WaterSnapshots;

struct Args {
    size: usize,
    frames: usize,
    check_distance: usize,
    /// The first peer's UDP port, for `--p2p`.
    p2p: Option<u16>,
}

fn args() -> Result<Args, String> {
    let mut args = Args {
        size: 256,
        frames: 600,
        check_distance: 7,
        p2p: None,
    };
    let mut port = 7731;
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        if flag == "--p2p" {
            args.p2p = Some(port);
            continue;
        }
        let value = it.next().ok_or(format!("{flag} needs a number"))?;
        let number = |v: &str| {
            v.parse()
                .map_err(|_| format!("{flag} {v}: not a whole number"))
        };
        match flag.as_str() {
            "--size" => args.size = number(&value)?,
            "--frames" => args.frames = number(&value)?,
            "--check-distance" => args.check_distance = number(&value)?,
            "--port" => {
                port = value
                    .parse()
                    .ok()
                    .filter(|&p| p > 0 && p < u16::MAX)
                    .ok_or(format!("--port {value}: 1 to 65534"))?;
            }
            _ => {
                return Err(format!(
                "unknown argument {flag}: use --size, --frames, --check-distance, --p2p or --port"
            ))
            }
        }
    }
    args.p2p = args.p2p.map(|_| port);
    if args.size < 16 {
        return Err(format!("--size {}: at least 16", args.size));
    }
    Ok(args)
}

/// Peer `local` (0 or 1) of a P2P session with the other on 127.0.0.1.
fn peer(local: usize, ports: [u16; 2]) -> Result<Session<Config>, String> {
    let remote = 1 - local;
    let socket = UdpNonBlockingSocket::bind_to_port(ports[local])
        .map_err(|e| format!("UDP port {}: {e}", ports[local]))?;
    let session = SessionBuilder::<Config>::new()
        .with_num_players(2)
        .and_then(|b| {
            b.with_desync_detection_mode(DesyncDetection::On { interval: 10 })
                .add_player(PlayerType::Local, local)
        })
        .and_then(|b| {
            let address = SocketAddr::from(([127, 0, 0, 1], ports[remote]));
            b.add_player(PlayerType::Remote(address), remote)
        })
        .and_then(|b| b.start_p2p_session(socket))
        .map_err(|e| e.to_string())?;
    Ok(Session::P2P(session))
}

/// Counts the desyncs a P2P session reports as mismatches.
fn watch_desyncs(mut session: ResMut<Session<Config>>, mut counts: ResMut<Counts>) {
    if let Session::P2P(session) = &mut *session {
        for event in session.events() {
            if let GgrsEvent::DesyncDetected { frame, .. } = event {
                eprintln!("rollback: desync at frame {frame}");
                counts.mismatches += 1;
            }
        }
    }
}

fn game(size: usize, session: Session<Config>) -> App {
    let mut app = rollback_game::app(size, session, |app| {
        app.add_plugins(SpringwaterPlugin::default().with_rollback());
    });
    app.add_systems(Update, watch_desyncs);
    app
}

fn main() {
    let (args, mut apps) = match args().and_then(|args| {
        let apps = match args.p2p {
            None => vec![game(
                args.size,
                rollback_game::sync_test(args.check_distance),
            )],
            Some(port) => {
                let ports = [port, port + 1];
                vec![
                    game(args.size, peer(0, ports)?),
                    game(args.size, peer(1, ports)?),
                ]
            }
        };
        Ok((args, apps))
    }) {
        Ok(it) => it,
        Err(e) => {
            eprintln!("rollback: {e}");
            std::process::exit(2);
        }
    };
    match args.p2p {
        None => println!(
            "{0}×{0} pool, sync test of check distance {1}, {2} frames",
            args.size, args.check_distance, args.frames
        ),
        Some(port) => println!(
            "{0}×{0} pool, two P2P peers on 127.0.0.1:{port} and :{1}, {2} updates",
            args.size,
            port + 1,
            args.frames
        ),
    }
    println!("peer  frame  water hash        rollbacks  mismatches  ms/frame");
    let (mut since, mut printed) = (Instant::now(), 0);
    for update in 1..=args.frames {
        for app in &mut apps {
            app.update();
        }
        if update % 60 == 0 || update == args.frames {
            let ms = since.elapsed().as_secs_f64() * 1e3 / (update - printed) as f64;
            (since, printed) = (Instant::now(), update);
            for (peer, app) in apps.iter_mut().enumerate() {
                let world = app.world_mut();
                let hash = world
                    .query::<&WaterSurface>()
                    .single(world)
                    .map(|ws| ws.surface().state_hash())
                    .unwrap_or_default();
                let frame = world.resource::<RollbackFrameCount>().0;
                let counts = world.resource::<Counts>();
                println!(
                    "{peer:>4}  {frame:>5}  {hash:016x}  {:>9}  {:>10}  {ms:>8.2}",
                    counts.loads, counts.mismatches
                );
            }
        }
    }
    let mut failed = false;
    for app in &apps {
        let snapshots = app.world().resource::<WaterSnapshots>();
        let counts = app.world().resource::<Counts>();
        println!(
            "saves kept: {}; save buffers allocated or grown: {}",
            snapshots.frames(),
            snapshots.buffers_grown()
        );
        failed |= counts.mismatches > 0;
    }
    if failed {
        eprintln!("rollback: the checksums differed");
        std::process::exit(1);
    }
}
