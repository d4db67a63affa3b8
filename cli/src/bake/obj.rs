//! Wavefront OBJ frames: the rest mesh beside a point cache, and the `water_0001.obj` …
//! sequence written into a directory. One `v`, `vn` and `vt` (refraction UV) per node,
//! row-major, the triangles as `f a/a/a b/b/b c/c/c` (1-based, counter-clockwise seen
//! from +y), as `springwater export` writes them.

use super::{Frame, Rest, Writer};
use crate::args::Short;
use crate::output::{named, Pending};
use springwater::mesh::Normals;
use springwater::refraction::Refraction;
use std::io::Write;
use std::path::Path;

/// The start of the first line of the rest mesh beside a point cache: a bake may replace
/// an OBJ that begins so, and no other.
pub const REST_TITLE: &str = "springwater bake: the rest mesh of";

/// Writes `frame` with `rest`'s triangles to `file` (`path` names it in errors).
pub fn write(
    file: std::fs::File,
    path: &Path,
    title: &str,
    rest: &Rest,
    frame: &Frame,
) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(file);
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
    frames: crate::output::Sequence,
    rest: Rest,
}

impl Sequence {
    pub fn new(frames: crate::output::Sequence, rest: &Rest) -> Self {
        Self {
            frames,
            rest: Rest {
                indices: rest.indices.clone(),
                cols: rest.cols,
                rows: rest.rows,
            },
        }
    }
}

impl Writer for Sequence {
    fn frame(&mut self, k: usize, frame: &Frame) -> std::io::Result<()> {
        let title = format!("springwater bake: frame {k}");
        let shown = self.frames.path().join(self.frames.name(k));
        let file =
            std::fs::File::create(self.frames.frame_path(k)).map_err(|e| named(&shown, e))?;
        write(file, &shown, &title, &self.rest, frame)
    }

    fn finish(self: Box<Self>) -> std::io::Result<Vec<Pending>> {
        Ok(vec![Pending::Frames(self.frames)])
    }
}
