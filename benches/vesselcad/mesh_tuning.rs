//! The search for curvo's settings behind the mesher bench's `TUNED` table (run
//! with `MESH_BENCH_TUNE=1`): for each family of curvo options, the fewest
//! triangles whose measured deviation is at most vesselcad's. See `mesh`.

use super::mesh::{
    CURVO_TRIANGLE_CAP, Case, Knobs, Piece, TUNING_STEPS, curvo_soup, max_deviation, within,
};

/// A one-parameter family of curvo settings, finer as the parameter decreases.
#[derive(Clone, Copy, Debug)]
enum Family {
    /// [`Knobs::Normal`] with a fixed `min_depth`, over `norm_tolerance`.
    Normal { min_depth: usize },
    /// [`Knobs::Grid`] over the cell edge.
    Grid,
    /// [`Knobs::MaxEdge`] over the edge.
    MaxEdge,
}

impl Family {
    /// The families searched.
    const ALL: [Family; 7] = [
        Family::Normal { min_depth: 0 },
        Family::Normal { min_depth: 4 },
        Family::Normal { min_depth: 6 },
        Family::Normal { min_depth: 8 },
        Family::Normal { min_depth: 10 },
        Family::Grid,
        Family::MaxEdge,
    ];

    /// The settings at parameter `x`.
    fn knobs(self, x: f64) -> Knobs {
        match self {
            Family::Normal { min_depth } => Knobs::Normal {
                norm_tolerance: x,
                min_depth,
            },
            Family::Grid => Knobs::Grid { edge: x },
            Family::MaxEdge => Knobs::MaxEdge { edge: x },
        }
    }

    /// The coarsest and finest parameters tried.
    fn range(self) -> (f64, f64) {
        match self {
            Family::Normal { .. } => (0.2, 1e-3),
            Family::Grid | Family::MaxEdge => (400.0, 2.0),
        }
    }
}

/// The outcome of searching one family.
#[derive(Clone, Copy, Debug)]
enum Search {
    /// The coarsest passing settings found, with their triangle count.
    Passed(Knobs, usize),
    /// No setting passed; the finest tried, its triangles and its deviation.
    Floor(Knobs, usize, f64),
}

/// The coarsest settings of `family` whose deviation is at most `target`: halve the
/// parameter from the coarse end until a mesh passes, then bisect (geometrically)
/// between the last failure and the first pass. Stops refining at the fine end of
/// the range or past [`CURVO_TRIANGLE_CAP`].
fn search(pieces: &[Piece], family: Family, target: f64) -> Search {
    let (coarse, fine) = family.range();
    let mut fail = None;
    let mut x = coarse;
    let pass = loop {
        let soup = curvo_soup(pieces, family.knobs(x));
        if within(pieces, &soup, target) {
            break x;
        }
        if x / 2.0 < fine || soup.len() * 4 > CURVO_TRIANGLE_CAP {
            let (deviation, _) = max_deviation(pieces, &soup);
            return Search::Floor(family.knobs(x), soup.len(), deviation);
        }
        fail = Some(x);
        x /= 2.0;
    };
    let mut lo = pass;
    if let Some(mut hi) = fail {
        for _ in 0..TUNING_STEPS {
            let mid = (lo * hi).sqrt();
            if within(pieces, &curvo_soup(pieces, family.knobs(mid)), target) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
    }
    Search::Passed(family.knobs(lo), curvo_soup(pieces, family.knobs(lo)).len())
}

/// Searches every family for `case` and prints the outcomes and the best one (run
/// with `MESH_BENCH_TUNE=1`; copy the best into [`TUNED`]).
pub(super) fn tune_curvo(case: &Case, target: f64) {
    let mut best: Option<(Knobs, usize)> = None;
    for family in Family::ALL {
        match search(&case.pieces, family, target) {
            Search::Passed(knobs, n) => {
                println!(
                    "  tuning {}: passes with {n} triangles: {knobs:?}",
                    case.name
                );
                if best.is_none_or(|b| n < b.1) {
                    best = Some((knobs, n));
                }
            }
            Search::Floor(knobs, n, deviation) => println!(
                "  tuning {}: does not pass; finest tried {knobs:?}: {n} triangles, {deviation:.4} mm",
                case.name
            ),
        }
    }
    println!("  tuning {}: best {best:?}", case.name);
}
