//! The watertightness check of the envelope tests: every vessel of a built scene
//! is a closed, consistently oriented 2-manifold apart from the bores of open
//! nozzles, and encloses a positive volume.

use std::collections::HashMap;

use glam::{DAffine3, DVec3};
use vesselcad::design::Design;
use vesselcad::export::{Scene, SceneNodeKind};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

/// Welds positions on a fine grid (1e-6 mm cells, neighbours checked) into ids.
struct Welder {
    cells: HashMap<[i64; 3], Vec<(DVec3, usize)>>,
    count: usize,
}

const WELD: f64 = 1e-6;

impl Welder {
    fn id(&mut self, p: DVec3) -> usize {
        let key = (p / WELD).round().as_i64vec3().to_array();
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = self.cells.get(&[key[0] + dx, key[1] + dy, key[2] + dz]) {
                        for &(q, id) in list {
                            if (q - p).length() <= WELD {
                                return id;
                            }
                        }
                    }
                }
            }
        }
        let id = self.count;
        self.count += 1;
        self.cells.entry(key).or_default().push((p, id));
        id
    }
}

/// Is the point on the bore rim of an open nozzle (the intended open end)?
pub fn on_a_bore(p: DVec3, bores: &[(DAffine3, f64, f64)]) -> bool {
    bores.iter().any(|(frame, projection, radius)| {
        let q = frame.inverse().transform_point3(p);
        (q.z - projection).abs() < 1e-6
            && (q.truncate().length() - radius).abs() < 1e-6 * radius.max(1.0)
    })
}

/// Checks one vessel of the scene; `bores` are (nozzle frame in vessel, face z, bore radius).
pub fn check_vessel(scene: &Scene, tag: &str, bores: &[(DAffine3, f64, f64)]) {
    let vessel = scene.vessels.iter().find(|v| v.tag == tag).unwrap();
    let envelope = ["shell", "head", "reducer", "boot"];
    let mut welder = Welder {
        cells: HashMap::new(),
        count: 0,
    };
    let mut edges: HashMap<(usize, usize), i32> = HashMap::new();
    let mut positions: Vec<DVec3> = Vec::new();
    let mut volume = 0.0;
    for node in &vessel.nodes {
        let kind = node.extras["kind"].as_str().unwrap_or("");
        if node.kind == SceneNodeKind::Part && !envelope.contains(&kind) {
            continue;
        }
        for patch in &node.patches {
            let ids: Vec<usize> = patch
                .mesh
                .positions()
                .map(|p| {
                    let q = node.frame.transform_point3(p);
                    let id = welder.id(q);
                    if id == positions.len() {
                        positions.push(q);
                    }
                    id
                })
                .collect();
            for t in patch.mesh.triangles() {
                let [a, b, c] = [ids[t[0] as usize], ids[t[1] as usize], ids[t[2] as usize]];
                assert!(
                    a != b && b != c && a != c,
                    "{tag}/{}/{}: degenerate triangle after welding",
                    node.id,
                    patch.name
                );
                let (pa, pb, pc) = (positions[a], positions[b], positions[c]);
                volume += pa.dot(pb.cross(pc)) / 6.0;
                for (x, y) in [(a, b), (b, c), (c, a)] {
                    *edges.entry((x.min(y), x.max(y))).or_insert(0) +=
                        if x < y { 1 } else { -1 } * 1000 + 1;
                }
            }
        }
    }
    let mut open = 0;
    for (&(a, b), &code) in &edges {
        let uses = code.rem_euclid(1000);
        let balance = (code - uses) / 1000;
        match uses {
            2 => assert_eq!(
                balance, 0,
                "{tag}: edge {:?}–{:?} is used twice in one direction (inconsistent orientation)",
                positions[a], positions[b]
            ),
            1 => {
                assert!(
                    on_a_bore(positions[a], bores) && on_a_bore(positions[b], bores),
                    "{tag}: open edge {:?}–{:?} is not on a nozzle bore",
                    positions[a],
                    positions[b]
                );
                open += 1;
            }
            n => panic!(
                "{tag}: edge {:?}–{:?} is shared by {n} triangles",
                positions[a], positions[b]
            ),
        }
    }
    assert!(
        volume > 0.0,
        "{tag}: normals point inward (volume {volume})"
    );
    let _ = open;
}

/// The bores of a vessel's open nozzles from the resolved design.
pub fn bores(design: &Design, tag: &str) -> Vec<(DAffine3, f64, f64)> {
    let resolved = vesselcad::design::resolve(design).unwrap();
    let (i, _) = design
        .vessels
        .iter()
        .enumerate()
        .find(|(_, v)| v.tag == tag)
        .unwrap();
    resolved[i]
        .nozzles
        .iter()
        .zip(&design.vessels[i].nozzles)
        .filter(|(_, d)| d.flange != vesselcad::design::FlangeDesign::Blind)
        .map(|(n, _)| {
            let pipe = vesselcad::parts::tables::pipe(n.geometry.nps);
            let wall = pipe.wall(n.geometry.schedule).unwrap();
            (
                n.frame,
                n.geometry.projection,
                pipe.outside_diameter / 2.0 - wall,
            )
        })
        .collect()
}

/// Builds the design's model and checks every vessel; returns the model.
pub fn check_design(design: &Design, tolerance: f64) -> Model {
    check_design_with(design, TessellationOptions::chord(tolerance))
}

/// [`check_design`] with any tessellation options.
pub fn check_design_with(design: &Design, options: TessellationOptions) -> Model {
    let model = Model::from_design(design, options).unwrap();
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
    let scene = model.scene();
    for v in &design.vessels {
        check_vessel(&scene, &v.tag, &bores(design, &v.tag));
    }
    model
}
