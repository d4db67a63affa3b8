//! A ball resting at the centre of a calm pool stays there: `simulate --floater` over
//! 8,000 steps ends where it started (the water column carries its weight, see the
//! library's docs/floating.md).

mod common;

#[test]
fn a_ball_at_rest_in_the_middle_of_a_calm_pool_stays_there() {
    let out = common::ok(&[
        "simulate",
        "--size",
        "65x65",
        "--steps",
        "8000",
        "--floater",
        "32,32,1,2",
    ]);
    let line = out
        .lines()
        .find(|l| l.starts_with("floater 0 position"))
        .expect("a floater line");
    let v: Vec<f32> = line
        .split_whitespace()
        .skip(3)
        .take(3)
        .map(|x| x.parse().unwrap())
        .collect();
    assert!(
        (v[0] - 32.0).abs() < 0.01 && (v[2] - 32.0).abs() < 0.01,
        "{line}"
    );
}
