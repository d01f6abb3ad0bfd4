//! Nozzles in the FE shell mesh: radial, hillside, tangential and inclined
//! nozzles on a cylindrical course and nozzles on the centre of ellipsoidal,
//! torispherical and hemispherical heads, each neck meshed conforming with its
//! host round the exact intersection curve of the two mid-surfaces, a pad as a
//! thicker shell region, every node on its exact surface; and, solved by
//! CalculiX, the peak stress at the junction above the membrane stress and
//! converging under refinement (the table goes to the test output). The solver
//! tests are skipped, with a message, where `ccx` is absent.

mod common;

use common::fem::{assert_good, model, shell_nozzle, solve, with_nozzles};
use glam::DVec3;
use vesselcad::design::Design;
use vesselcad::fem::FeMesh;
use vesselcad::fem::results::intensity;

#[test]
fn radial_nozzle_with_pad_meshes_conforming_on_exact_surfaces() {
    let design = shell_nozzle(r#", "pad": { "od": 420, "thickness": 10 }"#);
    for size in [80.0, 40.0] {
        let m = model(&design, size);
        let mesh = &m.mesh;
        assert!(mesh.notes.is_empty(), "{:?}", mesh.notes);
        assert_good(&format!("nozzle at size {size}"), mesh);
        let neck = mesh
            .parts
            .iter()
            .position(|p| p.id == "N1")
            .expect("neck part");
        let pad = mesh
            .parts
            .iter()
            .position(|p| p.id == "N1/pad")
            .expect("pad part");
        assert_eq!(mesh.parts[neck].name, "V-1/N1");
        assert!((mesh.parts[pad].thickness - 20.0).abs() < 1e-12);
        assert_eq!(mesh.necks.len(), 1);
        // The neck shares its whole first ring with the course (and pad).
        let shell: Vec<usize> = (0..mesh.parts.len())
            .filter(|&k| k != neck)
            .flat_map(|k| mesh.part_nodes(k))
            .collect();
        let shared = mesh
            .part_nodes(neck)
            .into_iter()
            .filter(|n| shell.contains(n))
            .count();
        let ring = mesh.necks[0].nodes.len();
        assert_eq!(shared, 2 * ring, "curve corner and mid-side nodes shared");
        // Every node on its exact mid-surface: the course R = 495, the neck
        // r = (219.1 − 8.18) / 2 about the axis at 60° clockwise from north
        // (+y) through z = 750.
        let axis = DVec3::new(60f64.to_radians().sin(), 60f64.to_radians().cos(), 0.0);
        let r = 0.5 * (219.1 - 8.18);
        for (k, part) in mesh.parts.iter().enumerate() {
            for n in mesh.part_nodes(k) {
                let p = mesh.nodes[n];
                if part.id == "N1" {
                    let rel = p - DVec3::new(0.0, 0.0, 750.0);
                    let off = (rel - axis * rel.dot(axis)).length();
                    assert!((off - r).abs() < 1e-9, "neck node {n} at {p}: {off}");
                    assert!(
                        p.x.hypot(p.y) >= 495.0 - 1e-9,
                        "neck node {n} inside the course"
                    );
                } else if part.id == "S1" || part.id == "N1/pad" {
                    let d = (p.x.hypot(p.y) - 495.0).abs();
                    assert!(d < 1e-9, "{} node {n} at {p} is {d} mm off", part.name);
                }
            }
        }
    }
}

/// The peak membrane-plus-bending stress intensity of the course and the neck
/// near the junction is well above the course's membrane P·R/t = 49.5 MPa (the
/// stress concentration of an unreinforced opening) and settles as the mesh is
/// refined: the last two refinements differ by less than 10 %.
#[test]
fn junction_peak_above_membrane_and_converging() {
    let design = shell_nozzle("");
    let mut table = Vec::new();
    // CI solves two sizes; `cargo run --example fem_convergence` the full table.
    for size in [100.0, 60.0] {
        let m = model(&design, size);
        let Some(results) = solve(&m, &format!("nozzle{}", size as u32)) else {
            return;
        };
        let neck = m
            .mesh
            .parts
            .iter()
            .position(|p| p.id == "N1")
            .expect("neck");
        let course = m
            .mesh
            .parts
            .iter()
            .position(|p| p.id == "S1")
            .expect("course");
        let peak = |k: usize| {
            m.mesh
                .part_nodes(k)
                .into_iter()
                .map(|n| results[n].surface_intensity)
                .fold(0.0, f64::max)
        };
        // Membrane away from the nozzle and heads: opposite side, mid-height.
        let far = m
            .mesh
            .part_nodes(course)
            .into_iter()
            .filter(|&n| {
                let p = m.mesh.nodes[n];
                p.y < -300.0 && (p.z - 750.0).abs() < 150.0
            })
            .map(|n| intensity(results[n].membrane))
            .fold(0.0, f64::max);
        table.push((size, m.mesh.elements.len(), far, peak(course), peak(neck)));
    }
    eprintln!("size mm | elements | far Pm MPa | course peak Pm+Pb | neck peak Pm+Pb");
    for (size, e, far, c, n) in &table {
        eprintln!("{size:7.0} | {e:8} | {far:10.2} | {c:17.2} | {n:15.2}");
    }
    for &(_, _, far, c, _) in &table {
        assert!((far - 49.5).abs() < 2.0, "far membrane {far}");
        assert!(c > 1.5 * far, "peak {c} not above membrane {far}");
    }
    let k = table.len();
    let (a, b) = (table[k - 2].3, table[k - 1].3);
    assert!(
        (a - b).abs() <= 0.1 * b,
        "peaks {a} and {b} differ by more than 10 %"
    );
}

/// Distance of `p` from the line through `o` along unit `d`.
fn off_axis(p: DVec3, o: DVec3, d: DVec3) -> f64 {
    let rel = p - o;
    (rel - d * rel.dot(d)).length()
}

/// Asserts that `mesh` has no notes, is conforming and well shaped, that the
/// neck `N1` shares its whole first ring (corners and mid-sides) with its host,
/// and that every neck node is `r` from the axis through `o` along `d` and every
/// node of `host` (and its pad) satisfies `on_host` to 1e-9 mm.
fn assert_neck(
    what: &str,
    mesh: &FeMesh,
    (o, d, r): (DVec3, DVec3, f64),
    host: &str,
    on_host: impl Fn(DVec3) -> f64,
) {
    assert!(mesh.notes.is_empty(), "{what}: {:?}", mesh.notes);
    assert_good(what, mesh);
    let neck = mesh
        .parts
        .iter()
        .position(|p| p.id == "N1")
        .expect("neck part");
    let others: Vec<usize> = (0..mesh.parts.len())
        .filter(|&k| k != neck)
        .flat_map(|k| mesh.part_nodes(k))
        .collect();
    let shared = mesh
        .part_nodes(neck)
        .into_iter()
        .filter(|n| others.contains(n))
        .count();
    assert_eq!(mesh.necks.len(), 1, "{what}");
    assert_eq!(
        shared,
        2 * mesh.necks[0].nodes.len(),
        "{what}: the intersection's corner and mid-side nodes are shared"
    );
    let pad = format!("{host}/pad");
    for (k, part) in mesh.parts.iter().enumerate() {
        for n in mesh.part_nodes(k) {
            let p = mesh.nodes[n];
            let off = if part.id == "N1" {
                (off_axis(p, o, d) - r).abs()
            } else if part.id == host || part.id == pad || part.id == "N1/pad" {
                on_host(p).abs()
            } else {
                continue;
            };
            assert!(
                off < 1e-9,
                "{what}: {} node {n} at {p} is {off} mm off",
                part.name
            );
        }
    }
}

/// Hillside, tangential and inclined nozzles: the neck's nodes on its
/// cylinder, the course's on R = 495, the intersection shared.
#[test]
fn non_radial_nozzles_mesh_conforming_on_exact_surfaces() {
    let r = 0.5 * (219.1 - 8.18);
    let (sin, cos) = 60f64.to_radians().sin_cos();
    // Orientation 60° clockwise from north (+y); sideways towards 150°.
    let n = DVec3::new(sin, cos, 0.0);
    let a = DVec3::new(150f64.to_radians().sin(), 150f64.to_radians().cos(), 0.0);
    let cases = [
        ("hillside", r#", "offset": 200"#, 200.0, 0.0),
        (
            "tangential",
            r#", "offset": -330, "pad": { "od": 300, "thickness": 8 }"#,
            -330.0,
            0.0,
        ),
        ("inclined", r#", "inclination": 30"#, 0.0, 30.0),
        (
            "inclined hillside",
            r#", "offset": 150, "inclination": -20"#,
            150.0,
            -20.0,
        ),
    ];
    for (what, extra, offset, incl) in cases {
        let design = shell_nozzle(extra);
        let (si, ci) = f64::to_radians(incl).sin_cos();
        let d = n * ci + DVec3::Z * si;
        let o = DVec3::new(0.0, 0.0, 750.0) + a * offset;
        for size in [80.0, 40.0] {
            let m = model(&design, size);
            assert_neck(
                &format!("{what} at {size}"),
                &m.mesh,
                (o, d, r),
                "S1",
                |p| p.x.hypot(p.y) - 495.0,
            );
        }
    }
}

/// A vessel with 2:1, torispherical or hemispherical heads and NPS 8 nozzles
/// (one with a pad) on the centre of both heads.
fn head_nozzles(head: &str) -> Design {
    let nozzles = r#"{ "mark": "N1", "size": 8, "rating": 150, "host": "H2", "orientation": 0,
           "projection": 800, "pad": { "od": 400, "thickness": 10 } },
        { "mark": "N2", "size": 6, "rating": 150, "host": "H1", "orientation": 0,
           "projection": 750 }"#;
    with_nozzles(head, 1000.0, 1500.0, 10.0, 1000.0, nozzles)
}

/// Centre nozzles on each head kind: the necks on their cylinders about the
/// vessel axis, the head nodes on the head's mid-surface, the intersection
/// circle shared; no cap is left at either pole.
#[test]
fn centre_head_nozzles_mesh_conforming_on_exact_surfaces() {
    let r = 0.5 * (219.1 - 8.18);
    for (head, on_head) in [
        (
            r#""shape": "ellipsoidal""#,
            // Semi-axes 495 × 245 about the tangent line z = 1500.
            (|p: DVec3| {
                let (x, z) = (p.x.hypot(p.y) / 495.0, (p.z - 1500.0) / 245.0);
                (x * x + z * z).sqrt() - 1.0
            }) as fn(DVec3) -> f64,
        ),
        (r#""shape": "hemispherical""#, |p: DVec3| {
            (p - DVec3::new(0.0, 0.0, 1500.0)).length() - 495.0
        }),
        (r#""shape": "torispherical""#, |_| 0.0),
    ] {
        let design = head_nozzles(head);
        for size in [80.0, 40.0] {
            let m = model(&design, size);
            let mesh = &m.mesh;
            let what = format!("{head} at {size}");
            assert!(mesh.notes.is_empty(), "{what}: {:?}", mesh.notes);
            assert_good(&what, mesh);
            assert_eq!(mesh.necks.len(), 2, "{what}");
            let names: Vec<&str> = mesh.parts.iter().map(|p| p.id.as_str()).collect();
            for id in ["N1", "N2", "N1/pad"] {
                assert!(names.contains(&id), "{what}: {names:?}");
            }
            let h2: Vec<usize> = ["H2", "N1/pad"]
                .iter()
                .filter_map(|id| mesh.parts.iter().position(|p| p.id == *id))
                .flat_map(|k| mesh.part_nodes(k))
                .collect();
            let neck = mesh.parts.iter().position(|p| p.id == "N1").expect("N1");
            let neck_nodes = mesh.part_nodes(neck);
            let shared = neck_nodes.iter().filter(|n| h2.contains(n)).count();
            assert_eq!(
                shared,
                2 * mesh.necks[0].nodes.len().max(mesh.necks[1].nodes.len())
            );
            for &n in &neck_nodes {
                let p = mesh.nodes[n];
                assert!((p.x.hypot(p.y) - r).abs() < 1e-9, "{what}: neck node {p}");
                assert!(
                    p.z >= 1500.0,
                    "{what}: neck node {p} below the tangent line"
                );
            }
            for &n in &h2 {
                let p = mesh.nodes[n];
                assert!(
                    on_head(p).abs() < 1e-9,
                    "{what}: head node {p} off the head"
                );
                assert!(
                    p.x.hypot(p.y) >= r - 1e-9,
                    "{what}: head node {p} inside the neck"
                );
            }
        }
    }
}

/// Solved by CalculiX: the peak membrane-plus-bending stress intensity at a
/// hillside nozzle's and at a centre head nozzle's junction is well above the
/// membrane stress of the host away from it.
#[test]
fn non_radial_and_head_nozzle_peaks_above_membrane() {
    for (what, design, host, far) in [
        ("hillside", shell_nozzle(r#", "offset": 200"#), "S1", 49.5),
        (
            "head centre",
            head_nozzles(r#""shape": "hemispherical""#),
            "H2",
            24.75,
        ),
    ] {
        let m = model(&design, 60.0);
        let Some(results) = solve(&m, &what.replace(' ', "_")) else {
            return;
        };
        let part = |id: &str| m.mesh.parts.iter().position(|p| p.id == id).expect(id);
        let peak = |k: usize| {
            m.mesh
                .part_nodes(k)
                .into_iter()
                .map(|n| results[n].surface_intensity)
                .fold(0.0, f64::max)
        };
        let (host_peak, neck_peak) = (peak(part(host)), peak(part("N1")));
        eprintln!(
            "{what}: host {host} peak Pm+Pb {host_peak:.2} MPa, neck {neck_peak:.2} MPa, membrane {far} MPa"
        );
        assert!(
            host_peak.max(neck_peak) > 1.5 * far,
            "{what}: peak {host_peak} / {neck_peak} not above membrane {far}"
        );
    }
}
