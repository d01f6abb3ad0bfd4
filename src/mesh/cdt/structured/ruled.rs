//! The rows of an oblique cone (an eccentric reducer's) between its two end
//! rings.
//!
//! The cone is the ruled surface between its end circles, both parametrized
//! alike from +X: the points at one u on the two circles lie on one generator
//! through the apex (the homothety from the apex maps one circle onto the
//! other), so its u-lines are generators and its v-lines circles, every one the
//! same circle scaled from the apex. A triangle whose vertices lie between two
//! generators (between two u values) lies in the convex hull of the cone
//! between them, whose farthest point from the cone is on the plane of the two
//! generators at the larger end: the sagitta there of the chord between them.
//! So a strip whose every triangle lies between two consecutive u values of a
//! ring, below that ring's circle (towards the large end) no further than the
//! large end, deviates no more than that ring's chords at the large end.
//!
//! The end rings share no u values (the large end has more, each sized on its
//! own circle), and the lattice has no row between them (the cone is straight
//! along its generators): the one strip zipping the two rings (by the shorter
//! 3D diagonal, which the generators' lean turns across them) held slender
//! triangles spanning up to a segment of each ring, the small ring's at the
//! large end's radius (r₁/r₂ of its sagitta), and refinement of such slivers
//! in (u, v) left triangles turned over in 3D. Here the rows
//! are the lattice's levels, each holding one ring's u values (the large
//! end's below the middle row, the small end's above it), and a middle row
//! holding both rings' values and the midpoints of the small ring's segments.
//! Zipped by |Δu| (`zip_by`), a strip between a row and one holding all its u
//! values keeps each triangle between two consecutive values of the coarser
//! row; below the small ring's segments the triangles reaching the middle row
//! span half a segment (the midpoint is the apex of the segment's own
//! triangle): within the tolerance without refinement, and no triangle leans
//! across more than one segment.

/// The rows (v, u values) of an oblique cone's region from the lattice's
/// `rows` (their levels only are kept) and its end rings' u values, `bottom`
/// at the large end `lo.y`, `top` at `hi.y`; every row runs from `lo_u` to
/// `hi_u` (the seam) exactly.
pub(super) fn rows(
    rows: Vec<(f64, Vec<f64>)>,
    bottom: &[f64],
    top: &[f64],
    (lo_u, hi_u): (f64, f64),
    (lo_v, hi_v): (f64, f64),
) -> Vec<(f64, Vec<f64>)> {
    let seam = |mut u: Vec<f64>| {
        if let Some(first) = u.first_mut() {
            *first = lo_u;
        }
        if let Some(last) = u.last_mut() {
            *last = hi_u;
        }
        let eps = 1e-9 * (hi_u - lo_u);
        u.dedup_by(|a, b| *a - *b <= eps);
        u
    };
    // The middle row in the gap between levels that holds the middle of v.
    let middle = 0.5 * (lo_v + hi_v);
    let levels: Vec<f64> = std::iter::once(lo_v)
        .chain(rows.iter().map(|r| r.0))
        .chain(std::iter::once(hi_v))
        .collect();
    let gap = levels
        .windows(2)
        .find(|w| w[0] <= middle && middle < w[1])
        .unwrap_or(&levels[..2]);
    let v_middle = 0.5 * (gap[0] + gap[1]);
    let mut both: Vec<f64> = bottom
        .iter()
        .chain(top)
        .copied()
        .chain(top.windows(2).map(|w| 0.5 * (w[0] + w[1])))
        .collect();
    both.sort_by(f64::total_cmp);
    let mut out = Vec::with_capacity(rows.len() + 1);
    let mut middle_row = Some((v_middle, seam(both)));
    for (v, _) in rows {
        if v > v_middle
            && let Some(row) = middle_row.take()
        {
            out.push(row);
        }
        let ring = if v < v_middle { bottom } else { top };
        out.push((v, seam(ring.to_vec())));
    }
    out.extend(middle_row);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Between the two rings, one middle row holding both rings' values and the
    /// small ring's midpoints; lattice levels keep their v, each with the ring
    /// of its side.
    #[test]
    fn the_middle_row_holds_both_rings() {
        let bottom = [0.0, 0.25, 0.5, 0.75, 1.0];
        let top = [0.0, 0.4, 1.0];
        let plain = rows(Vec::new(), &bottom, &top, (0.0, 1.0), (0.0, 1.0));
        assert_eq!(
            plain,
            vec![(0.5, vec![0.0, 0.2, 0.25, 0.4, 0.5, 0.7, 0.75, 1.0])]
        );
        let lattice = vec![(0.2, vec![]), (0.4, vec![]), (0.9, vec![])];
        let out = rows(lattice, &bottom, &top, (0.0, 1.0), (0.0, 1.0));
        let levels: Vec<f64> = out.iter().map(|r| r.0).collect();
        assert_eq!(levels, [0.2, 0.4, 0.65, 0.9]);
        assert_eq!(out[1].1, bottom);
        assert_eq!(out[3].1, top);
        assert_eq!(out[2].1.len(), 8);
    }
}
