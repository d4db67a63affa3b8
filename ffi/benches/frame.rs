//! One game frame through the C ABI against the same frame through the Rust API, in one
//! group so the ratio comes from one run: `ffi_frame/{rust,c_abi}/{n}x{n}`.
//!
//! The frame: advance by 1/60 s (with a new drop every 120 frames, so the water never
//! settles into subnormal values that slow the step down), write the packed vertex buffer (normals, refraction and
//! interleave in one call), update the LOD from the eye and copy the index buffer when it
//! changed, sample the water under four floating objects. The C ABI side calls the
//! exported `extern "C"` functions (handle lookup, lock, argument checks, panic guard);
//! from C, a call through the dynamic library adds one indirect jump on top.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use springwater::buffers::{interleave, Vertex, VertexBuffers};
use springwater::mesh::{LodMesh, LodParams, Normals};
use springwater::refraction::{normals_and_refraction, Refraction, RefractionParams};
use springwater::{Params, Surface};
use springwater_ffi::*;
use std::time::Duration;

const EYE: [f32; 3] = [10.0, 30.0, -20.0];
const FLOATERS: [[f32; 2]; 4] = [[5.0, 5.0], [20.5, 30.25], [40.0, 12.0], [60.0, 60.0]];

/// The Rust side's frame state: the surface and the buffers a renderer keeps.
struct RustFrame {
    surface: Surface,
    lod: LodMesh,
    normals: Normals,
    uv: Refraction,
    vertices: Vec<Vertex>,
    indices: Vec<u32>,
    points: Vec<[f32; 2]>,
    heights: Vec<f32>,
    up: Vec<glam::Vec3>,
    velocity: Vec<glam::Vec3>,
    frames: u64,
}

impl RustFrame {
    fn new(n: usize) -> Self {
        let mut surface = Surface::new(Params::with_size(n, n)).unwrap();
        surface
            .drop_at(n as f32 / 2.0, n as f32 / 2.0, 1.0, 4.0)
            .unwrap();
        Self {
            vertices: vec![Vertex::default(); surface.node_count()],
            surface,
            lod: LodMesh::new(LodParams::default()).unwrap(),
            normals: Normals::new(),
            uv: Refraction::default(),
            indices: Vec::new(),
            points: FLOATERS.to_vec(),
            heights: Vec::new(),
            up: Vec::new(),
            velocity: Vec::new(),
            frames: 0,
        }
    }

    fn frame(&mut self) {
        self.frames += 1;
        if self.frames.is_multiple_of(120) {
            let c = self.surface.params().cols as f32 / 2.0;
            self.surface.drop_at(c, c, 1.0, 4.0).unwrap();
        }
        self.surface.advance(1.0 / 60.0).unwrap();
        let view = self.surface.mesh_view();
        let eye = glam::Vec3::from(EYE);
        let optics = RefractionParams::default();
        normals_and_refraction(&view, eye, &optics, &mut self.normals, &mut self.uv).unwrap();
        let out = VertexBuffers {
            vertices: Some(&mut self.vertices),
            ..Default::default()
        };
        interleave(&view, &self.normals, &self.uv, out).unwrap();
        if self.lod.update(&view, eye) {
            self.indices.clear();
            self.indices.extend_from_slice(self.lod.indices());
        }
        let s = &self.surface;
        s.heights_at(&self.points, &mut self.heights).unwrap();
        s.normals_at(&self.points, &mut self.up).unwrap();
        s.velocities_at(&self.points, &mut self.velocity).unwrap();
    }
}

/// The C side's frame state: a handle and the caller's buffers.
struct CFrame {
    surface: *mut SwSurface,
    vertices: Vec<SwVertex>,
    indices: Vec<u32>,
    xz: Vec<f32>,
    samples: Vec<SwSample>,
    frames: u64,
    centre: f32,
}

impl CFrame {
    fn new(n: usize) -> Self {
        let mut params = sw_params_default();
        params.cols = n as u32;
        params.rows = n as u32;
        let mut surface = std::ptr::null_mut();
        // SAFETY: valid pointers to locals.
        unsafe {
            assert_eq!(sw_surface_create(&params, &mut surface), SW_OK);
        }
        assert_eq!(
            sw_surface_drop_at(surface, n as f32 / 2.0, n as f32 / 2.0, 1.0, 4.0),
            SW_OK
        );
        Self {
            surface,
            vertices: vec![SwVertex::default(); n * n],
            indices: Vec::new(),
            xz: FLOATERS.iter().flatten().copied().collect(),
            samples: vec![SwSample::default(); FLOATERS.len()],
            frames: 0,
            centre: n as f32 / 2.0,
        }
    }

    fn frame(&mut self) {
        let s = self.surface;
        self.frames += 1;
        if self.frames.is_multiple_of(120) {
            assert_eq!(
                sw_surface_drop_at(s, self.centre, self.centre, 1.0, 4.0),
                SW_OK
            );
        }
        let mut view = sw_refraction_default();
        [view.eye_x, view.eye_y, view.eye_z] = EYE;
        // SAFETY: every pointer is to a live buffer of the length passed.
        unsafe {
            assert_eq!(
                sw_surface_advance(s, 1.0 / 60.0, std::ptr::null_mut()),
                SW_OK
            );
            let (ptr, len) = (self.vertices.as_mut_ptr(), self.vertices.len());
            assert_eq!(sw_surface_write_vertices(s, &view, ptr, len), SW_OK);
            let mut changed = 0;
            assert_eq!(
                sw_surface_update_lod(s, EYE[0], EYE[1], EYE[2], &mut changed),
                SW_OK
            );
            if changed != 0 {
                let mut count = 0;
                sw_surface_lod_indices(s, std::ptr::null_mut(), 0, &mut count);
                self.indices.resize(count, 0);
                let ptr = self.indices.as_mut_ptr();
                assert_eq!(sw_surface_lod_indices(s, ptr, count, &mut count), SW_OK);
            }
            let (xz, n) = (self.xz.as_ptr(), FLOATERS.len());
            let out = self.samples.as_mut_ptr();
            assert_eq!(sw_surface_sample(s, xz, n, out, n), SW_OK);
        }
    }
}

impl Drop for CFrame {
    fn drop(&mut self) {
        sw_surface_destroy(self.surface);
    }
}

fn frame(c: &mut Criterion) {
    let mut g = c.benchmark_group("ffi_frame");
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for n in [128usize, 512] {
        let size = format!("{n}x{n}");
        g.throughput(Throughput::Elements((n * n) as u64));
        let mut rust = RustFrame::new(n);
        g.bench_function(BenchmarkId::new("rust", &size), |b| b.iter(|| rust.frame()));
        let mut c_abi = CFrame::new(n);
        g.bench_function(BenchmarkId::new("c_abi", &size), |b| {
            b.iter(|| c_abi.frame())
        });
    }
    g.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
