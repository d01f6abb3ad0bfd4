//! The code checks on a fitted scan, and the defects they find, located as an
//! inspector writes them (part, elevation from the datum, orientation).
//!
//! Courses are read on a grid of the fitted deviation (about 50 mm square). Each
//! cross-section gets a trimmed least-squares fit of the harmonics 0–2 of the
//! radial deviation: the second gives the out-of-roundness (D_max − D_min = 4·|c₂|,
//! ASME VIII-1 UG-80(a): ≤ 1 % of D), the first the section's centre, whose line
//! over the elevations gives the plumbness (API 650 §7.5.2 and common practice:
//! ≤ 1/200). What the harmonics leave is local: connected areas past the dent
//! threshold are dents (inward) or bulges (outward), except ridges running most
//! of a course's height within a 900 mm width, which are weld peaking, measured
//! with a 900 mm sweep board across the ridge (API 650 §7.5.4: ≤ 13 mm). Heads
//! are held to UG-81 (+1¼ % / −⅝ % of D). A tank's bottom edge elevation is
//! measured at API 653 Annex B stations (at least 8, at most 32 ft = 9.75 m
//! apart) and fitted by a cosine (planar tilt), with its R² and the out-of-plane
//! residual. A finding is reported when it is measurable (past its detection
//! floor), and flagged when it exceeds its limit.

mod local;

use std::f64::consts::{PI, TAU};

use glam::DVec3;
use serde::Serialize;

use super::band::{least_squares, solve_dense};
use super::envelope::{Envelope, Role};
use super::fit::{PatchFit, deviation_at};
use super::profile::u_of_angle;
use super::project::Foot;
use super::settlement::{Settlement, settlement};
use crate::design::VesselKind;
use local::{
    LOCAL_RULE, PatchArea, areas, cell, confirmed, harmonic, join_across_patches, revolution_areas,
};

/// Grid step of the course checks, mm.
pub const GRID: f64 = 50.0;

/// Length of the sweep board for peaking, mm (API 650 §7.5.4).
pub const BOARD: f64 = 900.0;

/// A finding: one measured defect with its place and its limit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Finding {
    /// `out_of_roundness`, `dent`, `bulge`, `peaking`, `plumbness`, `settlement`,
    /// `head_shape`.
    pub kind: &'static str,
    /// Part id (the vessel tag for plumbness and settlement).
    pub part: String,
    /// Size in `unit`.
    pub size: f64,
    /// `mm`, `%` (of D) or `1/x` (a ratio written as the fraction).
    pub unit: &'static str,
    /// Elevation from the datum, mm.
    pub elevation: f64,
    /// Orientation, degrees.
    pub orientation: f64,
    /// Extent across, mm (dents, bulges, peaking length).
    pub extent: Option<f64>,
    /// The limit in `unit`, if a code sets one.
    pub limit: Option<f64>,
    /// Whether the limit is exceeded.
    pub exceeds: bool,
    /// The rule.
    pub rule: &'static str,
}

/// What the checks found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Checks {
    /// Every finding.
    pub findings: Vec<Finding>,
    /// Worst out-of-roundness per course: (course, % of D).
    pub roundness: Vec<(String, f64)>,
    /// Largest outward and inward deviation per head: (head, +mm, −mm).
    pub heads: Vec<(String, f64, f64)>,
    /// Plumbness as a ratio (horizontal / vertical), for vertical vessels.
    pub plumbness: Option<f64>,
    /// Settlement, for tanks.
    pub settlement: Option<Settlement>,
}

/// Detection floors and the dent threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckOptions {
    /// Smallest local deviation reported as a dent or bulge, mm.
    pub dent_threshold: f64,
    /// Smallest out-of-roundness reported, fraction of D.
    pub roundness_floor: f64,
    /// Smallest plumbness reported, ratio.
    pub plumbness_floor: f64,
    /// Smallest settlement amplitude reported, mm.
    pub settlement_floor: f64,
}

impl CheckOptions {
    /// 3 mm dents, 0.2 % roundness, 1/2000 plumbness, 5 mm settlement.
    pub const DEFAULT: Self = Self {
        dent_threshold: 3.0,
        roundness_floor: 0.002,
        plumbness_floor: 0.0005,
        settlement_floor: 5.0,
    };
}

fn median(mut xs: Vec<f64>) -> f64 {
    if xs.is_empty() {
        return 0.0;
    }
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// The translation t that best explains normal deviations d ≈ n·t.
pub(super) fn best_shift(samples: &[(Foot, f64)]) -> DVec3 {
    let mut a = vec![vec![0.0; 3]; 3];
    let mut b = vec![0.0; 3];
    for (f, d) in samples {
        let n = f.normal.to_array();
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += n[i] * n[j];
            }
            b[i] += n[i] * d;
        }
    }
    let trace = a[0][0] + a[1][1] + a[2][2];
    for (i, row) in a.iter_mut().enumerate() {
        row[i] += 1e-6 * trace + 1e-12;
    }
    solve_dense(a, b).map_or(DVec3::ZERO, |t| DVec3::new(t[0], t[1], t[2]))
}

/// Harmonics 0–2 of one section, trimmed: (coefficients, residuals).
pub(super) fn section_harmonics(
    angles: &[f64],
    values: &[f64],
    covered: &[bool],
) -> ([f64; 5], Vec<f64>) {
    let rows: Vec<[f64; 5]> = angles
        .iter()
        .map(|&t| [1.0, t.cos(), t.sin(), (2.0 * t).cos(), (2.0 * t).sin()])
        .collect();
    let mut weights: Vec<f64> = covered.iter().map(|&c| if c { 1.0 } else { 0.0 }).collect();
    let mut coefficients = [0.0; 5];
    let mut residuals = values.to_vec();
    for _ in 0..3 {
        if let Some(c) = least_squares(&rows, values, &weights, 5) {
            coefficients.copy_from_slice(&c);
        }
        residuals = rows
            .iter()
            .zip(values)
            .map(|(r, y)| y - (0..5).map(|k| r[k] * coefficients[k]).sum::<f64>())
            .collect();
        let sigma = 1.4826
            * median(
                residuals
                    .iter()
                    .zip(covered)
                    .filter(|(_, c)| **c)
                    .map(|(r, _)| r.abs())
                    .collect(),
            );
        let limit = (3.0 * sigma).max(1.0);
        weights = residuals
            .iter()
            .zip(covered)
            .map(|(r, &c)| if c && r.abs() <= limit { 1.0 } else { 0.0 })
            .collect();
    }
    (coefficients, residuals)
}

/// Runs every check. `fits[i]` is the fit of `envelope.surfaces[i]`, if any;
/// `points` are in the vessel frame with their `feet`.
pub fn check(
    envelope: &Envelope,
    fits: &[Option<PatchFit>],
    points: &[DVec3],
    feet: &[Option<Foot>],
    options: &CheckOptions,
) -> Checks {
    let mut checks = Checks::default();
    let tank = envelope.kind == VesselKind::Tank;
    let vertical = envelope.kind != VesselKind::Horizontal;
    let mut centres: Vec<(f64, f64, f64)> = Vec::new();
    let mut pieces: Vec<PatchArea> = Vec::new();
    for (index, s) in envelope.surfaces.iter().enumerate() {
        let part = &envelope.parts[s.part];
        let Some(fit) = &fits[index] else { continue };
        match part.role {
            Role::Course => course_checks(
                envelope,
                index,
                fit,
                feet,
                options,
                tank,
                &mut checks,
                &mut centres,
            ),
            Role::Head => {
                let design = &s.patch.surface;
                let (mut out, mut inward) = (0.0f64, 0.0f64);
                let mut at = (0.0, DVec3::ZERO);
                // Where there are points (a fit says nothing where none fell),
                // less the head's best shift (a template reads the shape, not
                // where the head stands: a leaning vessel moves its heads).
                let own: Vec<(Foot, f64)> = feet
                    .iter()
                    .flatten()
                    .filter(|f| f.surface == index)
                    .map(|f| (*f, deviation_at(design, &fit.surface, f.u, f.v)))
                    .collect();
                let shift = best_shift(&own);
                for (f, d) in &own {
                    let d = d - f.normal.dot(shift);
                    out = out.max(d);
                    inward = inward.min(d);
                    if d.abs() > at.0 {
                        at = (d.abs(), f.point);
                    }
                }
                let entry = checks.heads.iter_mut().find(|h| h.0 == part.id);
                match entry {
                    Some(h) => {
                        h.1 = h.1.max(out);
                        h.2 = h.2.min(inward);
                    }
                    None => checks.heads.push((part.id.clone(), out, inward)),
                }
                let d = part.diameter;
                for (value, limit) in [(out, 0.0125 * d), (inward, -0.00625 * d)] {
                    if value.abs() > limit.abs() {
                        checks.findings.push(Finding {
                            kind: "head_shape",
                            part: part.id.clone(),
                            size: value,
                            unit: "mm",
                            elevation: at.1.z,
                            orientation: envelope.orientation_of(at.1),
                            extent: None,
                            limit: Some(limit),
                            exceeds: true,
                            rule: "ASME VIII-1 UG-81(a): within +1¼ % and −⅝ % of D of the specified shape",
                        });
                    }
                }
                pieces.extend(revolution_areas(
                    envelope,
                    index,
                    fit,
                    feet,
                    options.dent_threshold,
                ));
            }
            Role::Cone => pieces.extend(revolution_areas(
                envelope,
                index,
                fit,
                feet,
                options.dent_threshold,
            )),
            _ => {}
        }
    }
    checks.findings.extend(join_across_patches(pieces));
    if vertical && centres.len() >= 3 {
        let n = centres.len() as f64;
        let mz = centres.iter().map(|c| c.0).sum::<f64>() / n;
        let (mx, my) = (
            centres.iter().map(|c| c.1).sum::<f64>() / n,
            centres.iter().map(|c| c.2).sum::<f64>() / n,
        );
        let szz: f64 = centres.iter().map(|c| (c.0 - mz).powi(2)).sum();
        if szz > 0.0 {
            let sx = centres.iter().map(|c| (c.0 - mz) * (c.1 - mx)).sum::<f64>() / szz;
            let sy = centres.iter().map(|c| (c.0 - mz) * (c.2 - my)).sum::<f64>() / szz;
            let ratio = sx.hypot(sy);
            checks.plumbness = Some(ratio);
            if ratio > options.plumbness_floor {
                let top = centres.iter().map(|c| c.0).fold(f64::MIN, f64::max);
                checks.findings.push(Finding {
                    kind: "plumbness",
                    part: envelope.tag.clone(),
                    size: ratio,
                    unit: "ratio",
                    elevation: top,
                    orientation: envelope.orientation_of(DVec3::new(sx, sy, 0.0)),
                    extent: None,
                    limit: Some(1.0 / 200.0),
                    exceeds: ratio > 1.0 / 200.0,
                    rule: "out of plumb at most 1/200 of the height (API 650 §7.5.2)",
                });
            }
        }
    }
    // The scanner's noise as the bottom course's fit reads it.
    let bottom_noise = envelope
        .surfaces
        .iter()
        .zip(fits)
        .filter(|(s, f)| envelope.parts[s.part].role == Role::Course && f.is_some())
        .min_by(|a, b| {
            envelope.parts[a.0.part]
                .span
                .0
                .total_cmp(&envelope.parts[b.0.part].span.0)
        })
        .and_then(|(_, f)| f.as_ref().map(|f| f.rms))
        .unwrap_or(1.0);
    if tank && let Some(s) = settlement(envelope, points, bottom_noise) {
        let worst = s
            .deviations
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
        if let Some((k, &value)) = worst
            && value.abs() > (3.0 * s.uncertainty).max(options.dent_threshold)
        {
            checks.findings.push(Finding {
                kind: "out_of_plane_settlement",
                part: envelope.tag.clone(),
                size: value,
                unit: "mm",
                elevation: s.elevations[k],
                orientation: s.stations[k],
                extent: Some(s.spacing),
                limit: s.allowable,
                exceeds: s.allowable.is_some_and(|a| value.abs() > a),
                rule: "API 653 B.3.2.1: out-of-plane settlement S_i ≤ 11·L²·Y / (2·E·H)",
            });
        }
        if s.amplitude > options.settlement_floor {
            checks.findings.push(Finding {
                kind: "settlement",
                part: envelope.tag.clone(),
                size: s.amplitude,
                unit: "mm",
                elevation: 0.0,
                orientation: s.lowest,
                extent: None,
                limit: None,
                exceeds: false,
                rule: if s.cosine_valid {
                    "API 653 Annex B: cosine (planar tilt) fit of the shell's bottom edge"
                } else {
                    "API 653 Annex B: cosine fit of the shell's bottom edge with R² < 0.9: \
                     not a planar tilt, evaluate by B.2.2.5"
                },
            });
        }
        checks.settlement = Some(s);
    }
    checks
}

/// The course checks: roundness per section, section centres, dents, bulges,
/// peaking.
#[expect(
    clippy::too_many_arguments,
    reason = "one pass over a course's sections fills several outputs"
)]
#[expect(
    clippy::needless_range_loop,
    reason = "index arithmetic over matrix rows and columns reads as the algorithm"
)]
fn course_checks(
    envelope: &Envelope,
    index: usize,
    fit: &PatchFit,
    feet: &[Option<Foot>],
    options: &CheckOptions,
    tank: bool,
    checks: &mut Checks,
    centres: &mut Vec<(f64, f64, f64)>,
) {
    let s = &envelope.surfaces[index];
    let part = &envelope.parts[s.part];
    let design = &s.patch.surface;
    let d = part.diameter;
    let r = d / 2.0;
    let length = (part.span.1 - part.span.0).max(1.0);
    let nz = ((length / GRID).ceil() as usize).max(2);
    let nt = ((PI * d / GRID).ceil() as usize).clamp(72, 2880);
    let angles: Vec<f64> = (0..nt).map(|k| TAU * k as f64 / nt as f64).collect();
    let (v0, v1) = design.domain().1;
    // Grid nodes near points: a fit says nothing inside a gap of the scan.
    let own: Vec<(f64, f64)> = feet
        .iter()
        .flatten()
        .filter(|f| f.surface == index)
        .map(|f| (super::profile::angle_of_u(f.u), (f.v - v0) / (v1 - v0)))
        .collect();
    // The points themselves: (angle, v, normal deviation).
    let raw: Vec<(f64, f64, f64)> = feet
        .iter()
        .flatten()
        .filter(|f| f.surface == index)
        .map(|f| (super::profile::angle_of_u(f.u), f.v, f.deviation))
        .collect();
    let area = TAU * r * length;
    let reach = (1.5 * (area / own.len().max(1) as f64).sqrt()).max(GRID);
    let (rz, rt) = (
        (reach / length * nz as f64).ceil() as i64,
        (reach / (TAU * r) * nt as f64).ceil() as i64,
    );
    let mut covered = vec![vec![false; nt]; nz + 1];
    for &(t, s01) in &own {
        let (cz, ct) = (
            (s01 * nz as f64).round() as i64,
            (t / TAU * nt as f64).round() as i64,
        );
        for dz in -rz..=rz {
            let z = cz + dz;
            if z < 0 || z > nz as i64 {
                continue;
            }
            for dt in -rt..=rt {
                let t = (ct + dt).rem_euclid(nt as i64) as usize;
                covered[z as usize][t] = true;
            }
        }
    }
    let mut residual = vec![vec![0.0; nt]; nz + 1];
    let mut background = vec![[0.0; 5]; nz + 1];
    let mut worst = (0.0, 0.0, 0.0);
    for (iz, row) in residual.iter_mut().enumerate() {
        let v = v0 + (v1 - v0) * iz as f64 / nz as f64;
        let values: Vec<f64> = angles
            .iter()
            .map(|&t| deviation_at(design, &fit.surface, u_of_angle(t), v))
            .collect();
        let (c, res) = section_harmonics(&angles, &values, &covered[iz]);
        background[iz] = c;
        *row = res
            .iter()
            .zip(&covered[iz])
            .map(|(r, &c)| if c { *r } else { 0.0 })
            .collect();
        if covered[iz].iter().filter(|&&c| c).count() < nt / 2 {
            continue;
        }
        let local = design.point(0.0, v);
        let z = s.frame.transform_point3(local).z;
        let ovality = 4.0 * c[3].hypot(c[4]);
        if iz > 0 && iz < nz && ovality > worst.0 {
            worst = (ovality, z, 0.5 * c[4].atan2(c[3]));
        }
        // The section's centre off the course's design axis there: an
        // eccentric reducer's courses stand on axes apart by design.
        let axis = s.frame.transform_point3(DVec3::new(0.0, 0.0, local.z));
        let centre = s.frame.transform_point3(DVec3::new(c[1], c[2], local.z));
        centres.push((axis.z, centre.x - axis.x, centre.y - axis.y));
    }
    let fraction = worst.0 / d;
    checks.roundness.push((part.id.clone(), 100.0 * fraction));
    if fraction > options.roundness_floor {
        let axis = s
            .frame
            .transform_vector3(DVec3::new(worst.2.cos(), worst.2.sin(), 0.0));
        checks.findings.push(Finding {
            kind: "out_of_roundness",
            part: part.id.clone(),
            size: 100.0 * fraction,
            unit: "%",
            elevation: worst.1,
            orientation: envelope.orientation_of(axis) % 180.0,
            extent: None,
            limit: Some(1.0),
            exceeds: fraction > 0.01,
            rule: "ASME VIII-1 UG-80(a): D_max − D_min ≤ 1 % of D at any cross-section",
        });
    }
    // Local areas: 4-connected cells past the threshold, wrapping around; a
    // dent or bulge only where the points confirm it.
    let threshold = options.dent_threshold;
    let step_arc = TAU * r / nt as f64;
    let board = (0.5 * BOARD / step_arc).round() as usize;
    let found = areas(&residual, threshold);
    let points = raw.iter().map(|&(t, v, deviation)| {
        let (iz, it) = cell(t, (v - v0) / (v1 - v0), nz + 1, nt);
        (iz, it, deviation - harmonic(&background[iz], t))
    });
    let supported = confirmed(&found, nz + 1, nt, points, fit.rms);
    for (area, supported) in found.into_iter().zip(supported) {
        let (cells, sign) = (area.cells, area.sign);
        let (zmin, zmax) = cells
            .iter()
            .fold((usize::MAX, 0), |m, c| (m.0.min(c.0), m.1.max(c.0)));
        let mut columns: Vec<usize> = cells.iter().map(|c| c.1).collect();
        columns.sort_unstable();
        columns.dedup();
        let z_extent = (zmax - zmin) as f64 * length / nz as f64;
        let arc_extent = columns.len() as f64 * step_arc;
        let place = |iz: usize, it: usize| {
            let v = v0 + (v1 - v0) * iz as f64 / nz as f64;
            s.frame
                .transform_point3(design.point(u_of_angle(angles[it]), v))
        };
        if sign > 0.0 && z_extent >= (2.0 * arc_extent).max(500.0) && arc_extent <= BOARD {
            // A ridge along a long seam: peaking by the sweep board.
            let mut readings = Vec::new();
            let mut at = Vec::new();
            for a in zmin..=zmax {
                let row = &residual[a];
                let best = cells
                    .iter()
                    .filter(|c| c.0 == a)
                    .map(|&(_, b)| {
                        let left = row[(b + nt - board % nt) % nt];
                        let right = row[(b + board) % nt];
                        (row[b] - 0.5 * (left + right), b)
                    })
                    .max_by(|x, y| x.0.total_cmp(&y.0));
                if let Some((value, b)) = best {
                    readings.push(value);
                    at.push(b as f64);
                }
            }
            let column = median(at) as usize;
            // The board on the points themselves where there are enough:
            // the fit rounds a ridge's crest within the noise.
            let band = (
                v0 + (v1 - v0) * zmin as f64 / nz as f64,
                v0 + (v1 - v0) * zmax as f64 / nz as f64,
            );
            let value =
                board_on_points(&raw, r, angles[column], band).unwrap_or_else(|| median(readings));
            let mid = place((zmin + zmax) / 2, column);
            // A ridge split in pieces along its seam is one seam: keep the
            // longest piece's reading.
            let same_seam = checks.findings.iter_mut().find(|f| {
                f.kind == "peaking"
                    && f.part == part.id
                    && super::defects::wrap(
                        (f.orientation - envelope.orientation_of(mid)).to_radians(),
                    )
                    .abs()
                        * r
                        < BOARD / 2.0
            });
            if let Some(f) = same_seam {
                if f.extent.unwrap_or(0.0) < z_extent {
                    f.size = value;
                    f.elevation = mid.z;
                    f.orientation = envelope.orientation_of(mid);
                }
                f.extent = Some(f.extent.unwrap_or(0.0) + z_extent);
                continue;
            }
            checks.findings.push(Finding {
                kind: "peaking",
                part: part.id.clone(),
                size: value,
                unit: "mm",
                elevation: mid.z,
                orientation: envelope.orientation_of(mid),
                extent: Some(z_extent),
                limit: tank.then_some(13.0),
                exceeds: tank && value > 13.0,
                rule: "peaking at a long seam with a 900 mm sweep board (API 650 §7.5.4: ≤ 13 mm)",
            });
            continue;
        }
        if !supported {
            continue;
        }
        let extreme = cells
            .iter()
            .copied()
            .max_by(|x, y| (residual[x.0][x.1] * sign).total_cmp(&(residual[y.0][y.1] * sign)))
            .unwrap_or(cells[0]);
        let at = place(extreme.0, extreme.1);
        checks.findings.push(Finding {
            kind: if sign < 0.0 { "dent" } else { "bulge" },
            part: part.id.clone(),
            size: residual[extreme.0][extreme.1].abs(),
            unit: "mm",
            elevation: at.z,
            orientation: envelope.orientation_of(at),
            extent: Some(z_extent.max(arc_extent)),
            limit: None,
            exceeds: false,
            rule: LOCAL_RULE,
        });
    }
}

/// Points within this arc of a ridge's line read its crest, mm.
const BOARD_REACH: f64 = 0.5 * BOARD + 150.0;

/// The sweep board's reading of a ridge on a course of radius `r` near the angle
/// `theta` (radians), from the points `raw` (angle, v, normal deviation) whose v
/// lies in `band`: a tent `h·max(0, 1 − |a − a₀|/w)` plus a line in the arc `a`
/// from the seam, fitted by least squares over a₀ (±60 mm, 2 mm steps) and w
/// (100 to 900 mm, 10 mm steps); the reading is the gap between the model at
/// a₀ and a straight 900 mm board resting on it at a₀ ± 450 mm. `None` under
/// 200 points.
fn board_on_points(raw: &[(f64, f64, f64)], r: f64, theta: f64, band: (f64, f64)) -> Option<f64> {
    let data: Vec<(f64, f64)> = raw
        .iter()
        .filter(|p| p.1 >= band.0 && p.1 <= band.1)
        .map(|p| (r * super::defects::wrap(p.0 - theta), p.2))
        .filter(|p| p.0.abs() <= BOARD_REACH)
        .collect();
    if data.len() < 200 {
        return None;
    }
    let half = 0.5 * BOARD;
    let tent = |a: f64, a0: f64, w: f64| (1.0 - (a - a0).abs() / w).max(0.0);
    let mut best: Option<(f64, f64)> = None;
    for i in -30..=30 {
        let a0 = 2.0 * i as f64;
        for k in 0..=80 {
            let w = 100.0 + 10.0 * k as f64;
            let rows: Vec<[f64; 5]> = data
                .iter()
                .map(|&(a, _)| [1.0, a / half, tent(a, a0, w), 0.0, 0.0])
                .collect();
            let values: Vec<f64> = data.iter().map(|p| p.1).collect();
            let Some(c) = least_squares(&rows, &values, &vec![1.0; data.len()], 3) else {
                continue;
            };
            let sse: f64 = rows
                .iter()
                .zip(&values)
                .map(|(row, y)| (y - c[0] - c[1] * row[1] - c[2] * row[2]).powi(2))
                .sum();
            if best.is_none_or(|b| sse < b.0) {
                let ends = 0.5 * (tent(a0 - half, a0, w) + tent(a0 + half, a0, w));
                best = Some((sse, c[2] * (1.0 - ends)));
            }
        }
    }
    best.map(|b| b.1)
}
