//! Sweep triangulation of a cavity with several holes: the cavity split into
//! pieces monotone along the sweep, each piece triangulated by the stack walk
//! (de Berg, Cheong, van Kreveld, Overmars, *Computational Geometry*, 3rd ed.,
//! §3.2–3.3).
//!
//! Sits inside `ring`, before its ear clipping: `cavity::fill` hands a cavity
//! with several holes here first. On a course the cavity is a slab between two
//! chains and its holes are wide and flat in the size metric's chart, stacked
//! or side by side; its Delaunay triangulation is mostly rungs between facing
//! runs of vertices. Sweeping along the chart's x (round the course) meets the
//! vertices of facing runs in turn, so the stack walk lays those rungs itself
//! and the Lawson flips that follow (`ring::Loops::finish_local`) have little
//! left to do; ear clipping left fans across the slab that took many flips.
//!
//! The sweep runs in the chart turned a quarter clockwise, `(x', y') = (y, −x)`,
//! so that it goes downwards in y' as in the book: a vertex comes before
//! another when its y' is greater, or equal with a smaller x'. No vertex is
//! added. `None` when the loops are not a proper polygon with holes (a loop
//! folding back on itself, two vertices at one point, an edge missing from the
//! sweep's status): the caller then clips ears.

use glam::DVec2;

use crate::mesh::cdt::flip::orient;

/// A vertex's role in the sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    /// Both neighbours later, convex: a piece starts.
    Start,
    /// Both neighbours later, reflex: a piece splits.
    Split,
    /// Both neighbours earlier, convex: a piece ends.
    End,
    /// Both neighbours earlier, reflex: two pieces merge.
    Merge,
    /// One neighbour earlier, one later.
    Regular,
}

/// Triangles covering the polygon whose loops `next` describes (local vertex
/// → next vertex of its loop, the polygon on the left of every edge) with its
/// vertices at `chart`: each `[a, b, c]` counter-clockwise in the chart.
/// `None` when the loops are not a proper polygon with holes (see the module
/// doc).
pub(super) fn triangulate(next: &[u32], chart: &[[f64; 2]]) -> Option<Vec<[u32; 3]>> {
    let n = next.len();
    if n < 3 || chart.len() != n || chart.iter().flatten().any(|c| !c.is_finite()) {
        return None;
    }
    let p: Vec<DVec2> = chart.iter().map(|&[x, y]| DVec2::new(y, -x)).collect();
    let mut prev = vec![u32::MAX; n];
    for (k, &j) in next.iter().enumerate() {
        let slot = prev.get_mut(j as usize)?;
        if *slot != u32::MAX {
            return None;
        }
        *slot = k as u32;
    }
    // Sweep order: y falling, then x rising (`total_cmp`'s order), sorted as
    // integer keys rather than through the points.
    let mut keyed: Vec<(u64, u64, u32)> = p
        .iter()
        .enumerate()
        .map(|(k, q)| (!ordered(q.y), ordered(q.x), k as u32))
        .collect();
    keyed.sort_unstable();
    let order: Vec<u32> = keyed.into_iter().map(|(_, _, k)| k).collect();
    if order
        .windows(2)
        .any(|w| p[w[0] as usize] == p[w[1] as usize])
    {
        return None;
    }
    // Each vertex's place in the sweep: `before` is one comparison.
    let mut rank = vec![0u32; n];
    for (r, &v) in order.iter().enumerate() {
        rank[v as usize] = r as u32;
    }
    let before = |a: usize, b: usize| rank[a] < rank[b];
    let mut roles = Vec::with_capacity(n);
    for v in 0..n {
        let (a, b) = (prev[v] as usize, next[v] as usize);
        let turn = orient(p[a], p[v], p[b]);
        roles.push(match (before(a, v), before(b, v)) {
            (false, false) if turn > 0.0 => Role::Start,
            (false, false) if turn < 0.0 => Role::Split,
            (true, true) if turn > 0.0 => Role::End,
            (true, true) if turn < 0.0 => Role::Merge,
            (false, false) | (true, true) => return None,
            _ => Role::Regular,
        });
    }
    let diagonals = split_monotone(next, &prev, &p, &order, &roles, &before)?;
    let mut tris = Vec::with_capacity(n + 2 * diagonals.len());
    faces(next, &p, &diagonals, &before, &mut tris)?;
    Some(tris)
}

/// `x`'s bits as an integer in `f64::total_cmp`'s order.
fn ordered(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | 1 << 63
    }
}

/// The diagonals that split the polygon into pieces monotone along the sweep
/// (MakeMonotone): each split vertex joined to the latest vertex above it
/// between its neighbouring edges, each merge vertex to the next one below.
fn split_monotone(
    next: &[u32],
    prev: &[u32],
    p: &[DVec2],
    order: &[u32],
    roles: &[Role],
    before: &impl Fn(usize, usize) -> bool,
) -> Option<Vec<(u32, u32)>> {
    // Edges crossing the sweep line with the polygon on their right, by their
    // first vertex (edge k runs from k to next[k]), and each edge's helper.
    let mut status: Vec<u32> = Vec::new();
    let mut helper = vec![u32::MAX; p.len()];
    let mut diagonals = Vec::new();
    let remove = |status: &mut Vec<u32>, e: u32| -> Option<()> {
        let at = status.iter().position(|&s| s == e)?;
        status.swap_remove(at);
        Some(())
    };
    // The status edge directly left of v (smallest gap in x' at v's height).
    let left_of = |status: &[u32], v: usize| -> Option<u32> {
        let q = p[v];
        let mut best: Option<(f64, u32)> = None;
        for &e in status {
            let (a, b) = (p[e as usize], p[next[e as usize] as usize]);
            if e as usize == v || next[e as usize] as usize == v || orient(a, b, q) <= 0.0 {
                continue;
            }
            let x = if a.y == b.y {
                a.x.max(b.x)
            } else {
                a.x + (b.x - a.x) * ((q.y - a.y) / (b.y - a.y))
            };
            if best.is_none_or(|(bx, _)| x > bx) {
                best = Some((x, e));
            }
        }
        best.map(|(_, e)| e)
    };
    let merge_helper = |helper: &[u32], e: u32| {
        let h = helper[e as usize];
        (h != u32::MAX && roles[h as usize] == Role::Merge).then_some(h)
    };
    // Each role is up to three steps of the book's handlers, in this order:
    // close the edge arriving from above, join the edge to the left, open the
    // edge leaving downwards.
    for &v in order {
        let e_prev = prev[v as usize];
        let role = roles[v as usize];
        // A regular vertex with the boundary going down has the polygon on its
        // right; going up, on its left.
        let down = role == Role::Regular && before(e_prev as usize, v as usize);
        if matches!(role, Role::End | Role::Merge) || down {
            if let Some(h) = merge_helper(&helper, e_prev) {
                diagonals.push((v, h));
            }
            remove(&mut status, e_prev)?;
        }
        if role == Role::Split {
            let e = left_of(&status, v as usize)?;
            diagonals.push((v, *helper.get(e as usize).filter(|&&h| h != u32::MAX)?));
            helper[e as usize] = v;
        } else if role == Role::Merge || (role == Role::Regular && !down) {
            let e = left_of(&status, v as usize)?;
            if let Some(h) = merge_helper(&helper, e) {
                diagonals.push((v, h));
            }
            helper[e as usize] = v;
        }
        if matches!(role, Role::Start | Role::Split) || down {
            status.push(v);
            helper[v as usize] = v;
        }
    }
    // A diagonal along a loop edge, or twice, would be no split at all.
    let mut keys: Vec<(u32, u32)> = diagonals
        .iter()
        .map(|&(a, b)| (a.min(b), a.max(b)))
        .collect();
    keys.sort_unstable();
    let repeated = keys.windows(2).any(|w| w[0] == w[1]);
    let on_loop = diagonals
        .iter()
        .any(|&(a, b)| a == b || next[a as usize] == b || next[b as usize] == a);
    (!repeated && !on_loop).then_some(diagonals)
}

/// Triangulates each piece the diagonals cut the polygon into (pieces are
/// traced by turning at each vertex onto the next edge clockwise from the one
/// arrived by) into `tris`.
fn faces(
    next: &[u32],
    p: &[DVec2],
    diagonals: &[(u32, u32)],
    before: &impl Fn(usize, usize) -> bool,
    tris: &mut Vec<[u32; 3]>,
) -> Option<()> {
    let n = next.len();
    // Both directions of each diagonal, by first vertex: vertex b's are
    // `half[first[b]..first[b + 1]]`.
    let mut half: Vec<(u32, u32)> = diagonals
        .iter()
        .flat_map(|&(a, b)| [(a, b), (b, a)])
        .collect();
    half.sort_unstable();
    let mut first = vec![0u32; n + 1];
    for &(a, _) in &half {
        first[a as usize + 1] += 1;
    }
    for k in 0..n {
        first[k + 1] += first[k];
    }
    let partners = |b: u32| first[b as usize] as usize..first[b as usize + 1] as usize;
    // The edge after a → b on the piece left of it.
    let turn = |a: u32, b: u32| -> u32 {
        let range = partners(b);
        if range.is_empty() {
            return next[b as usize];
        }
        let angle = |c: u32| pseudo_angle(p[c as usize] - p[b as usize]);
        let from = angle(a);
        let clockwise = |c: u32| {
            let t = (from - angle(c)).rem_euclid(4.0);
            if c == a || t == 0.0 { 4.0 } else { t }
        };
        half[range]
            .iter()
            .map(|&(_, c)| c)
            .chain([next[b as usize]])
            .min_by(|&x, &y| clockwise(x).total_cmp(&clockwise(y)))
            .unwrap_or(next[b as usize])
    };
    // Whether each loop edge (slot: its first vertex) and each diagonal half
    // (slot: n + its place in `half`) has been walked.
    let mut walked = vec![false; n + half.len()];
    let slot = |a: u32, b: u32| -> Option<usize> {
        if next[a as usize] == b {
            return Some(a as usize);
        }
        let range = partners(a);
        let at = half[range.clone()].iter().position(|&(_, c)| c == b)?;
        Some(n + range.start + at)
    };
    let mut piece = Vec::new();
    let starts = (0..n as u32)
        .map(|a| (a, next[a as usize]))
        .chain(half.iter().copied());
    for (a0, b0) in starts {
        if walked[slot(a0, b0)?] {
            continue;
        }
        piece.clear();
        let (mut a, mut b) = (a0, b0);
        loop {
            let k = slot(a, b)?;
            if walked[k] || piece.len() > n {
                return None;
            }
            walked[k] = true;
            piece.push(a);
            (a, b) = (b, turn(a, b));
            if (a, b) == (a0, b0) {
                break;
            }
        }
        monotone(&piece, p, before, tris)?;
    }
    Some(())
}

/// A direction's angle from +x counter-clockwise, measured in quarter turns
/// along the unit diamond (0 ≤ a < 4): in the order of the true angle, without
/// trigonometry.
fn pseudo_angle(d: DVec2) -> f64 {
    let (x, y) = (d.x, d.y);
    let r = x.abs() + y.abs();
    match (x >= 0.0, y >= 0.0) {
        (true, true) => y / r,
        (false, true) => 1.0 - x / r,
        (false, false) => 2.0 - y / r,
        (true, false) => 3.0 + x / r,
    }
}

/// Triangulates one piece monotone along the sweep (its vertices in order
/// round it, the piece on their left) by the stack walk into `tris`.
fn monotone(
    piece: &[u32],
    p: &[DVec2],
    before: &impl Fn(usize, usize) -> bool,
    tris: &mut Vec<[u32; 3]>,
) -> Option<()> {
    let m = piece.len();
    if m < 3 {
        return None;
    }
    let vertex = |i: usize| piece[i] as usize;
    let top = (0..m).reduce(|a, b| if before(vertex(b), vertex(a)) { b } else { a })?;
    // Round the piece from its top: forward runs the left chain down to the
    // bottom, then the right chain back up.
    let round = |k: usize| vertex(if top + k < m { top + k } else { top + k - m });
    let bottom = (1..m).reduce(|a, b| if before(round(a), round(b)) { b } else { a })?;
    let down = (1..=bottom).all(|k| before(round(k - 1), round(k)));
    let up = (bottom..m).all(|k| before(round(if k + 1 < m { k + 1 } else { 0 }), round(k)));
    if !(down && up) {
        return None;
    }
    // Both chains merged in sweep order, each vertex with its chain (true:
    // left); the top counts as left, the bottom as right.
    let mut sorted: Vec<(usize, bool)> = Vec::with_capacity(m);
    sorted.push((round(0), true));
    let (mut i, mut j) = (1, m - 1);
    while i < bottom || j > bottom {
        if j == bottom || (i < bottom && before(round(i), round(j))) {
            sorted.push((round(i), true));
            i += 1;
        } else {
            sorted.push((round(j), false));
            j -= 1;
        }
    }
    sorted.push((round(bottom), false));
    let mut emit = |a: usize, b: usize, c: usize| {
        let t = [a as u32, b as u32, c as u32];
        tris.push(if orient(p[a], p[b], p[c]) < 0.0 {
            [t[0], t[2], t[1]]
        } else {
            t
        });
    };
    let mut stack: Vec<(usize, bool)> = vec![sorted[0], sorted[1]];
    for k in 2..m - 1 {
        let (u, on_left) = sorted[k];
        let &(_, top_left) = stack.last()?;
        if on_left != top_left {
            for w in stack.windows(2) {
                emit(u, w[0].0, w[1].0);
            }
            stack.clear();
            stack.push(sorted[k - 1]);
            stack.push(sorted[k]);
        } else {
            let mut last = stack.pop()?;
            while let Some(&q) = stack.last() {
                let inside = if on_left {
                    orient(p[q.0], p[last.0], p[u]) > 0.0
                } else {
                    orient(p[u], p[last.0], p[q.0]) > 0.0
                };
                if !inside {
                    break;
                }
                emit(u, last.0, q.0);
                last = stack.pop()?;
            }
            stack.push(last);
            stack.push(sorted[k]);
        }
    }
    let (u, _) = sorted[m - 1];
    for w in stack.windows(2) {
        emit(u, w[0].0, w[1].0);
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `next` for loops of the given lengths, numbered one after another.
    fn loops(lengths: &[u32]) -> Vec<u32> {
        let mut next = Vec::new();
        let mut first = 0;
        for &len in lengths {
            next.extend((first + 1..first + len).chain([first]));
            first += len;
        }
        next
    }

    #[test]
    fn integer_keys_order_as_total_cmp() {
        let values = [
            f64::NEG_INFINITY,
            -1e300,
            -2.5,
            -f64::MIN_POSITIVE,
            -0.0,
            0.0,
            f64::MIN_POSITIVE,
            1e-300,
            1.0,
            2.5,
            f64::MAX,
            f64::INFINITY,
            -f64::NAN,
            f64::NAN,
        ];
        for a in values {
            for b in values {
                assert_eq!(
                    ordered(a).cmp(&ordered(b)),
                    a.total_cmp(&b),
                    "{a} against {b}"
                );
            }
        }
    }

    #[test]
    fn a_square_round_a_square_hole_is_eight_triangles() {
        let chart = [
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [0.0, 4.0],
            // The hole, clockwise.
            [1.0, 1.0],
            [1.0, 3.0],
            [3.0, 3.0],
            [3.0, 1.0],
        ];
        let tris = triangulate(&loops(&[4, 4]), &chart).expect("triangulated");
        assert_eq!(tris.len(), 8);
        let p = |k: u32| DVec2::from_array(chart[k as usize]);
        let area: f64 = tris.iter().map(|t| orient(p(t[0]), p(t[1]), p(t[2]))).sum();
        assert!(tris.iter().all(|t| orient(p(t[0]), p(t[1]), p(t[2])) > 0.0));
        assert_eq!(area, 2.0 * (16.0 - 4.0));
    }

    #[test]
    fn the_pseudo_angle_orders_directions_as_the_angle_does() {
        let angles: Vec<f64> = (0..64)
            .map(|k| std::f64::consts::TAU * k as f64 / 64.0)
            .collect();
        let pseudo: Vec<f64> = angles
            .iter()
            .map(|a| pseudo_angle(DVec2::new(a.cos(), a.sin())))
            .collect();
        assert!(pseudo.windows(2).all(|w| w[0] < w[1]), "{pseudo:?}");
        assert!(pseudo.iter().all(|&a| (0.0..4.0).contains(&a)));
    }

    #[test]
    fn loops_that_are_no_polygon_are_refused() {
        // Two vertices at one point.
        let twice = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 0.0]];
        assert!(triangulate(&loops(&[4]), &twice).is_none());
        // A loop folding back along itself.
        let spike = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.0]];
        assert!(triangulate(&loops(&[3]), &spike).is_none());
        // A vertex past the end, a NaN.
        assert!(triangulate(&[1, 2, 5], &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).is_none());
        let nan = [[0.0, 0.0], [1.0, f64::NAN], [0.0, 1.0]];
        assert!(triangulate(&loops(&[3]), &nan).is_none());
    }
}
