use springwater::*;
fn main() {
    for (c, r) in [(2usize, 2usize), (5, 3), (17, 9), (64, 64), (33, 70)] {
        let p = Params::with_size(c, r);
        let mut a = Surface::new(p).unwrap();
        a.drop_at(c as f32 / 2.0, r as f32 / 2.0, 1.0, 2.0).unwrap();
        let mut b = a.clone();
        for _ in 0..200 {
            a.step().unwrap();
            b.step_with(Stepper::Reference).unwrap();
        }
        let mut maxd = 0f32;
        for k in 0..3 {
            for (x, y) in a.positions()[k].iter().zip(b.positions()[k]) {
                maxd = maxd.max((x - y).abs());
            }
        }
        println!("{c}x{r}: maxdiff {maxd:e} energy {:?} {:?}", a.energy().total(), b.energy().total());
    }
}
