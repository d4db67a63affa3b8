//! Wavefront OBJ frames: the rest mesh beside a point cache, and the `water_0001.obj` …
//! sequence written into a directory. One `v`, `vn` and `vt` (refraction UV) per node,
//! row-major, the triangles as `f a/a/a b/b/b c/c/c` (1-based, counter-clockwise seen
//! from +y), as `springwater export` writes them.

use super::{create_io, named, Frame, Rest, Writer};
use crate::args::Short;
use springwater::mesh::Normals;
use springwater::refraction::Refraction;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `frame` with `rest`'s triangles to `path`.
pub fn write(path: &Path, title: &str, rest: &Rest, frame: &Frame) -> std::io::Result<()> {
    let mut w = create_io(path)?;
    let result = (|| {
        writeln!(w, "# {title}")?;
        mesh(
            &mut w,
            frame.positions,
            frame.normals,
            frame.uv,
            &rest.indices,
        )?;
        w.flush()
    })();
    result.map_err(|e| named(path, e))
}

/// The body of an OBJ (after its comment line): a `v`, `vn` and `vt` per node, then the
/// faces. Numbers in the shortest form that reads back to the same `f32` (exponent
/// notation where that is shorter, as in `simulate --csv`).
pub fn mesh(
    w: &mut impl Write,
    [x, y, z]: [&[f32]; 3],
    normals: &Normals,
    uv: &Refraction,
    indices: &[u32],
) -> std::io::Result<()> {
    let s = Short;
    for i in 0..x.len() {
        writeln!(w, "v {} {} {}", s(x[i]), s(y[i]), s(z[i]))?;
    }
    for i in 0..x.len() {
        let (a, b, c) = (normals.x[i], normals.y[i], normals.z[i]);
        writeln!(w, "vn {} {} {}", s(a), s(b), s(c))?;
    }
    for i in 0..x.len() {
        writeln!(w, "vt {} {}", s(uv.u[i]), s(uv.v[i]))?;
    }
    for t in indices.chunks_exact(3) {
        let (a, b, c) = (t[0] + 1, t[1] + 1, t[2] + 1);
        writeln!(w, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}")?;
    }
    Ok(())
}

/// One OBJ per frame in a directory.
pub struct Sequence {
    dir: PathBuf,
    rest: Rest,
}

impl Sequence {
    /// Creates the directory if needed and checks that a frame can be written there.
    pub fn create(dir: &Path, rest: &Rest) -> std::io::Result<Self> {
        std::fs::create_dir_all(dir).map_err(|e| {
            std::io::Error::new(e.kind(), format!("cannot create {}: {e}", dir.display()))
        })?;
        let first = frame_path(dir, 1);
        create_io(&first)?;
        Ok(Self {
            dir: dir.to_path_buf(),
            rest: Rest {
                indices: rest.indices.clone(),
                cols: rest.cols,
                rows: rest.rows,
            },
        })
    }
}

/// `DIR/water_0001.obj` for frame 1.
pub fn frame_path(dir: &Path, k: usize) -> PathBuf {
    dir.join(format!("water_{k:04}.obj"))
}

impl Writer for Sequence {
    fn frame(&mut self, k: usize, frame: &Frame) -> std::io::Result<()> {
        let title = format!("springwater bake: frame {k}");
        write(&frame_path(&self.dir, k), &title, &self.rest, frame)
    }

    fn finish(self: Box<Self>) -> std::io::Result<()> {
        Ok(())
    }
}
