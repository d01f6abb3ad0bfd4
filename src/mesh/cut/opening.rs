//! Cutting an opening: a nozzle's neck (or a boot's shell, which is cut the same
//! way) placed in its host part's frame, intersected with the host's patches until
//! one holds the whole loop.
//!
//! Shared by the ECS Geometry stage (`systems::cut_openings`) and the direct full
//! build (`export::build_scene`), so both trim exactly alike. An opening that no
//! single host patch holds is cut on neighbouring patches joined in v and split at
//! their seam (`seams`). A loop that goes
//! round the host's pole (a nozzle centred on a head) gets an extra sample exactly
//! on the host's seam angle, shared by the neck, so the host can be cut there: one
//! Newton solve on the seam ([`loop_crossing`]), a bisection over generators where
//! that fails. In a straight course the loops are marched on its canonical copy
//! and placed along its axis (`axial`), so a cut kept from before can be placed
//! again without marching ([`cut_opening_reusing`]).

use std::f64::consts::TAU;
use std::sync::Arc;

use glam::{DAffine3, DVec2, DVec3};

use crate::nurbs::builders::{line, revolve};

use super::axial::{AxialCut, Placement, axial_range, canonical_host, cut_key};
use super::error::{CutError, CutLoop};
use super::outcome::{Cut, PAD_PATCH, PadCut};
use super::reach::Reach;
use super::seams::{HostTrim, Placed, insert_seam_samples, split_at_seams};
use super::shared_key;
use crate::mesh::surface::Extrusion;
use crate::nurbs::intersect::{
    HostIsoline, IntersectionLoop, LoopSample, intersect_generator, loop_crossing,
    neck_host_intersection,
};
use crate::nurbs::{NurbsError, NurbsSurface};
use crate::parts::{Analytic, Patch};

/// Bisection steps placing the seam sample.
const SEAM_STEPS: usize = 80;

/// One loop (`which`, of the surface `neck`) against one host patch (named
/// `patch`), with a seam sample if it goes round the pole.
fn loop_on(
    (which, neck): (CutLoop, &NurbsSurface),
    (patch, host): (&'static str, &NurbsSurface),
    tolerance: f64,
) -> Result<IntersectionLoop, CutError> {
    let mut curve =
        neck_host_intersection(neck, host, tolerance).map_err(|source| CutError::Intersection {
            which,
            patch,
            source,
        })?;
    if curve.host_turns(host) != 0 {
        add_seam_sample(neck, host, &mut curve).map_err(|(u, source)| {
            CutError::PoleSeamSample {
                which,
                patch,
                u,
                source,
            }
        })?;
    }
    Ok(curve)
}

/// The opening of a nozzle in its host: the host patch it lies in, the neck–host
/// loop and, with a pad of outside diameter `pad_od`, the pad's outer loop, all in
/// the host part's frame. `nozzle_frame` and `host_frame` map the nozzle's and the
/// host's local frames into one common frame (the vessel's).
pub fn cut_opening(
    neck: &Patch,
    pad_od: Option<f64>,
    nozzle_frame: &DAffine3,
    host_frame: &DAffine3,
    host_patches: &[&Patch],
    tolerance: f64,
) -> Result<Cut, CutError> {
    cut_opening_reusing(
        neck,
        pad_od,
        nozzle_frame,
        host_frame,
        host_patches,
        tolerance,
        None,
    )
    .map(|c| c.cut)
}

/// An opening as [`cut_opening_reusing`] gives it.
#[derive(Clone, Debug)]
pub struct ReusableCut {
    /// The opening.
    pub cut: Cut,
    /// The reinforcing pad's patch and trim, if the nozzle has a pad.
    pub pad: Option<PadCut>,
    /// Its loops on the canonical host, when it lies in a straight course: keep it
    /// to place the opening again after a move along the course's axis.
    pub axial: Option<Arc<AxialCut>>,
    /// Whether it was placed from the `kept` cut without marching.
    pub reused: bool,
}

/// [`cut_opening`], placing the opening from `kept` without marching when the
/// nozzle only moved along the axis of the straight course `kept` was cut in (see
/// `mesh::axial`), or in a round course turned about it (`mesh::turn`). `kept`
/// must come from a cut with the same pad and tolerance, and of the same neck
/// unless it was marched on a canonical neck (`mesh::reach`): then it applies
/// when this neck's canonical neck is the same (a projection edit), which is
/// checked here. The result is bit for bit the one a fresh cut gives.
pub fn cut_opening_reusing(
    neck: &Patch,
    pad_od: Option<f64>,
    nozzle_frame: &DAffine3,
    host_frame: &DAffine3,
    host_patches: &[&Patch],
    tolerance: f64,
    kept: Option<&Arc<AxialCut>>,
) -> Result<ReusableCut, CutError> {
    OpeningPlan::new(
        neck,
        pad_od,
        nozzle_frame,
        host_frame,
        host_patches.to_vec(),
        tolerance,
    )
    .cut(kept)
}

/// An opening to cut, with what is settled before any marching: the nozzle's
/// placement in its host (turned and moved from a canonical one in a straight
/// course) and the neck the loops are marched on. Its [`shared_key`](Self::shared_key)
/// names the canonical march it would be placed from, so that openings cut
/// from one march find each other first (see `mesh::cut::SharedCuts`).
pub struct OpeningPlan<'a> {
    pad_od: Option<f64>,
    nozzle_frame: DAffine3,
    host_frame: DAffine3,
    host_patches: Vec<&'a Patch>,
    tolerance: f64,
    placement: Placement,
    reach: Reach<'a>,
}

impl<'a> OpeningPlan<'a> {
    /// The plan of the opening `neck` (with a pad of `pad_od`, in the nozzle's
    /// frame `nozzle_frame`) cuts in the host part of `host_patches` (in
    /// `host_frame`), to `tolerance` mm.
    pub fn new(
        neck: &'a Patch,
        pad_od: Option<f64>,
        nozzle_frame: &DAffine3,
        host_frame: &DAffine3,
        host_patches: Vec<&'a Patch>,
        tolerance: f64,
    ) -> Self {
        let relative = host_frame.inverse() * *nozzle_frame;
        let axial_hosts = host_patches
            .iter()
            .any(|p| Extrusion::of(&p.surface).is_some());
        let placement = Placement::of(&relative, &host_patches);
        let reach = Reach::of(
            neck,
            &placement.sized_at(&relative),
            &host_patches,
            axial_hosts,
        );
        Self {
            pad_od,
            nozzle_frame: *nozzle_frame,
            host_frame: *host_frame,
            host_patches,
            tolerance,
            placement,
            reach,
        }
    }

    /// The key of the canonical march the opening would be placed from, when it
    /// lies in a one-patch straight course and its neck is plain (a canonical
    /// neck of its radius: then openings of any projection share the march); see
    /// `mesh::cut::SharedCuts`.
    pub fn shared_key(&self) -> Option<u128> {
        let [host] = self.host_patches.as_slice() else {
            return None;
        };
        let ext = Extrusion::of(&host.surface)?;
        let course = cut_key(&host.surface, &ext, &self.placement);
        Some(shared_key(
            course,
            self.reach.key()?,
            self.pad_od,
            self.tolerance,
        ))
    }

    /// The opening (see [`cut_opening_reusing`]).
    ///
    /// # Errors
    ///
    /// A [`CutError`] naming the host patch and loop where the opening cannot
    /// be cut.
    pub fn cut(&self, kept: Option<&Arc<AxialCut>>) -> Result<ReusableCut, CutError> {
        let reach = &self.reach;
        let cut = cut_with(self, kept)?;
        Ok(ReusableCut {
            cut: reach.on_neck(cut.cut),
            pad: reach.on_pad(cut.pad),
            ..cut
        })
    }
}

/// [`OpeningPlan::cut`] on the plan's neck to march on (its (u, v) in the
/// result are on that neck).
fn cut_with(plan: &OpeningPlan, kept: Option<&Arc<AxialCut>>) -> Result<ReusableCut, CutError> {
    let OpeningPlan {
        pad_od,
        nozzle_frame,
        host_frame,
        host_patches,
        tolerance,
        placement,
        reach,
    } = plan;
    let (pad_od, tolerance) = (*pad_od, *tolerance);
    let host_patches: &[&Patch] = host_patches;
    let relative = host_frame.inverse() * *nozzle_frame;
    let across = placement.canonical;
    if let Some(kept) = kept
        && kept.reach() == reach.key()
        && let Some(host) = host_patches.get(kept.host())
        && kept.fits(&host.surface, placement)
        && let Ok(cut) = kept.place(host, placement)
    {
        return Ok(ReusableCut {
            cut,
            pad: kept.pad_cut(host, placement)?,
            axial: Some(kept.clone()),
            reused: true,
        });
    }
    let neck = reach.surface();
    let neck = neck.as_ref();
    let place = |s: &NurbsSurface, at: &DAffine3| s.transformed(at).map_err(CutError::Placement);
    let construction = |source| CutError::Construction {
        what: "the reinforcing pad's outside cylinder",
        source,
    };
    // The pad's outside cylinder spans the neck's height (in the nozzle frame).
    let top = reach.top;
    let pad_cylinder = match pad_od {
        None => None,
        Some(od) => {
            let generator = line(
                DVec3::new(od / 2.0, 0.0, 0.0),
                DVec3::new(od / 2.0, 0.0, top),
            )
            .map_err(construction)?;
            Some(revolve(&generator, DVec3::ZERO, DVec3::Z, TAU).map_err(construction)?)
        }
    };
    let neck_placed = place(neck, &relative)?;
    let pad = pad_cylinder
        .as_ref()
        .map(|c| place(c, &relative))
        .transpose()?;
    // Placed at the canonical position along the axis, when a host patch is a
    // straight course.
    let canonical = if host_patches
        .iter()
        .any(|p| Extrusion::of(&p.surface).is_some())
    {
        let p = pad_cylinder
            .as_ref()
            .map(|c| place(c, &across))
            .transpose()?;
        Some((place(neck, &across)?, p))
    } else {
        None
    };
    let mut last = None;
    for k in try_order(&neck_placed, host_patches) {
        let patch = host_patches[k];
        let result = match (Extrusion::of(&patch.surface), &canonical) {
            (Some(ext), Some((n, p))) => {
                let zs = axial_range(std::iter::once(n).chain(p));
                canonical_host(&patch.surface, &ext, zs)
                    .and_then(|host| loops(n, p.as_ref(), (patch.name, &host), tolerance))
                    .and_then(|marched| {
                        let axial = AxialCut::new(
                            k,
                            &patch.surface,
                            &ext,
                            placement,
                            zs,
                            marched,
                            reach.key(),
                        );
                        let cut = axial.place(patch, placement)?;
                        Ok(ReusableCut {
                            cut,
                            pad: axial.pad_cut(patch, placement)?,
                            axial: Some(Arc::new(axial)),
                            reused: false,
                        })
                    })
            }
            _ => loops(
                &neck_placed,
                pad.as_ref(),
                (patch.name, &patch.surface),
                tolerance,
            )
            .and_then(|(neck_loop, pad_loop)| {
                let pad = match &pad_loop {
                    Some(outer) => Some(PadCut {
                        patch: pad_patch(patch, nozzle_frame, host_frame)?,
                        outer: Arc::new(outer.clone()),
                        inner: Arc::new(neck_loop.clone()),
                    }),
                    None => None,
                };
                Ok(ReusableCut {
                    cut: Cut {
                        hosts: vec![(k, HostTrim::Hole)],
                        neck: neck_loop,
                        pad: pad_loop,
                    },
                    pad,
                    axial: None,
                    reused: false,
                })
            }),
        };
        match result {
            Ok(cut) => return Ok(cut),
            Err(e) => last = Some(e),
        }
    }
    let across = cut_across_seams(
        &neck_placed,
        pad.as_ref(),
        host_patches,
        tolerance,
        &(nozzle_frame.inverse() * *host_frame),
    )?;
    match across {
        Some((cut, pad)) => Ok(ReusableCut {
            cut,
            pad,
            axial: None,
            reused: false,
        }),
        // One patch: its own reason; several: none holds the opening.
        None => Err(match last {
            None => CutError::NoHostPatch,
            Some(e) if host_patches.len() == 1 => e,
            Some(e) => CutError::NotWithinPatch { cause: Box::new(e) },
        }),
    }
}

/// The neck's and the pad's loops on one host surface. They are independent:
/// marched side by side (an edit's latency is that of the longer one).
fn loops(
    neck: &NurbsSurface,
    pad: Option<&NurbsSurface>,
    host: (&'static str, &NurbsSurface),
    tolerance: f64,
) -> Result<(IntersectionLoop, Option<IntersectionLoop>), CutError> {
    let (neck_loop, pad_loop) = rayon::join(
        || loop_on((CutLoop::Neck, neck), host, tolerance),
        || pad.map(|p| loop_on((CutLoop::Pad, p), host, tolerance)),
    );
    Ok((neck_loop?, pad_loop.transpose()?))
}

/// The order in which to try the host patches for the whole loop: by how much of
/// the neck's first generator runs inside each patch's bounding box (that of its
/// control net, which holds the surface), most first; ties in the given order. Only
/// one patch can hold the whole loop, so the order changes no result, only how
/// often a cut first fails on a patch its neck does not meet (slow to rule out: a
/// head nozzle's neck starts on the plane of the straight flange's top edge).
fn try_order(neck: &NurbsSurface, host_patches: &[&Patch]) -> Vec<usize> {
    let ((u0, _), (v0, v1)) = neck.domain();
    let (a, b) = (neck.point(u0, v0), neck.point(u0, v1));
    let inside: Vec<f64> = host_patches
        .iter()
        .map(|p| {
            let aabb = p.surface.bounding_box();
            segment_in_box(a, b, aabb.min, aabb.max)
        })
        .collect();
    let mut order: Vec<usize> = (0..host_patches.len()).collect();
    order.sort_by(|&i, &j| inside[j].total_cmp(&inside[i]));
    order
}

/// The fraction of the segment from `a` to `b` inside the box `[lo, hi]` (slab
/// test): 0 where it misses the box or only touches it.
fn segment_in_box(a: DVec3, b: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for axis in 0..3 {
        let (p, q, l, h) = (a[axis], d[axis], lo[axis], hi[axis]);
        if q == 0.0 {
            if p < l || p > h {
                return 0.0;
            }
            continue;
        }
        let (x, y) = ((l - p) / q, (h - p) / q);
        t0 = t0.max(x.min(y));
        t1 = t1.min(x.max(y));
    }
    let inside = t1 - t0;
    if inside.is_finite() {
        inside.max(0.0)
    } else {
        0.0
    }
}

/// The opening cut across the seams of a run of neighbouring host patches (joined
/// in v), if one holds the loop: `Ok(None)` if none does, an error if one does but
/// the opening cannot be cut there. With a `pad` (its outside cylinder, placed
/// as the neck is), the pad's loop is the one cut across the seam and the
/// pad's patch is the run joined, moved into the nozzle's frame by
/// `into_nozzle` (see [`pad_across`]).
fn cut_across_seams(
    neck: &NurbsSurface,
    pad: Option<&NurbsSurface>,
    host_patches: &[&Patch],
    tolerance: f64,
    into_nozzle: &DAffine3,
) -> Result<Option<(Cut, Option<PadCut>)>, CutError> {
    let count = host_patches.len();
    let hole = pad.unwrap_or(neck);
    for len in 2..=count {
        for first in 0..=count - len {
            let run = &host_patches[first..first + len];
            let rest: Vec<&NurbsSurface> = run[1..].iter().map(|p| &p.surface).collect();
            let Ok((joined, shifts)) = run[0].surface.joined_v(&rest) else {
                continue;
            };
            let Ok(mut curve) = neck_host_intersection(hole, &joined, tolerance) else {
                continue;
            };
            let names: Vec<&'static str> = run.iter().map(|p| p.name).collect();
            if curve.host_turns(&joined) != 0 {
                return Err(CutError::AcrossSeamRoundPole { patches: names });
            }
            let placed: Vec<Placed> = run
                .iter()
                .zip(&shifts)
                .map(|(p, &shift)| Placed {
                    v: p.surface.domain().1,
                    shift,
                })
                .collect();
            let seams: Vec<f64> = placed[..len - 1].iter().map(|p| p.v.1 + p.shift).collect();
            insert_seam_samples(hole, &joined, &mut curve, &seams, &names)?;
            let notches = split_at_seams(&curve, &placed, &names)?;
            let hosts = notches
                .into_iter()
                .enumerate()
                .filter(|(_, n)| !n.is_empty())
                .map(|(k, n)| (first + k, HostTrim::Notches(n.into())))
                .collect();
            if pad.is_none() {
                return Ok(Some((
                    Cut {
                        hosts,
                        neck: curve,
                        pad: None,
                    },
                    None,
                )));
            }
            let (neck_loop, pad_cut) =
                pad_across(neck, run, (&joined, &seams), &curve, tolerance, into_nozzle)?;
            return Ok(Some((
                Cut {
                    hosts,
                    neck: neck_loop,
                    pad: Some(curve),
                },
                Some(pad_cut),
            )));
        }
    }
    Ok(None)
}

/// A reinforcing pad across the seam between two host patches `run` (joined
/// in v into `joined`, whose seam lies at v = `seams[0]`): the neck's loop on
/// the joined surface and the pad's patch, the joined surface moved into the
/// nozzle's frame by `into_nozzle` with the knuckle's and the next piece's
/// analytic surfaces as one ([`Analytic::knuckled`]), trimmed by the pad's
/// loop `outer` (cut on the joined surface, with its seam samples) and the
/// neck's. The pad lies on the host's outside surface as it does on one
/// patch; the two patches' pieces of it meet on their seam inside the one
/// patch, exactly (the joined surface is each patch's own, unchanged).
///
/// # Errors
///
/// [`CutError::PadAcrossSeam`] when the run is not a knuckle (a torus) and
/// the piece tangent to it beyond (a sphere, a cone or a plane), or crosses
/// more than one seam; the neck's loop's own errors, or
/// [`CutError::AcrossSeamRoundPole`] when it goes round the pole.
fn pad_across(
    neck: &NurbsSurface,
    run: &[&Patch],
    (joined, seams): (&NurbsSurface, &[f64]),
    outer: &IntersectionLoop,
    tolerance: f64,
    into_nozzle: &DAffine3,
) -> Result<(IntersectionLoop, PadCut), CutError> {
    let names: Vec<&'static str> = run.iter().map(|p| p.name).collect();
    let refused = || CutError::PadAcrossSeam {
        patches: names.clone(),
    };
    let ([a, b], [seam]) = (run, seams) else {
        return Err(refused());
    };
    let ((u0, _), _) = joined.domain();
    let seam_point = joined.point(u0, *seam);
    let analytic = Analytic::knuckled(&a.analytic, &b.analytic, seam_point)
        .or_else(|| Analytic::knuckled(&b.analytic, &a.analytic, seam_point))
        .ok_or_else(refused)?;
    let inner = neck_host_intersection(neck, joined, tolerance).map_err(|source| {
        CutError::Intersection {
            which: CutLoop::Neck,
            patch: a.name,
            source,
        }
    })?;
    if inner.host_turns(joined) != 0 {
        return Err(CutError::AcrossSeamRoundPole { patches: names });
    }
    let surface = joined
        .transformed(into_nozzle)
        .map_err(CutError::Placement)?;
    let pad = PadCut {
        patch: Patch::new(PAD_PATCH, surface, analytic.transformed(into_nozzle)),
        outer: Arc::new(outer.clone()),
        inner: Arc::new(inner.clone()),
    };
    Ok((inner, pad))
}

/// Inserts a sample of the loop exactly at the host's seam angle u0 (mod period);
/// fails with the seam angle and the kernel's reason, if a solve failed.
fn add_seam_sample(
    neck: &NurbsSurface,
    host: &NurbsSurface,
    curve: &mut IntersectionLoop,
) -> Result<(), (f64, Option<NurbsError>)> {
    let ((u0, u1), _) = host.domain();
    let (nu0, nu1) = neck.domain().0;
    let (period, neck_period) = (u1 - u0, nu1 - nu0);
    let n = curve.host_uv.len();
    let turns = f64::from(curve.host_turns(host));
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, mut b) = (curve.host_uv[i].x, curve.host_uv[j].x);
        let (na, mut nb) = (curve.neck_uv[i].x, curve.neck_uv[j].x);
        if j == 0 {
            b += turns * period;
            nb += neck_period;
        }
        // Already on the seam: the nearest seam angle, not the next one above (a
        // sample a hair past u0 would otherwise be measured against u0 + period).
        let nearest = u0 + ((a - u0) / period).round() * period;
        if (a - nearest).abs() <= 1e-12 * period {
            return Ok(());
        }
        let lo = a.min(b);
        let target = u0 + ((lo - u0) / period).ceil() * period;
        if !(target > lo && target < a.max(b)) {
            continue;
        }
        let at = i + 1;
        let from = LoopSample {
            neck_uv: curve.neck_uv[i],
            host_uv: curve.host_uv[i],
        };
        let to = LoopSample {
            neck_uv: DVec2::new(nb, curve.neck_uv[j].y),
            host_uv: DVec2::new(b, curve.host_uv[j].y),
        };
        // One Newton solve on the seam angle; the bisection over generators below
        // only where it does not converge.
        if let Ok(c) = loop_crossing(neck, host, HostIsoline::U(target), from, to) {
            curve.points.insert(at, c.point);
            curve.neck_uv.insert(at, c.neck_uv);
            curve.host_uv.insert(at, c.host_uv);
            return Ok(());
        }
        let (mut x0, mut x1) = (na, nb);
        let mut hit = None;
        for _ in 0..SEAM_STEPS {
            let mid = 0.5 * (x0 + x1);
            let h = intersect_generator(neck, host, mid).map_err(|e| (target, Some(e)))?;
            let expected = a + (b - a) * (mid - na) / (nb - na);
            let hu = h.host_uv.x + period * ((expected - h.host_uv.x) / period).round();
            if (hu < target) == (a < target) {
                x0 = mid;
            } else {
                x1 = mid;
            }
            hit = Some((mid, h));
            if (hu - target).abs() <= 1e-13 * period {
                break;
            }
        }
        let Some((nu, h)) = hit else {
            return Err((target, None));
        };
        curve.points.insert(at, h.point);
        curve.neck_uv.insert(at, DVec2::new(nu, h.neck_v));
        curve.host_uv.insert(at, DVec2::new(target, h.host_uv.y));
        return Ok(());
    }
    Err((u0, None))
}

/// The reinforcing pad's patch off a straight course: the host patch's surface
/// moved into the nozzle's frame (its (u, v) unchanged, so the pad's loops trim it
/// directly). The pad lies on the host's outside surface; its thickness is
/// carried, not modelled.
fn pad_patch(
    host: &Patch,
    nozzle_frame: &DAffine3,
    host_frame: &DAffine3,
) -> Result<Patch, CutError> {
    let relative = nozzle_frame.inverse() * *host_frame;
    let surface = host
        .surface
        .transformed(&relative)
        .map_err(CutError::Placement)?;
    Ok(Patch::new(
        PAD_PATCH,
        surface,
        host.analytic.transformed(&relative),
    ))
}
