//! `springwater export`: run the steps, then write the frame a renderer would draw as a
//! Wavefront OBJ (`cli/README.md`): one `v`, `vn` and `vt` (refraction UV) per node, row-major,
//! and the LOD triangles for the eye as `f a/a/a b/b/b c/c/c` (1-based, counter-clockwise
//! seen from +y).

use crate::args::{
    lib_error, list, next_flag, string, unexpected, value, CliResult, Flag, ModelArgs,
};
use crate::output::Output;
use crate::start::run_steps_until;
use lexopt::Parser;
use springwater::mesh::{compute_normals, LodMesh, LodParams, Normals};
use springwater::refraction::{refract, Refraction, RefractionParams};
use springwater::Surface;
use std::io::Write;
use std::path::PathBuf;

pub fn run(p: &mut Parser) -> CliResult<()> {
    let mut model = ModelArgs::default();
    let mut eye: Option<[f32; 3]> = None;
    let mut depth: Option<f32> = None;
    let mut optics = RefractionParams::default();
    let mut lod = LodParams::default();
    let mut obj: Option<PathBuf> = None;
    while let Some(arg) = next_flag(p)? {
        if model.parse_flag(&arg, p)? {
            continue;
        }
        match arg {
            Flag::Long(l) => match l.as_str() {
                "eye" => eye = Some(list(&string(p, "--eye")?, "--eye X,Y,Z")?),
                "depth" => depth = Some(value(p, "--depth")?),
                "ior" => optics.ior = value(p, "--ior")?,
                "obj" => obj = Some(string(p, "--obj")?.into()),
                "patch-cells" => lod.patch_cells = value(p, "--patch-cells")?,
                "first-range" => lod.first_range = value(p, "--first-range")?,
                "levels" => lod.levels = value(p, "--levels")?,
                _ => return Err(unexpected(Flag::Long(l), "export")),
            },
            other => return Err(unexpected(other, "export")),
        }
    }
    let eye = glam::Vec3::from(
        eye.ok_or("export: --eye X,Y,Z is required (the camera in the water's space)")?,
    );
    optics.depth =
        depth.ok_or("export: --depth D is required (the bottom's depth below the rest surface)")?;
    let obj = obj.ok_or("export: --obj FILE is required")?;
    optics
        .validate()
        .map_err(|e| format!("export: {}", lib_error(e)))?;
    let mut lod = LodMesh::new(lod).map_err(|e| format!("export: {}", lib_error(e)))?;
    let mut surface = model.surface()?;
    // Open the output first: an unwritable path fails before any work is done.
    let out = Output::create(&obj, "--obj")?;
    let hidden = indicatif::ProgressBar::hidden();
    model.with_threads(|| run_steps_until(&mut surface, model.steps, &hidden))??;

    let view = surface.mesh_view();
    let mut normals = Normals::new();
    compute_normals(&view, &mut normals);
    let mut uv = Refraction::default();
    refract(&view, &normals, eye, &optics, &mut uv).map_err(|e| format!("export: {e}"))?;
    lod.update(&view, eye);
    let fail = |e: std::io::Error| format!("cannot write {}: {e}", obj.display());
    write_obj(
        &surface,
        &normals,
        &uv,
        &lod,
        eye,
        &optics,
        out.file().map_err(fail)?,
    )
    .map_err(fail)?;
    out.commit().map_err(|e| e.to_string())?;
    say!(
        "wrote {}: {} vertices, {} triangles (full grid: {})",
        obj.display(),
        surface.node_count(),
        lod.triangle_count(),
        2 * (surface.grid().cols - 1) * (surface.grid().rows - 1)
    );
    Ok(())
}

fn write_obj(
    s: &Surface,
    normals: &Normals,
    uv: &Refraction,
    lod: &LodMesh,
    eye: glam::Vec3,
    optics: &RefractionParams,
    file: std::fs::File,
) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(file);
    let g = s.grid();
    writeln!(
        w,
        "# springwater export: {}x{} nodes after {} steps, eye {},{},{}, depth {}, ior {}",
        g.cols,
        g.rows,
        s.steps(),
        eye.x,
        eye.y,
        eye.z,
        optics.depth,
        optics.ior
    )?;
    let indices = lod.indices();
    crate::bake::obj::mesh(&mut w, s.positions(), normals, uv, indices)?;
    w.flush()
}
