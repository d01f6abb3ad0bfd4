//! One entity's contribution to one view: its silhouettes and edges classified
//! visible or hidden, and its centrelines.
//!
//! The input is what the Tessellate stage left on the entity's patches (exact
//! surface, trimmed region, mesh) and its frame; the output is an [`EntityView`].
//! This is the unit of work the Project stage caches and rebuilds; what an
//! entity's views share (silhouette normal grids, boundary edges) is evaluated
//! once per entity as a [`PreparedEntity`].

use std::sync::Arc;

use glam::{DAffine3, DVec2, DVec3};

use super::classify::{Sampling, classify};
use super::edges::boundary_polylines;
use super::occlusion::Occluder;
use super::silhouette::{NormalGrid, SurfacePoint, silhouettes};
use super::{EntityView, LineKind, Projection, ViewLine};
use crate::mesh::Mesh;
use crate::mesh::cdt::Region;
use crate::parts::{Analytic, Patch};

/// One patch of an entity as the Project stage sees it.
#[derive(Clone, Debug)]
pub struct PatchInput {
    /// The exact patch (part frame).
    pub patch: Arc<Patch>,
    /// Its trimmed (u, v) region, when laid out.
    pub region: Option<Arc<Region>>,
    /// Its mesh (part frame).
    pub mesh: Arc<Mesh>,
}

/// A part or nozzle: its stable id, part → vessel frame and patches.
#[derive(Clone, Debug)]
pub struct EntityInput {
    /// Stable id, `tag/id`.
    pub id: String,
    /// Part (nozzle) frame → vessel frame.
    pub frame: DAffine3,
    /// Its patches, a nozzle's pad last.
    pub patches: Vec<PatchInput>,
}

/// How views are sampled, from the vessel's size and the chordal tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewSettings {
    /// Largest silhouette grid step on the surface, mm.
    pub silhouette_spacing: f64,
    /// Hidden-line sampling.
    pub sampling: Sampling,
}

impl ViewSettings {
    /// Settings for a vessel whose largest extent is `size` mm, meshed to the
    /// chordal `tolerance` mm.
    pub fn for_vessel(size: f64, tolerance: f64) -> Self {
        let size = size.max(1.0);
        Self {
            silhouette_spacing: (size / 400.0).max(4.0 * tolerance),
            sampling: Sampling {
                step: size / 600.0,
                nudge: 2.0 * tolerance + 1e-6 * size,
                depth_tolerance: 2.0 * tolerance + 1e-6 * size,
            },
        }
    }
}

/// Bounds of the entity's meshes in the view, `None` when it has none.
pub fn footprint(entity: &EntityInput, projection: &Projection) -> Option<(DVec2, DVec2)> {
    let mut it = entity.patches.iter().flat_map(|p| {
        p.mesh
            .positions
            .iter()
            .map(|&q| projection.project(entity.frame.transform_point3(q)))
    });
    let first = it.next()?;
    Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
}

/// What an entity's views share, whatever the view: per patch, its normal grid
/// for silhouettes and its boundary polylines (vessel frame). Built once for the
/// views of an entity rebuilt together.
#[derive(Clone, Debug)]
pub struct PreparedEntity {
    patches: Vec<PreparedPatch>,
}

#[derive(Clone, Debug)]
struct PreparedPatch {
    grid: NormalGrid,
    closed_u: bool,
    boundaries: Vec<Vec<SurfacePoint>>,
}

impl PreparedEntity {
    /// Evaluates the view-independent part of `entity`'s lines.
    pub fn new(entity: &EntityInput, settings: &ViewSettings) -> Self {
        let patches = entity
            .patches
            .iter()
            .map(|p| PreparedPatch {
                grid: NormalGrid::new(&p.patch.surface, settings.silhouette_spacing),
                closed_u: crate::mesh::closed_in_u(&p.patch.surface),
                boundaries: boundary_polylines(&p.mesh, &entity.frame),
            })
            .collect();
        Self { patches }
    }
}

/// The entity's lines in one view: silhouettes and boundary edges, visible or
/// hidden against `occluder`, then its centrelines.
pub fn build_entity_view(
    entity: &EntityInput,
    prepared: &PreparedEntity,
    projection: &Projection,
    occluder: &Occluder,
    settings: &ViewSettings,
) -> EntityView {
    let mut lines = Vec::new();
    for (p, prep) in entity.patches.iter().zip(&prepared.patches) {
        for s in silhouettes(
            &p.patch.surface,
            &prep.grid,
            p.region.as_deref(),
            &entity.frame,
            projection.toward_viewer,
            prep.closed_u,
        ) {
            classify(&s, projection, occluder, &settings.sampling, &mut lines);
        }
        for b in &prep.boundaries {
            classify(b, projection, occluder, &settings.sampling, &mut lines);
        }
    }
    lines.extend(centrelines(entity, projection));
    EntityView {
        id: entity.id.clone(),
        lines,
    }
}

/// An axis of revolution of a patch, part frame: a point on it and its direction.
fn axis_of(analytic: &Analytic) -> Option<(DVec3, DVec3)> {
    match *analytic {
        Analytic::Cylinder { point, axis, .. } => Some((point, axis)),
        Analytic::Cone { apex, axis, .. } => Some((apex, axis)),
        Analytic::Torus { center, axis, .. } | Analytic::Spheroid { center, axis, .. } => {
            Some((center, axis))
        }
        _ => None,
    }
}

/// Centrelines of every distinct axis of revolution among the entity's patches,
/// over the patches' extent along it plus an overshoot; an axis seen end-on is
/// drawn as a cross.
fn centrelines(entity: &EntityInput, projection: &Projection) -> Vec<ViewLine> {
    // (point on axis, direction, extent along it, largest radius), vessel frame.
    let mut axes: Vec<(DVec3, DVec3, f64, f64, f64)> = Vec::new();
    for p in &entity.patches {
        let Some((point, dir)) = axis_of(&p.patch.analytic) else {
            continue;
        };
        let point = entity.frame.transform_point3(point);
        let dir = (entity.frame.matrix3 * dir).normalize();
        let (mut lo, mut hi, mut radius) = (f64::MAX, f64::MIN, 0.0f64);
        for &q in &p.mesh.positions {
            let q = entity.frame.transform_point3(q);
            let t = (q - point).dot(dir);
            lo = lo.min(t);
            hi = hi.max(t);
            radius = radius.max((q - point - dir * t).length());
        }
        if lo > hi {
            continue;
        }
        let same = axes.iter_mut().find(|(o, d, ..)| {
            d.cross(dir).length() < 1e-9 && (point - *o).cross(*d).length() < 1e-6
        });
        match same {
            Some((o, d, a, b, r)) => {
                let shift = (point - *o).dot(*d);
                let (l, h) = if d.dot(dir) > 0.0 {
                    (lo + shift, hi + shift)
                } else {
                    (shift - hi, shift - lo)
                };
                *a = a.min(l);
                *b = b.max(h);
                *r = r.max(radius);
            }
            None => axes.push((point, dir, lo, hi, radius)),
        }
    }
    let mut out = Vec::new();
    for (o, d, lo, hi, r) in axes {
        let along = projection.project(d);
        if along.length() < 1e-6 {
            let c = projection.project(o);
            let arm = 1.15 * r;
            out.push(ViewLine {
                kind: LineKind::Centre,
                points: vec![c - DVec2::X * arm, c + DVec2::X * arm],
            });
            out.push(ViewLine {
                kind: LineKind::Centre,
                points: vec![c - DVec2::Y * arm, c + DVec2::Y * arm],
            });
        } else {
            let over = 0.08 * (hi - lo) + 0.15 * r;
            let a = projection.project(o + d * (lo - over));
            let b = projection.project(o + d * (hi + over));
            if (b - a).length() > 1e-9 {
                out.push(ViewLine {
                    kind: LineKind::Centre,
                    points: vec![a, b],
                });
            }
        }
    }
    out
}

/// Builds the views of the `selected` entities (indices into `entities`) in all
/// four `projections`, against occluders made of every entity's meshes: what the
/// Project stage does for a vessel, without the ECS (benchmarks, tools).
pub fn build_views(
    entities: &[EntityInput],
    projections: &[Projection; 4],
    settings: &ViewSettings,
    selected: &[usize],
) -> Vec<[EntityView; 4]> {
    use rayon::prelude::*;
    let occluders: Vec<Occluder> = projections
        .par_iter()
        .map(|p| {
            Occluder::build(
                p,
                entities
                    .iter()
                    .flat_map(|e| e.patches.iter().map(move |q| (&*q.mesh, e.frame))),
            )
        })
        .collect();
    let prepared: Vec<PreparedEntity> = selected
        .par_iter()
        .map(|&i| PreparedEntity::new(&entities[i], settings))
        .collect();
    let jobs: Vec<(usize, usize)> = (0..selected.len())
        .flat_map(|n| (0..4).map(move |k| (n, k)))
        .collect();
    let mut built: Vec<EntityView> = jobs
        .par_iter()
        .map(|&(n, k)| {
            let entity = &entities[selected[n]];
            build_entity_view(
                entity,
                &prepared[n],
                &projections[k],
                &occluders[k],
                settings,
            )
        })
        .collect();
    let mut out = Vec::with_capacity(selected.len());
    while built.len() >= 4 {
        let rest = built.split_off(4);
        let four: [EntityView; 4] = match built.try_into() {
            Ok(f) => f,
            Err(_) => break,
        };
        out.push(four);
        built = rest;
    }
    out
}
