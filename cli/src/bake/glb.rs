//! glTF 2.0 binary (`.glb`): one mesh whose base is the rest frame (positions, normals,
//! refraction UVs as `TEXCOORD_0`, the triangles), one morph target per frame (the
//! position and normal offsets from the rest frame) and an animation that weighs frame k's
//! target 1 at time k/fps and the others 0; each floater is a node with a translation
//! and a rotation animation on the same clock (its centre of mass and its orientation, a
//! unit quaternion `[x, y, z, w]` from the body's frame to the water's).
//!
//! **Interpolation: LINEAR.** At the keys the two are the same (one weight is 1); between
//! keys, linear weights blend two neighbouring frames' offsets, which is the linear
//! interpolation of the positions, so the water moves smoothly when a game engine or a
//! Blender scene plays at another rate than the bake's; STEP would hold each frame and
//! stutter. The weights output (frames+1 keys of `frames` weights each, all 0 but one)
//! is a sparse accessor, so it costs 8 bytes a frame instead of growing as frames².
//! Rotations interpolate by spherical linear interpolation (glTF's LINEAR for rotations),
//! and each key is the quaternion, or its negative (the same rotation), on the side of the
//! key before, so no importer turns a body the long way round between two keys.
//!
//! **Streaming.** A GLB puts its JSON chunk (which needs every accessor's length and
//! `min`/`max`) before its binary chunk, so the binary data is written frame by frame to
//! a scratch file beside the output (removed at the end), and at the end the header and
//! JSON are written and the binary data copied after them: memory stays the size of one
//! frame whatever `--frames` is, at the cost of writing the data twice. (Reserving room
//! for the JSON at the front and seeking back would avoid the copy, but the JSON's length
//! grows with the frames and the floaters; the copy keeps the writer simple.)
//!
//! **The JSON is written by hand.** The document has one fixed shape (a scene, nodes, one
//! mesh, one animation, accessors and buffer views); `gltf-json` would bring serde,
//! serde_json and two proc-macro crates to the command line (it has no serde today) for
//! a few dozen lines of `format!`. Floats are printed in Rust's shortest round-trip form,
//! so `min`/`max` match the data exactly, as the Khronos validator checks.

use super::{Frame, Rest, Writer};
use crate::args::CliResult;
use crate::output::{named, Output, Pending};
use springwater::Params;
use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, Seek, Write};
use std::path::{Path, PathBuf};

const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Refuses, before any step, a bake whose `.glb` would pass the format's 32-bit lengths:
/// the bytes counted at full detail (the most triangles an eye's LOD can have).
pub fn check_size(path: &Path, p: &Params, frames: usize, floaters: usize) -> CliResult<()> {
    let n = (p.cols * p.rows) as u64;
    let triangles = 2 * (p.cols as u64 - 1) * (p.rows as u64 - 1);
    let frames = frames as u64;
    // Per floater and key: a translation (12 bytes) and a rotation (16).
    let bytes =
        n * 32 + triangles * 12 + frames * (n * 24 + 12 + 28 * floaters as u64) + frames * 200;
    let limit = u32::MAX as u64 - (1 << 20);
    if bytes > limit {
        let per_frame = n * 24 + 12 + 28 * floaters as u64 + 200;
        let most = limit.saturating_sub(n * 32 + triangles * 12) / per_frame;
        let fewer = if most == 0 {
            "not one frame of this grid fits; use a smaller grid".to_owned()
        } else {
            format!(
                "bake at most {} of this grid, or a smaller grid",
                crate::args::count(most, "frame")
            )
        };
        return Err(format!(
            "--out {}: a .glb holds at most 4 GiB and this bake needs about {:.1} GiB; \
             {fewer}, or write .pc2 or .mdd",
            path.display(),
            bytes as f64 / (1u64 << 30) as f64,
        ));
    }
    Ok(())
}

pub struct Glb {
    path: PathBuf,
    out: Output,
    part_path: PathBuf,
    /// The scratch file (removed when dropped) and a buffered handle on it.
    _scratch: Output,
    part: BufWriter<File>,
    /// Bytes written to `part`.
    offset: u64,
    frames: usize,
    fps: f32,
    /// The rest frame, which every target is an offset from.
    base: [Vec<f32>; 6],
    /// Buffer views (JSON objects), in order.
    views: Vec<String>,
    /// Accessors (JSON objects), in order.
    accessors: Vec<String>,
    /// Per frame, its target's position and normal accessors.
    targets: Vec<[usize; 2]>,
    /// Per floater, its centre at every key.
    tracks: Vec<Vec<[f32; 3]>>,
    /// Per floater, its orientation at every key, each on the side of the one before.
    turns: Vec<Vec<[f32; 4]>>,
}

impl Glb {
    pub fn create(
        out: Output,
        rest: &Rest,
        first: &Frame,
        frames: usize,
        fps: f32,
    ) -> std::io::Result<Self> {
        let n = rest.cols * rest.rows;
        let path = out.path().to_path_buf();
        let scratch = Output::scratch(&path)?;
        let part_path = scratch.path().to_path_buf();
        let part = BufWriter::new(scratch.file().map_err(|e| named(&path, e))?);
        let [x, y, z] = first.positions;
        let normals = first.normals;
        let mut glb = Self {
            path,
            out,
            part_path,
            _scratch: scratch,
            part,
            offset: 0,
            frames,
            fps,
            base: [
                x[..n].to_vec(),
                y[..n].to_vec(),
                z[..n].to_vec(),
                normals.x[..n].to_vec(),
                normals.y[..n].to_vec(),
                normals.z[..n].to_vec(),
            ],
            views: Vec::new(),
            accessors: Vec::new(),
            targets: Vec::with_capacity(frames),
            tracks: first.floaters.iter().map(|&c| vec![c]).collect(),
            turns: first.orientations.iter().map(|&q| vec![q]).collect(),
        };
        let result = (|| {
            let [x, y, z, nx, ny, nz] = glb.base.clone();
            glb.vec3s(n, |i| [x[i], y[i], z[i]], true)?;
            glb.vec3s(n, |i| [nx[i], ny[i], nz[i]], false)?;
            let (u, v) = (&first.uv.u, &first.uv.v);
            let view = glb.view(n as u64 * 8, Some(ARRAY_BUFFER), |w| {
                for i in 0..n {
                    w.write_all(&u[i].to_le_bytes())?;
                    w.write_all(&v[i].to_le_bytes())?;
                }
                Ok(())
            })?;
            glb.accessor(format!(
                r#"{{"bufferView":{view},"componentType":{FLOAT},"count":{n},"type":"VEC2"}}"#
            ));
            let indices = &rest.indices;
            let view = glb.view(indices.len() as u64 * 4, Some(ELEMENT_ARRAY_BUFFER), |w| {
                indices
                    .iter()
                    .try_for_each(|i| w.write_all(&i.to_le_bytes()))
            })?;
            glb.accessor(format!(
                r#"{{"bufferView":{view},"componentType":{UNSIGNED_INT},"count":{},"type":"SCALAR"}}"#,
                indices.len()
            ));
            Ok(())
        })();
        result.map_err(|e| named(&glb.part_path, e))?;
        Ok(glb)
    }

    /// Appends a buffer view of `length` bytes that `write` fills; returns its index.
    fn view(
        &mut self,
        length: u64,
        target: Option<u32>,
        write: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
    ) -> std::io::Result<usize> {
        write(&mut self.part)?;
        let mut json = format!(
            r#"{{"buffer":0,"byteOffset":{},"byteLength":{length}"#,
            self.offset
        );
        if let Some(t) = target {
            let _ = write!(json, r#","target":{t}"#);
        }
        json.push('}');
        self.offset += length;
        self.views.push(json);
        Ok(self.views.len() - 1)
    }

    fn accessor(&mut self, json: String) -> usize {
        self.accessors.push(json);
        self.accessors.len() - 1
    }

    /// Writes `n` float triples as a vertex attribute accessor (with `min`/`max` when
    /// `bounds`, as POSITION needs); returns the accessor's index.
    fn vec3s(
        &mut self,
        n: usize,
        at: impl Fn(usize) -> [f32; 3],
        bounds: bool,
    ) -> std::io::Result<usize> {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        let view = self.view(n as u64 * 12, Some(ARRAY_BUFFER), |w| {
            for i in 0..n {
                let v = at(i);
                for a in 0..3 {
                    // -0.0 is written as 0.0: the bounds then print as the data reads.
                    let c = v[a] + 0.0;
                    lo[a] = lo[a].min(c);
                    hi[a] = hi[a].max(c);
                    w.write_all(&c.to_le_bytes())?;
                }
            }
            Ok(())
        })?;
        let mut json =
            format!(r#"{{"bufferView":{view},"componentType":{FLOAT},"count":{n},"type":"VEC3""#);
        if bounds {
            let _ = write!(
                json,
                r#","min":[{},{},{}],"max":[{},{},{}]"#,
                lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
            );
        }
        json.push('}');
        Ok(self.accessor(json))
    }

    /// The tail of the binary chunk (times, weights, floater paths) and the JSON.
    fn write_animation(&mut self) -> std::io::Result<String> {
        let frames = self.frames;
        let keys = frames + 1;
        let fps = self.fps;
        let time = |k: usize| k as f32 / fps;
        let view = self.view(keys as u64 * 4, None, |w| {
            (0..keys).try_for_each(|k| w.write_all(&time(k).to_le_bytes()))
        })?;
        let times = self.accessor(format!(
            r#"{{"bufferView":{view},"componentType":{FLOAT},"count":{keys},"type":"SCALAR","min":[0],"max":[{}]}}"#,
            time(frames)
        ));
        // Key k (from 1) weighs target k − 1 (frame k) 1: element k·frames + k − 1.
        let indices = self.view(frames as u64 * 4, None, |w| {
            (1..=frames).try_for_each(|k| w.write_all(&((k * frames + k - 1) as u32).to_le_bytes()))
        })?;
        let ones = self.view(frames as u64 * 4, None, |w| {
            (0..frames).try_for_each(|_| w.write_all(&1f32.to_le_bytes()))
        })?;
        let weights = self.accessor(format!(
            r#"{{"componentType":{FLOAT},"count":{},"type":"SCALAR","sparse":{{"count":{frames},"indices":{{"bufferView":{indices},"componentType":{UNSIGNED_INT}}},"values":{{"bufferView":{ones}}}}}}}"#,
            keys * frames
        ));
        let tracks = std::mem::take(&mut self.tracks);
        let turns = std::mem::take(&mut self.turns);
        // Per floater, its translation and rotation accessors.
        let mut paths = Vec::new();
        for (track, turn) in tracks.iter().zip(&turns) {
            let view = self.view(keys as u64 * 12, None, |w| {
                track
                    .iter()
                    .flatten()
                    .try_for_each(|c| w.write_all(&c.to_le_bytes()))
            })?;
            let moves = self.accessor(format!(
                r#"{{"bufferView":{view},"componentType":{FLOAT},"count":{keys},"type":"VEC3"}}"#
            ));
            let view = self.view(keys as u64 * 16, None, |w| {
                turn.iter()
                    .flatten()
                    .try_for_each(|c| w.write_all(&c.to_le_bytes()))
            })?;
            let rotations = self.accessor(format!(
                r#"{{"bufferView":{view},"componentType":{FLOAT},"count":{keys},"type":"VEC4"}}"#
            ));
            paths.push([moves, rotations]);
        }

        let list = |items: &mut dyn Iterator<Item = String>| items.collect::<Vec<_>>().join(",");
        let nodes = 1 + tracks.len();
        let mut node_json = vec![r#"{"name":"water","mesh":0}"#.to_owned()];
        for (k, (track, turn)) in tracks.iter().zip(&turns).enumerate() {
            let [x, y, z] = track[0];
            let [qx, qy, qz, qw] = turn[0];
            node_json.push(format!(
                r#"{{"name":"floater {k}","translation":[{x},{y},{z}],"rotation":[{qx},{qy},{qz},{qw}]}}"#
            ));
        }
        let targets = list(
            &mut self
                .targets
                .iter()
                .map(|[p, n]| format!(r#"{{"POSITION":{p},"NORMAL":{n}}}"#)),
        );
        let zeros = list(&mut (0..frames).map(|_| "0".to_owned()));
        let names = list(&mut (1..=frames).map(|k| format!(r#""frame {k}""#)));
        let mut samplers = vec![format!(
            r#"{{"input":{times},"output":{weights},"interpolation":"LINEAR"}}"#
        )];
        let mut channels = vec![r#"{"sampler":0,"target":{"node":0,"path":"weights"}}"#.to_owned()];
        for (k, outputs) in paths.iter().enumerate() {
            for (output, path) in outputs.iter().zip(["translation", "rotation"]) {
                channels.push(format!(
                    r#"{{"sampler":{},"target":{{"node":{},"path":"{path}"}}}}"#,
                    samplers.len(),
                    k + 1
                ));
                samplers.push(format!(
                    r#"{{"input":{times},"output":{output},"interpolation":"LINEAR"}}"#
                ));
            }
        }
        Ok(format!(
            concat!(
                r#"{{"asset":{{"version":"2.0","generator":"springwater bake {version}"}},"#,
                r#""scene":0,"scenes":[{{"name":"water","nodes":[{scene}]}}],"#,
                r#""nodes":[{nodes}],"#,
                r#""meshes":[{{"name":"water","primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3,"mode":4,"targets":[{targets}]}}],"weights":[{zeros}],"extras":{{"targetNames":[{names}]}}}}],"#,
                r#""animations":[{{"name":"water","samplers":[{samplers}],"channels":[{channels}]}}],"#,
                r#""accessors":[{accessors}],"bufferViews":[{views}],"buffers":[{{"byteLength":{length}}}]}}"#
            ),
            version = env!("CARGO_PKG_VERSION"),
            scene = list(&mut (0..nodes).map(|k| k.to_string())),
            nodes = node_json.join(","),
            targets = targets,
            zeros = zeros,
            names = names,
            samplers = samplers.join(","),
            channels = channels.join(","),
            accessors = self.accessors.join(","),
            views = self.views.join(","),
            length = self.offset,
        ))
    }
}

/// `q`, or `−q` (the same rotation) when that is nearer `before`: consecutive keys on the
/// same side of the quaternion sphere, so interpolating between them takes the short way.
fn same_side(before: [f32; 4], q: [f32; 4]) -> [f32; 4] {
    let dot: f32 = before.iter().zip(&q).map(|(a, b)| a * b).sum();
    if dot < 0.0 {
        q.map(|c| -c)
    } else {
        q
    }
}

impl Writer for Glb {
    fn frame(&mut self, _k: usize, frame: &Frame) -> std::io::Result<()> {
        let n = self.base[0].len();
        let [x, y, z] = frame.positions;
        let normals = frame.normals;
        let base = std::mem::take(&mut self.base);
        let result = (|| {
            let [bx, by, bz, bnx, bny, bnz] = &base;
            let p = self.vec3s(n, |i| [x[i] - bx[i], y[i] - by[i], z[i] - bz[i]], true)?;
            let q = self.vec3s(
                n,
                |i| {
                    [
                        normals.x[i] - bnx[i],
                        normals.y[i] - bny[i],
                        normals.z[i] - bnz[i],
                    ]
                },
                false,
            )?;
            self.targets.push([p, q]);
            Ok(())
        })();
        self.base = base;
        for (track, &c) in self.tracks.iter_mut().zip(frame.floaters) {
            track.push(c);
        }
        for (turn, &q) in self.turns.iter_mut().zip(frame.orientations) {
            turn.push(same_side(*turn.last().unwrap_or(&q), q));
        }
        result.map_err(|e| named(&self.part_path, e))
    }

    fn finish(mut self: Box<Self>) -> std::io::Result<Vec<Pending>> {
        let json = self
            .write_animation()
            .and_then(|json| self.part.flush().map(|()| json))
            .map_err(|e| named(&self.part_path, e))?;
        let result = (|| {
            let mut json = json.into_bytes();
            while json.len() % 4 != 0 {
                json.push(b' ');
            }
            let bin = self.offset; // a multiple of 4: every element is 4 bytes
            let total = 12 + 8 + json.len() as u64 + 8 + bin;
            let total = u32::try_from(total).map_err(|_| {
                std::io::Error::new(std::io::ErrorKind::InvalidData, "larger than 4 GiB")
            })?;
            let mut w = BufWriter::new(self.out.file()?);
            w.write_all(b"glTF")?;
            w.write_all(&2u32.to_le_bytes())?;
            w.write_all(&total.to_le_bytes())?;
            w.write_all(&(json.len() as u32).to_le_bytes())?;
            w.write_all(b"JSON")?;
            w.write_all(&json)?;
            w.write_all(&(bin as u32).to_le_bytes())?;
            w.write_all(b"BIN\0")?;
            let mut part = self.part.get_ref();
            part.rewind()?;
            std::io::copy(&mut part, &mut w)?;
            w.flush()
        })();
        result.map_err(|e| named(&self.path, e))?;
        Ok(vec![Pending::File(self.out)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::commit_all;
    use glam::{Quat, Vec3};
    use springwater::mesh::Normals;
    use springwater::refraction::Refraction;

    /// A JSON value, read just far enough to follow a glTF's indices.
    #[derive(Debug, Clone, PartialEq)]
    enum Json {
        Number(f64),
        Text(String),
        List(Vec<Json>),
        Object(Vec<(String, Json)>),
        Other,
    }

    impl Json {
        fn get(&self, key: &str) -> &Json {
            match self {
                Json::Object(fields) => fields
                    .iter()
                    .find(|(k, _)| k == key)
                    .map(|(_, v)| v)
                    .unwrap_or_else(|| panic!("no {key} in {self:?}")),
                _ => panic!("{self:?} is not an object"),
            }
        }

        fn at(&self, i: usize) -> &Json {
            match self {
                Json::List(items) => &items[i],
                _ => panic!("{self:?} is not a list"),
            }
        }

        fn list(&self) -> &[Json] {
            match self {
                Json::List(items) => items,
                _ => panic!("{self:?} is not a list"),
            }
        }

        fn number(&self) -> f64 {
            match self {
                Json::Number(n) => *n,
                _ => panic!("{self:?} is not a number"),
            }
        }

        fn index(&self) -> usize {
            self.number() as usize
        }
    }

    /// Parses the JSON at the start of `s`; returns it and the rest of `s`.
    fn parse(s: &str) -> (Json, &str) {
        fn rest(s: &str, n: usize) -> &str {
            s[n..].trim_start()
        }
        let s = s.trim_start();
        match s.as_bytes()[0] {
            b'{' | b'[' => {
                let object = s.starts_with('{');
                let (mut s, mut fields, mut items) = (rest(s, 1), Vec::new(), Vec::new());
                while !s.starts_with(['}', ']']) {
                    if object {
                        let (Json::Text(key), after) = parse(s) else {
                            panic!("a key expected at {s:.20}")
                        };
                        let (value, after) = parse(rest(after, 1));
                        fields.push((key, value));
                        s = after;
                    } else {
                        let (value, after) = parse(s);
                        items.push(value);
                        s = after;
                    }
                    s = s.strip_prefix(',').unwrap_or(s).trim_start();
                }
                let value = if object {
                    Json::Object(fields)
                } else {
                    Json::List(items)
                };
                (value, rest(s, 1))
            }
            b'"' => {
                let end = s[1..].find('"').expect("a closed string") + 1;
                (Json::Text(s[1..end].to_owned()), &s[end + 1..])
            }
            b'-' | b'0'..=b'9' => {
                let end = s
                    .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
                    .unwrap_or(s.len());
                (Json::Number(s[..end].parse().unwrap()), &s[end..])
            }
            _ => {
                let end = s.find([',', '}', ']']).unwrap_or(s.len());
                (Json::Other, &s[end..])
            }
        }
    }

    /// Writes a .glb of a 2 × 2 grid and one floater taking `turns` (one orientation per
    /// key, the first the rest frame's) and returns its JSON and binary chunk.
    fn bake(name: &str, turns: &[Quat]) -> (Json, Vec<u8>) {
        let dir = std::env::temp_dir().join(format!("springwater-glb-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        let (xs, ys, zs) = (
            vec![0.0, 1.0, 0.0, 1.0],
            vec![0.0; 4],
            vec![0.0, 0.0, 1.0, 1.0],
        );
        let normals = Normals {
            x: vec![0.0; 4],
            y: vec![1.0; 4],
            z: vec![0.0; 4],
        };
        let uv = Refraction {
            u: xs.clone(),
            v: zs.clone(),
            fresnel: vec![0.0; 4],
        };
        let rest = Rest {
            indices: vec![0, 2, 1, 1, 2, 3],
            cols: 2,
            rows: 2,
        };
        let frame = |k: usize| -> ([[f32; 3]; 1], [[f32; 4]; 1]) {
            ([[0.5, 0.1 * k as f32, 0.5]], [turns[k].to_array()])
        };
        let (c, q) = frame(0);
        let first = Frame {
            positions: [&xs, &ys, &zs],
            normals: &normals,
            uv: &uv,
            floaters: &c,
            orientations: &q,
        };
        let out = Output::create(&path, "--out").unwrap();
        let frames = turns.len() - 1;
        let mut glb = Box::new(Glb::create(out, &rest, &first, frames, 24.0).unwrap());
        for k in 1..=frames {
            let (c, q) = frame(k);
            let f = Frame {
                floaters: &c,
                orientations: &q,
                ..first
            };
            glb.frame(k, &f).unwrap();
        }
        commit_all(glb.finish().unwrap()).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        let json_len = u32_at(12);
        let json = std::str::from_utf8(&bytes[20..20 + json_len]).unwrap();
        let bin = 20 + json_len + 8;
        (parse(json).0, bytes[bin..].to_vec())
    }

    /// The keys of the channel animating `path` of node `node`.
    fn keys(json: &Json, bin: &[u8], node: usize, path: &str) -> Vec<Vec<f32>> {
        let animation = json.get("animations").at(0);
        let channel = animation
            .get("channels")
            .list()
            .iter()
            .find(|c| {
                let t = c.get("target");
                t.get("node").index() == node && t.get("path") == &Json::Text(path.into())
            })
            .unwrap_or_else(|| panic!("no {path} channel for node {node}"));
        let sampler = animation.get("samplers").at(channel.get("sampler").index());
        assert_eq!(sampler.get("interpolation"), &Json::Text("LINEAR".into()));
        let accessor = json.get("accessors").at(sampler.get("output").index());
        let view = json
            .get("bufferViews")
            .at(accessor.get("bufferView").index());
        let width = match accessor.get("type") {
            Json::Text(t) if t == "VEC3" => 3,
            Json::Text(t) if t == "VEC4" => 4,
            other => panic!("{other:?}"),
        };
        let at = view.get("byteOffset").index();
        let count = accessor.get("count").index();
        let floats: Vec<f32> = bin[at..at + count * width * 4]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect();
        floats.chunks_exact(width).map(<[f32]>::to_vec).collect()
    }

    #[test]
    fn a_heeled_body_keeps_its_orientation_in_its_rotation_channel() {
        // Heeled 20° to starboard, then rolling back while it yaws and pitches.
        let heel = |deg: f32| Quat::from_rotation_x(deg.to_radians());
        let turns = [
            heel(20.0),
            heel(12.0) * Quat::from_rotation_y(0.3),
            Quat::from_rotation_z(0.2) * heel(-5.0),
        ];
        let (json, bin) = bake("heeled.glb", &turns);
        let node = json.get("nodes").at(1);
        assert_eq!(node.get("name"), &Json::Text("floater 0".into()));
        let rotation: Vec<f32> = node
            .get("rotation")
            .list()
            .iter()
            .map(|c| c.number() as f32)
            .collect();
        assert_eq!(rotation, turns[0].to_array(), "the node rests in its pose");
        let rotations = keys(&json, &bin, 1, "rotation");
        let want: Vec<Vec<f32>> = turns.iter().map(|q| q.to_array().to_vec()).collect();
        assert_eq!(
            rotations, want,
            "one key per frame, the orientation bit for bit"
        );
        let moves = keys(&json, &bin, 1, "translation");
        assert_eq!(moves[2], vec![0.5, 0.2, 0.5], "the translation beside it");
    }

    #[test]
    fn rotation_keys_stay_on_one_side_of_the_quaternion_sphere() {
        // −q is the same turn as q: written as given, the interpolation between keys 1
        // and 2 would go the long way round (nearly a full turn for a body barely moving).
        let q = Quat::from_rotation_x(0.4);
        let flipped = Quat::from_xyzw(-q.x, -q.y, -q.z, -q.w) * Quat::from_rotation_y(0.01);
        let (json, bin) = bake("flipped.glb", &[Quat::IDENTITY, q, flipped]);
        let rotations = keys(&json, &bin, 1, "rotation");
        let dot = |a: &[f32], b: &[f32]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f32>();
        assert!(dot(&rotations[1], &rotations[2]) > 0.99, "{rotations:?}");
        // The same rotation: the key is the negated quaternion.
        let back = Quat::from_slice(&rotations[2]);
        let turned = back * Vec3::Z;
        assert!((turned - flipped * Vec3::Z).length() < 1e-6);
        assert_eq!(rotations[2], flipped.to_array().map(|c| -c).to_vec());
    }
}
