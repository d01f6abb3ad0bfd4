//! Unit tests of the cavity fills: zip, sweep, ears and the cover check.

use super::*;
use crate::mesh::cdt::patch::Vertex;
use glam::DVec3;

/// A mesh of bare (u, v) vertices.
fn mesh_of(uvs: impl IntoIterator<Item = DVec2>) -> TriMesh {
    let mut mesh = TriMesh::default();
    mesh.verts.extend(uvs.into_iter().map(|uv| Vertex {
        uv,
        point: DVec3::new(uv.x, uv.y, 0.0),
        normal: DVec3::Z,
        metric: Metric::UNSET,
        pole: false,
    }));
    mesh
}

const ISOTROPIC: Metric = Metric {
    uu: 1.0,
    uv: 0.0,
    vv: 1.0,
};

/// The loops of a cavity whose boundary is the mesh's first `np` vertices
/// and whose holes are `holes`.
fn loops_of(
    mesh: &TriMesh,
    np: u32,
    holes: impl IntoIterator<Item = std::ops::Range<u32>>,
    metric: &Metric,
) -> Loops {
    Loops::new(mesh, &(0..np).collect::<Vec<_>>(), holes, metric).expect("loops")
}

/// Twice the area the triangles cover, in (u, v).
fn double_area(mesh: &TriMesh, tris: &[[u32; 3]]) -> f64 {
    let uv = |k: u32| mesh.verts[k as usize].uv;
    tris.iter()
        .map(|t| orient(uv(t[0]), uv(t[1]), uv(t[2])))
        .sum()
}

fn double_area_of(pts: &[DVec2]) -> f64 {
    (0..pts.len())
        .map(|k| pts[k].perp_dot(pts[(k + 1) % pts.len()]))
        .sum()
}

#[test]
fn a_zip_the_greedy_walk_cannot_finish_is_found_by_the_least_diagonals() {
    // A cavity of a generated plant's course (its boundary, then its hole,
    // clockwise) and the size metric there: a convex opening close to the
    // bottom row, where the greedy walk pairs the hole with the wrong row.
    let outer = [
        [0.614222018, 0.0],
        [0.625, 0.0],
        [0.635777982, 0.0],
        [0.639439295, 0.5],
        [0.629813098, 0.5],
        [0.620186902, 0.5],
        [0.610560705, 0.5],
    ];
    let hole = [
        [0.625871739, 0.06249439],
        [0.626763493, 0.062177212],
        [0.627621718, 0.06162726],
        [0.628387967, 0.060857453],
        [0.629010507, 0.059909796],
        [0.629455312, 0.058848241],
        [0.629711874, 0.057745101],
        [0.629791913, 0.056666667],
        [0.629711874, 0.055588232],
        [0.629455312, 0.054485092],
        [0.629010507, 0.053423537],
        [0.628387967, 0.05247588],
        [0.627621718, 0.051706073],
        [0.626763493, 0.051156121],
        [0.625871739, 0.050838944],
        [0.625, 0.05074],
        [0.624128261, 0.050838944],
        [0.623236507, 0.051156121],
        [0.622378282, 0.051706073],
        [0.621612033, 0.05247588],
        [0.620989493, 0.053423537],
        [0.620544688, 0.054485092],
        [0.620288126, 0.055588232],
        [0.620208087, 0.056666667],
        [0.620288126, 0.057745101],
        [0.620544688, 0.058848241],
        [0.620989493, 0.059909796],
        [0.621612033, 0.060857453],
        [0.622378282, 0.06162726],
        [0.623236507, 0.062177212],
        [0.624128261, 0.06249439],
        [0.625, 0.062593333],
    ];
    let pts: Vec<DVec2> = outer
        .iter()
        .chain(&hole)
        .map(|&p| DVec2::from_array(p))
        .collect();
    let mesh = mesh_of(pts.iter().copied());
    let (np, n) = (outer.len() as u32, pts.len() as u32);
    let metric = Metric {
        uu: 11124.125563292135,
        uv: 0.0,
        vv: 0.7763158295853231,
    };
    let loops = loops_of(&mesh, np, std::iter::once(np..n), &metric);
    assert!(
        loops.zip_greedy(&mesh).is_none(),
        "the greedy walk gets stuck"
    );
    let tris = loops.zip(&mesh).expect("a zip");
    assert!(loops.cover(&mesh, &tris));
    let expected = double_area_of(&pts[..np as usize]) + double_area_of(&pts[np as usize..]);
    assert!((double_area(&mesh, &tris) - expected).abs() < 1e-12);
    let tris = loops.finish(&mesh, tris).expect("flipped");
    assert_eq!(
        tris.iter().flat_map(|t| t.1).filter(|&f| f).count(),
        hole.len()
    );
}

/// A course-like cavity: a slab `width` × 1 with `columns` + 1 vertices
/// along its bottom and top (collinear) and, when `middle`, one more on
/// each side at half height (a lattice row's ends), round `holes` (each its
/// centre, semi-axes and vertex count: ellipses, clockwise). Its points,
/// boundary length and hole ranges.
fn slab(
    width: f64,
    columns: usize,
    middle: bool,
    holes: &[(DVec2, DVec2, usize)],
) -> (Vec<DVec2>, u32, Vec<std::ops::Range<u32>>) {
    let step = width / columns as f64;
    let mut pts: Vec<DVec2> = (0..=columns)
        .map(|i| DVec2::new(step * i as f64, 0.0))
        .collect();
    if middle {
        pts.push(DVec2::new(width, 0.5));
    }
    pts.extend(
        (0..=columns)
            .rev()
            .map(|i| DVec2::new(step * i as f64, 1.0)),
    );
    if middle {
        pts.push(DVec2::new(0.0, 0.5));
    }
    let np = pts.len() as u32;
    let mut ranges = Vec::new();
    for &(centre, axes, n) in holes {
        let first = pts.len() as u32;
        pts.extend((0..n).map(|k| {
            let a = -std::f64::consts::TAU * k as f64 / n as f64;
            centre + axes * DVec2::new(a.cos(), a.sin())
        }));
        ranges.push(first..pts.len() as u32);
    }
    (pts, np, ranges)
}

/// Twice the area of a cavity: its boundary less its holes.
fn cavity_double_area(pts: &[DVec2], np: u32, holes: &[std::ops::Range<u32>]) -> f64 {
    let loop_area =
        |r: std::ops::Range<u32>| double_area_of(&pts[r.start as usize..r.end as usize]);
    loop_area(0..np) + holes.iter().cloned().map(loop_area).sum::<f64>()
}

#[test]
fn the_sweep_covers_stacked_and_side_by_side_holes_once() {
    // A course's cavity in its size metric: wide, flat holes, two stacked
    // and one beside them, between two rows of a few vertices each.
    let holes = [
        (DVec2::new(1.2, 0.3), DVec2::new(0.9, 0.05), 24),
        (DVec2::new(1.3, 0.72), DVec2::new(0.7, 0.04), 16),
        (DVec2::new(3.0, 0.5), DVec2::new(0.5, 0.1), 12),
    ];
    let (pts, np, ranges) = slab(4.0, 4, true, &holes);
    let mesh = mesh_of(pts.iter().copied());
    let loops = loops_of(&mesh, np, ranges.clone(), &ISOTROPIC);
    let tris = loops.sweep(&mesh).expect("a cover");
    let n = pts.len();
    // Euler: a polygon of n vertices with h holes has n + 2h − 2 triangles.
    assert_eq!(tris.len(), n + 2 * holes.len() - 2);
    assert!((0..n as u32).all(|k| tris.iter().flatten().any(|&x| x == k)));
    let expected = cavity_double_area(&pts, np, &ranges);
    assert!((double_area(&mesh, &tris) - expected).abs() < 1e-12);
    // Flipped to Delaunay, every hole segment is fixed.
    let flipped = loops.finish(&mesh, tris).expect("flipped");
    let fixed = flipped.iter().flat_map(|t| t.1).filter(|&f| f).count();
    assert_eq!(fixed, 24 + 16 + 12);
}

#[test]
fn the_sweep_leaves_the_flips_less_to_do_than_ear_clipping() {
    // Stacked flat holes in a narrow slab (the course's common case): the
    // sweep lays the rungs between them, ear clipping fans across the slab.
    let holes = [
        (DVec2::new(1.0, 0.25), DVec2::new(0.5, 0.02), 20),
        (DVec2::new(1.0, 0.75), DVec2::new(0.45, 0.02), 20),
    ];
    let (pts, np, ranges) = slab(2.0, 2, false, &holes);
    let mesh = mesh_of(pts.iter().copied());
    let loops = loops_of(&mesh, np, ranges, &ISOTROPIC);
    let edges = |tris: &[[u32; 3]]| -> rustc_hash::FxHashSet<(u32, u32)> {
        tris.iter()
            .flat_map(|t| (0..3).map(move |i| (t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3]))))
            .collect()
    };
    let delaunay = |tris: Vec<[u32; 3]>| -> Vec<[u32; 3]> {
        let flipped = loops.finish(&mesh, tris).expect("flipped");
        flipped.iter().map(|t| t.0).collect()
    };
    let swept = loops.sweep(&mesh).expect("a sweep");
    let clipped = loops.ears(&mesh).expect("ears");
    let target = edges(&delaunay(swept.clone()));
    assert_eq!(
        target,
        edges(&delaunay(clipped.clone())),
        "one Delaunay triangulation"
    );
    let off = |tris: &[[u32; 3]]| edges(tris).difference(&target).count();
    assert!(
        off(&swept) * 2 < off(&clipped),
        "swept {} edges off, ear-clipped {}",
        off(&swept),
        off(&clipped)
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]
    /// Holes in cells of a grid over the slab (so none overlap), of any
    /// flatness and vertex count, with the chart stretched as a course's
    /// metric stretches it: the sweep always covers the cavity once.
    #[test]
    fn the_sweep_covers_any_cavity_of_separate_holes(
        columns in 1usize..8,
        middle: bool,
        cells in proptest::collection::vec((proptest::bool::weighted(0.6), 0.1f64..0.45, 0.02f64..0.45, 3usize..28), 12),
        stretch in 0.05f64..20.0,
    ) {
        let (cols, rows) = (4, 3);
        let (width, cell_h) = (4.0, 1.0 / rows as f64);
        let holes: Vec<(DVec2, DVec2, usize)> = cells
            .iter()
            .enumerate()
            .filter(|(_, c)| c.0)
            .map(|(i, &(_, rx, ry, n))| {
                let (col, row) = ((i % cols) as f64, (i / cols) as f64);
                let centre = DVec2::new((col + 0.5) * width / cols as f64, (row + 0.5) * cell_h);
                (centre, DVec2::new(rx * width / cols as f64, ry * cell_h), n)
            })
            .collect();
        proptest::prop_assume!(holes.len() >= 2);
        let (pts, np, ranges) = slab(width, columns, middle, &holes);
        let mesh = mesh_of(pts.iter().copied());
        let metric = Metric { uu: 1.0, uv: 0.0, vv: stretch * stretch };
        let loops = loops_of(&mesh, np, ranges.clone(), &metric);
        let tris = loops.sweep(&mesh);
        proptest::prop_assert!(tris.is_some(), "no sweep");
        let tris = tris.unwrap_or_default();
        proptest::prop_assert_eq!(tris.len(), pts.len() + 2 * holes.len() - 2);
        let expected = cavity_double_area(&pts, np, &ranges);
        proptest::prop_assert!((double_area(&mesh, &tris) - expected).abs() < 1e-9);
    }
}

#[test]
fn ear_clipping_loses_no_collinear_vertex() {
    // A rectangle with many vertices along its bottom and top (collinear,
    // which ear clipping drops) round two holes one above the other.
    let mut pts: Vec<DVec2> = (0..=10).map(|i| DVec2::new(0.1 * i as f64, 0.0)).collect();
    pts.extend((0..=10).rev().map(|i| DVec2::new(0.1 * i as f64, 2.0)));
    let np = pts.len() as u32;
    let circle = |c: DVec2, r: f64, n: usize| -> Vec<DVec2> {
        (0..n)
            .map(|k| {
                let a = -std::f64::consts::TAU * k as f64 / n as f64;
                c + r * DVec2::new(a.cos(), a.sin())
            })
            .collect()
    };
    let (a, b) = (
        circle(DVec2::new(0.5, 0.5), 0.3, 20),
        circle(DVec2::new(0.5, 1.5), 0.2, 12),
    );
    pts.extend(&a);
    pts.extend(&b);
    let mesh = mesh_of(pts.iter().copied());
    let (na, n) = (np + a.len() as u32, pts.len() as u32);
    let loops = loops_of(&mesh, np, [np..na, na..n], &ISOTROPIC);
    // Ear clipping alone leaves row vertices out.
    let mut raw: Vec<u32> = Vec::new();
    earcut::Earcut::new().earcut(loops.chart.iter().copied(), &loops.starts, &mut raw);
    assert!((0..np).any(|k| !raw.contains(&k)));
    let tris = loops.ears(&mesh).expect("a cover");
    assert!((0..n).all(|k| tris.iter().flatten().any(|&x| x == k)));
    let expected = double_area_of(&pts[..np as usize]) + double_area_of(&a) + double_area_of(&b);
    assert!((double_area(&mesh, &tris) - expected).abs() < 1e-12);
    let tris = loops.finish(&mesh, tris).expect("flipped");
    assert_eq!(tris.iter().flat_map(|t| t.1).filter(|&f| f).count(), 32);
}

#[test]
fn a_bad_triangulation_is_not_taken_for_a_cover() {
    let pts = [
        DVec2::ZERO,
        DVec2::X,
        DVec2::ONE,
        DVec2::Y,
        DVec2::new(0.4, 0.4),
        DVec2::new(0.4, 0.6),
        DVec2::new(0.6, 0.5),
    ];
    let mesh = mesh_of(pts);
    let loops = loops_of(&mesh, 4, std::iter::once(4..7), &ISOTROPIC);
    let good = loops.ears(&mesh).expect("a cover");
    assert!(loops.cover(&mesh, &good));
    // The square's two triangles ignore the hole; one triangle dropped
    // leaves a segment out; a triangle turned round is clockwise.
    assert!(!loops.cover(&mesh, &[[0, 1, 2], [0, 2, 3]]));
    assert!(!loops.cover(&mesh, &good[1..]));
    let mut turned = good.clone();
    turned[0].swap(1, 2);
    assert!(!loops.cover(&mesh, &turned));
}
