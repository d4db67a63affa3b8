use springwater::*;
fn main() {
    let (cols, rows) = (41, 33);
    let mut s = Surface::new(Params {
        viscosity: 0.0,
        ..Params::with_size(cols, rows)
    })
    .unwrap();
    s.drop_at(20.0, 16.0, 1.0, 2.5).unwrap();
    for _ in 0..500 {
        s.step().unwrap();
    }
    let g = s.grid();
    let [x, y, _z] = s.positions();
    let mut worst = (0f32, 0, 0, 0f32);
    for r in 0..rows {
        for c in 0..cols {
            let (i, n) = (g.index(c, r), g.index(cols - 1 - c, r));
            let e = ((x[i] - c as f32) + (x[n] - (cols - 1 - c) as f32)).abs();
            if e > worst.0 {
                worst = (e, c, r, x[i] - c as f32);
            }
        }
    }
    let scale = y.iter().fold(0.0f32, |m, v| m.max(v.abs()));
    println!("worst {:?} scale {scale}", worst);
}
