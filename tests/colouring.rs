//! The colour batches: every spring in exactly one band, and bands of one colour never
//! touch the same node.

use proptest::prelude::*;
use springwater::internals::{bands, Tiling, Tuning};
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

/// A pass of several steps ([`Tiling`]): at every level the bands' rows cover the grid
/// once; an even band (colour 0, run first) needs only rows it integrated itself one
/// level down; an odd band (colour 1, run second) needs, beyond its own rows, only rows
/// that an even band beside it integrated one level down, among the two it hands over
/// next to each cut.
fn check_tiling(rows: usize, band_rows: usize, levels: usize) -> Result<(), TestCaseError> {
    let t = Tiling::new(rows, band_rows, levels);
    let bands = t.bands();
    for level in 1..=levels {
        let mut next = 0;
        for b in 0..bands {
            let own = t.rows_at(b, level);
            prop_assert_eq!(
                own.start,
                next,
                "band {} at level {} leaves a gap",
                b,
                level
            );
            prop_assert!(own.start <= own.end);
            next = own.end;
            // Rows a level-`level` row needs: itself and its two neighbours.
            let needed = own.start.saturating_sub(1)..(own.end + 1).min(rows);
            let below_own = t.rows_at(b, level - 1);
            for r in needed.clone().filter(|_| !own.is_empty()) {
                if level == 1 || below_own.contains(&r) {
                    continue; // level 0 is the front buffer; or its own row
                }
                prop_assert_eq!(
                    b % 2,
                    1,
                    "even band {} needs row {} at level {}",
                    b,
                    r,
                    level - 1
                );
                let other = if r < below_own.start { b - 1 } else { b + 1 };
                let theirs = t.rows_at(other, level - 1);
                let handed = if other < b {
                    theirs.end.saturating_sub(2)..theirs.end
                } else {
                    theirs.start..(theirs.start + 2).min(theirs.end)
                };
                prop_assert!(
                    handed.contains(&r),
                    "odd band {} needs row {} at level {}, not handed over by band {}",
                    b,
                    r,
                    level - 1,
                    other
                );
            }
        }
        prop_assert_eq!(next, rows, "level {} does not reach the last row", level);
    }
    Ok(())
}

proptest! {
    #[test]
    fn passes_of_several_steps_cut_the_rows_without_conflicts(
        rows in 2usize..200, band_rows in 1usize..40, levels in 1usize..=8,
    ) {
        check_tiling(rows, band_rows, levels)?;
    }
}
