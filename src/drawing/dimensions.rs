//! Automatic dimensions of the front elevation: overall tangent-to-tangent length,
//! overall length or height over heads and supports, head depths, the tangent
//! lines and the base marked, the OD of each course, skirt height, saddle
//! spacing and the centreline's height above the saddles' base, nozzle projections (where
//! the nozzle lies in the view plane, so the length is true) and nozzle elevations
//! or positions as ordinate callouts.
//!
//! Dimensions are chosen from the model (`plan`) in view coordinates, then placed
//! (`place`) in tracks outside the view's lines on the side nearest their features:
//! ordinates first, then linear dimensions packed first-fit into parallel tracks so
//! that no two dimension lines or texts in a track overlap. Tracks are spaced by
//! more than the lettering, so texts of different tracks do not overlap either, and
//! everything lies outside the view's box; the layout reserves the paper margins
//! this needs (`margins`).

use glam::{DVec2, DVec3};

use super::data::VesselData;
use super::layout::{Margins, Placement};
use super::sheet::{Align, Item, Layer, Measure, PlacedDimension, Rect};
use super::text::text_width;
use crate::constraints::PartGeometry;
use crate::design::PartDesign;
use crate::project::{Projection, ViewKind};

/// Which side of the view a dimension goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DimSide {
    /// Left of the view, measuring vertically.
    Left,
    /// Right of the view, measuring vertically.
    Right,
    /// Below the view, measuring horizontally.
    Below,
    /// Above the view, measuring horizontally.
    Above,
}

impl DimSide {
    const ALL: [DimSide; 4] = [
        DimSide::Left,
        DimSide::Right,
        DimSide::Below,
        DimSide::Above,
    ];

    fn vertical(self) -> bool {
        matches!(self, DimSide::Left | DimSide::Right)
    }

    /// Unit vector pointing away from the view.
    fn outward(self) -> DVec2 {
        match self {
            DimSide::Left => -DVec2::X,
            DimSide::Right => DVec2::X,
            DimSide::Below => -DVec2::Y,
            DimSide::Above => DVec2::Y,
        }
    }
}

/// A linear dimension between two feature points (view coordinates, model mm).
#[derive(Clone, Debug, PartialEq)]
pub struct LinearDim {
    /// Side it is placed on.
    pub side: DimSide,
    /// First feature point.
    pub a: DVec2,
    /// Second feature point.
    pub b: DVec2,
    /// Its text.
    pub text: String,
}

/// An ordinate callout: a feature point and its label.
#[derive(Clone, Debug, PartialEq)]
pub struct Ordinate {
    /// Side it is placed on.
    pub side: DimSide,
    /// Feature point (view coordinates, model mm).
    pub at: DVec2,
    /// Label, e.g. `"N1 EL 10000"`.
    pub text: String,
    /// The elevation or position it labels, mm from the datum.
    pub value: f64,
}

/// The dimensions of a front view.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Dimensions {
    /// Linear dimensions.
    pub linear: Vec<LinearDim>,
    /// Ordinate callouts.
    pub ordinates: Vec<Ordinate>,
}

/// A length for a dimension text: whole mm, or one decimal when not whole.
pub fn format_mm(v: f64) -> String {
    if (v - v.round()).abs() < 0.05 {
        format!("{:.0}", v.round())
    } else {
        format!("{v:.1}")
    }
}

/// Outside radius of the stack at axial position `z` and the lateral offset of
/// the course's axis there (beyond an eccentric reducer), vessel frame; the
/// largest course radius on the vessel axis when `z` is outside every course.
fn section_at(data: &VesselData, z: f64) -> (DVec3, f64) {
    data.parts
        .iter()
        .find_map(|p| match &p.geometry {
            PartGeometry::Shell(s) if p.span.0 <= z + 1e-6 && z <= p.span.1 + 1e-6 => {
                let t = p.frame.translation;
                Some((DVec3::new(t.x, t.y, 0.0), s.outside_diameter / 2.0))
            }
            _ => None,
        })
        .unwrap_or((DVec3::ZERO, data.summary.max_diameter / 2.0))
}

/// The point of the stack's outline at axial position `z` on the `radial`
/// side (its course's axis offset plus its radius), vessel frame.
fn outline_at(data: &VesselData, radial: DVec3, z: f64) -> DVec3 {
    let (shift, r) = section_at(data, z);
    shift + radial * r + DVec3::Z * z
}

/// Chooses the front view's dimensions from the model.
pub fn plan(data: &VesselData) -> Dimensions {
    let front = data.view(ViewKind::Front).projection;
    let vertical = data.is_vertical();
    // The radial direction in the view plane and the view axis along the vessel.
    let radial = if vertical { front.right } else { front.up };
    let p = |v: DVec3| front.project(v);
    let tt = data.summary.tangent_length;
    let mut dims = Dimensions::default();
    let (low_side, high_side, axial_side) = if vertical {
        (DimSide::Below, DimSide::Above, DimSide::Right)
    } else {
        (DimSide::Left, DimSide::Right, DimSide::Above)
    };
    // Overall tangent-to-tangent length.
    dims.linear.push(LinearDim {
        side: axial_side,
        a: p(outline_at(data, radial, 0.0)),
        b: p(outline_at(data, radial, tt)),
        text: format!("T/T {}", format_mm(tt)),
    });
    for part in &data.parts {
        match (&part.design, &part.geometry) {
            (PartDesign::Shell(s), PartGeometry::Shell(g)) => {
                let z = 0.5 * (part.span.0 + part.span.1);
                let r = g.outside_diameter / 2.0;
                // About the course's own axis (offset beyond an eccentric reducer).
                let t = part.frame.translation;
                let centre = DVec3::new(t.x, t.y, z);
                dims.linear.push(LinearDim {
                    side: if z < tt / 2.0 { low_side } else { high_side },
                    a: p(centre - radial * r),
                    b: p(centre + radial * r),
                    text: format!("OD {} ({})", format_mm(g.outside_diameter), s.id),
                });
            }
            (_, PartGeometry::Head(_)) => {
                // Head depth: from its tangent line on the outline to the crown.
                // (A head's span may reach past its tangent line into the
                // course: which end it closes is told by its middle.)
                let bottom = 0.5 * (part.span.0 + part.span.1) < 0.5 * tt;
                let (tl, crown) = if bottom {
                    (0.0, part.span.0)
                } else {
                    (tt, part.span.1)
                };
                let t = part.frame.translation;
                dims.linear.push(LinearDim {
                    side: axial_side,
                    a: p(outline_at(data, radial, tl)),
                    b: p(DVec3::new(t.x, t.y, crown)),
                    text: format!("HEAD {}", format_mm((crown - tl).abs())),
                });
            }
            (PartDesign::Boot(b), PartGeometry::Boot(g)) => {
                // The boot's frame has its axis (+Z) through the course's axis:
                // the cylinder runs from the host's outside radius to the boot
                // head's tangent line. Its OD along the vessel axis, its length
                // below the shell and its position as an ordinate.
                let host = g.host_diameter / 2.0;
                let shell = part.frame.transform_point3(DVec3::new(0.0, 0.0, host));
                let tl = part
                    .frame
                    .transform_point3(DVec3::new(0.0, 0.0, host + g.length));
                let r = g.diameter / 2.0;
                dims.linear.push(LinearDim {
                    side: DimSide::Below,
                    a: p(tl - DVec3::Z * r),
                    b: p(tl + DVec3::Z * r),
                    text: format!("BOOT OD {} ({})", format_mm(g.diameter), b.id),
                });
                dims.linear.push(LinearDim {
                    side: low_side,
                    a: p(shell),
                    b: p(tl),
                    text: format!("BOOT {} ({})", format_mm(g.length), b.id),
                });
                dims.ordinates.push(Ordinate {
                    side: DimSide::Below,
                    at: p(tl),
                    text: format!("{} POS {}", b.id, format_mm(b.position)),
                    value: b.position,
                });
            }
            (PartDesign::Skirt(_), geometry) => {
                let edge = outline_at(data, radial, 0.0);
                dims.linear.push(LinearDim {
                    side: DimSide::Right,
                    a: p(edge + DVec3::Z * part.span.0),
                    b: p(edge),
                    text: format!("SKIRT {}", format_mm(-part.span.0)),
                });
                // The base ring's outside diameter, on the bearing plane.
                if let PartGeometry::Skirt(g) = geometry
                    && g.base_ring_width > 0.0
                {
                    let od = g.bottom_diameter() + 2.0 * g.base_ring_width;
                    let t = part.frame.translation;
                    let centre = DVec3::new(t.x, t.y, part.span.0);
                    dims.linear.push(LinearDim {
                        side: DimSide::Below,
                        a: p(centre - radial * (od / 2.0)),
                        b: p(centre + radial * (od / 2.0)),
                        text: format!("BASE RING OD {}", format_mm(od)),
                    });
                }
            }
            _ => {}
        }
    }
    course_lengths(data, axial_side, &mut dims);
    // Overall length or height, over heads and supports.
    let (lo, hi) = data.summary.extent;
    if hi - lo > tt + 1e-6 {
        dims.linear.push(LinearDim {
            side: axial_side,
            a: p(DVec3::Z * lo),
            b: p(DVec3::Z * hi),
            text: format!("OVERALL {}", format_mm(hi - lo)),
        });
    }
    // Saddle spacing.
    let saddles: Vec<(f64, f64)> = data
        .parts
        .iter()
        .filter_map(|part| match &part.geometry {
            PartGeometry::Saddle(_) => {
                Some((0.5 * (part.span.0 + part.span.1), part.frame.translation.y))
            }
            _ => None,
        })
        .collect();
    if let [(z0, _), (z1, _)] = saddles[..] {
        let bottom = data
            .view(ViewKind::Front)
            .bounds()
            .map_or(0.0, |(lo, _)| lo.y);
        dims.linear.push(LinearDim {
            side: DimSide::Below,
            a: DVec2::new(p(DVec3::Z * z0).x, bottom),
            b: DVec2::new(p(DVec3::Z * z1).x, bottom),
            text: format!("SADDLES {}", format_mm((z1 - z0).abs())),
        });
        // Height of the vessel's centreline above the saddles' base.
        let x = p(DVec3::Z * z0.max(z1)).x;
        dims.linear.push(LinearDim {
            side: DimSide::Right,
            a: DVec2::new(x, bottom),
            b: DVec2::new(x, p(DVec3::ZERO).y),
            text: format!("C/L {}", format_mm(p(DVec3::ZERO).y - bottom)),
        });
    }
    // Nozzles: projections where true length, elevations/positions as ordinates.
    for n in &data.nozzles {
        let axis = (n.frame.matrix3 * DVec3::Z).normalize();
        let origin = n.frame.translation;
        let mark = &n.design.mark;
        let projection = n.design.projection;
        let in_plane = true_length(&front, axis);
        let along_vessel = axis.cross(DVec3::Z).length() < 1e-6;
        if let Some(elevation) = n.design.elevation {
            // Where the projection is measured from: on the course's axis (offset
            // beyond an eccentric reducer), and for a hillside nozzle beside it.
            let foot = origin;
            let face = foot + axis * projection;
            if in_plane && !along_vessel {
                dims.linear.push(LinearDim {
                    side: if elevation < tt / 2.0 {
                        low_side
                    } else {
                        high_side
                    },
                    a: p(foot),
                    b: p(face),
                    text: format!("{mark} {}", format_mm(projection)),
                });
            }
            let at = p(face);
            // Vertical vessels: on the side the nozzle points to; horizontal ones:
            // below (the T/T and head-nozzle dimensions are above).
            let side = match (vertical, at.x > 1e-6) {
                (true, true) => DimSide::Right,
                (true, false) => DimSide::Left,
                (false, _) => DimSide::Below,
            };
            let label = if vertical { "EL" } else { "POS" };
            dims.ordinates.push(Ordinate {
                side,
                at,
                text: format!("{mark} {label} {}", format_mm(elevation)),
                value: elevation,
            });
        } else if along_vessel && true_length(&front, axis) {
            // Head nozzle: projection from the head's tangent line to the face.
            let tl = if axis.z > 0.0 { tt } else { 0.0 };
            let start = DVec3::new(origin.x, origin.y, tl);
            dims.linear.push(LinearDim {
                side: axial_side,
                a: p(start),
                b: p(start + axis * projection),
                text: format!("{mark} {}", format_mm(projection)),
            });
        }
    }
    if vertical {
        for (z, name) in [(0.0, "BTL"), (tt, "TTL")] {
            dims.ordinates.push(Ordinate {
                side: DimSide::Left,
                at: p(outline_at(data, -radial, z)),
                text: format!("{name} EL {}", format_mm(z)),
                value: z,
            });
        }
        // The base (skirt, legs or bottom head) below the datum.
        if lo < -1e-6 {
            let base = data
                .view(ViewKind::Front)
                .bounds()
                .map_or(p(DVec3::Z * lo), |(b, _)| {
                    DVec2::new(p(DVec3::Z * lo).x, b.y)
                });
            dims.ordinates.push(Ordinate {
                side: DimSide::Left,
                at: base,
                text: format!("BASE EL {}", format_mm(lo)),
                value: lo,
            });
        }
    } else {
        // Tangent lines marked at the outline's bottom.
        for (z, name) in [(0.0, "LTL"), (tt, "RTL")] {
            dims.ordinates.push(Ordinate {
                side: DimSide::Below,
                at: p(outline_at(data, -radial, z)),
                text: format!("{name} POS {}", format_mm(z)),
                value: z,
            });
        }
    }
    dims
}

/// Chooses the side elevation's dimensions: the projection of every shell nozzle
/// the front elevation foreshortens and the side view shows at true length (its
/// elevation is already on the front view, where the axis is true length).
pub fn plan_side(data: &VesselData) -> Dimensions {
    let front = data.view(ViewKind::Front).projection;
    let side_view = data.view(ViewKind::Side).projection;
    let tt = data.summary.tangent_length;
    let mut dims = Dimensions::default();
    for n in &data.nozzles {
        let Some(elevation) = n.design.elevation else {
            continue;
        };
        let axis = (n.frame.matrix3 * DVec3::Z).normalize();
        if true_length(&front, axis) || !true_length(&side_view, axis) {
            continue;
        }
        let foot = n.frame.translation;
        let face = foot + axis * n.design.projection;
        let shown = side_view.project(axis);
        // Measured across the view's axis: below/above (horizontal) or
        // left/right (vertical), on the half where the nozzle sits.
        let side = if shown.x.abs() >= shown.y.abs() {
            if data.is_vertical() && elevation >= tt / 2.0 {
                DimSide::Above
            } else {
                DimSide::Below
            }
        } else if shown.y > 0.0 {
            DimSide::Right
        } else {
            DimSide::Left
        };
        dims.linear.push(LinearDim {
            side,
            a: side_view.project(foot),
            b: side_view.project(face),
            text: format!("{} {}", n.design.mark, format_mm(n.design.projection)),
        });
    }
    dims
}

/// The length of each course and reducer along the axis, as a chain beside the
/// T/T dimension, where the stack has more than one of them (one course is the
/// T/T itself).
fn course_lengths(data: &VesselData, side: DimSide, dims: &mut Dimensions) {
    let front = data.view(ViewKind::Front).projection;
    let radial = if data.is_vertical() {
        front.right
    } else {
        front.up
    };
    let mut courses: Vec<(f64, f64, &str)> = data
        .parts
        .iter()
        .filter_map(|part| match &part.design {
            PartDesign::Shell(s) => Some((part.span.0, part.span.1, s.id.as_str())),
            PartDesign::Reducer(r) => Some((part.span.0, part.span.1, r.id.as_str())),
            _ => None,
        })
        .collect();
    if courses.len() < 2 {
        return;
    }
    courses.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (z0, z1, id) in courses {
        dims.linear.push(LinearDim {
            side,
            a: front.project(outline_at(data, radial, z0)),
            b: front.project(outline_at(data, radial, z1)),
            text: format!("{id} {}", format_mm(z1 - z0)),
        });
    }
}

/// Whether a direction shows its true length in the view.
fn true_length(front: &Projection, axis: DVec3) -> bool {
    axis.dot(front.toward_viewer).abs() < 1e-6
}

/// Spacing between linear tracks, mm, for lettering of height `h`.
fn track_spacing(h: f64) -> f64 {
    2.2 * h + 2.5
}

/// Distance from the view's box to the first track or ordinate line, mm.
fn first_offset(h: f64) -> f64 {
    2.0 * h + 3.0
}

/// Tracks per side after packing, and each linear dimension's track.
fn pack(dims: &Dimensions, h: f64, scale: f64) -> (Vec<usize>, [usize; 4]) {
    let mut tracks: Vec<Vec<Vec<(f64, f64)>>> = vec![Vec::new(); 4];
    let mut order: Vec<usize> = (0..dims.linear.len()).collect();
    let along = |d: &LinearDim, p: DVec2| if d.side.vertical() { p.y } else { p.x };
    let span = |d: &LinearDim| (along(d, d.b) - along(d, d.a)).abs();
    order.sort_by(|&i, &j| span(&dims.linear[i]).total_cmp(&span(&dims.linear[j])));
    let mut assigned = vec![0usize; dims.linear.len()];
    for i in order {
        let d = &dims.linear[i];
        let s = DimSide::ALL.iter().position(|&x| x == d.side).unwrap_or(0);
        let (a, b) = (along(d, d.a) / scale, along(d, d.b) / scale);
        let mid = 0.5 * (a + b);
        let half_text = 0.5 * text_width(&d.text, h) + 1.0;
        let interval = (
            a.min(b).min(mid - half_text) - 1.0,
            a.max(b).max(mid + half_text) + 1.0,
        );
        let t = tracks[s]
            .iter()
            .position(|used| {
                used.iter()
                    .all(|&(lo, hi)| interval.1 < lo || hi < interval.0)
            })
            .unwrap_or_else(|| {
                tracks[s].push(Vec::new());
                tracks[s].len() - 1
            });
        tracks[s][t].push(interval);
        assigned[i] = t;
    }
    let counts = std::array::from_fn(|s| tracks[s].len());
    (assigned, counts)
}

/// Width of the widest ordinate label on each side, mm.
fn ordinate_widths(dims: &Dimensions, h: f64) -> [f64; 4] {
    std::array::from_fn(|s| {
        dims.ordinates
            .iter()
            .filter(|o| o.side == DimSide::ALL[s])
            .map(|o| text_width(&o.text, h))
            .fold(0.0, f64::max)
    })
}

/// Depth of the ordinate band on each side (0 without ordinates), mm.
fn ordinate_depths(dims: &Dimensions, h: f64) -> [f64; 4] {
    let widths = ordinate_widths(dims, h);
    std::array::from_fn(|s| {
        if dims.ordinates.iter().any(|o| o.side == DimSide::ALL[s]) {
            first_offset(h) + widths[s] + 3.0
        } else {
            0.0
        }
    })
}

/// Paper margins the dimensions need round the view at `scale`.
pub fn margins(dims: &Dimensions, h: f64, scale: f64) -> Margins {
    let (_, counts) = pack(dims, h, scale);
    let ord = ordinate_depths(dims, h);
    let depth = |s: usize| {
        let tracks = if counts[s] > 0 {
            first_offset(h) + track_spacing(h) * (counts[s] as f64 - 1.0) + h + 2.0
        } else {
            0.0
        };
        ord[s] + tracks
    };
    Margins {
        left: depth(0),
        right: depth(1),
        bottom: depth(2),
        top: depth(3),
    }
}

/// An arrowhead at `tip` pointing along `dir` (unit), length `len`.
fn arrow(tip: DVec2, dir: DVec2, len: f64) -> Item {
    let back = tip - dir * len;
    let side = dir.perp() * (len / 3.0) * 0.5;
    Item::Fill {
        layer: Layer::Dimension,
        points: vec![tip, back + side, back - side],
    }
}

/// Places the dimensions of view `k` whose lines lie in `view_box`; appends the
/// items, the placed dimensions and, in the same order, the indices of their
/// text items (for the label placer).
#[expect(
    clippy::too_many_arguments,
    reason = "the view's dimensions are placed into the sheet's shared item, dimension and text lists"
)]
pub fn place(
    dims: &Dimensions,
    k: usize,
    view_box: Rect,
    placement: &Placement,
    h: f64,
    items: &mut Vec<Item>,
    placed: &mut Vec<PlacedDimension>,
    texts: &mut Vec<usize>,
) {
    let view = ViewKind::ALL[k];
    let to_sheet = |p: DVec2| placement.to_sheet(k, p);
    let ord = ordinate_depths(dims, h);
    // Where a side's band starts (the box edge) as a coordinate across the side.
    let edge = |side: DimSide| match side {
        DimSide::Left => view_box.min.x,
        DimSide::Right => view_box.max.x,
        DimSide::Below => view_box.min.y,
        DimSide::Above => view_box.max.y,
    };
    let with_across = |side: DimSide, along: f64, across: f64| {
        if side.vertical() {
            DVec2::new(across, along)
        } else {
            DVec2::new(along, across)
        }
    };
    // Ordinates.
    for side in DimSide::ALL {
        let mut list: Vec<(DVec2, &str, f64)> = dims
            .ordinates
            .iter()
            .filter(|o| o.side == side)
            .map(|o| (to_sheet(o.at), o.text.as_str(), o.value))
            .collect();
        if list.is_empty() {
            continue;
        }
        let out = side.outward();
        let base = edge(side) + out.dot(DVec2::ONE) * first_offset(h);
        let along = |p: DVec2| if side.vertical() { p.y } else { p.x };
        list.sort_by(|a, b| along(a.0).total_cmp(&along(b.0)));
        let mut last = f64::MIN;
        let lo = list.first().map_or(0.0, |l| along(l.0));
        let hi = list.last().map_or(0.0, |l| along(l.0));
        items.push(Item::Line {
            layer: Layer::Dimension,
            points: vec![with_across(side, lo, base), with_across(side, hi, base)],
            closed: false,
        });
        for (p, text, value) in list {
            let first = items.len();
            let level = along(p);
            let slot = level.max(last + 1.5 * h);
            last = slot;
            // Extension from the feature to the ordinate line, a tick, and a jog to
            // the label when it had to move.
            let start = p + out * 1.5;
            items.push(Item::Line {
                layer: Layer::Dimension,
                points: vec![start, with_across(side, level, base)],
                closed: false,
            });
            let label_at = base + out.dot(DVec2::ONE) * 2.5;
            items.push(Item::Line {
                layer: Layer::Dimension,
                points: vec![
                    with_across(side, level, base),
                    with_across(side, slot, label_at - out.dot(DVec2::ONE) * 0.8),
                ],
                closed: false,
            });
            let w = text_width(text, h);
            let (at, align, rotation, text_box) = match side {
                DimSide::Left => (
                    DVec2::new(label_at, slot - 0.5 * h),
                    Align::End,
                    0.0,
                    Rect::new(
                        DVec2::new(label_at - w, slot - 0.5 * h),
                        DVec2::new(label_at, slot + 0.5 * h),
                    ),
                ),
                DimSide::Right => (
                    DVec2::new(label_at, slot - 0.5 * h),
                    Align::Start,
                    0.0,
                    Rect::new(
                        DVec2::new(label_at, slot - 0.5 * h),
                        DVec2::new(label_at + w, slot + 0.5 * h),
                    ),
                ),
                DimSide::Below => (
                    DVec2::new(slot + 0.5 * h, label_at),
                    Align::End,
                    90.0,
                    Rect::new(
                        DVec2::new(slot - 0.5 * h, label_at - w),
                        DVec2::new(slot + 0.5 * h, label_at),
                    ),
                ),
                DimSide::Above => (
                    DVec2::new(slot + 0.5 * h, label_at),
                    Align::Start,
                    90.0,
                    Rect::new(
                        DVec2::new(slot - 0.5 * h, label_at),
                        DVec2::new(slot + 0.5 * h, label_at + w),
                    ),
                ),
            };
            texts.push(items.len());
            items.push(Item::Text {
                at,
                height: h,
                align,
                rotation,
                text: text.to_string(),
            });
            placed.push(PlacedDimension {
                view,
                text: text.to_string(),
                text_box,
                line_box: Rect::new(
                    with_across(side, level, base),
                    with_across(side, level, base),
                ),
                measure: Measure::Ordinate {
                    feature: p,
                    leader_end: with_across(side, slot, label_at),
                    vertical: side.vertical(),
                    value,
                },
                items: first..items.len(),
            });
        }
    }
    // Linear dimensions.
    let (assigned, _) = pack(dims, h, placement.scale);
    for (d, &t) in dims.linear.iter().zip(&assigned) {
        let first = items.len();
        let s = DimSide::ALL.iter().position(|&x| x == d.side).unwrap_or(0);
        let side = d.side;
        let out = side.outward();
        let sign = out.dot(DVec2::ONE);
        let across = edge(side) + sign * (ord[s] + first_offset(h) + track_spacing(h) * t as f64);
        let (a, b) = (to_sheet(d.a), to_sheet(d.b));
        let along = |p: DVec2| if side.vertical() { p.y } else { p.x };
        let (pa, pb) = (
            with_across(side, along(a), across),
            with_across(side, along(b), across),
        );
        for (f, q) in [(a, pa), (b, pb)] {
            items.push(Item::Line {
                layer: Layer::Dimension,
                points: vec![f + (q - f).normalize_or_zero() * 1.5, q + out * 1.5],
                closed: false,
            });
        }
        items.push(Item::Line {
            layer: Layer::Dimension,
            points: vec![pa, pb],
            closed: false,
        });
        let dir = (pb - pa).normalize_or_zero();
        let len = 0.9 * h;
        items.push(arrow(pa, -dir, len));
        items.push(arrow(pb, dir, len));
        let mid = 0.5 * (along(a) + along(b));
        let w = text_width(&d.text, h);
        let (at, rotation, text_box) = if side.vertical() {
            let x = across - 1.0;
            (
                DVec2::new(x, mid),
                90.0,
                Rect::new(
                    DVec2::new(x - h, mid - 0.5 * w),
                    DVec2::new(x, mid + 0.5 * w),
                ),
            )
        } else {
            let y = across + 1.0;
            (
                DVec2::new(mid, y),
                0.0,
                Rect::new(
                    DVec2::new(mid - 0.5 * w, y),
                    DVec2::new(mid + 0.5 * w, y + h),
                ),
            )
        };
        texts.push(items.len());
        items.push(Item::Text {
            at,
            height: h,
            align: Align::Middle,
            rotation,
            text: d.text.clone(),
        });
        placed.push(PlacedDimension {
            view,
            text: d.text.clone(),
            text_box,
            line_box: Rect::new(pa, pb),
            measure: Measure::Linear {
                a,
                b,
                line: pa,
                vertical: side.vertical(),
                value: (along(d.b) - along(d.a)).abs(),
            },
            items: first..items.len(),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drawing::vessel_data;
    use crate::mesh::TessellationOptions;
    use crate::model::Model;

    /// The front view's dimensions of a column whose upper course S2 (OD 1400)
    /// stands 300 mm east of the lower one beyond an eccentric reducer: its OD is
    /// dimensioned across its own axis, and the T/T and TTL callouts reach its
    /// outline, not the vessel axis's.
    #[test]
    fn dimensions_beyond_an_eccentric_reducer_follow_the_offset_axis() {
        let design = crate::design::parse(
            r#"{"format": "vesselcad/1", "vessels": [{"tag": "X", "kind": "vertical",
              "parts": [
                {"head": {"id": "H1", "shape": "ellipsoidal"}},
                {"shell": {"id": "S1", "od": 2000, "length": 2000}},
                {"reducer": {"id": "R1", "length": 800, "eccentric": 90}},
                {"shell": {"id": "S2", "od": 1400, "length": 2000}},
                {"head": {"id": "H2", "shape": "ellipsoidal"}}
              ]}]}"#,
        )
        .unwrap();
        let model = Model::from_design(&design, TessellationOptions::chord(5.0)).unwrap();
        let data = vessel_data(&model, "X").unwrap();
        let front = data.view(ViewKind::Front).projection;
        let p = |v: DVec3| front.project(v);
        let dims = plan(&data);
        let find = |prefix: &str| {
            dims.linear
                .iter()
                .find(|d| d.text.starts_with(prefix))
                .unwrap_or_else(|| panic!("no {prefix} dimension in {dims:?}"))
        };
        let centre = DVec3::new(300.0, 0.0, 3800.0);
        let od = find("OD 1400 (S2)");
        let mid = (od.a + od.b) / 2.0;
        assert!((mid - p(centre)).length() < 1e-9, "{mid} vs {}", p(centre));
        assert!(((od.a - od.b).length() - 1400.0).abs() < 1e-9);
        // The T/T dimension's top end lies on S2's outline at the top tangent line.
        let tt = find("T/T ");
        let top = DVec3::new(300.0, 0.0, 4800.0) + front.right * 700.0;
        assert!((tt.b - p(top)).length() < 1e-9, "{} vs {}", tt.b, p(top));
        let ttl = dims
            .ordinates
            .iter()
            .find(|o| o.text.starts_with("TTL"))
            .unwrap();
        let left = DVec3::new(300.0, 0.0, 4800.0) - front.right * 700.0;
        assert!((ttl.at - p(left)).length() < 1e-9);
    }
}
