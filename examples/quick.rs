use springwater::*;
fn bits(s: &Surface) -> Vec<u32> { s.positions().iter().chain(s.velocities().iter()).flat_map(|c| c.iter().map(|v| v.to_bits())).collect() }
fn main() {
    for (c, r) in [(2usize, 2usize), (5, 3), (17, 9), (64, 64), (33, 70), (100, 37)] {
        let p = Params::with_size(c, r);
        let mut a = Surface::new(p).unwrap();
        a.drop_at(c as f32 / 3.0, r as f32 / 2.0, 1.0, 2.0).unwrap();
        let mut b = a.clone();
        for _ in 0..200 { a.step().unwrap(); b.step_with(Stepper::Reference).unwrap(); }
        println!("{c}x{r}: bitwise {}", bits(&a) == bits(&b));
    }
    let mut s = Surface::new(Params::with_size(37, 29)).unwrap();
    let before = bits(&s);
    for _ in 0..100 { s.step().unwrap(); }
    println!("flat: equal {}", before == bits(&s));
}
