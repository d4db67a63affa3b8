//! The step's colour batches run on a host's own job system ([`JobSystem`]) with results
//! bitwise identical to rayon's pool, whatever threads and order the host uses; a job
//! system that breaks its contract (skips tasks, runs one twice, passes indices out of
//! range) cannot corrupt the state.

mod common;

use common::state_bits;
use springwater::{Error, JobSystem, Params, Surface};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// Runs every task on the calling thread, last index first.
struct Backwards;

impl JobSystem for Backwards {
    fn workers(&self) -> usize {
        3
    }
    fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
        (0..count).rev().for_each(task);
    }
}

/// Spreads the tasks over `threads` scoped threads that take indices from a shared
/// counter, the way a work-stealing job system does; counts the batches it ran.
struct Scoped {
    threads: usize,
    batches: AtomicUsize,
}

impl JobSystem for Scoped {
    fn workers(&self) -> usize {
        self.threads
    }
    fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
        self.batches.fetch_add(1, Ordering::Relaxed);
        let next = AtomicUsize::new(0);
        std::thread::scope(|s| {
            for _ in 0..self.threads {
                s.spawn(|| loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= count {
                        break;
                    }
                    task(i);
                });
            }
        });
    }
}

/// Breaks the contract in one of several ways.
enum Broken {
    /// Never runs the last task.
    SkipsLast,
    /// Runs every task twice, the second time on other threads at once.
    RunsTwice,
    /// Also calls indices past the count.
    PastTheEnd,
}

impl JobSystem for Broken {
    fn workers(&self) -> usize {
        2
    }
    fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
        match self {
            Broken::SkipsLast => (0..count.saturating_sub(1)).for_each(task),
            Broken::RunsTwice => std::thread::scope(|s| {
                for _ in 0..2 {
                    s.spawn(|| (0..count).for_each(task));
                }
            }),
            Broken::PastTheEnd => (0..count + 3).for_each(task),
        }
    }
}

fn run(jobs: Option<Arc<dyn JobSystem>>) -> Surface {
    common::every_stepping_path(|s| s.set_job_system(jobs))
}

#[test]
fn a_hosts_job_system_gives_the_default_bits() {
    let default = run(None);
    let scoped = Arc::new(Scoped {
        threads: 4,
        batches: AtomicUsize::new(0),
    });
    let cases: [(&str, Arc<dyn JobSystem>); 3] = [
        ("backwards on one thread", Arc::new(Backwards)),
        ("four scoped threads", scoped.clone()),
        (
            "a broken one running tasks twice",
            Arc::new(Broken::RunsTwice),
        ),
    ];
    for (name, jobs) in cases {
        let hosted = run(Some(jobs));
        assert_eq!(hosted.steps(), default.steps());
        assert!(
            state_bits(&hosted) == state_bits(&default),
            "{name}: the state differs from rayon's pool"
        );
    }
    // Every pass went through the job system: two colours per pass.
    assert!(scoped.batches.load(Ordering::Relaxed) >= 2 * 20);
    let past = run(Some(Arc::new(Broken::PastTheEnd)));
    assert!(state_bits(&past) == state_bits(&default));
}

#[test]
fn a_job_system_that_skips_a_task_fails_the_step_and_changes_nothing() {
    let mut s = Surface::new(Params::with_size(64, 96)).unwrap();
    s.drop_at(32.0, 40.0, 1.0, 3.0).unwrap();
    s.step_n(4).unwrap();
    let before = state_bits(&s);
    s.set_job_system(Some(Arc::new(Broken::SkipsLast)));
    for result in [s.step(), s.step_n(6), s.advance(0.1).map(|_| ())] {
        assert_eq!(result, Err(Error::JobSystem));
        assert!(state_bits(&s) == before);
        assert_eq!(s.steps(), 4);
    }
    let message = Error::JobSystem.to_string();
    assert!(message.contains("job system"), "{message}");
    s.set_job_system(None);
    s.step().unwrap();
}

#[test]
fn the_job_system_is_kept_by_clones_and_restores_and_replaces_a_pool() {
    let jobs: Arc<dyn JobSystem> = Arc::new(Backwards);
    let mut s = Surface::new(Params::with_size(33, 33)).unwrap();
    s.set_job_system(Some(jobs.clone()));
    let saved = s.to_bytes();
    s.drop_at(16.0, 16.0, 1.0, 3.0).unwrap();
    s.restore(&saved).unwrap();
    assert!(Arc::ptr_eq(s.job_system().unwrap(), &jobs));
    assert!(Arc::ptr_eq(s.clone().job_system().unwrap(), &jobs));
    assert!(Surface::from_bytes(&saved).unwrap().job_system().is_none());
    #[cfg(feature = "parallel")]
    {
        let pool = Arc::new(
            rayon::ThreadPoolBuilder::new()
                .num_threads(2)
                .build()
                .unwrap(),
        );
        s.set_thread_pool(Some(pool));
        assert!(s.job_system().is_none());
        s.set_job_system(Some(jobs));
        assert!(s.thread_pool().is_none());
    }
}

/// A job system whose tasks record the thread they ran on: the batches really spread.
#[test]
fn the_bands_spread_over_the_hosts_threads() {
    struct Recording(
        Scoped,
        Mutex<std::collections::HashSet<std::thread::ThreadId>>,
    );
    impl JobSystem for Recording {
        fn workers(&self) -> usize {
            self.0.workers()
        }
        fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
            self.0.run(count, &|i| {
                self.1.lock().unwrap().insert(std::thread::current().id());
                std::thread::sleep(std::time::Duration::from_millis(1));
                task(i)
            });
        }
    }
    let jobs = Arc::new(Recording(
        Scoped {
            threads: 3,
            batches: AtomicUsize::new(0),
        },
        Mutex::new(Default::default()),
    ));
    let mut s = Surface::new(Params::with_size(64, 256)).unwrap();
    s.set_job_system(Some(jobs.clone()));
    s.step_n(8).unwrap();
    assert!(jobs.1.lock().unwrap().len() >= 2);
}

/// The render-side stages on a surface's view (normals, refraction, interleaving) run
/// their parts through the surface's job system, and give rayon's bits whatever the job
/// system does: a part it skipped runs on the calling thread, a part it repeated runs
/// once.
#[test]
fn the_render_side_stages_run_on_the_job_system_with_the_same_bits() {
    use springwater::buffers::{fill_frame, interleave, Vertex, VertexBuffers};
    use springwater::mesh::{compute_normals, Normals};
    use springwater::refraction::{normals_and_refraction, refract, Refraction, RefractionParams};

    /// What every stage writes, as bits.
    fn stages(s: &Surface) -> Vec<u32> {
        let view = s.mesh_view();
        let eye = springwater::glam::Vec3::new(40.0, 30.0, -20.0);
        let params = RefractionParams::default();
        let (mut normals, mut uv) = (Normals::new(), Refraction::default());
        let (mut n2, mut uv2) = (Normals::new(), Refraction::default());
        compute_normals(&view, &mut normals);
        refract(&view, &normals, eye, &params, &mut uv).unwrap();
        normals_and_refraction(&view, eye, &params, &mut n2, &mut uv2).unwrap();
        let mut vertices = vec![Vertex::default(); s.node_count()];
        let mut positions = vec![[0.0f32; 3]; s.node_count()];
        interleave(
            &view,
            &normals,
            &uv,
            VertexBuffers {
                vertices: Some(&mut vertices),
                positions: Some(&mut positions),
                ..Default::default()
            },
        )
        .unwrap();
        let mut fused = vec![Vertex::default(); s.node_count()];
        let out = VertexBuffers {
            vertices: Some(&mut fused),
            ..Default::default()
        };
        fill_frame(&view, eye, &params, out).unwrap();
        assert!(fused == vertices);
        let floats = [
            &normals.x,
            &normals.y,
            &normals.z,
            &uv.u,
            &uv.v,
            &uv.fresnel,
        ]
        .into_iter()
        .chain([&n2.x, &n2.y, &n2.z, &uv2.u, &uv2.v, &uv2.fresnel])
        .flat_map(|c| c.iter().copied());
        let packed = bytemuck::cast_slice::<Vertex, f32>(&vertices)
            .iter()
            .copied();
        let flat = positions.iter().flatten().copied();
        floats.chain(packed).chain(flat).map(f32::to_bits).collect()
    }

    let mut s = Surface::new(Params::with_size(131, 257)).unwrap();
    s.drop_at(60.0, 100.0, 1.5, 4.0).unwrap();
    s.step_n(12).unwrap();
    let default = stages(&s);
    let scoped = Arc::new(Scoped {
        threads: 3,
        batches: AtomicUsize::new(0),
    });
    let cases: [(&str, Arc<dyn JobSystem>); 5] = [
        ("four scoped threads", scoped.clone()),
        ("backwards on one thread", Arc::new(Backwards)),
        ("skipping the last task", Arc::new(Broken::SkipsLast)),
        ("running tasks twice", Arc::new(Broken::RunsTwice)),
        ("calling past the end", Arc::new(Broken::PastTheEnd)),
    ];
    for (name, jobs) in cases {
        s.set_job_system(Some(jobs));
        assert!(stages(&s) == default, "{name}: the stages' output differs");
    }
    // normals, refract, the fused pass, interleave and fill_frame: one batch each.
    assert_eq!(scoped.batches.load(Ordering::Relaxed), 5);
}

/// A view the caller builds from its own slices runs its render-side stages on the job
/// system it is given, with the bits of the surface's own view.
#[test]
fn a_view_built_by_the_caller_runs_on_the_job_system_it_is_given() {
    use springwater::buffers::{fill_frame, Vertex, VertexBuffers};
    use springwater::mesh::{compute_normals, Normals};
    use springwater::refraction::RefractionParams;
    use springwater::MeshView;

    let mut s = Surface::new(Params::with_size(97, 131)).unwrap();
    s.drop_at(40.0, 60.0, 1.2, 4.0).unwrap();
    s.step_n(9).unwrap();
    let eye = springwater::glam::Vec3::new(40.0, 25.0, -15.0);
    let frame = |view: &MeshView<'_>| {
        let mut normals = Normals::new();
        compute_normals(view, &mut normals);
        let mut vertices = vec![Vertex::default(); s.node_count()];
        let out = VertexBuffers {
            vertices: Some(&mut vertices),
            ..Default::default()
        };
        fill_frame(view, eye, &RefractionParams::default(), out).unwrap();
        (normals, vertices)
    };
    let expected = frame(&s.mesh_view());
    let [x, y, z] = s.positions();
    let scoped = Scoped {
        threads: 2,
        batches: AtomicUsize::new(0),
    };
    let view = MeshView::new(s.grid(), s.params().spacing, x, y, z)
        .unwrap()
        .with_job_system(&scoped);
    let got = frame(&view);
    assert_eq!(
        scoped.batches.load(Ordering::Relaxed),
        2,
        "one batch per stage"
    );
    let bits = |(n, v): &(Normals, Vec<Vertex>)| -> Vec<u32> {
        let normals = [&n.x, &n.y, &n.z].into_iter().flatten().copied();
        let vertices = bytemuck::cast_slice::<Vertex, f32>(v).iter().copied();
        normals.chain(vertices).map(f32::to_bits).collect()
    };
    assert!(bits(&got) == bits(&expected));
}
