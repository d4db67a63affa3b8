//! The colour batches: every spring in exactly one band, and bands of one colour never
//! touch the same node.

use proptest::prelude::*;
use springwater::springs::bands;
use springwater::{Grid, Params, Surface};
use std::collections::{HashMap, HashSet};

fn check(cols: usize, rows: usize, band_rows: usize) -> Result<(), TestCaseError> {
    let grid = Grid::new(cols, rows);
    let all: Vec<_> = bands(rows, band_rows).collect();
    let mut seen = HashMap::new();
    for band in &all {
        for id in band.springs(grid) {
            *seen.entry(id).or_insert(0) += 1;
        }
    }
    prop_assert_eq!(seen.len(), grid.spring_count());
    for (id, _) in grid.springs() {
        prop_assert_eq!(
            seen.get(&id),
            Some(&1),
            "spring {:?} not in exactly one band",
            id
        );
    }
    for colour in 0..2 {
        let mut owner: HashMap<usize, usize> = HashMap::new();
        for (b, band) in all.iter().enumerate().filter(|(_, b)| b.colour == colour) {
            let nodes: HashSet<usize> = band
                .springs(grid)
                .flat_map(|id| [id.origin, grid.spring_end(id.family, id.origin).unwrap()])
                .collect();
            for n in nodes {
                if let Some(other) = owner.insert(n, b) {
                    prop_assert!(
                        false,
                        "node {} touched by bands {} and {} of colour {}",
                        n,
                        other,
                        b,
                        colour
                    );
                }
            }
        }
    }
    Ok(())
}

proptest! {
    #[test]
    fn every_spring_in_one_band_and_colours_never_share_a_node(
        cols in 2usize..40, rows in 2usize..60, band_rows in 1usize..12,
    ) {
        check(cols, rows, band_rows)?;
    }
}

#[test]
fn the_surfaces_own_bands_are_a_valid_colouring() {
    let s = Surface::new(Params::with_size(33, 150)).unwrap();
    let all: Vec<_> = s.bands().collect();
    assert!(all.len() > 2, "a 150-row grid has several bands");
    let band_rows = all[0].rows.len();
    check(33, 150, band_rows).unwrap();
}
