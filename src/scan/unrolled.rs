//! Unrolled deviation maps for the report: each course and cone unrolled to
//! orientation × elevation, each head seen along the axis as a polar map
//! (orientation × distance from the axis), every cell coloured by the fitted
//! surface's normal deviation from the design with the GLB's scale
//! ([`colour`]), and drawn as SVG.
//!
//! Cells hold the mean deviation of the fitted surface (the design where no
//! points fell: no fit, the cell is grey) sampled a few times per cell on each
//! of the part's patches; positions are in the vessel frame as the findings
//! give them (elevation along the axis from the datum, orientation by the
//! plant convention of [`Envelope::orientation_of`]).

use std::fmt::Write;

use super::envelope::{Envelope, Role};
use super::fit::deviation_at;
use super::glb::colour;
use super::inspect::Inspection;

/// Sectors of orientation (5° each).
const SECTORS: usize = 72;
/// Height of a course's row, mm (rows at most [`MAX_ROWS`]).
const ROW: f64 = 100.0;
/// Most rows of a course's map.
const MAX_ROWS: usize = 60;
/// Rings of a head's polar map.
const RINGS: usize = 12;
/// Samples per cell in each direction.
const SAMPLES: usize = 4;

/// How a part is unrolled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Orientation across, elevation up: courses and cones.
    Unrolled,
    /// Seen along the axis: orientation around, distance from the axis out.
    Polar,
}

/// One cell of a map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapCell {
    /// Orientation range, degrees.
    pub orientation: (f64, f64),
    /// Elevation range (unrolled) or distance from the axis (polar), mm.
    pub band: (f64, f64),
    /// Mean normal deviation of the fitted surface, mm (outward positive);
    /// `None` where the part has no fit or no sample fell.
    pub deviation: Option<f64>,
}

/// A part's map: `sectors × rows` cells, `cells[row * sectors + sector]`.
#[derive(Clone, Debug, PartialEq)]
pub struct UnrolledMap {
    /// The part's id.
    pub part: String,
    /// How it is unrolled.
    pub layout: Layout,
    /// Sectors of orientation.
    pub sectors: usize,
    /// Rows (elevation bands or rings).
    pub rows: usize,
    /// The cells.
    pub cells: Vec<MapCell>,
}

impl UnrolledMap {
    /// The cell of the largest |deviation|.
    pub fn extreme(&self) -> Option<&MapCell> {
        self.cells
            .iter()
            .filter(|c| c.deviation.is_some())
            .max_by(|a, b| {
                let (x, y) = (a.deviation.unwrap_or(0.0), b.deviation.unwrap_or(0.0));
                x.abs().total_cmp(&y.abs())
            })
    }
}

/// The map of every course, cone and head of `envelope`, in design order.
pub fn unrolled_maps(envelope: &Envelope, inspection: &Inspection) -> Vec<UnrolledMap> {
    let mut maps = Vec::new();
    for (index, part) in envelope.parts.iter().enumerate() {
        if !part.role.is_envelope() {
            continue;
        }
        let layout = if part.role == Role::Head {
            Layout::Polar
        } else {
            Layout::Unrolled
        };
        // Samples of the part: (orientation, elevation or radius, deviation).
        let mut samples = Vec::new();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (k, s) in envelope.surfaces.iter().enumerate() {
            if s.part != index {
                continue;
            }
            let design = &s.patch.surface;
            let fit = inspection.fits.get(k).and_then(Option::as_ref);
            let ((u0, u1), (v0, v1)) = design.domain();
            let (nu, nv) = (SECTORS * SAMPLES, MAX_ROWS * SAMPLES);
            for i in 0..nu {
                for j in 0..nv {
                    let u = u0 + (u1 - u0) * (i as f64 + 0.5) / nu as f64;
                    let v = v0 + (v1 - v0) * (j as f64 + 0.5) / nv as f64;
                    let p = s.frame.transform_point3(design.point(u, v));
                    let y = match layout {
                        Layout::Unrolled => p.z,
                        Layout::Polar => p.truncate().length(),
                    };
                    lo = lo.min(y);
                    hi = hi.max(y);
                    let d = fit.map(|f| deviation_at(design, &f.surface, u, v));
                    samples.push((envelope.orientation_of(p), y, d));
                }
            }
        }
        if samples.is_empty() {
            continue;
        }
        let rows = match layout {
            Layout::Unrolled => (((hi - lo) / ROW).ceil() as usize).clamp(1, MAX_ROWS),
            Layout::Polar => {
                lo = 0.0;
                RINGS
            }
        };
        let height = (hi - lo).max(1e-9);
        let mut sum = vec![(0.0, 0usize); SECTORS * rows];
        for (o, y, d) in samples {
            let Some(d) = d else { continue };
            let a = ((o / 360.0 * SECTORS as f64) as usize).min(SECTORS - 1);
            let b = (((y - lo) / height * rows as f64) as usize).min(rows - 1);
            let cell = &mut sum[b * SECTORS + a];
            cell.0 += d;
            cell.1 += 1;
        }
        let step = 360.0 / SECTORS as f64;
        let cells = sum
            .into_iter()
            .enumerate()
            .map(|(k, (total, count))| {
                let (a, b) = ((k % SECTORS) as f64, (k / SECTORS) as f64);
                MapCell {
                    orientation: (a * step, (a + 1.0) * step),
                    band: (
                        lo + height * b / rows as f64,
                        lo + height * (b + 1.0) / rows as f64,
                    ),
                    deviation: (count > 0).then(|| total / count as f64),
                }
            })
            .collect();
        maps.push(UnrolledMap {
            part: part.id.clone(),
            layout,
            sectors: SECTORS,
            rows,
            cells,
        });
    }
    maps
}

/// `#rrggbb` of a deviation on the GLB's scale, grey without one.
fn fill(deviation: Option<f64>, scale: f64) -> String {
    let [r, g, b] = deviation.map_or([0.6, 0.6, 0.6], |d| colour(d, scale));
    let byte = |c: f32| (c.clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("#{:02x}{:02x}{:02x}", byte(r), byte(g), byte(b))
}

/// `text` made safe inside a double-quoted attribute.
fn attr(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('"', "&quot;")
}

/// The map as an SVG element; `scale` mm is full colour (as the GLB's).
pub fn to_svg(map: &UnrolledMap, scale: f64) -> String {
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let mut s = String::new();
    let tip = |c: &MapCell| match c.deviation {
        Some(d) => format!("{d:+.2} mm"),
        None => "no data".to_string(),
    };
    match map.layout {
        Layout::Unrolled => {
            // 2 px a degree across, 8 px a row, elevation up.
            let (w, h) = (720.0, 8.0 * map.rows as f64);
            let _ = write!(
                s,
                "<svg class=\"map\" data-part=\"{part}\" xmlns=\"http://www.w3.org/2000/svg\" \
                 width=\"{}\" height=\"{}\" viewBox=\"-60 -10 {} {}\" font-size=\"11\">",
                w + 80.0,
                h + 40.0,
                w + 80.0,
                h + 40.0,
                part = attr(&map.part)
            );
            for (k, c) in map.cells.iter().enumerate() {
                let (a, b) = (k % map.sectors, k / map.sectors);
                let _ = write!(
                    s,
                    "<rect x=\"{}\" y=\"{}\" width=\"10\" height=\"8\" fill=\"{}\">\
                     <title>EL {:.0}-{:.0} / {:.0}-{:.0}°: {}</title></rect>",
                    a * 10,
                    h - 8.0 * (b + 1) as f64,
                    fill(c.deviation, scale),
                    c.band.0,
                    c.band.1,
                    c.orientation.0,
                    c.orientation.1,
                    tip(c)
                );
            }
            for o in [0, 90, 180, 270, 360] {
                let _ = write!(
                    s,
                    "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{o}°</text>",
                    2 * o,
                    h + 14.0
                );
            }
            let (bottom, top) = (map.cells[0].band.0, map.cells[map.cells.len() - 1].band.1);
            let _ = write!(
                s,
                "<text x=\"-4\" y=\"{h}\" text-anchor=\"end\">EL {bottom:.0}</text>\
                 <text x=\"-4\" y=\"10\" text-anchor=\"end\">EL {top:.0}</text></svg>"
            );
        }
        Layout::Polar => {
            // Plan view: 0° up, orientation clockwise, the rim at 150 px.
            let rim = map.cells[map.cells.len() - 1].band.1.max(1e-9);
            let px = 150.0 / rim;
            let _ = write!(
                s,
                "<svg class=\"map\" data-part=\"{}\" xmlns=\"http://www.w3.org/2000/svg\" \
                 width=\"400\" height=\"350\" viewBox=\"-200 -175 400 350\" font-size=\"11\">",
                attr(&map.part)
            );
            let at = |o: f64, r: f64| {
                let t = o.to_radians();
                (r * px * t.sin(), -r * px * t.cos())
            };
            for c in &map.cells {
                let (o0, o1) = c.orientation;
                let (r0, r1) = c.band;
                let (a, b, cc, d) = (at(o0, r1), at(o1, r1), at(o1, r0), at(o0, r0));
                let _ = write!(
                    s,
                    "<path d=\"M{:.1},{:.1}A{R:.1},{R:.1} 0 0 1 {:.1},{:.1}L{:.1},{:.1}\
                     A{r:.1},{r:.1} 0 0 0 {:.1},{:.1}Z\" fill=\"{}\" stroke=\"none\">\
                     <title>r {:.0}-{:.0} / {:.0}-{:.0}°: {}</title></path>",
                    a.0,
                    a.1,
                    b.0,
                    b.1,
                    cc.0,
                    cc.1,
                    d.0,
                    d.1,
                    fill(c.deviation, scale),
                    r0,
                    r1,
                    o0,
                    o1,
                    tip(c),
                    R = r1 * px,
                    r = r0 * px,
                );
            }
            for (o, x, y, anchor) in [
                (0, 0.0, -156.0, "middle"),
                (90, 156.0, 4.0, "start"),
                (180, 0.0, 166.0, "middle"),
                (270, -156.0, 4.0, "end"),
            ] {
                let _ = write!(
                    s,
                    "<text x=\"{x}\" y=\"{y}\" text-anchor=\"{anchor}\">{o}°</text>"
                );
            }
            s.push_str("</svg>");
        }
    }
    s
}
