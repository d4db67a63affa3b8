//! Render-side stages that read the simulation through a borrowed [`MeshView`].

mod standin;
mod view;

pub use standin::{compute_normals, LodMesh, LodParams, Normals};
pub use view::MeshView;
