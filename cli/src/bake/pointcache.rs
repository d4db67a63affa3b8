//! The point caches DCC tools read onto a mesh (Blender's Mesh Cache modifier, 3ds Max's
//! Point Cache, Houdini), beside the rest mesh as an OBJ of the same name:
//!
//! - **MDD** (NewTek, big-endian): `i32` frame count, `i32` point count, one `f32` time in
//!   seconds per frame, then per frame every point's `x y z` as `f32`.
//! - **PC2** (little-endian): `"POINTCACHE2\0"`, `i32` version 1, `i32` point count,
//!   `f32` start frame, `f32` sample rate (frames per sample), `i32` sample count, then per
//!   sample every point's `x y z` as `f32`.
//!
//! Both hold frames 1 to N (the first sample is frame 1, PC2's start frame is 1), so that
//! scene frame k shows frame k with the Mesh Cache modifier's `frame_start` at 1; the OBJ
//! is frame 0, the state before the first frame.

use super::{obj, Frame, Rest, Writer};
use crate::output::{named, Output, Pending};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;

pub struct PointCache {
    path: PathBuf,
    out: Output,
    rest: Output,
    file: BufWriter<File>,
    big_endian: bool,
    points: usize,
}

impl PointCache {
    /// Writes the rest OBJ and the cache's header; `mdd` picks MDD over PC2.
    pub fn create(
        out: Output,
        rest_obj: Output,
        mdd: bool,
        rest: &Rest,
        first: &Frame,
        frames: usize,
        fps: f32,
    ) -> std::io::Result<Self> {
        let points = rest.cols * rest.rows;
        let too_many = || {
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "a point cache counts frames and points in 32 bits: too many",
            )
        };
        let count = i32::try_from(frames).map_err(|_| too_many())?;
        let n = i32::try_from(points).map_err(|_| too_many())?;
        let path = out.path().to_path_buf();
        let mut file = BufWriter::new(out.file().map_err(|e| named(&path, e))?);
        let title = format!(
            "{} {}, frame 0",
            obj::REST_TITLE,
            path.file_name().unwrap_or_default().to_string_lossy()
        );
        // A full-detail mesh, whatever the eye: every node is used, so importers keep
        // every vertex, in order.
        let obj_file = rest_obj.file().map_err(|e| named(rest_obj.path(), e))?;
        obj::write(obj_file, rest_obj.path(), &title, rest, first)?;
        let header = (|| {
            if mdd {
                file.write_all(&count.to_be_bytes())?;
                file.write_all(&n.to_be_bytes())?;
                for k in 1..=frames {
                    file.write_all(&(k as f32 / fps).to_be_bytes())?;
                }
            } else {
                file.write_all(b"POINTCACHE2\0")?;
                file.write_all(&1i32.to_le_bytes())?;
                file.write_all(&n.to_le_bytes())?;
                file.write_all(&1f32.to_le_bytes())?;
                file.write_all(&1f32.to_le_bytes())?;
                file.write_all(&count.to_le_bytes())?;
            }
            Ok(())
        })();
        header.map_err(|e| named(&path, e))?;
        Ok(Self {
            path,
            out,
            rest: rest_obj,
            file,
            big_endian: mdd,
            points,
        })
    }
}

impl Writer for PointCache {
    fn frame(&mut self, _k: usize, frame: &Frame) -> std::io::Result<()> {
        let [x, y, z] = frame.positions;
        let result = (|| {
            for i in 0..self.points {
                for v in [x[i], y[i], z[i]] {
                    let bytes = if self.big_endian {
                        v.to_be_bytes()
                    } else {
                        v.to_le_bytes()
                    };
                    self.file.write_all(&bytes)?;
                }
            }
            Ok(())
        })();
        result.map_err(|e| named(&self.path, e))
    }

    fn finish(mut self: Box<Self>) -> std::io::Result<Vec<Pending>> {
        self.file.flush().map_err(|e| named(&self.path, e))?;
        Ok(vec![Pending::File(self.rest), Pending::File(self.out)])
    }
}
