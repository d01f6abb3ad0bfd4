//! Choosing the front and side elevations' dimensions from the model, in view
//! coordinates: overall lengths, head depths, course ODs and lengths, supports,
//! nozzle projections and elevations (see the parent module).

use super::{DimSide, Dimensions, LinearDim, Ordinate, format_mm};
use glam::{DVec2, DVec3};

use crate::constraints::PartGeometry;
use crate::design::PartDesign;
use crate::drawing::data::VesselData;
use crate::project::{Projection, ViewKind};

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
