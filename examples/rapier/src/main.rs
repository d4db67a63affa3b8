//! A barge heeled 15° is dropped next to a dock, drifting towards it; every half second
//! this prints its height and heel.
//!
//! ```text
//! cargo run --release -p springwater-rapier-example
//! ```

use rapier3d::math::Vector;
use rapier3d::prelude::{ColliderBuilder, RigidBodyBuilder};
use springwater::glam::Quat;
use springwater::{Params, Surface};
use springwater_rapier_example::{heel, tick, world_for, Floating, TICK};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut water = Surface::new(Params::with_size(64, 64))?;
    let mut world = world_for(&water);
    // A dock: a fixed block standing half in the water; the water does not know it, Rapier
    // keeps the barge out of it.
    let dock = world.bodies.insert(RigidBodyBuilder::fixed());
    world.colliders.insert_with_parent(
        ColliderBuilder::cuboid(3.0, 1.0, 12.0).translation(Vector::new(24.0, 0.0, 32.0)),
        dock,
        &mut world.bodies,
    );
    // A barge 4 × 1 × 3 at half the water's density, dropped heeled 15° beside the dock,
    // drifting towards it.
    let density = 0.5 * water.buoyancy().density;
    let (barge, _) = world.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(30.0, 1.5, 32.0))
            .rotation(Vector::new(0.0, 0.0, 15f32.to_radians()))
            .linvel(Vector::new(-2.0, 0.0, 0.0))
            .can_sleep(false),
        ColliderBuilder::cuboid(1.5, 0.5, 2.0).density(density),
    );
    let bodies = [Floating::new(&mut world, barge)?];
    println!("time s   height   heel °");
    for step in 0..=600 {
        if step % 30 == 0 {
            let body = &world.bodies[barge];
            let rotation = Quat::from_array(body.rotation().to_array());
            let height = body.center_of_mass().y;
            let t = step as f32 * TICK;
            println!("{t:6.1}  {height:7.3}  {:7.2}", heel(rotation));
        }
        tick(&mut world, &mut water, &bodies)?;
    }
    Ok(())
}
