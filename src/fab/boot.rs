//! A boot's plates, developed exactly like a course's: the boot's mid-surface
//! is a cylinder of radius `r`, unrolled to `x = r·φ` (φ about the boot's
//! axis from its local +X, seen from outside) and `y` along its axis, from
//! the head's tangent line (`y = 0`, the boot-to-head circumferential seam)
//! up to its host end, the saddle-shaped curve where the boot meets its
//! course ([`super::openings::cut_boot`]: every vertex a point of the exact
//! intersection, unrolled). The boot is split round its circumference into
//! [`BootShell::plate_count`] equal plates by the shop's maximum plate length, the first
//! longitudinal seam at φ = 0.
//!
//! A plate's [`mid_area`](BootPlate::mid_area) is the exact mid-surface area
//! of its region, `∫ r·(T − s(φ)) dφ` with `s` the exact host end, by
//! Gauss–Legendre on each sample interval (the closed-form check is in
//! `tests/fab_boot.rs`). Its DXF ([`boot_drawing`]) is drawn like a plate's:
//! `CUT` the outline, `MARK` the quarter lines with their angles, `TEXT` the
//! id, grade, thickness and rolling radius.

use std::f64::consts::{FRAC_PI_2, TAU};

use dxf::Drawing;
use glam::DVec2;

use super::develop::{BootShell, Rolled};
use super::openings::NozzleCut;
use super::plate_dxf::{closed, entity, line, new_drawing, text, vertex};
use super::shop::{Attachment, Shop};
use crate::nurbs::GaussLegendre;

/// One plate of a boot.
#[derive(Clone, Debug, PartialEq)]
pub struct BootPlate {
    /// Plate id, `V-101-B1-P1`.
    pub id: String,
    /// The boot's part id.
    pub part: String,
    /// Number of the plate round the boot, from 0.
    pub index: usize,
    /// Thickness, mm.
    pub thickness: f64,
    /// Rolling (mid) radius, mm.
    pub radius: f64,
    /// Angle of its first seam about the boot's axis, radians.
    pub from: f64,
    /// Angle it spans, radians.
    pub angle: f64,
    /// The closed cutting outline, plate coordinates, mm: the straight edge
    /// at the tangent line, the two seams, the host end between them.
    pub outline: Vec<DVec2>,
    /// Exact mid-surface area of its region, mm².
    pub mid_area: f64,
}

impl BootPlate {
    /// Width along the circumference and greatest height, mm.
    pub fn extent(&self) -> (f64, f64) {
        let high = self.outline.iter().fold(0.0f64, |m, p| m.max(p.y));
        (self.radius * self.angle, high)
    }

    /// The DXF file name, `V-101-B1-P1.dxf`.
    pub fn file_name(&self) -> String {
        format!("{}.dxf", self.id)
    }
}

/// The plates of `boot`, cut into `course` as `cut` (its host end sampled at
/// a multiple of [`BootShell::plate_count`]), ids prefixed by the vessel's
/// `tag`.
pub fn boot_plates(
    tag: &str,
    boot: &BootShell,
    cut: &NozzleCut,
    course: &Rolled,
    shop: &Shop,
) -> Vec<BootPlate> {
    let n = boot.plate_count(shop.max_plate_length);
    let m = cut.saddle.len().saturating_sub(1);
    if m == 0 || !m.is_multiple_of(n) {
        return Vec::new();
    }
    let per = m / n;
    let meets = match shop.attachment {
        Attachment::SetIn => course.outside.0 - course.thickness,
        Attachment::SetOn => course.outside.0,
    };
    let rule = GaussLegendre::new(16);
    let height = |phi: f64| {
        cut.neck
            .crossing(boot.radius, meets, phi)
            .map_or(0.0, |(_, s)| boot.tangent - s)
    };
    let step = TAU / m as f64;
    (0..n)
        .map(|k| {
            let from = TAU * k as f64 / n as f64;
            let x0 = boot.radius * from;
            let angle = TAU / n as f64;
            let end = &cut.saddle[k * per..=(k + 1) * per];
            let mut outline = vec![DVec2::ZERO, DVec2::new(boot.radius * angle, 0.0)];
            outline.extend(end.iter().rev().map(|p| DVec2::new(p.x - x0, p.y)));
            let mid_area = (0..per)
                .map(|i| {
                    let a = from + step * i as f64;
                    boot.radius * rule.integrate(a, a + step, height)
                })
                .sum();
            BootPlate {
                id: format!("{tag}-{}-P{}", boot.id, k + 1),
                part: boot.id.clone(),
                index: k,
                thickness: boot.thickness,
                radius: boot.radius,
                from,
                angle,
                outline,
                mid_area,
            }
        })
        .collect()
}

/// The boot plate's drawing: outline, quarter lines (0° at the boot's local
/// +X) and text. `grade` is the material.
pub fn boot_drawing(plate: &BootPlate, grade: &str) -> Drawing {
    let mut d = new_drawing();
    let points = plate.outline.iter().map(|&p| vertex(p, 0.0)).collect();
    d.add_entity(entity("CUT", closed(points)));
    let (width, high) = plate.extent();
    let size = (0.02 * width).clamp(8.0, 40.0);
    for quarter in 0..4 {
        let phi = f64::from(quarter) * FRAC_PI_2;
        let rel = phi - plate.from;
        if rel < -1e-9 || rel > plate.angle + 1e-9 {
            continue;
        }
        let x = plate.radius * rel;
        d.add_entity(entity(
            "MARK",
            line(DVec2::new(x, 0.0), DVec2::new(x, 0.3 * high)),
        ));
        text(
            &mut d,
            DVec2::new(x + 0.2 * size, 0.1 * high),
            size,
            &format!("{}°", quarter * 90),
        );
    }
    text(&mut d, DVec2::new(0.0, -2.0 * size), size, &plate.id);
    text(
        &mut d,
        DVec2::new(0.0, -3.5 * size),
        size,
        &format!(
            "{grade}  t = {} mm  boot {}  roll to R {:.1} (mid)  y = 0 at the head's tangent line",
            plate.thickness, plate.part, plate.radius
        ),
    );
    d
}
