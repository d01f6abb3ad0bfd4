//! Unit tests of packing: normals, positions to 40 and 32 bits, interior
//! vertices, index widths.

use super::*;

#[test]
fn octahedral_normals_round_trip_within_1e_4_rad() {
    let mut worst = 0.0f64;
    let n = 60;
    for i in 0..=n {
        for j in 0..2 * n {
            let theta = std::f64::consts::PI * i as f64 / n as f64;
            let phi = std::f64::consts::PI * j as f64 / n as f64;
            let v = DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            let back = OctNormal::encode(v).decode();
            assert!((back.length() - 1.0).abs() < 1e-12);
            worst = worst.max(back.angle_between(v));
        }
    }
    for axis in [
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ] {
        assert!(OctNormal::encode(axis).decode().angle_between(axis) < 1e-9);
    }
    assert!(worst < 1e-4, "{worst}");
    assert!(OctNormal::encode(DVec3::ZERO).decode().is_nan());
    assert!(OctNormal::encode(DVec3::NAN).decode().is_nan());
}

#[test]
fn packing_keeps_indices_and_positions_to_40_bits() {
    let mesh = Mesh {
        positions: vec![
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1e4 + 1e-9, 0.0, -3.0),
            DVec3::new(0.0, 7.0, 1.0 / 3.0),
        ],
        normals: vec![
            DVec3::Z,
            DVec3::NEG_Y,
            DVec3::new(1.0, 1.0, -1.0).normalize(),
        ],
        indices: vec![0, 1, 2],
    };
    let packed = PackedMesh::pack(&mesh);
    // All three on the boundary: within 2^-40 of the extent (1e4 mm).
    for (a, b) in packed.positions().zip(&mesh.positions) {
        assert!(
            (a - *b).abs().max_element() <= 1e4 * 2f64.powi(-40),
            "{a} {b}"
        );
    }
    assert_eq!(packed.indices().collect::<Vec<_>>(), mesh.indices);
    assert_eq!(packed.triangles().collect::<Vec<_>>(), [[0, 1, 2]]);
    let back = packed.unpack();
    for (a, b) in back.normals.iter().zip(&mesh.normals) {
        assert!(a.angle_between(*b) < 1e-4);
    }
    let ((a0, a1), (b0, b1)) = (packed.bounds().unwrap(), mesh.bounds().unwrap());
    assert!((a0 - b0).abs().max_element() <= 1e-8 && (a1 - b1).abs().max_element() <= 1e-8);
}

#[test]
fn boundary_vertices_within_2e_40_and_interior_ones_within_2e_32_of_the_extent() {
    // A fan round an interior vertex on a 10 m patch; the rim is the boundary.
    let rim = 12;
    let centre = DVec3::new(1_234.567_890_123, -9_876.543_21, 0.1);
    let mut positions: Vec<DVec3> = (0..rim)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / rim as f64;
            centre + DVec3::new(5000.0 * a.cos(), 5000.0 * a.sin(), 1.0 / 3.0)
        })
        .collect();
    positions.insert(3, centre + DVec3::new(0.123_456_789, 1e-7, 2.0 / 3.0));
    positions.push(centre + DVec3::new(-7.654_321, 3.3, 0.7));
    let (hub, other) = (3u32, rim as u32 + 1);
    let ring: Vec<u32> = (0..=rim as u32).filter(|&i| i != hub).collect();
    let mut indices = Vec::new();
    for k in 0..rim {
        let (a, b) = (ring[k], ring[(k + 1) % rim]);
        // Split every other wedge through the second interior vertex.
        if k == 5 {
            indices.extend([hub, a, other, other, a, b, hub, other, b]);
        } else {
            indices.extend([hub, a, b]);
        }
    }
    let mesh = Mesh {
        normals: vec![DVec3::Z; positions.len()],
        positions,
        indices,
    };
    let packed = PackedMesh::pack(&mesh);
    assert_eq!(packed.boundary_count(), rim);
    assert_eq!(packed.vertex_count(), rim + 2);
    // Same triangles (by position) in the same order.
    let before: Vec<[DVec3; 3]> = mesh
        .indices
        .chunks(3)
        .map(|t| [0, 1, 2].map(|k| mesh.positions[t[k] as usize]))
        .collect();
    let after: Vec<[DVec3; 3]> = packed
        .triangles()
        .map(|t| t.map(|i| packed.position(i as usize)))
        .collect();
    let extent = 10_000.0;
    for (b, a) in before.iter().zip(&after) {
        for k in 0..3 {
            // The rim is the boundary; the two hub vertices are not.
            if (b[k] - centre).truncate().length() > 4999.0 {
                assert!((a[k] - b[k]).abs().max_element() <= extent * 2f64.powi(-40));
            } else {
                assert!((a[k] - b[k]).abs().max_element() <= extent * 2f64.powi(-32));
            }
        }
    }
    assert!(packed.heap_bytes() < mesh.heap_bytes());
}

proptest::proptest! {
    /// The per-vertex lists name the same interior vertices as counting every
    /// edge, on any triangles: repeated indices, edges used three times,
    /// triangles turned either way, vertices used by none.
    #[test]
    fn interior_vertices_agree_with_counting_edges(
        count in 3usize..24,
        raw in proptest::collection::vec((0u32..24, 0u32..24, 0u32..24), 0..40),
        degenerate in proptest::bool::weighted(0.2),
    ) {
        let n = count as u32;
        // Without repeats (the mesher's kind) unless `degenerate`.
        let indices: Vec<u32> = raw
            .iter()
            .map(|&(a, b, c)| [a % n, b % n, c % n])
            .filter(|t| degenerate || (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]))
            .flatten()
            .collect();
        proptest::prop_assert_eq!(
            super::interior_vertices(&indices, count),
            super::interior::interior_vertices_by_edges(&indices, count)
        );
    }
}

#[test]
fn interior_vertices_of_a_big_patch_agree_with_counting_edges() {
    // A 120 × 90 grid (more vertices than one parallel task takes) with
    // every seventh quad left out, so that holes' rims are boundary too.
    let (nu, nv) = (120u32, 90u32);
    let mut indices = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            if (i * 31 + j * 17) % 7 == 0 {
                continue;
            }
            let a = j * (nu + 1) + i;
            let (b, c) = (a + 1, a + nu + 1);
            indices.extend([a, b, c + 1, a, c + 1, c]);
        }
    }
    let count = ((nu + 1) * (nv + 1)) as usize;
    assert!(count > 2 * super::PARALLEL_VERTICES);
    let interior = super::interior_vertices(&indices, count);
    assert_eq!(
        interior,
        super::interior::interior_vertices_by_edges(&indices, count)
    );
    assert!(interior.iter().filter(|&&i| i).count() > count / 3);
    assert!(interior.iter().filter(|&&i| !i).count() > count / 10);
}

#[test]
fn interior_vertices_of_a_closed_fan_and_an_open_one() {
    // A closed fan of six round vertex 0 (1..=6), then an open one round 7.
    let mut indices = Vec::new();
    for k in 0..6u32 {
        indices.extend([0, 1 + k, 1 + (k + 1) % 6]);
    }
    indices.extend([7, 8, 9, 7, 9, 10]);
    let interior = super::interior_vertices(&indices, 12);
    assert!(interior[0]);
    assert!(interior[1..].iter().all(|&i| !i), "{interior:?}");
}

#[test]
fn round_small_is_round() {
    let mut cases = vec![
        0.0,
        -0.0,
        0.5,
        -0.5,
        1.5,
        -2.5,
        0.49999999999999994,
        -0.49999999999999994,
        4503599627370495.5,
        4503599627370497.0,
        -4503599627370495.5,
        (1u64 << 61) as f64 + 512.0,
        32767.0,
        -32766.5,
    ];
    let mut x = 0.123_456_789_f64;
    for _ in 0..10_000 {
        x = (x * 7919.0 + 0.3251).fract();
        cases.push((x - 0.5) * 1e12);
        cases.push((x - 0.5) * 65536.0);
        cases.push(((x - 0.5) * 1000.0).floor() + 0.5);
    }
    for c in cases {
        assert_eq!(super::round_small(c), c.round(), "{c:e}");
    }
}

#[test]
fn large_meshes_keep_u32_indices() {
    let count = (1 << 16) + 3;
    let mesh = Mesh {
        positions: (0..count).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect(),
        normals: vec![DVec3::Z; count],
        indices: vec![0, 1, (count - 1) as u32],
    };
    let packed = PackedMesh::pack(&mesh);
    assert_eq!(packed.index(2), (count - 1) as u32);
    assert!(packed.heap_bytes() > count * 19);
    // A non-finite position is kept as it is, for the exporters to report.
    let mut bad = mesh.clone();
    bad.positions[1].y = f64::NAN;
    assert!(PackedMesh::pack(&bad).position(1).y.is_nan());
}
