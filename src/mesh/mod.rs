//! Render-side stages that read the simulation through a borrowed [`MeshView`].

mod view;

pub use view::MeshView;
