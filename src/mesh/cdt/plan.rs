//! The mesher's decisions in one place: which path meshes a patch region and in
//! which order a cavity round openings is filled.
//!
//! [`plan`] is the decision table for a region (see its doc); [`CAVITY_FILLS`]
//! the fill order for a cavity. The path a meshing took is recorded in its
//! [`MeshStats`](super::MeshStats) (`path`, `cavity_fills`) and counted by the
//! Tessellate stage's `WorkCounters`.

use super::patch::PatchInfo;
use super::quarter;
use super::region::Region;

/// How a patch region was meshed: the rows of the mesher's decision table (see
/// `cdt::plan`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum MeshPath {
    /// A whole surface of revolution without openings, meshed on its first
    /// quarter turn by the structured path and turned round by exact 90°
    /// rotations (`sector`).
    Sector,
    /// A whole patch closed in u: the lattice's rows zipped seam to seam round
    /// the cavities of its openings (`structured`, `cavity`).
    Structured,
    /// Any region: seeds on a curvature-sized lattice, spade's constrained
    /// Delaunay triangulation and chordal refinement (`seed`, `initial`,
    /// `refine`).
    #[default]
    General,
}

/// How a cavity of the structured path was filled, in the order tried
/// ([`CAVITY_FILLS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CavityFill {
    /// The triangles a previous meshing of the patch kept for a cavity whose
    /// inputs are the same bit for bit (`kept`).
    Kept,
    /// One hole zipped to the cavity's boundary: greedily, or by the least
    /// total diagonal when the greedy walk is stuck (`cavity_fill`).
    Zip,
    /// Several holes: the cavity swept into pieces monotone round the course,
    /// each walked with a stack (`sweep`).
    Sweep,
    /// Ear clipping (the `earcut` crate) when the sweep gives no cover.
    Ears,
    /// spade's constrained Delaunay triangulation of the cavity's loops, when
    /// no fill above is accepted.
    Spade,
}

/// The fills of a cavity, in the order `cavity::fill` tries them. The first
/// three are accepted when their triangles are strictly counter-clockwise in
/// (u, v) (the sweep and ear clipping also when they cover the cavity less its
/// holes exactly once) and still are after Lawson's flips to Delaunay; failing
/// that, spade triangulates the cavity; failing that too, the patch takes the
/// general path.
pub const CAVITY_FILLS: [CavityFill; 5] = [
    CavityFill::Kept,
    CavityFill::Zip,
    CavityFill::Sweep,
    CavityFill::Ears,
    CavityFill::Spade,
];

impl CavityFill {
    /// Its index in [`CAVITY_FILLS`] (and in `MeshStats::cavity_fills`).
    pub const fn index(self) -> usize {
        self as usize
    }
}

/// What [`plan`] decided for a region: the paths to try, in order (sector,
/// structured, then general); the first that gives a mesh is taken.
pub(super) struct Plan {
    /// The first quarter of the region, when the sector path applies.
    pub quarter: Option<Region>,
    /// Whether the structured path applies (the patch is closed in u).
    pub structured: bool,
}

/// The decision table of a (validated, oriented: rows along u) patch region.
///
/// | Region | Path tried first | Falls back to | when |
/// |---|---|---|---|
/// | the whole parameter rectangle of a surface closed in u whose control points and side vertices repeat every quarter turn about Z, no holes (a plain course or cone, every head kind's knuckle and cone, every crown but a sphere's, a skirt and its base ring, a nozzle's neck, hub and flange faces) | [`MeshPath::Sector`]: the quarter by the structured path, turned three times | `Structured` on the whole turn | the quarter's sides are not rings or poles, or a quarter's triangles do not turn into the next quarter's exactly |
/// | a whole sphere patch with a ring and a pole, no holes, meshed to a chordal tolerance alone (a hemispherical, torispherical or F&D crown) | [`MeshPath::Structured`] on the whole turn, its rows chosen by the whole-triangle bound (`structured::sphere`) | the lattice's rows | the ring is not uniform from the seam, or the surface's turn is not four quarter arcs |
/// | the whole rectangle of a patch closed in u, with holes (a course, head or cone with openings) or sides that do not repeat, or a nozzle neck whose bottom is its host's cut (a path along v on a straight neck) | [`MeshPath::Structured`]: rows zipped seam to seam, each opening's cavity filled ([`CAVITY_FILLS`]), every triangle screened, failures mended | `General` | a side is neither a ring nor a pole, a cavity reaches the seam or a pole or overlaps another and cannot be merged, a cavity cannot be filled, or a seam edge is beyond the tolerance |
/// | anything else: a patch open in u (such as a reinforcing pad), a patch whose opening crosses its seam | [`MeshPath::General`]: seeds, spade, chordal refinement | — (an error) | spade rejects a loop segment, or refinement runs away |
///
/// The structured and sector meshes are screened (`screen`: closed form on
/// planes, cylinders and spheres, `certify`; probes and a cubic peak model
/// elsewhere); a triangle the screen cannot pass is assessed in full
/// (`refine::assess`) and refined with the general path's refinement, so a
/// structured patch may end with inserted vertices. Every path ends in
/// `output::finish` (weld poles and seams, check every triangle).
pub(super) fn plan(info: &PatchInfo, region: &Region) -> Plan {
    Plan {
        quarter: quarter::quarter(info, region),
        structured: info.closed_u,
    }
}

#[cfg(test)]
mod tests {
    use glam::{DAffine3, DVec3};

    use super::*;
    use crate::mesh::cdt::mesh_patch_region;
    use crate::mesh::test_parts::{course, frame, neck, nozzle};
    use crate::mesh::{TessellationOptions, cut_opening, host_region, pad_region, patch_region};
    use crate::parts::heads::{Head, HeadKind};
    use crate::parts::{Patch, Reducer, ReducerAlignment, Shell, Skirt};

    /// The path of a whole patch (no openings) at `options`.
    fn path_of(patch: &Patch, options: &TessellationOptions) -> MeshPath {
        let region = patch_region(&patch.surface, options, &[], None).expect("a region");
        let out = mesh_patch_region(patch, &region, options).expect("a mesh");
        out.stats.path
    }

    /// The path each kind of patch takes, as `plan`'s table says: plain surfaces
    /// of revolution by the sector, openings' hosts and trimmed necks by the
    /// structured path with a zip, pads by the general path.
    #[test]
    fn each_patch_kind_takes_its_path() {
        let options = TessellationOptions::chord(1.0);
        let mut seen: Vec<(String, MeshPath)> = Vec::new();
        let mut whole = |part: &str, patches: Vec<Patch>| {
            for patch in &patches {
                seen.push((format!("{part}: {}", patch.name), path_of(patch, &options)));
            }
        };
        whole(
            "course",
            Shell {
                outside_diameter: 2000.0,
                length: 3000.0,
            }
            .patches()
            .expect("a course"),
        );
        whole(
            "cone",
            Reducer {
                large_diameter: 2000.0,
                small_diameter: 1200.0,
                length: 800.0,
                alignment: ReducerAlignment::Concentric,
            }
            .patches()
            .expect("a cone"),
        );
        whole(
            "skirt",
            Skirt {
                top_diameter: 2000.0,
                height: 1500.0,
                flare_angle: 0.0,
                thickness: 12.0,
                base_ring_width: 100.0,
            }
            .patches()
            .expect("a skirt"),
        );
        let kinds = [
            ("hemispherical", HeadKind::Hemispherical),
            ("2:1 ellipsoidal", HeadKind::TWO_TO_ONE),
            ("ellipsoidal 1.5", HeadKind::Ellipsoidal { ratio: 1.5 }),
            ("F&D", HeadKind::asme_fd(2000.0)),
            (
                "toriconical",
                HeadKind::Toriconical {
                    half_angle: 30.0,
                    knuckle_radius: 200.0,
                },
            ),
            (
                "conical",
                HeadKind::Conical {
                    half_angle: 30.0,
                    small_diameter: 0.0,
                },
            ),
        ];
        for (name, kind) in kinds {
            whole(name, Head::new(2000.0, kind).patches().expect("a head"));
        }
        whole("nozzle", nozzle(300.0).patches().expect("a nozzle"));

        // An opening: the course with a hole, the neck cut at its bottom, the pad.
        let host = course();
        let neck = neck(1400.0);
        let at = frame(DVec3::new(0.0, 0.0, 1500.0), DVec3::new(0.6, 0.8, 0.0));
        let cut = cut_opening(&neck, Some(450.0), &at, &DAffine3::IDENTITY, &[&host], 1.0)
            .expect("a cut");
        let holed = host_region(&host.surface, &options, &[&cut.neck], &[], None).expect("holed");
        let out = mesh_patch_region(&host, &holed, &options).expect("a holed course");
        seen.push(("course with an opening".into(), out.stats.path));
        let mut fills = [0; CAVITY_FILLS.len()];
        fills[CavityFill::Zip.index()] = 1;
        assert_eq!(out.stats.cavity_fills, fills, "one cavity, zipped");
        let trimmed = patch_region(&neck.surface, &options, &[], Some(&cut.neck)).expect("neck");
        let out = mesh_patch_region(&neck, &trimmed, &options).expect("a trimmed neck");
        seen.push(("neck cut by its host".into(), out.stats.path));
        let pad = crate::mesh::cut_opening_reusing(
            &neck,
            Some(450.0),
            &at,
            &DAffine3::IDENTITY,
            &[&host],
            1.0,
            None,
        )
        .expect("a cut")
        .pad
        .expect("a pad");
        let region =
            pad_region(&pad.patch.surface, &options, &pad.outer, &pad.inner).expect("a pad");
        let out = mesh_patch_region(&pad.patch, &region, &options).expect("a pad mesh");
        seen.push(("pad".into(), out.stats.path));

        let table: Vec<String> = seen.iter().map(|(k, p)| format!("{k} -> {p:?}")).collect();
        let expected = [
            "course: shell -> Sector",
            "cone: cone -> Sector",
            "skirt: skirt -> Sector",
            "skirt: base ring -> Sector",
            "hemispherical: crown -> Structured",
            "2:1 ellipsoidal: crown -> Sector",
            "ellipsoidal 1.5: crown -> Sector",
            "F&D: knuckle -> Sector",
            "F&D: crown -> Structured",
            "toriconical: knuckle -> Sector",
            "toriconical: cone -> Sector",
            "conical: cone -> Sector",
            "nozzle: neck -> Sector",
            "nozzle: hub -> Sector",
            "nozzle: flange back -> Sector",
            "nozzle: flange rim -> Sector",
            "nozzle: flange face -> Sector",
            "nozzle: raised face rim -> Sector",
            "nozzle: gasket face -> Sector",
            "course with an opening -> Structured",
            "neck cut by its host -> Structured",
            "pad -> General",
        ];
        assert_eq!(table, expected, "{}", table.join("\n"));
    }
}
