//! What the plugin costs per frame around the step itself, headless.
//!
//! `cargo run --release -p springwater-bevy --example frame_cost [frames] [compute-threads]`
//!
//! Runs a rained-on pool of 128² and of 512² nodes with one floating ball in a
//! MinimalPlugins app with a fixed 1/60 s clock (one step per frame) and times the
//! plugin's three sets with marker systems between them: SyncInputs (parameter changes,
//! messages, buoyancy), Step (springwater's `advance_with`), Writeback (normals +
//! refraction, LOD, mesh write in place). Means over the frames after a warm-up; one run,
//! so noisy on a shared machine. Bevy's task pools are made once per process: by
//! default with Bevy's default options (on two cores the compute pool has one thread),
//! else with a compute pool of `compute-threads` threads.
//!
//! The library's own render-side stages are then timed alone on the final state, on the
//! same pool, to tell the plugin's glue (LOD check, mesh write) from them.

use std::time::{Duration, Instant};

use bevy::app::{TaskPoolOptions, TaskPoolPlugin, TaskPoolThreadAssignmentPolicy};
use bevy::asset::AssetPlugin;
use bevy::mesh::MeshPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy::transform::TransformPlugin;
use springwater::buffers::{interleave, VertexBuffers};
use springwater::disturb::Rain;
use springwater::mesh::Normals;
use springwater::refraction::{normals_and_refraction, Refraction};
use springwater_bevy::prelude::*;

/// Every task on the calling thread, in order.
struct Inline;

impl springwater::JobSystem for Inline {
    fn workers(&self) -> usize {
        1
    }
    fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
        (0..count).for_each(task);
    }
}

#[derive(Resource, Default)]
struct Marks {
    last: Option<Instant>,
    sums: [Duration; 3],
    on: bool,
}

fn mark<const PHASE: usize>(mut marks: ResMut<Marks>) {
    let now = Instant::now();
    if PHASE > 0 && marks.on {
        if let Some(last) = marks.last {
            marks.sums[PHASE - 1] += now - last;
        }
    }
    marks.last = Some(now);
}

fn measure(size: usize, frames: u32, compute: Option<usize>) -> ([Duration; 3], [Duration; 3]) {
    let mut options = TaskPoolOptions::default();
    if let Some(threads) = compute {
        options.compute = TaskPoolThreadAssignmentPolicy {
            min_threads: threads,
            ..options.compute
        };
    }
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins.set(TaskPoolPlugin {
            task_pool_options: options,
        }),
        AssetPlugin::default(),
        MeshPlugin,
        TransformPlugin,
        SpringwaterPlugin::default(),
    ))
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f32(
        1.0 / 60.0,
    )))
    .init_resource::<Marks>()
    .add_systems(
        PostUpdate,
        (
            mark::<0>.before(WaterSystems::SyncInputs),
            mark::<1>
                .after(WaterSystems::SyncInputs)
                .before(WaterSystems::Step),
            mark::<2>
                .after(WaterSystems::Step)
                .before(WaterSystems::Writeback),
            mark::<3>.after(WaterSystems::Writeback),
        ),
    );
    let half = (size / 2) as f32;
    app.world_mut().spawn((
        Water::with_size(size, size),
        WaterDisturbance::new(Rain::new(1.2 * (size * size) as f32 / 4096.0, 7)),
    ));
    app.world_mut().spawn((
        WaterViewer,
        Transform::from_xyz(half, half * 0.5, -half * 0.3),
    ));
    let settings = BuoyancySettings::default();
    app.world_mut().spawn((
        Buoyant::sphere(2.0, 0.5, &settings),
        Transform::from_xyz(half, 1.0, half),
    ));
    for _ in 0..30 {
        app.update();
    }
    app.world_mut().resource_mut::<Marks>().on = true;
    for _ in 0..frames {
        app.update();
    }
    let sets = app.world().resource::<Marks>().sums.map(|d| d / frames);
    // springwater's own render-side stage inside Writeback (normals + refraction), timed
    // alone on the final state, to tell the plugin's glue (LOD check, mesh write) from it.
    let mut waters = app.world_mut().query::<(&Water, &WaterSurface)>();
    let (water, ws) = waters.single(app.world()).expect("one water");
    let (mut normals, mut uv) = (Normals::new(), Refraction::default());
    let eye = [half, half * 0.5, -half * 0.3];
    let start = Instant::now();
    for _ in 0..frames {
        normals_and_refraction(
            &ws.surface().mesh_view(),
            eye.into(),
            &water.refraction,
            &mut normals,
            &mut uv,
        )
        .expect("refraction");
    }
    let stages = start.elapsed() / frames;
    let view = ws.surface().mesh_view();
    let n = view.grid().node_count();
    let (mut p, mut nr, mut t) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n], vec![[0.0; 2]; n]);
    let start = Instant::now();
    for _ in 0..frames {
        let out = VertexBuffers {
            positions: Some(&mut p),
            normals: Some(&mut nr),
            uvs: Some(&mut t),
            vertices: None,
        };
        interleave(&view, &normals, &uv, out).expect("interleave");
    }
    let interleaving = start.elapsed() / frames;
    // The same surface (its body, its pending state) stepped alone on one thread, without
    // its rain: what the physics costs, against the plugin's Step set on one compute thread.
    let mut alone = ws.surface().clone();
    alone.set_job_system(Some(std::sync::Arc::new(Inline)));
    let start = Instant::now();
    for _ in 0..frames {
        alone.step().expect("step");
    }
    let step_alone = start.elapsed() / frames;
    (sets, [stages, interleaving, step_alone])
}

fn main() {
    let arg = |i: usize| std::env::args().nth(i).and_then(|a| a.parse::<u32>().ok());
    let frames = arg(1).unwrap_or(200);
    let compute = arg(2).map(|n| n as usize);
    let mut pool = String::new();
    println!("size   sync-inputs        step  write-back | alone: normals+refraction  interleave  step on 1 thread");
    for size in [128, 512] {
        let ([sync, step, write], [stages, inter, alone]) = measure(size, frames, compute);
        println!("{size:>3}²  {sync:>11.1?} {step:>11.1?} {write:>11.1?}  {stages:>25.1?} {inter:>11.1?} {alone:>17.1?}");
        pool = format!(
            "{} thread(s)",
            bevy::tasks::ComputeTaskPool::get().thread_num()
        );
    }
    let default = if compute.is_none() {
        " (Bevy's default)"
    } else {
        ""
    };
    println!("mean per frame over {frames} frames; compute pool of {pool}{default}");
}
