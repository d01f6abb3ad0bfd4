//! The entry points: mesh one region of a patch, from validated input through
//! seeding, spade's constrained triangulation and chordal refinement to the welded
//! output.

use rayon::prelude::*;

use super::general::{initial, refine, seed};
use super::output::{RegionMesh, finish};
use super::patch::{PatchInfo, wants_transpose};
use super::plan::plan;
use super::structured::kept::{KeptCavities, Memo};
use super::trimesh::TriMesh;
use super::{CdtError, MeshStats, Region, metric::Sizing, structured};
use crate::mesh::{Mesh, TessellationOptions};
use crate::nurbs::NurbsSurface;
use crate::parts::{Analytic, Patch};

/// Share of the tolerance the seed lattice aims at, leaving room for the lattice's
/// irregularities so that refinement has little to add.
const SEED_SHARE: f64 = 0.96;

/// Meshes the part of `surface` inside `region` to `options` (chordal tolerance,
/// angle tolerance, maximum edge length).
///
/// The loop vertices are kept as they are and no vertex is added on a loop segment
/// (only on a side that collapses to a point, where every vertex welds into the
/// pole); every triangle's deviation from the surface at its parametric centroid
/// and at its interior edge midpoints is within `options.tolerance`. Positions are
/// exact points `S(u, v)` (u wrapped on a surface closed in u), normals the exact
/// normals, triangles counter-clockwise in (u, v) so they face along `S_u × S_v`.
/// Vertices at one 3D point (a pole, the two sides of a seam) are welded into one.
/// A surface whose collapsed side is a u side, or that is closed in v only, is
/// meshed with u and v exchanged internally (so there v may wrap instead of u);
/// the result is expressed in the surface's own (u, v) all the same.
/// Deterministic: the same input gives the same mesh.
pub fn mesh_region(
    surface: &NurbsSurface,
    region: &Region,
    options: &TessellationOptions,
) -> Result<(Mesh, MeshStats), CdtError> {
    let out = mesh_region_with_uvs(surface, region, options)?;
    Ok((out.mesh, out.stats))
}

/// [`mesh_region`] of a vessel patch: the same mesh contract, with the deviation
/// probes measured against the patch's analytic surface in closed form (much
/// cheaper than inverting the NURBS, and equal to it to rounding since the patch
/// lies on that surface).
///
/// Returns the whole [`RegionMesh`]: its `on_loops` flags let the packer skip
/// counting the mesh's edges ([`PackedMesh::pack_marked`](crate::mesh::PackedMesh::pack_marked)).
pub fn mesh_patch_region(
    patch: &Patch,
    region: &Region,
    options: &TessellationOptions,
) -> Result<RegionMesh, CdtError> {
    let memo = Memo::default();
    Ok(mesh_with(&patch.surface, Some(&patch.analytic), region, options, memo)?.0)
}

/// [`mesh_patch_region`] for a surface and the analytic surface it lies on.
pub fn mesh_region_on(
    surface: &NurbsSurface,
    analytic: &Analytic,
    region: &Region,
    options: &TessellationOptions,
) -> Result<(Mesh, MeshStats), CdtError> {
    let (out, _) = mesh_with(surface, Some(analytic), region, options, Memo::default())?;
    Ok((out.mesh, out.stats))
}

/// [`mesh_patch_region`] of a patch meshed before: the cavities `kept` from
/// that meshing whose inputs come out the same bit for bit are taken instead of
/// triangulated again (the mesh is the same as without them, see `kept`).
/// `surface` is the patch's [`surface_key`](crate::mesh::surface_key) at
/// `options`: a kept cavity screened on the same key keeps its verdicts.
/// Returns the cavities this meshing met, to keep for the next one.
pub fn mesh_patch_region_keeping(
    patch: &Patch,
    region: &Region,
    options: &TessellationOptions,
    kept: Option<&KeptCavities>,
    surface: u128,
) -> Result<(RegionMesh, KeptCavities), CdtError> {
    let memo = Memo::new(kept, true).on_surface(surface);
    mesh_with(&patch.surface, Some(&patch.analytic), region, options, memo)
}

/// [`mesh_region`] that also returns the (u, v) of every output vertex.
pub fn mesh_region_with_uvs(
    surface: &NurbsSurface,
    region: &Region,
    options: &TessellationOptions,
) -> Result<RegionMesh, CdtError> {
    Ok(mesh_with(surface, None, region, options, Memo::default())?.0)
}

/// Validates, transposes when the surface wants it, and meshes.
fn mesh_with(
    surface: &NurbsSurface,
    analytic: Option<&Analytic>,
    region: &Region,
    options: &TessellationOptions,
    mut memo: Memo,
) -> Result<(RegionMesh, KeptCavities), CdtError> {
    options.validate()?;
    region.validate()?;
    if wants_transpose(surface) {
        let out = mesh_oriented(
            &surface.transposed(),
            analytic,
            &region.transposed(),
            options,
            &mut memo,
        )?;
        return Ok((out.transposed(), memo.into_kept()));
    }
    let out = mesh_oriented(surface, analytic, region, options, &mut memo)?;
    Ok((out, memo.into_kept()))
}

/// Meshes a validated region of a surface whose rows run along u.
fn mesh_oriented(
    surface: &NurbsSurface,
    analytic: Option<&Analytic>,
    region: &Region,
    options: &TessellationOptions,
    memo: &mut Memo,
) -> Result<RegionMesh, CdtError> {
    let (lo, hi) = region.bounds();
    let info = PatchInfo::new(surface, lo, hi, |cap| {
        Sizing::new(options, SEED_SHARE * SEED_SHARE, cap)
    })
    .with_analytic(analytic);
    let mut stats = MeshStats::default();
    // The options' vertex budget bounds each region (seeds, loop vertices and
    // insertions); beyond it meshing stops with `CdtError::BudgetExceeded`.
    let budget = options.max_vertices.saturating_sub(region.vertex_count());
    // The seeds' and the structured path's errors count what they place within
    // `budget`; the error names the option and counts the loop vertices too.
    let named = |e: CdtError| match e {
        CdtError::BudgetExceeded { needed, .. } => CdtError::BudgetExceeded {
            max_vertices: options.max_vertices,
            needed: needed.saturating_add(region.vertex_count()),
        },
        e => e,
    };
    let plan = plan(&info, region);
    if let Some((path, mut rings)) =
        structured::triangulate(&info, region, &plan, options, budget, memo).map_err(named)?
        && rings
            .seam
            .iter()
            .all(|&(t, i)| refine::edge_within(&info, &rings.mesh, t, i, options))
    {
        structured::fix_seam(&mut rings.mesh, &rings.seam);
        stats.refinement_insertions += rings.insertions;
        stats.cavities_reused += memo.reused;
        stats.cavity_fills = memo.fills;
        stats.path = path;
        // Every triangle screened within: nothing to measure (nor the loops'
        // allowances to work out).
        if rings
            .within
            .as_deref()
            .is_some_and(|w| w.iter().all(|&x| x))
        {
            return finish(&info, &rings.mesh, rings.copies.as_ref(), stats);
        }
        let assessment = refine::assess_all(&info, &rings.mesh, options, rings.within.as_deref());
        if assessment.all_good() {
            return finish(&info, &rings.mesh, rings.copies.as_ref(), stats);
        }
        // Give the rings metrics and neighbour links and refine what is left.
        let mut mesh = rings.mesh;
        mesh.verts
            .par_iter_mut()
            .with_min_len(super::MIN_VERTICES)
            .filter(|v| v.metric.uu.is_nan())
            .for_each(|v| info.fill_metric(v));
        let fixed: rustc_hash::FxHashSet<(u32, u32)> = (0..mesh.tris.len() as u32)
            .flat_map(|t| (0..3).map(move |i| (t, i)))
            .filter(|&(t, i)| mesh.fixed[t as usize][i])
            .map(|(t, i)| mesh.edge(t, i))
            .collect();
        let TriMesh { verts, tris, .. } = mesh;
        let mut mesh = TriMesh::new(verts, tris, |a, b| {
            fixed.contains(&(a, b)) || fixed.contains(&(b, a))
        });
        refine::refine_assessed(
            &info,
            &mut mesh,
            options.max_vertices,
            &mut stats,
            assessment,
        )?;
        return finish(&info, &mesh, None, stats);
    }
    // The general path: no cavity of the structured attempt is in this mesh.
    memo.restart();
    let seeds = seed::seeds(&info, region, budget).map_err(named)?;
    let poled = seed::with_pole_vertices(&info, region, &seeds);
    let region = poled.as_ref().unwrap_or(region);
    let mut mesh = initial::triangulate(&info, region, &seeds, &mut stats)?;
    refine::refine(&info, &mut mesh, options, options.max_vertices, &mut stats)?;
    finish(&info, &mesh, None, stats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::cdt::quarter::turn;
    use crate::parts::Patch;
    use crate::parts::heads::{Head, HeadKind};

    /// The structured mesh of the whole of `patch` (transposed when the mesher
    /// would), handed to `f` with the patch's facts; nothing when the patch takes
    /// the general path.
    fn with_rings(
        patch: &Patch,
        options: &TessellationOptions,
        f: impl FnOnce(&PatchInfo, &crate::mesh::cdt::structured::lattice::Rings),
    ) {
        let region =
            crate::mesh::patch_region(&patch.surface, options, &[], None).expect("a region");
        let (surface, region) = if wants_transpose(&patch.surface) {
            (patch.surface.transposed(), region.transposed())
        } else {
            (patch.surface.clone(), region)
        };
        let (lo, hi) = region.bounds();
        let info = PatchInfo::new(&surface, lo, hi, |cap| {
            Sizing::new(options, SEED_SHARE * SEED_SHARE, cap)
        })
        .with_analytic(Some(&patch.analytic));
        let plan = plan(&info, &region);
        let rings = structured::triangulate(
            &info,
            &region,
            &plan,
            options,
            options.max_vertices,
            &mut Memo::default(),
        )
        .expect("meshed");
        if let Some((_, rings)) = rings {
            f(&info, &rings);
        }
    }

    /// The whole turns of every head shape's patches: each triangle flagged as an
    /// exact copy is, bit for bit, the quarter turn of the first quarter's
    /// triangle it copies, and the output is the same as with every triangle
    /// checked. Pure rotations give the checks the same numbers, so only the
    /// first quarter's copies need checking.
    #[test]
    fn a_whole_turn_is_checked_once_per_copied_triangle() {
        let options = TessellationOptions::chord(1.0);
        let (mut copied, mut total) = (0, 0);
        let kinds = [
            HeadKind::Hemispherical,
            HeadKind::TWO_TO_ONE,
            HeadKind::asme_fd(2400.0),
        ];
        for kind in kinds {
            for patch in Head::new(2400.0, kind).patches().expect("a head") {
                with_rings(&patch, &options, |info, rings| {
                    let Some(copies) = &rings.copies else {
                        return;
                    };
                    let mesh = &rings.mesh;
                    let m = copies.per_quarter;
                    for t in m..mesh.tris.len() {
                        if !copies.exact[t % m] {
                            continue;
                        }
                        copied += 1;
                        for i in 0..3 {
                            let p = mesh.verts[mesh.tris[t][i] as usize].point;
                            let first = mesh.verts[mesh.tris[t % m][i] as usize].point;
                            assert_eq!(p.to_array(), turn(first, t / m).to_array());
                        }
                    }
                    total += mesh.tris.len() - m;
                    let once =
                        finish(info, mesh, Some(copies), MeshStats::default()).expect("once");
                    let every = finish(info, mesh, None, MeshStats::default()).expect("every");
                    assert_eq!(once.mesh, every.mesh);
                    assert_eq!(once.uvs, every.uvs);
                    assert_eq!(once.stats, every.stats);
                });
            }
        }
        // Most of the later quarters' triangles are copies.
        assert!(4 * copied > 3 * total, "{copied} of {total}");
    }

    /// On a plane, cylinder or sphere the closed-form bound decides: a
    /// triangle is screened within exactly when its largest distance to the
    /// surface, sampled densely, is within the tolerance. A course, a nozzle neck
    /// and a hemispherical head at three tolerances, every triangle of their
    /// structured meshes. The probes alone pass some triangles beyond the
    /// tolerance (they see as little as 15/16 of the peak): the bound does not.
    #[test]
    fn the_closed_form_bound_is_the_screen_verdict() {
        use crate::mesh::cdt::checks::screen::Screen;
        use crate::parts::Shell;
        let (mut bounded, mut total, mut missed) = (0usize, 0usize, 0usize);
        let mut patches: Vec<crate::parts::Patch> = Vec::new();
        patches.extend(
            Shell {
                outside_diameter: 1800.0,
                length: 2400.0,
            }
            .patches()
            .expect("a course"),
        );
        patches.extend(
            Shell {
                outside_diameter: 219.1,
                length: 300.0,
            }
            .patches()
            .expect("a neck"),
        );
        patches.extend(
            Head::new(2400.0, HeadKind::Hemispherical)
                .patches()
                .expect("a head"),
        );
        for tolerance in [0.2, 1.0, 4.0] {
            let options = TessellationOptions::chord(tolerance);
            for patch in &patches {
                with_rings(patch, &options, |info, rings| {
                    let all: Vec<u32> = (0..rings.mesh.tris.len() as u32).collect();
                    let screen = Screen::new(info, &options).expect("an analytic surface");
                    let with_bound = screen.triangles(&rings.mesh, &all);
                    let probes = Screen::new(info, &options)
                        .expect("an analytic surface")
                        .probes_only()
                        .triangles(&rings.mesh, &all);
                    for (t, (&b, &p)) in with_bound.iter().zip(&probes).enumerate() {
                        let corners =
                            rings.mesh.tris[t].map(|k| rings.mesh.verts[k as usize].point);
                        let sampled = sampled_deviation(&patch.analytic, corners);
                        let flat = (corners[1] - corners[0])
                            .cross(corners[2] - corners[0])
                            .length()
                            == 0.0;
                        if !flat && b {
                            assert!(
                                sampled <= tolerance * (1.0 + 1e-9),
                                "triangle {t} passed at {sampled} > {tolerance}"
                            );
                        }
                        if !flat && !b && p && sampled > tolerance {
                            missed += 1;
                        }
                    }
                    total += all.len();
                    bounded += with_bound.iter().filter(|&&b| b).count();
                });
            }
        }
        println!("{missed} triangles over the tolerance passed by the probes alone");
        assert!(10 * bounded > 9 * total, "{bounded} of {total}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

        /// The chordal check exists twice: the structured path's screen
        /// (`screen`, with the closed-form bound and the peak model) and the
        /// full assessment the refinement runs (`refine::assess`). Every
        /// triangle the screen passes (the verdicts the structured path hands
        /// on, mending included) also passes the full assessment, on every
        /// head kind's patches, a course and a cone, at any diameter and
        /// tolerance.
        #[test]
        fn every_triangle_the_screen_passes_passes_the_full_assessment(
            od in 200.0f64..6000.0,
            tolerance in 0.05f64..5.0,
            kind in 0usize..7,
        ) {
            use crate::parts::{Reducer, ReducerAlignment, Shell};
            let patches: Vec<Patch> = match kind {
                0 => Shell { outside_diameter: od, length: 1.5 * od }.patches(),
                1 => Reducer {
                    large_diameter: od,
                    small_diameter: 0.6 * od,
                    length: 0.5 * od,
                    alignment: ReducerAlignment::Concentric,
                }
                .patches(),
                2 => Head::new(od, HeadKind::Hemispherical).patches(),
                3 => Head::new(od, HeadKind::TWO_TO_ONE).patches(),
                4 => Head::new(od, HeadKind::Ellipsoidal { ratio: 2.7 }).patches(),
                5 => Head::new(od, HeadKind::asme_fd(od)).patches(),
                _ => Head::new(
                    od,
                    HeadKind::Toriconical { half_angle: 30.0, knuckle_radius: 0.1 * od },
                )
                .patches(),
            }
            .expect("a part");
            let options = TessellationOptions::chord(tolerance);
            let (mut screened, mut total) = (0usize, 0usize);
            for patch in &patches {
                with_rings(patch, &options, |info, rings| {
                    let Some(within) = rings.within.as_deref() else {
                        return;
                    };
                    let mut mesh = rings.mesh.clone();
                    structured::fix_seam(&mut mesh, &rings.seam);
                    let full = refine::assess_all(info, &mesh, &options, None);
                    for (t, &w) in within.iter().enumerate() {
                        assert!(
                            !w || full.within(t),
                            "{}: triangle {t} passed the screen, not the assessment",
                            patch.name
                        );
                    }
                    screened += within.iter().filter(|&&w| w).count();
                    total += within.len();
                });
            }
            // The screen passes most triangles (the property is not vacuous).
            proptest::prop_assert!(2 * screened > total, "{screened} of {total}");
        }
    }

    /// The largest distance to `analytic` over triangle `p`, 45 barycentric
    /// points and more (the 8th subdivision).
    fn sampled_deviation(analytic: &Analytic, p: [glam::DVec3; 3]) -> f64 {
        let n = 16;
        let mut worst: f64 = 0.0;
        for i in 0..=n {
            for j in 0..=n - i {
                let l = [i, j, n - i - j].map(|x| x as f64 / n as f64);
                worst = worst.max(analytic.distance(p[0] * l[0] + p[1] * l[1] + p[2] * l[2]));
            }
        }
        worst
    }
}
