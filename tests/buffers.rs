//! Renderer-ready buffers: the interleaved positions, normals, texture coordinates and
//! packed vertices equal the structure-of-arrays slices bit for bit, and a buffer of the
//! wrong length is refused with nothing written.

use glam::Vec3;
use springwater::buffers::{interleave, Vertex, VertexBuffers};
use springwater::mesh::Normals;
use springwater::refraction::{normals_and_refraction, Refraction, RefractionParams};
use springwater::{Error, Params, Surface};

/// A surface with waves, its normals and refraction coordinates.
fn scene(cols: usize, rows: usize) -> (Surface, Normals, Refraction) {
    let mut s = Surface::new(Params::with_size(cols, rows)).unwrap();
    s.drop_at(cols as f32 / 3.0, rows as f32 / 2.0, 1.0, 3.0)
        .unwrap();
    s.drop_at(cols as f32 / 1.5, rows as f32 / 3.0, -0.7, 2.0)
        .unwrap();
    s.step_n(7).unwrap();
    let (mut normals, mut uv) = (Normals::new(), Refraction::default());
    let eye = Vec3::new(cols as f32 / 2.0, 15.0, -8.0);
    normals_and_refraction(
        &s.mesh_view(),
        eye,
        &RefractionParams::default(),
        &mut normals,
        &mut uv,
    )
    .unwrap();
    (s, normals, uv)
}

fn bits3(v: &[[f32; 3]]) -> Vec<[u32; 3]> {
    v.iter().map(|a| a.map(f32::to_bits)).collect()
}

fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|a| a.to_bits()).collect()
}

#[test]
fn interleaved_buffers_equal_the_soa_slices_bitwise() {
    // Small (one block), and large enough to be split over threads, with a ragged end.
    for (cols, rows) in [(9, 7), (131, 67)] {
        let (s, normals, uv) = scene(cols, rows);
        let view = s.mesh_view();
        let n = s.node_count();
        let mut positions = vec![[f32::NAN; 3]; n];
        let mut normal_buf = vec![[f32::NAN; 3]; n];
        let mut uvs = vec![[f32::NAN; 2]; n];
        let mut vertices = vec![
            Vertex {
                position: [f32::NAN; 3],
                normal: [f32::NAN; 3],
                uv: [f32::NAN; 2],
            };
            n
        ];
        interleave(
            &view,
            &normals,
            &uv,
            VertexBuffers {
                positions: Some(&mut positions),
                normals: Some(&mut normal_buf),
                uvs: Some(&mut uvs),
                vertices: Some(&mut vertices),
            },
        )
        .unwrap();
        let [x, y, z] = s.positions();
        let split3 = |v: &[[f32; 3]], k: usize| v.iter().map(|a| a[k]).collect::<Vec<_>>();
        for (k, c) in [x, y, z].into_iter().enumerate() {
            assert_eq!(bits(&split3(&positions, k)), bits(c));
            let from_vertices: Vec<f32> = vertices.iter().map(|v| v.position[k]).collect();
            assert_eq!(bits(&from_vertices), bits(c));
        }
        for (k, c) in [&normals.x, &normals.y, &normals.z].into_iter().enumerate() {
            assert_eq!(bits(&split3(&normal_buf, k)), bits(c));
            let from_vertices: Vec<f32> = vertices.iter().map(|v| v.normal[k]).collect();
            assert_eq!(bits(&from_vertices), bits(c));
        }
        for (k, c) in [&uv.u, &uv.v].into_iter().enumerate() {
            let from_uvs: Vec<f32> = uvs.iter().map(|a| a[k]).collect();
            assert_eq!(bits(&from_uvs), bits(c));
            let from_vertices: Vec<f32> = vertices.iter().map(|v| v.uv[k]).collect();
            assert_eq!(bits(&from_vertices), bits(c));
        }
        // The positions-only path agrees too.
        let mut only = vec![[0.0f32; 3]; n];
        view.write_positions(&mut only).unwrap();
        assert_eq!(bits3(&only), bits3(&positions));
    }
}

#[test]
fn a_vertex_is_32_bytes_of_plain_floats() {
    assert_eq!(std::mem::size_of::<Vertex>(), 32);
    assert_eq!(std::mem::align_of::<Vertex>(), 4);
    let v = Vertex {
        position: [1.0, 2.0, 3.0],
        normal: [4.0, 5.0, 6.0],
        uv: [7.0, 8.0],
    };
    let floats: &[f32] = bytemuck::cast_slice(std::slice::from_ref(&v));
    assert_eq!(floats, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]);
}

#[test]
fn wrong_lengths_are_refused_and_nothing_is_written() {
    let (s, normals, uv) = scene(12, 10);
    let view = s.mesh_view();
    let n = s.node_count();
    let mut good = vec![[-1.0f32; 3]; n];
    let mut short = vec![[-1.0f32; 2]; n - 1];
    let err = interleave(
        &view,
        &normals,
        &uv,
        VertexBuffers {
            positions: Some(&mut good),
            uvs: Some(&mut short),
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(
        matches!(err, Error::LengthMismatch { got, expected, .. } if got == n - 1 && expected == n),
        "{err}"
    );
    assert!(
        good.iter().all(|p| *p == [-1.0; 3]),
        "the good buffer was written"
    );
    let mut long = vec![Vertex::default(); n + 1];
    assert!(interleave(
        &view,
        &normals,
        &uv,
        VertexBuffers {
            vertices: Some(&mut long),
            ..Default::default()
        }
    )
    .is_err());
    assert!(long.iter().all(|v| *v == Vertex::default()));
    // Stage outputs of another grid are refused too.
    let (_, other_normals, other_uv) = scene(5, 5);
    let mut vertices = vec![Vertex::default(); n];
    for (nr, u) in [(&other_normals, &uv), (&normals, &other_uv)] {
        let out = VertexBuffers {
            vertices: Some(&mut vertices),
            ..Default::default()
        };
        assert!(interleave(&view, nr, u, out).is_err());
    }
    assert!(vertices.iter().all(|v| *v == Vertex::default()));
    assert!(view.write_positions(&mut vec![[0.0; 3]; n + 3]).is_err());
}

/// `fill_frame` (the stages and the buffers in one pass, through per-thread scratch) gives
/// the bits of `normals_and_refraction` followed by `interleave`, on grids whose rows split
/// into its blocks unevenly (one row longer than a block, blocks of hundreds of rows, rows
/// longer than the scratch a thread keeps);
/// bad input is refused with nothing written.
#[test]
fn fill_frame_equals_the_stages_then_interleave() {
    use springwater::buffers::fill_frame;
    let shapes = [
        (9, 7),
        (67, 45),
        (130, 70),
        (1031, 9),
        (3, 2000),
        (16_390, 3),
    ];
    for (cols, rows) in shapes {
        let (s, normals, uv) = scene(cols, rows);
        let n = s.node_count();
        let view = s.mesh_view();
        let eye = Vec3::new(cols as f32 / 2.0, 15.0, -8.0);
        let params = RefractionParams::default();
        let mut expected = vec![Vertex::default(); n];
        let mut expected_uv = vec![[0.0f32; 2]; n];
        let mut expected_normals = vec![[0.0f32; 3]; n];
        interleave(
            &view,
            &normals,
            &uv,
            VertexBuffers {
                vertices: Some(&mut expected),
                uvs: Some(&mut expected_uv),
                normals: Some(&mut expected_normals),
                ..Default::default()
            },
        )
        .unwrap();
        let mut got = vec![Vertex::default(); n];
        let mut got_uv = vec![[0.0f32; 2]; n];
        let mut got_normals = vec![[0.0f32; 3]; n];
        let mut got_positions = vec![[0.0f32; 3]; n];
        let out = VertexBuffers {
            vertices: Some(&mut got),
            uvs: Some(&mut got_uv),
            normals: Some(&mut got_normals),
            positions: Some(&mut got_positions),
        };
        fill_frame(&view, eye, &params, out).unwrap();
        let as_bits = |v: &[Vertex]| bits(bytemuck::cast_slice(v));
        assert!(
            as_bits(&got) == as_bits(&expected),
            "{cols}x{rows}: vertices"
        );
        let flat = |v: &[[f32; 3]]| bits(v.as_flattened());
        assert!(got_uv == expected_uv, "{cols}x{rows}: uvs");
        assert!(
            flat(&got_normals) == flat(&expected_normals),
            "{cols}x{rows}: normals"
        );
        let positions: Vec<[f32; 3]> = (0..n).map(|i| view.position(i).to_array()).collect();
        assert!(
            flat(&got_positions) == flat(&positions),
            "{cols}x{rows}: positions"
        );

        // A short buffer or a bad eye: an error, and nothing written anywhere.
        let mut short = vec![Vertex::default(); n - 1];
        let mut fresh = vec![Vertex::default(); n];
        let out = VertexBuffers {
            vertices: Some(&mut short),
            ..Default::default()
        };
        let e = fill_frame(&view, eye, &params, out).unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }), "{e}");
        let out = VertexBuffers {
            vertices: Some(&mut fresh),
            ..Default::default()
        };
        let bad_eye = Vec3::new(f32::NAN, 1.0, 1.0);
        assert!(fill_frame(&view, bad_eye, &params, out).is_err());
        assert!(short.iter().chain(&fresh).all(|v| *v == Vertex::default()));
    }
}
