//! The patch mesher (`patch_region` + `mesh_region`) against curvo's adaptive
//! tessellation, at 0.1 mm chordal tolerance, on the same exact surfaces:
//!
//! - an ASME F&D head, OD 2400 (knuckle and crown);
//! - a sphere of R = 1000 mm: the patch of a hemispherical head of OD 2000, meshed
//!   twice (the head and its mirror cost the same);
//! - a shell course OD 2400 × 6000 with six nozzles: the shell patch's region with
//!   its six openings as laid out by the model (the design below), and, as a
//!   separate figure, the full model build of that design.
//!
//! # Equal measured deviation
//!
//! Tolerances are not comparable between meshers (curvo's is a bound on the change of
//! the unit normal across a cell, not a distance), so both are compared at an equal
//! MEASURED deviation: [`max_deviation`] samples every triangle at its centroid and
//! edge midpoints, inverts each sample onto the exact surface with
//! `NurbsSurface::closest_point` and takes the largest distance. vesselcad is run at
//! 0.1 mm; curvo's settings are then searched ([`tune_curvo`](super::mesh_tuning::tune_curvo), with
//! `MESH_BENCH_TUNE=1`) for the fewest triangles at a measured deviation at most
//! vesselcad's, over several families: `norm_tolerance` alone, `norm_tolerance`
//! after `min_depth` 4–10 forced divisions, a uniform grid (`min_divs_u/v`), and
//! `max_edge_length`. The winners are recorded in [`TUNED`], so a normal run only
//! measures them. What the search found (curvo 0.3.3):
//!
//! - `norm_tolerance` alone cannot get below 1.10 mm on the F&D head nor 4.18 mm on
//!   the sphere, however small (2.6 M and 1.3 M triangles): curvo stops dividing a
//!   cell once a corner's normal is degenerate, which every cell at a pole is.
//! - On the shell with openings no setting reaches 0.1 mm: the trimmed path
//!   triangulates curvo's grid points and the hole polylines by a Delaunay
//!   triangulation in (u, v); the cylinder's linear direction gets no grid points,
//!   so triangles chord across the shell (1139 mm with `norm_tolerance` alone), and
//!   `max_edge_length` 100 mm already makes 2.5 M triangles at 0.40 mm.
//!
//! # Ideal triangle count
//!
//! An equilateral triangle inscribed in a sphere of radius ρ = 1/κ deviates most at
//! its circumcentre, by the sagitta of its circumscribed circle of radius r:
//! δ = ρ − √(ρ² − r²), so r² = δ(2ρ − δ). With δ = tolerance t and κ the local
//! largest principal curvature, the triangle covers `a(κ) = (3√3/4)·t·(2/κ − t)`;
//! the ideal count is `∫ dA / a(κ)`, summed here over the triangles of vesselcad's
//! own mesh (area × 1/a(κ) at the triangle's parametric centroid, [`ideal_counts`]).
//! For the sphere R = 1000 at 0.1 mm this is 4πR²/a = 48 370. Using the LARGEST
//! curvature makes it an isotropic ideal: on a cylinder, triangles stretched along
//! the axis could need fewer. The table also gives an anisotropic ideal, triangles
//! equilateral in the second fundamental form, `a = (3√3/2)·t/√K` where the Gaussian
//! curvature K > 0 (0 where K ≤ 0: the shell's has no finite ideal).
//!
//! Targets (the issue): at most 1.3× the ideal count, and at least 5× curvo's speed
//! per triangle. vesselcad meshes a case's patches in parallel, as the model's
//! Tessellate stage does, with rayon's default pool (one thread per core); curvo
//! has no parallel mode. The setup table gives vesselcad's time on one thread too. The setup prints one table with the figures; criterion then times
//! each mesher with throughput in triangles. `MESH_BENCH_CASE=sphere` limits the
//! setup to the cases whose name contains the text.

use std::hint::black_box;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use curvo::prelude::{
    AdaptiveTessellationOptions, CompoundCurve2D, NurbsCurve2D, NurbsSurface3D, Tessellation,
    TrimmedSurface,
};
use glam::{DVec2, DVec3};
use nalgebra::{Point2, Point4};
use rayon::prelude::*;
use vesselcad::components::{PatchRegion, PatchSurface};
use vesselcad::design::{Design, parse};
use vesselcad::mesh::cdt::{Region, mesh_region_on, mesh_region_with_uvs};
use vesselcad::mesh::{Mesh, TessellationOptions, patch_region};
use vesselcad::model::{Model, Views};
use vesselcad::nurbs::NurbsSurface;
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::{Analytic, Patch};

/// Chordal tolerance of the comparison, mm.
const TOLERANCE: f64 = 0.1;
/// Deepest subdivision allowed to curvo (its default, 8, is too shallow at 0.1 mm).
const CURVO_MAX_DEPTH: usize = 24;
/// Bisection steps of a curvo setting once a passing value is bracketed.
pub(super) const TUNING_STEPS: usize = 6;
/// Largest triangle count a curvo trial may reach before the search stops refining.
pub(super) const CURVO_TRIANGLE_CAP: usize = 3_000_000;
/// A `norm_tolerance` that never divides a cell (unit normals differ by at most 2).
const NO_NORMAL_DIVISION: f64 = 4.0;

/// A vertical shell course OD 2400 × 6000 with six nozzles clear of the seam.
const SHELL_DESIGN: &str = r#"{
  "format": "vesselcad/1",
  "units": "mm",
  "vessels": [{
    "tag": "B-1",
    "kind": "vertical",
    "parts": [{ "shell": { "id": "S1", "od": 2400, "length": 6000 } }],
    "nozzles": [
      { "mark": "M1", "size": 24, "rating": 150, "host": "S1", "orientation": 30, "elevation": 3000, "projection": 1600 },
      { "mark": "N1", "size": 8, "rating": 150, "host": "S1", "orientation": 100, "elevation": 1200, "projection": 1600 },
      { "mark": "N2", "size": 6, "rating": 150, "host": "S1", "orientation": 150, "elevation": 4800, "projection": 1600 },
      { "mark": "N3", "size": 4, "rating": 300, "host": "S1", "orientation": 200, "elevation": 2200, "projection": 1600 },
      { "mark": "N4", "size": 3, "rating": 150, "host": "S1", "orientation": 260, "elevation": 3900, "projection": 1600 },
      { "mark": "N5", "size": 2, "rating": 150, "host": "S1", "orientation": 320, "elevation": 800, "projection": 1600 }
    ]
  }]
}"#;

/// One surface to mesh, for both meshers.
pub(super) struct Piece {
    /// The patch's name.
    name: &'static str,
    /// The exact surface.
    surface: NurbsSurface,
    /// The analytic surface it represents exactly (a fast distance for tuning).
    analytic: Analytic,
    /// The region with openings, when fixed; `None` lays out the sides with
    /// `patch_region` on every run.
    region: Option<Region>,
    /// The same surface (and openings) for curvo.
    curvo: CurvoInput,
}

/// A surface as curvo takes it.
pub(super) enum CurvoInput {
    /// The whole surface.
    Untrimmed(NurbsSurface3D<f64>),
    /// The surface with holes (polylines through vesselcad's hole vertices).
    Trimmed(Box<TrimmedSurface<f64>>),
}

/// A benchmark case: the pieces meshed together, and curvo's settings for it.
pub(super) struct Case {
    pub(super) name: &'static str,
    pub(super) pieces: Vec<Piece>,
    curvo: Knobs,
}

/// A triangle soup, each triangle paired with the piece it lies on.
type Soup = Vec<(usize, [DVec3; 3])>;

/// curvo's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Knobs {
    /// Adaptive division on the change of the unit normal across a cell
    /// (`norm_tolerance`), after `min_depth` unconditional divisions.
    Normal {
        /// curvo's `norm_tolerance`.
        norm_tolerance: f64,
        /// curvo's `min_depth`.
        min_depth: usize,
    },
    /// A uniform grid of cells about `edge` mm long (`min_divs_u` / `min_divs_v`
    /// from the control polygon's length), no adaptive division.
    Grid {
        /// Target cell edge, mm.
        edge: f64,
    },
    /// Adaptive division on `max_edge_length` (and the default `norm_tolerance`).
    MaxEdge {
        /// curvo's `max_edge_length`, mm.
        edge: f64,
    },
}

/// curvo's settings per case, found with `MESH_BENCH_TUNE=1` (see [`tune_curvo`](super::mesh_tuning::tune_curvo)):
/// of all the families searched, the one giving the fewest triangles at a measured
/// deviation at most vesselcad's. No setting reaches it on the shell with openings
/// (see the module docs); the one used there is a compromise between deviation and
/// run time.
const TUNED: [Knobs; 3] = [
    // F&D head: 66 608 triangles (norm_tolerance alone: 1.10 mm at best).
    Knobs::MaxEdge { edge: 30.38 },
    // Sphere: 101 850 triangles (norm_tolerance alone: 4.18 mm at best).
    Knobs::Grid { edge: 27.55 },
    // Shell with openings: no setting reaches 0.1 mm.
    Knobs::Normal {
        norm_tolerance: 0.02,
        min_depth: 10,
    },
];

/// curvo's surface with the same degrees, knots and homogeneous control points.
fn to_curvo(surface: &NurbsSurface) -> NurbsSurface3D<f64> {
    let points = (0..surface.u_count())
        .map(|i| {
            (0..surface.v_count())
                .map(|j| {
                    let h = surface.homogeneous_point_at(i, j);
                    Point4::new(h.x, h.y, h.z, h.w)
                })
                .collect()
        })
        .collect();
    NurbsSurface3D::new(
        surface.u_degree(),
        surface.v_degree(),
        surface.u_knots().as_slice().to_vec(),
        surface.v_knots().as_slice().to_vec(),
        points,
    )
}

/// A piece meshed whole (sides from `patch_region`, no holes).
fn whole(patch: &Patch) -> Piece {
    Piece {
        name: patch.name,
        surface: patch.surface.clone(),
        analytic: patch.analytic,
        region: None,
        curvo: CurvoInput::Untrimmed(to_curvo(&patch.surface)),
    }
}

/// The shell patch of [`SHELL_DESIGN`] with its region as the model laid it out.
fn shell_with_openings() -> Piece {
    let design = shell_design();
    let model = Model::from_design(&design, TessellationOptions::chord(TOLERANCE))
        .expect("the shell design is valid");
    let world = model.world();
    let mut query = world
        .try_query::<(&PatchSurface, &PatchRegion)>()
        .expect("the model has patches with regions");
    let (patch, region) = query
        .iter(world)
        .find(|(s, _)| s.0.name == "shell")
        .map(|(s, r)| {
            (
                s.0.clone(),
                r.region.clone().expect("views kept: region kept"),
            )
        })
        .expect("the design has a shell patch");
    let holes = region
        .holes
        .iter()
        .map(|hole| {
            let mut points: Vec<Point2<f64>> =
                hole.uv.iter().map(|p| Point2::new(p.x, p.y)).collect();
            points.push(points[0]);
            CompoundCurve2D::from(NurbsCurve2D::polyline(&points, false))
        })
        .collect();
    let curvo = CurvoInput::Trimmed(Box::new(TrimmedSurface::new(
        to_curvo(&patch.surface),
        None,
        holes,
    )));
    Piece {
        name: patch.name,
        surface: patch.surface.clone(),
        analytic: patch.analytic,
        region: Some((*region).clone()),
        curvo,
    }
}

fn shell_design() -> Design {
    parse(SHELL_DESIGN).expect("the shell design is valid")
}

/// The three cases.
fn cases() -> Vec<Case> {
    let od = 2400.0;
    let fd = Head::new(od, HeadKind::asme_fd(od))
        .patches()
        .expect("the ASME F&D head is valid");
    let hemisphere = Head::new(2000.0, HeadKind::Hemispherical)
        .patches()
        .expect("the hemispherical head is valid");
    vec![
        Case {
            name: "F&D head OD 2400",
            pieces: fd.iter().map(whole).collect(),
            curvo: TUNED[0],
        },
        Case {
            name: "sphere R 1000",
            pieces: vec![whole(&hemisphere[0]), whole(&hemisphere[0])],
            curvo: TUNED[1],
        },
        Case {
            name: "shell 2400x6000 + 6 nozzles",
            pieces: vec![shell_with_openings()],
            curvo: TUNED[2],
        },
    ]
}

/// The region of a piece: the fixed one, or its sides laid out now.
fn region_of<'a>(
    piece: &'a Piece,
    options: &TessellationOptions,
    laid_out: &'a mut Option<Region>,
) -> &'a Region {
    match &piece.region {
        Some(r) => r,
        None => laid_out
            .insert(patch_region(&piece.surface, options, &[], None).expect("the patch lays out")),
    }
}

/// vesselcad's mesh of one piece.
fn ours(piece: &Piece, options: &TessellationOptions) -> Mesh {
    let mut laid_out = None;
    let region = region_of(piece, options, &mut laid_out);
    mesh_region_on(&piece.surface, &piece.analytic, region, options)
        .expect("the patch meshes")
        .0
}

/// vesselcad's meshes of all pieces, the patches in parallel as the model's
/// Tessellate stage meshes them (curvo has no parallel mode; the setup table also
/// gives vesselcad's time on one thread).
fn mesh_ours(pieces: &[Piece], options: &TessellationOptions) {
    pieces.par_iter().for_each(|p| {
        black_box(ours(p, options));
    });
}

/// Largest length of the control polygon's rows along u and columns along v, mm
/// (an upper bound of the isocurves' lengths).
fn polygon_lengths(surface: &NurbsSurface) -> (f64, f64) {
    let points = surface.control_points();
    let (nu, nv) = (surface.u_count(), surface.v_count());
    let at = |i: usize, j: usize| points[i * nv + j];
    let along_u = (0..nv)
        .map(|j| {
            (1..nu)
                .map(|i| (at(i, j) - at(i - 1, j)).length())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    let along_v = (0..nu)
        .map(|i| {
            (1..nv)
                .map(|j| (at(i, j) - at(i, j - 1)).length())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    (along_u, along_v)
}

/// curvo's options for `knobs` on `piece`.
fn curvo_options(piece: &Piece, knobs: Knobs) -> AdaptiveTessellationOptions<f64> {
    let base = AdaptiveTessellationOptions::<f64>::default().with_max_depth(CURVO_MAX_DEPTH);
    match knobs {
        Knobs::Normal {
            norm_tolerance,
            min_depth,
        } => base
            .with_norm_tolerance(norm_tolerance)
            .with_min_depth(min_depth),
        Knobs::Grid { edge } => {
            let (along_u, along_v) = polygon_lengths(&piece.surface);
            base.with_norm_tolerance(NO_NORMAL_DIVISION)
                .with_min_divs_u((along_u / edge).ceil() as usize)
                .with_min_divs_v((along_v / edge).ceil() as usize)
        }
        Knobs::MaxEdge { edge } => base.with_max_edge_length(edge),
    }
}

/// curvo's tessellation of one piece, as triangles (its zero-area triangles at a
/// pole, where two corners of a cell coincide, are left out).
fn theirs(piece: &Piece, knobs: Knobs) -> Vec<[DVec3; 3]> {
    let options = Some(curvo_options(piece, knobs));
    let tess = match &piece.curvo {
        CurvoInput::Untrimmed(s) => s.tessellate(options),
        CurvoInput::Trimmed(s) => s
            .tessellate(options)
            .expect("curvo meshes the trimmed shell"),
    };
    let points: Vec<DVec3> = tess
        .points()
        .iter()
        .map(|p| DVec3::new(p.x, p.y, p.z))
        .collect();
    tess.faces()
        .iter()
        .map(|f| f.map(|k| points[k]))
        .filter(|t| !degenerate(t))
        .collect()
}

/// True for a triangle of (relative) zero area.
fn degenerate(t: &[DVec3; 3]) -> bool {
    let longest = (0..3)
        .map(|i| (t[(i + 1) % 3] - t[i]).length_squared())
        .fold(0.0, f64::max);
    (t[1] - t[0]).cross(t[2] - t[0]).length() <= 1e-12 * longest
}

/// The triangles of a mesh.
fn triangles(mesh: &Mesh) -> impl Iterator<Item = [DVec3; 3]> + '_ {
    mesh.indices
        .chunks_exact(3)
        .map(|t| [0, 1, 2].map(|k| mesh.positions[t[k] as usize]))
}

/// The points of a triangle at which its deviation is measured: the centroid and
/// the three edge midpoints.
fn samples(t: &[DVec3; 3]) -> [DVec3; 4] {
    [
        (t[0] + t[1] + t[2]) / 3.0,
        0.5 * (t[0] + t[1]),
        0.5 * (t[1] + t[2]),
        0.5 * (t[2] + t[0]),
    ]
}

/// Distance from `p` to the exact surface (point inversion).
fn distance(surface: &NurbsSurface, p: DVec3) -> f64 {
    surface
        .closest_point(p)
        .map_or(f64::INFINITY, |c| c.distance)
}

/// The measured deviation: the largest distance to its exact surface (point
/// inversion) of the centroid and edge midpoints of every triangle, mm, and the
/// sample where it occurs.
pub(super) fn max_deviation(pieces: &[Piece], soup: &Soup) -> (f64, DVec3) {
    soup.par_iter()
        .flat_map_iter(|(k, t)| samples(t).map(|p| (distance(&pieces[*k].surface, p), p)))
        .reduce(|| (0.0, DVec3::ZERO), |a, b| if b.0 > a.0 { b } else { a })
}

/// Whether every sample of every triangle is within `limit` of its analytic surface
/// (stops at the first one that is not). Used while tuning; the analytic surfaces
/// are the patches' exact shapes, so this agrees with point inversion.
pub(super) fn within(pieces: &[Piece], soup: &Soup, limit: f64) -> bool {
    soup.par_iter().all(|(k, t)| {
        samples(t)
            .iter()
            .all(|&p| pieces[*k].analytic.distance(p) <= limit)
    })
}

/// The principal curvatures at (u, v), 1/mm: (largest |κ|, Gaussian curvature K).
fn curvatures(surface: &NurbsSurface, uv: DVec2) -> (f64, f64) {
    let d = surface.derivatives(uv.x, uv.y);
    let n = d.du.cross(d.dv).normalize_or_zero();
    let (e, f, g) = (d.du.dot(d.du), d.du.dot(d.dv), d.dv.dot(d.dv));
    let (l, m, nn) = (d.duu.dot(n), d.duv.dot(n), d.dvv.dot(n));
    let det = e * g - f * f;
    if det <= 0.0 {
        return (0.0, 0.0);
    }
    let gauss = (l * nn - m * m) / det;
    let mean = (e * nn - 2.0 * f * m + g * l) / (2.0 * det);
    (mean.abs() + (mean * mean - gauss).max(0.0).sqrt(), gauss)
}

/// Ideal triangle counts of one piece (see the module docs).
#[derive(Clone, Copy, Debug, Default)]
struct Ideal {
    /// Equilateral triangles sized by the largest curvature.
    isotropic: f64,
    /// Triangles equilateral in the second fundamental form where K > 0,
    /// `a = (3√3/2)·t/√K`; 0 where K ≤ 0 (a cylinder's triangles could span it).
    anisotropic: f64,
}

/// The ideal counts of each piece: the sum over vesselcad's triangles of area /
/// a(κ), with κ and K at the triangle's parametric centroid.
fn ideal_counts(pieces: &[Piece], options: &TessellationOptions) -> Vec<Ideal> {
    let t = options.tolerance;
    let root3 = 3f64.sqrt();
    pieces
        .par_iter()
        .map(|piece| {
            let mut laid_out = None;
            let region = region_of(piece, options, &mut laid_out);
            let out = mesh_region_with_uvs(&piece.surface, region, options).expect("meshes");
            let mut ideal = Ideal::default();
            for tri in out.mesh.indices.chunks_exact(3) {
                let p = [0, 1, 2].map(|k| out.mesh.positions[tri[k] as usize]);
                let uv = [0, 1, 2].map(|k| out.uvs[tri[k] as usize]);
                let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
                let (kappa, gauss) = curvatures(&piece.surface, (uv[0] + uv[1] + uv[2]) / 3.0);
                if kappa > 0.0 {
                    ideal.isotropic += area / (0.75 * root3 * t * (2.0 / kappa - t));
                }
                if gauss > 0.0 {
                    ideal.anisotropic += area * gauss.sqrt() / (1.5 * root3 * t);
                }
            }
            ideal
        })
        .collect()
}

/// curvo's soup for a case.
pub(super) fn curvo_soup(pieces: &[Piece], knobs: Knobs) -> Soup {
    pieces
        .iter()
        .enumerate()
        .flat_map(|(k, p)| theirs(p, knobs).into_iter().map(move |t| (k, t)))
        .collect()
}

/// vesselcad's soup for a case.
fn our_soup(pieces: &[Piece], options: &TessellationOptions) -> Soup {
    pieces
        .iter()
        .enumerate()
        .flat_map(|(k, p)| {
            let mesh = ours(p, options);
            triangles(&mesh).map(move |t| (k, t)).collect::<Vec<_>>()
        })
        .collect()
}

/// Milliseconds of the fastest of `runs` runs of `f`.
fn best_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        })
        .fold(f64::INFINITY, f64::min)
}

/// A case with its triangle counts.
struct Prepared {
    case: Case,
    ours: usize,
    theirs: usize,
}

/// Whether the setup searches curvo's settings (`MESH_BENCH_TUNE=1`).
fn tuning() -> bool {
    std::env::var_os("MESH_BENCH_TUNE").is_some()
}

/// Meshes and measures every case once, printing the table (and, when tuning,
/// searching curvo's settings first).
fn prepare() -> Vec<Prepared> {
    let options = TessellationOptions::chord(TOLERANCE);
    println!();
    println!(
        "meshers at {TOLERANCE} mm; max dev = centroid and edge midpoints of every triangle, \
         point inversion; ideal = isotropic count (see the module docs)"
    );
    println!(
        "{:<28} {:<44} {:>9} {:>9} {:>7} {:>9} {:>7} {:>9} {:>9} {:>9}",
        "case", "mesher", "tris", "ideal", "/ideal", "aniso", "/aniso", "max dev", "ms", "Mtri/s"
    );
    let mut out = Vec::new();
    for case in cases() {
        if let Ok(only) = std::env::var("MESH_BENCH_CASE")
            && !case.name.contains(&only)
        {
            continue;
        }
        let soup = our_soup(&case.pieces, &options);
        let (deviation, _) = max_deviation(&case.pieces, &soup);
        if tuning() {
            super::mesh_tuning::tune_curvo(&case, deviation);
        }
        let ideals = ideal_counts(&case.pieces, &options);
        let ideal = ideals.iter().map(|i| i.isotropic).sum::<f64>();
        let anisotropic = ideals.iter().map(|i| i.anisotropic).sum::<f64>();
        let row = |mesher: String, n: usize, dev: f64, ms: f64| {
            println!(
                "{:<28} {:<44} {:>9} {:>9.0} {:>7.2} {:>9.0} {:>7.2} {:>9.4} {:>9.1} {:>9.3}",
                case.name,
                mesher,
                n,
                ideal,
                n as f64 / ideal,
                anisotropic,
                n as f64 / anisotropic,
                dev,
                ms,
                n as f64 / ms / 1e3
            )
        };
        let ms = best_ms(3, || mesh_ours(&case.pieces, &options));
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a one-thread pool");
        let ms_one = one.install(|| best_ms(3, || mesh_ours(&case.pieces, &options)));
        row(
            format!("vesselcad ({} threads)", rayon::current_num_threads()),
            soup.len(),
            deviation,
            ms,
        );
        row("vesselcad (1 thread)".into(), soup.len(), deviation, ms_one);
        if case.pieces.len() > 1 {
            for (k, ideal) in ideals.iter().enumerate() {
                let n = soup.iter().filter(|t| t.0 == k).count();
                println!(
                    "{:<28} {:<44} {:>9} {:>9.0} {:>7.2} {:>9.0} {:>7.2}",
                    "",
                    format!("  {}", case.pieces[k].name),
                    n,
                    ideal.isotropic,
                    n as f64 / ideal.isotropic,
                    ideal.anisotropic,
                    n as f64 / ideal.anisotropic
                );
            }
        }
        let theirs_soup = curvo_soup(&case.pieces, case.curvo);
        let (their_deviation, _) = max_deviation(&case.pieces, &theirs_soup);
        let their_ms = best_ms(3, || {
            for p in &case.pieces {
                black_box(theirs(p, case.curvo));
            }
        });
        let reached = if their_deviation <= deviation {
            ""
        } else {
            " (dev > ours)"
        };
        row(
            format!("curvo {}{reached}", label(case.curvo)),
            theirs_soup.len(),
            their_deviation,
            their_ms,
        );
        let per_triangle =
            |ms: f64| (their_ms / theirs_soup.len() as f64) / (ms / soup.len() as f64);
        println!(
            "{:<28} vesselcad per triangle: {:.2}x curvo's speed ({:.2}x on 1 thread); \
             whole mesh: {:.1}x faster ({:.1}x on 1 thread)",
            "",
            per_triangle(ms),
            per_triangle(ms_one),
            their_ms / ms,
            their_ms / ms_one
        );
        out.push(Prepared {
            ours: soup.len(),
            theirs: theirs_soup.len(),
            case,
        });
    }
    let design = shell_design();
    let ms = best_ms(2, || {
        black_box(Model::from_design_with(&design, options, Views::Off).expect("valid"));
    });
    println!(
        "full model build of the shell design at {TOLERANCE} mm (no drawing views): {ms:.1} ms"
    );
    println!();
    out
}

/// A short description of curvo's settings.
fn label(knobs: Knobs) -> String {
    match knobs {
        Knobs::Normal {
            norm_tolerance,
            min_depth,
        } => format!("norm_tolerance {norm_tolerance}, min_depth {min_depth}"),
        Knobs::Grid { edge } => format!("uniform grid, cells {edge} mm"),
        Knobs::MaxEdge { edge } => format!("max_edge_length {edge} mm"),
    }
}

/// The prepared cases, computed once per process.
fn prepared() -> &'static [Prepared] {
    static PREPARED: OnceLock<Vec<Prepared>> = OnceLock::new();
    PREPARED.get_or_init(prepare)
}

/// Whether this topic is selected: no filter was given on the command line, or one
/// names it (`mesh`, `vesselcad`, `curvo`). The setup's tuning takes a minute or
/// so, which `cargo bench -- grid` should not pay for.
fn selected() -> bool {
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    filters.is_empty()
        || filters
            .iter()
            .any(|f| ["mesh", "vesselcad", "curvo"].iter().any(|t| f.contains(t)))
}

fn bench(c: &mut Criterion) {
    if !selected() {
        return;
    }
    let options = TessellationOptions::chord(TOLERANCE);
    let mut group = c.benchmark_group("mesh");
    for p in prepared() {
        group.throughput(Throughput::Elements(p.ours as u64));
        group.bench_function(BenchmarkId::new("vesselcad", p.case.name), |b| {
            b.iter(|| mesh_ours(&p.case.pieces, &options))
        });
        group.throughput(Throughput::Elements(p.theirs as u64));
        group.bench_function(BenchmarkId::new("curvo", p.case.name), |b| {
            b.iter(|| {
                for piece in &p.case.pieces {
                    black_box(theirs(piece, p.case.curvo));
                }
            })
        });
    }
    let design = shell_design();
    group.throughput(Throughput::Elements(1));
    group.bench_function("shell 2400x6000 + 6 nozzles full model build", |b| {
        b.iter(|| black_box(Model::from_design_with(&design, options, Views::Off).expect("valid")))
    });
    group.finish();
}

criterion_group! {
    name = group;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    targets = bench
}
