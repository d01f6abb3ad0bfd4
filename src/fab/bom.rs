//! The bill of materials of one vessel, from the model and its plate layout
//! ([`FabPlan`]): one line per plate of the rolled parts (grade, thickness,
//! the plate's exact developed size, area, mass), formed heads with their
//! blanks, nozzle pipe (NPS, schedule, cut length) and flanges (type, class,
//! facing, B16.5 bolting and gasket), reinforcing pads and supports.
//!
//! Masses are the weight model's (`crate::weights`), item by item, so the BOM
//! total is the vessel's empty (metal) weight: pressure parts by their walls
//! (`plate_size::wall_mass`), shared among the part's plates by their
//! developed mid-surface areas; supports, boot and pads as `weights::metal`
//! weighs them (a skirt's mass shared among its plates likewise); and each
//! nozzle split into its pipe (the neck outside the host, B36.10M wall) and
//! its flange (the rest of the model's nozzle body). A part the development
//! leaves out (an eccentric reducer) keeps one line with the closed-form size
//! of `plate_size`. A boot's mass is shared likewise among its plates and
//! its head's blank; a head's line names the openings marked on its blank.
//! Bolts and gaskets are listed on their flange's line, not weighed (the
//! weight model does not carry them).
//!
//! Materials: the vessel's `material` for plate (SA-516-70 when none is
//! given); pipe and flanges of the matching product form (SA-106-B / SA-105
//! for carbon steel, SA-312-TP316L / SA-182-F316L for stainless).

use std::f64::consts::PI;

use serde::Serialize;

use super::develop::Outline;
use super::plate_size::{Developed, developed, wall_mass};
use super::vessel_plan::FabPlan;
use crate::design::{FacingDesign, FlangeDesign, PartDesign, VesselDesign};
use crate::operating::{STAINLESS_DENSITY, metal_density, thickness};
use crate::parts::tables::{flange, pipe};
use crate::weights::metal::{DEFAULT_PLATE, items, neck_start_outside};

/// mm³ → m³.
const MM3_TO_M3: f64 = 1e-9;

/// One line of the BOM.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BomLine {
    /// Plate id (`V-1-S1-P2`), part id, nozzle mark, or `mark/flange`,
    /// `mark/pad`.
    pub item: String,
    /// The part or nozzle the line belongs to (a plate's part id).
    pub part: String,
    /// `plate`, `head`, `pipe`, `flange`, `pad`, `support`.
    pub kind: &'static str,
    /// What it is.
    pub description: String,
    /// Material specification.
    pub material: String,
    /// Plate or wall thickness, mm.
    pub thickness: Option<f64>,
    /// Developed plate (rolled and formed parts).
    pub developed: Option<Developed>,
    /// Size as printed: developed size, pipe cut length, pad OD.
    pub size: String,
    /// Area of one piece, m² (plates, heads, pads).
    pub area: Option<f64>,
    /// Pieces.
    pub quantity: u32,
    /// Mass of all pieces, kg.
    pub mass: f64,
    /// Bolting of a flange (B16.5): count × size.
    pub bolting: Option<String>,
    /// Gasket of a flange.
    pub gasket: Option<String>,
}

/// A vessel's bill of materials.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Bom {
    /// Vessel tag.
    pub vessel: String,
    /// Lines in design order: parts, then nozzles with their flanges and pads.
    pub lines: Vec<BomLine>,
    /// Sum of the lines' masses, kg.
    pub total_mass: f64,
}

/// Material specifications of the product forms of a vessel.
struct Grades {
    plate: String,
    pipe: &'static str,
    forging: &'static str,
}

fn grades(design: &VesselDesign) -> Grades {
    let stainless =
        metal_density(&design.design) == STAINLESS_DENSITY && design.design.metal_density.is_none();
    Grades {
        plate: design
            .design
            .material
            .clone()
            .unwrap_or_else(|| "SA-516-70".into()),
        pipe: if stainless {
            "SA-312-TP316L"
        } else {
            "SA-106-B"
        },
        forging: if stainless { "SA-182-F316L" } else { "SA-105" },
    }
}

/// The gasket a facing takes.
fn gasket(facing: FacingDesign, nps: &str, class: u32, outside: f64, raised: f64) -> String {
    match facing {
        FacingDesign::RaisedFace => {
            format!("spiral-wound ASME B16.20, NPS {nps} Class {class}, sealing on RF Ø{raised:.0}")
        }
        FacingDesign::FlatFace => {
            format!("full-face sheet ASME B16.21, NPS {nps} Class {class}, OD {outside:.0}")
        }
        FacingDesign::RingJoint => format!("ring-joint ASME B16.20, NPS {nps} Class {class}"),
    }
}

/// The developed plate of a plate of the layout.
fn plate_developed(fab: &FabPlan, plate: &super::plates::Plate) -> Developed {
    let course = &fab.seams.courses[plate.course_index];
    let rolled = &fab.developments.rolled[course.rolled];
    let rolling_radius = 0.5 * (rolled.radius_at(course.z.0) + rolled.radius_at(course.z.1));
    match plate.outline {
        Outline::Rectangle { width, height } => Developed::Rectangle {
            width,
            length: height,
            rolling_radius,
        },
        Outline::Sector {
            inner,
            outer,
            angle,
        } => Developed::Sector {
            inner,
            outer,
            angle: angle.to_degrees(),
            rolling_radius,
        },
        Outline::Oblique(o) => {
            let (width, height) = plate.outline.extent();
            Developed::Oblique {
                width,
                height,
                angle: o.developed_angle().to_degrees(),
                rolling_radius,
            }
        }
    }
}

/// One line per plate of part `part`, sharing `mass` by developed area; none
/// when the layout has no plate of it.
fn plate_lines(
    fab: &FabPlan,
    part: &str,
    description: &str,
    grade: &str,
    mass: f64,
) -> Vec<BomLine> {
    let plates: Vec<_> = fab.plates.iter().filter(|p| p.part == part).collect();
    let total: f64 = plates.iter().map(|p| p.mid_area).sum();
    plates
        .iter()
        .map(|p| {
            let d = plate_developed(fab, p);
            BomLine {
                item: p.id.clone(),
                part: part.to_string(),
                kind: "plate",
                description: format!("{description}, course {}", p.course),
                material: grade.to_string(),
                thickness: Some(p.thickness),
                size: d.label(),
                developed: Some(d),
                area: Some(p.mid_area * 1e-6),
                quantity: 1,
                mass: mass * p.mid_area / total,
                bolting: None,
                gasket: None,
            }
        })
        .collect()
}

/// `"; openings N1, M1 marked on the blank, cut after forming"` for the
/// openings mapped onto head `head`'s blank, or nothing.
fn marked_openings(fab: &FabPlan, head: &str) -> String {
    let marks: Vec<&str> = fab
        .openings
        .formed
        .iter()
        .filter(|f| f.host == head && f.blank.is_some())
        .map(|f| f.mark.as_str())
        .collect();
    if marks.is_empty() {
        String::new()
    } else {
        format!(
            "; openings {} marked on the blank, cut after forming",
            marks.join(", ")
        )
    }
}

/// A boot's lines: one per plate (its bounding rectangle, host end
/// saddle-cut) and its head's blank, sharing the boot's `mass` by developed
/// mid-surface area; `None` when the boot has no plates or head blank.
fn boot_lines(
    fab: &FabPlan,
    boot: &str,
    head_shape: &str,
    grade: &str,
    mass: f64,
) -> Option<Vec<BomLine>> {
    let shell = fab.developments.boots.iter().find(|b| b.id == boot)?;
    let head = shell.head.as_ref()?;
    let plates: Vec<_> = fab
        .boot_plates()
        .into_iter()
        .filter(|p| p.part == boot)
        .collect();
    if plates.is_empty() {
        return None;
    }
    let total = plates.iter().map(|p| p.mid_area).sum::<f64>() + head.mid_area;
    let mut out: Vec<BomLine> = plates
        .iter()
        .map(|p| {
            let (width, length) = p.extent();
            let d = Developed::Rectangle {
                width,
                length,
                rolling_radius: p.radius,
            };
            BomLine {
                item: p.id.clone(),
                part: boot.to_string(),
                kind: "plate",
                description: "boot shell, host end saddle-cut (size: its bounding rectangle)"
                    .into(),
                material: grade.to_string(),
                thickness: Some(p.thickness),
                size: d.label(),
                developed: Some(d),
                area: Some(p.mid_area * 1e-6),
                quantity: 1,
                mass: mass * p.mid_area / total,
                bolting: None,
                gasket: None,
            }
        })
        .collect();
    let d = Developed::Blank {
        diameter: head.diameter,
    };
    out.push(BomLine {
        item: head.id.clone(),
        part: boot.to_string(),
        kind: "head",
        description: format!("{} head of boot {boot}", head_shape.to_lowercase()),
        material: grade.to_string(),
        thickness: Some(head.thickness),
        size: d.label(),
        developed: Some(d),
        area: Some(head.mid_area * 1e-6),
        quantity: 1,
        mass: mass * head.mid_area / total,
        bolting: None,
        gasket: None,
    });
    Some(out)
}

/// The BOM of the vessel planned as `fab`.
pub fn bom(fab: &FabPlan) -> Bom {
    let (design, resolved) = (&fab.vessel, &fab.resolved);
    let density = metal_density(&design.design);
    let kg = |mm3: f64| mm3 * MM3_TO_M3 * density;
    let g = grades(design);
    let mut lines = Vec::new();
    let metal = items(design, &resolved.parts, &resolved.nozzles, density);
    for part in &resolved.parts {
        let Some(d) = design.parts.iter().find(|d| d.id() == part.id) else {
            continue;
        };
        if let Some(t) = thickness(d) {
            let Some(mass) = wall_mass(&part.geometry, t, density) else {
                continue;
            };
            let head = matches!(d, PartDesign::Head(_));
            let description = match d {
                PartDesign::Head(h) => {
                    format!("{:?} head", h.shape).to_lowercase() + &marked_openings(fab, &part.id)
                }
                PartDesign::Reducer(_) => "cone (reducer)".into(),
                _ => "shell course".into(),
            };
            let plates = plate_lines(fab, &part.id, &description, &g.plate, mass);
            if !plates.is_empty() {
                lines.extend(plates);
                continue;
            }
            let blank = fab.developments.heads.iter().find(|h| h.id == part.id);
            let dev = match blank {
                Some(b) => Some((
                    Developed::Blank {
                        diameter: b.diameter,
                    },
                    b.mid_area,
                )),
                None => developed(&part.geometry, t),
            };
            lines.push(BomLine {
                item: part.id.clone(),
                part: part.id.clone(),
                kind: if head { "head" } else { "plate" },
                description,
                material: g.plate.clone(),
                thickness: Some(t),
                size: dev.as_ref().map(|(d, _)| d.label()).unwrap_or_default(),
                area: dev.as_ref().map(|(_, a)| a * 1e-6),
                developed: dev.map(|(d, _)| d),
                quantity: 1,
                mass,
                bolting: None,
                gasket: None,
            });
        } else if let (PartDesign::Boot(b), Some(item)) =
            (d, metal.iter().find(|i| i.id == part.id))
            && let Some(boot) =
                boot_lines(fab, &part.id, &format!("{:?}", b.head), &g.plate, item.mass)
        {
            lines.extend(boot);
        } else if let Some(item) = metal
            .iter()
            .find(|i| i.id == part.id && i.kind != "nozzle" && i.kind != "pad")
        {
            let t = match d {
                PartDesign::Skirt(s) => s.thickness,
                PartDesign::Saddle(s) => s.web_thickness,
                _ => None,
            };
            let plates = plate_lines(fab, &part.id, "skirt", &g.plate, item.mass);
            if !plates.is_empty() {
                lines.extend(plates);
                continue;
            }
            let dev = developed(&part.geometry, t.unwrap_or(DEFAULT_PLATE));
            lines.push(BomLine {
                item: part.id.clone(),
                part: part.id.clone(),
                kind: "support",
                description: part.geometry.kind().to_string(),
                material: g.plate.clone(),
                thickness: t.or(Some(DEFAULT_PLATE)),
                size: dev.as_ref().map(|(d, _)| d.label()).unwrap_or_default(),
                area: dev.as_ref().map(|(_, a)| a * 1e-6),
                developed: dev.map(|(d, _)| d),
                quantity: 1,
                mass: item.mass,
                bolting: None,
                gasket: None,
            });
        }
    }
    for (n, nd) in resolved.nozzles.iter().zip(&design.nozzles) {
        let geo = &n.geometry;
        let row = pipe(geo.nps);
        let nps = geo.nps.label();
        if let (Some(host), Ok(wall), Ok(neck)) = (
            resolved.parts.get(n.host),
            row.wall(geo.schedule),
            geo.neck_length(),
        ) && let Some(body) = metal.iter().find(|i| i.id == n.mark && i.kind == "nozzle")
        {
            let start = neck_start_outside(n, host);
            let (ro, ri) = (
                row.outside_diameter / 2.0,
                row.outside_diameter / 2.0 - wall,
            );
            let cut = (neck - start).max(0.0);
            let pipe_mass = kg(PI * (ro * ro - ri * ri) * cut);
            lines.push(BomLine {
                item: n.mark.clone(),
                part: n.mark.clone(),
                kind: "pipe",
                description: format!("nozzle neck NPS {nps} Sch {}", geo.schedule.label()),
                material: g.pipe.into(),
                thickness: Some(wall),
                developed: None,
                size: format!("cut length {cut:.0}"),
                area: None,
                quantity: 1,
                mass: pipe_mass,
                bolting: None,
                gasket: None,
            });
            let dims = flange(geo.nps, geo.class).ok();
            let kind = match nd.flange {
                FlangeDesign::WeldNeck => "weld-neck flange",
                FlangeDesign::SlipOn => "slip-on flange",
                FlangeDesign::Blind => "weld-neck flange + blind flange",
            };
            lines.push(BomLine {
                item: format!("{}/flange", n.mark),
                part: n.mark.clone(),
                kind: "flange",
                description: format!("{kind} NPS {nps} Class {} {:?}", nd.rating, nd.facing),
                material: g.forging.into(),
                thickness: dims.map(|d| d.thickness),
                developed: None,
                size: dims.map_or(String::new(), |d| format!("OD {:.0}", d.outside_diameter)),
                area: None,
                quantity: 1,
                mass: body.mass - pipe_mass,
                bolting: dims.map(|d| {
                    format!(
                        "{} stud bolts {} in, bolt circle Ø{:.1}, holes Ø{:.1}",
                        d.bolt_count,
                        fraction(d.bolt_size_in),
                        d.bolt_circle_diameter,
                        d.bolt_hole_diameter
                    )
                }),
                gasket: dims.map(|d| {
                    gasket(
                        nd.facing,
                        nps,
                        nd.rating,
                        d.outside_diameter,
                        d.raised_face_diameter,
                    )
                }),
            });
        }
        if let (Some((od, t)), Some(pad)) = (
            n.pad,
            metal.iter().find(|i| i.id == n.mark && i.kind == "pad"),
        ) {
            let neck = geo.outside_diameter();
            lines.push(BomLine {
                item: format!("{}/pad", n.mark),
                part: n.mark.clone(),
                kind: "pad",
                description: format!("reinforcing pad, bore Ø{neck:.1}"),
                material: g.plate.clone(),
                thickness: Some(t),
                developed: None,
                size: format!("Ø{od:.0}"),
                area: Some(PI / 4.0 * (od * od - neck * neck).max(0.0) * 1e-6),
                quantity: 1,
                mass: pad.mass,
                bolting: None,
                gasket: None,
            });
        }
    }
    let total_mass = lines.iter().map(|l| l.mass).sum();
    Bom {
        vessel: resolved.tag.clone(),
        lines,
        total_mass,
    }
}

/// A bolt size in inches as B16.5 prints it: `5/8`, `1`, `1-1/8`.
fn fraction(inches: f64) -> String {
    let eighths = (inches * 8.0).round() as i64;
    let (whole, rest) = (eighths / 8, eighths % 8);
    let (num, den) = match rest {
        0 => (0, 1),
        2 | 6 => (rest / 2, 4),
        4 => (1, 2),
        r => (r, 8),
    };
    match (whole, num) {
        (w, 0) => w.to_string(),
        (0, n) => format!("{n}/{den}"),
        (w, n) => format!("{w}-{n}/{den}"),
    }
}

#[cfg(test)]
mod tests {
    use super::fraction;

    #[test]
    fn bolt_sizes_print_as_b16_5() {
        assert_eq!(fraction(0.625), "5/8");
        assert_eq!(fraction(0.75), "3/4");
        assert_eq!(fraction(1.0), "1");
        assert_eq!(fraction(1.125), "1-1/8");
        assert_eq!(fraction(1.5), "1-1/2");
    }
}
