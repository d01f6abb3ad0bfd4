//! The incremental model against a from-scratch build of its design: the two must
//! write the same GLB bytes. On failure the message names the first node that
//! differs (`tag` or `tag/id`) and what differs in it, not just "the bytes differ".

use vesselcad::export::{Scene, build_scene, write_glb};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

/// Asserts that `model`'s GLB equals the GLB of [`build_scene`] on its design.
pub fn assert_matches_full_build(model: &Model, options: &TessellationOptions) {
    let incremental_scene = model.scene();
    let full_scene = build_scene(&model.design(), options).expect("the design builds");
    let incremental = write_glb(&incremental_scene).expect("the model exports");
    let full = write_glb(&full_scene).expect("the full build exports");
    if incremental != full {
        panic!(
            "incremental GLB differs from the full build: {}",
            first_difference(&incremental_scene, &full_scene).unwrap_or_else(|| format!(
                "the scenes agree node by node, but the bytes differ ({} against {} bytes)",
                incremental.len(),
                full.len()
            ))
        );
    }
}

/// The first node where two scenes differ, and how; `None` if they agree. Within a
/// vessel, frames, extras and patch lists are compared before meshes.
pub fn first_difference(incremental: &Scene, full: &Scene) -> Option<String> {
    let tags = |s: &Scene| s.vessels.iter().map(|v| v.tag.clone()).collect::<Vec<_>>();
    if tags(incremental) != tags(full) {
        return Some(format!(
            "vessels {:?} against {:?}",
            tags(incremental),
            tags(full)
        ));
    }
    for (a, b) in incremental.vessels.iter().zip(&full.vessels) {
        if a.frame != b.frame {
            return Some(format!(
                "{}: frame {:?} against {:?}",
                a.tag, a.frame, b.frame
            ));
        }
        if a.extras != b.extras {
            return Some(format!(
                "{}: extras {} against {}",
                a.tag, a.extras, b.extras
            ));
        }
        let ids =
            |v: &[vesselcad::export::SceneNode]| v.iter().map(|n| n.id.clone()).collect::<Vec<_>>();
        if ids(&a.nodes) != ids(&b.nodes) {
            return Some(format!(
                "{}: nodes {:?} against {:?}",
                a.tag,
                ids(&a.nodes),
                ids(&b.nodes)
            ));
        }
        for (m, n) in a.nodes.iter().zip(&b.nodes) {
            let node = format!("{}/{}", a.tag, m.id);
            if m.kind != n.kind {
                return Some(format!("{node}: kind {:?} against {:?}", m.kind, n.kind));
            }
            if m.frame != n.frame {
                return Some(format!("{node}: frame {:?} against {:?}", m.frame, n.frame));
            }
            if m.extras != n.extras {
                return Some(format!("{node}: extras {} against {}", m.extras, n.extras));
            }
            let names = |p: &[vesselcad::export::ScenePatch]| {
                p.iter().map(|p| p.name.clone()).collect::<Vec<_>>()
            };
            if names(&m.patches) != names(&n.patches) {
                return Some(format!(
                    "{node}: patches {:?} against {:?}",
                    names(&m.patches),
                    names(&n.patches)
                ));
            }
        }
        // Meshes last: a host's mesh changes because a nozzle's frame did, and the
        // nozzle is the news.
        for (m, n) in a.nodes.iter().zip(&b.nodes) {
            for (p, q) in m.patches.iter().zip(&n.patches) {
                if p.mesh != q.mesh {
                    return Some(format!(
                        "{}/{}, patch {}: mesh of {} triangles against {} in the full build",
                        a.tag,
                        m.id,
                        p.name,
                        p.mesh.triangle_count(),
                        q.mesh.triangle_count()
                    ));
                }
            }
        }
    }
    None
}
