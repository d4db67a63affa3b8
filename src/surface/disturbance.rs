//! The [`Disturbance`] trait that [`Surface::advance_with`] applies before every substep
//! (defined beside `Surface` so that the physics does not depend on `crate::disturb`;
//! `springwater::disturb` re-exports it with its implementations).

use super::Surface;
use crate::error::Result;

/// Something that disturbs a surface as the game's time passes.
pub trait Disturbance {
    /// Disturbs `surface` for the step about to be taken, `dt` **seconds** of the game's
    /// clock long: `params().dt / params().time_scale` for a [`Surface::step`] (what
    /// [`Surface::advance_with`] passes). Call it right before the step (or let
    /// `advance_with` call it): forces it adds apply to that step only.
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()>;
}

/// No disturbance.
impl Disturbance for () {
    fn apply(&mut self, _: &mut Surface, _: f32) -> Result<()> {
        Ok(())
    }
}

impl<D: Disturbance + ?Sized> Disturbance for &mut D {
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()> {
        (**self).apply(surface, dt)
    }
}

impl<D: Disturbance + ?Sized> Disturbance for Box<D> {
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()> {
        (**self).apply(surface, dt)
    }
}

/// A disturbance that may be absent (`None` does nothing).
impl<D: Disturbance> Disturbance for Option<D> {
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()> {
        match self {
            Some(d) => d.apply(surface, dt),
            None => Ok(()),
        }
    }
}

/// Every disturbance of the slice, in order (for example `[&mut dyn Disturbance]`).
impl<D: Disturbance> Disturbance for [D] {
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()> {
        self.iter_mut().try_for_each(|d| d.apply(surface, dt))
    }
}

/// Every disturbance of the vector, in order.
impl<D: Disturbance> Disturbance for Vec<D> {
    fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()> {
        self.as_mut_slice().apply(surface, dt)
    }
}

macro_rules! tuple_disturbance {
    ($($name:ident)+) => {
        /// Each disturbance of the tuple, in order.
        impl<$($name: Disturbance),+> Disturbance for ($($name,)+) {
            #[allow(non_snake_case)]
            fn apply(&mut self, surface: &mut Surface, dt: f32) -> Result<()> {
                let ($($name,)+) = self;
                $($name.apply(surface, dt)?;)+
                Ok(())
            }
        }
    };
}
tuple_disturbance!(A);
tuple_disturbance!(A B);
tuple_disturbance!(A B C);
tuple_disturbance!(A B C E);
