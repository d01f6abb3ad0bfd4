//! The plant generator: a realistic, valid, deterministic plant of N vessels for
//! scale tests, benchmarks and the simulation.
//!
//! It sits before the whole data flow: its output is an ordinary [`Design`] that
//! loads, saves and builds like a hand-written one. The mix is about half
//! horizontal drums (two heads, saddles, sometimes a boot), a third vertical
//! columns (two or three courses joined by reducers, a skirt; the reducers of
//! every other column by index are eccentric, so the courses above them stand on
//! an offset axis) and the
//! rest storage tanks (flat bottom, roof); heads cycle through every kind; each
//! vessel has 4–20 nozzles including manways, and notes. Vessels stand on a square
//! plot grid of [`PLOT_PITCH`] cells, so footprints never overlap.
//!
//! Each vessel is drawn from its own random stream (seed, index), then checked with
//! the constraint rules; a draw that breaks a rule (rare) is redrawn from the next
//! stream, so every vessel of the output is valid and the plant depends only on
//! the seed and N.

use super::rng::SplitMix64;
use crate::constraints::resolve_vessel;
use crate::design::{
    BootDesign, Design, DesignConditions, DrawingInfo, FORMAT, FacingDesign, FlangeDesign,
    HeadDesign, HeadShape, NoteDesign, NozzleDesign, OperatingDesign, PadDesign, PartDesign,
    Placement, ReducerDesign, SaddleDesign, ShellDesign, SkirtDesign, Units, VesselDesign,
    VesselKind,
};

/// Side of the square plot cell each vessel stands in, mm.
pub const PLOT_PITCH: f64 = 30_000.0;

/// Redraws allowed for one vessel before the generator gives up.
const MAX_DRAWS: u64 = 64;

/// Why a plant could not be generated.
#[derive(Debug, thiserror::Error)]
pub enum GenerateError {
    /// Zero vessels were asked for.
    #[error("a plant needs at least one vessel (got --vessels 0)")]
    NoVessels,
    /// No valid draw was found for a vessel (a bug in the generator's ranges).
    #[error("vessel {index}: no valid design in {MAX_DRAWS} draws; last problem: {problem}")]
    NoValidDraw {
        /// Index of the vessel.
        index: usize,
        /// The first rule the last draw broke.
        problem: String,
    },
}

/// A plant of `vessels` vessels from `seed`.
///
/// # Errors
///
/// [`GenerateError::NoVessels`] for 0; [`GenerateError::NoValidDraw`] if a vessel
/// could not be drawn valid (not expected).
pub fn generate_plant(vessels: usize, seed: u64) -> Result<Design, GenerateError> {
    if vessels == 0 {
        return Err(GenerateError::NoVessels);
    }
    let root = SplitMix64::new(seed);
    let columns = (vessels as f64).sqrt().ceil() as usize;
    let out: Result<Vec<VesselDesign>, GenerateError> = (0..vessels)
        .map(|i| {
            let cell = (
                (i % columns) as f64 * PLOT_PITCH,
                (i / columns) as f64 * PLOT_PITCH,
            );
            let mut problem = String::new();
            for draw in 0..MAX_DRAWS {
                let mut rng = root.fork((i as u64) << 8 | draw);
                let v = vessel(&mut rng, i, cell);
                match resolve_vessel(&v, i) {
                    Ok(_) => return Ok(v),
                    Err(violations) => {
                        problem = violations
                            .first()
                            .map_or_else(String::new, |v| format!("{v}"));
                    }
                }
            }
            Err(GenerateError::NoValidDraw { index: i, problem })
        })
        .collect();
    Ok(Design {
        format: FORMAT.to_string(),
        units: Units::Mm,
        vessels: out?,
    })
}

/// Every head shape, in the order the generator cycles through them.
pub(super) const SHAPES: [HeadShape; 6] = [
    HeadShape::Ellipsoidal,
    HeadShape::Torispherical,
    HeadShape::Hemispherical,
    HeadShape::Toriconical,
    HeadShape::Conical,
    HeadShape::Flat,
];

/// Nozzle sizes (NPS) drawn for process nozzles.
const SIZES: [f64; 9] = [1.0, 1.5, 2.0, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0];

/// One vessel of kind chosen by `rng`, standing in the cell at `cell` (mm).
fn vessel(rng: &mut SplitMix64, index: usize, cell: (f64, f64)) -> VesselDesign {
    let roll = rng.unit();
    let kind = if roll < 0.5 {
        VesselKind::Horizontal
    } else if roll < 0.8 {
        VesselKind::Vertical
    } else {
        VesselKind::Tank
    };
    let (prefix, mut v) = match kind {
        VesselKind::Horizontal => ("V", drum(rng, index)),
        VesselKind::Vertical => ("C", column(rng, index)),
        VesselKind::Tank => ("TK", tank(rng)),
    };
    v.tag = format!("{prefix}-{:05}", index + 1);
    v.placement.position[0] += cell.0 + PLOT_PITCH / 2.0;
    v.placement.position[1] += cell.1 + PLOT_PITCH / 2.0;
    let stainless = rng.chance(0.2);
    v.design = DesignConditions {
        pressure: Some(rng.stepped(100.0, 3000.0, 50.0)),
        temperature: Some(rng.stepped(20.0, 350.0, 5.0)),
        corrosion_allowance: Some(if stainless { 0.0 } else { 3.0 }),
        material: Some(
            if stainless {
                "SA-240-316L"
            } else {
                "SA-516-70"
            }
            .to_string(),
        ),
        metal_density: None,
        external_pressure: None,
        joint_efficiency: None,
        wind: None,
        seismic: None,
    };
    notes(rng, &mut v);
    v
}

/// A head of `shape` with parameters drawn for an outside diameter `od`.
fn head(rng: &mut SplitMix64, id: &str, shape: HeadShape, od: f64, t: f64) -> PartDesign {
    let mut h = HeadDesign {
        id: id.to_string(),
        shape,
        ratio: None,
        crown_radius: None,
        knuckle_radius: None,
        half_angle: None,
        small_od: None,
        straight_flange: rng.stepped(0.0, 75.0, 25.0),
        thickness: Some(t),
    };
    match shape {
        HeadShape::Ellipsoidal => {
            if rng.chance(0.3) {
                h.ratio = Some(rng.stepped(1.6, 2.6, 0.1));
            } else {
                h.ratio = Some(2.0);
            }
        }
        HeadShape::Torispherical => {
            if rng.chance(0.4) {
                h.crown_radius = Some(0.8 * od);
                h.knuckle_radius = Some(0.1 * od);
            }
        }
        HeadShape::Toriconical => {
            h.half_angle = Some(rng.stepped(30.0, 45.0, 5.0));
            h.knuckle_radius = Some((0.1 * od).round());
        }
        HeadShape::Conical => {
            h.half_angle = Some(rng.stepped(30.0, 60.0, 5.0));
            if rng.chance(0.5) {
                h.small_od = Some((od * 0.25).round());
            }
        }
        HeadShape::Flat => {
            if rng.chance(0.5) {
                h.knuckle_radius = Some((0.06 * od).round());
            }
        }
        HeadShape::Hemispherical => {}
    }
    PartDesign::Head(h)
}

/// Wall thickness for an outside diameter, mm.
fn wall(od: f64) -> f64 {
    (od / 160.0).round().max(6.0) + 2.0
}

/// A horizontal drum: two heads, one course, two saddles, maybe a boot.
fn drum(rng: &mut SplitMix64, index: usize) -> VesselDesign {
    let od = rng.stepped(1200.0, 3600.0, 100.0);
    let length = (od * rng.range(2.5, 5.0) / 100.0).round() * 100.0;
    let t = wall(od);
    let left = SHAPES[index % SHAPES.len()];
    let right = *rng.pick(&[
        HeadShape::Ellipsoidal,
        HeadShape::Torispherical,
        HeadShape::Hemispherical,
        left,
    ]);
    let height = od / 2.0 + rng.stepped(600.0, 1500.0, 100.0);
    let mut parts = vec![
        head(rng, "H1", left, od, t),
        PartDesign::Shell(ShellDesign {
            id: "S1".into(),
            od,
            length,
            thickness: Some(t),
        }),
        head(rng, "H2", right, od, t),
    ];
    for id in ["SD1", "SD2"] {
        parts.push(PartDesign::Saddle(SaddleDesign {
            id: id.into(),
            position: None,
            contact_angle: 120.0,
            width: 300.0,
            height,
            web_thickness: None,
            wear_plate: None,
        }));
    }
    let boot = rng.chance(0.3);
    if boot {
        parts.push(PartDesign::Boot(BootDesign {
            id: "B1".into(),
            position: (length / 2.0).round(),
            od: 610.0,
            length: 900.0,
            head: HeadShape::Ellipsoidal,
        }));
    }
    let mut v = blank(VesselKind::Horizontal, parts);
    v.placement = Placement {
        position: [0.0, 0.0, height],
        rotation: *rng.pick(&[0.0, 90.0]),
    };
    // Side and top orientations; the bottom only without a boot.
    let orientations: &[(f64, f64)] = if boot {
        &[(90.0, 270.0), (45.0, 315.0)]
    } else {
        &[(90.0, 270.0), (0.0, 180.0), (45.0, 315.0)]
    };
    let courses = [Course {
        id: "S1",
        start: 0.0,
        end: length,
        od,
    }];
    // Bottom nozzles stay clear of the saddles (0.2 L and 0.8 L, 300 mm wide):
    // an opening may not reach a wear plate.
    let saddles = [0.2 * length, 0.8 * length].map(|p| (p - 150.0, p + 150.0));
    nozzles(rng, &mut v, &courses, orientations, t, &saddles);
    v.operating = Some(OperatingDesign {
        liquid_level: (rng.range(0.1, 0.8) * (od - 2.0 * t)).round(),
        liquid_density: Some(rng.stepped(600.0, 1100.0, 50.0)),
    });
    v
}

/// A vertical column: skirt, bottom head, two or three courses joined by
/// reducers, top head. The reducers of a column of even `index` are eccentric,
/// their flat sides at a multiple of 45° set by the index (drawn without the
/// random stream, so every other figure of the plant stays as it was).
fn column(rng: &mut SplitMix64, index: usize) -> VesselDesign {
    let n = rng.int(2, 3) as usize;
    let mut od = rng.stepped(1600.0, 3600.0, 100.0);
    let t = wall(od);
    let bottom = SHAPES[(index + 1) % SHAPES.len()];
    let skirt = rng.stepped(2000.0, 4000.0, 250.0);
    let mut parts = vec![
        PartDesign::Skirt(SkirtDesign {
            id: "SK".into(),
            height: skirt,
            flare_angle: 0.0,
            base_ring_width: 150.0,
            base_ring_thickness: None,
            thickness: Some(t),
            anchor_bolts: None,
        }),
        head(rng, "H1", bottom, od, t),
    ];
    let mut courses = Vec::new();
    let mut z = 0.0;
    for k in 0..n {
        if k > 0 {
            let length = rng.stepped(600.0, 1200.0, 100.0);
            parts.push(PartDesign::Reducer(ReducerDesign {
                id: format!("R{k}"),
                length,
                eccentric: index
                    .is_multiple_of(2)
                    .then(|| 45.0 * ((index / 2 + k) % 8) as f64),
                thickness: Some(t),
            }));
            z += length;
            // Narrower above, but wide enough for a manway (≥ 1200 mm).
            od = (od - rng.stepped(300.0, 500.0, 100.0)).max(1200.0);
        }
        let length = rng.stepped(5000.0, 12000.0, 500.0);
        let id: &'static str = ["S1", "S2", "S3"][k];
        parts.push(PartDesign::Shell(ShellDesign {
            id: id.into(),
            od,
            length,
            thickness: Some(t),
        }));
        courses.push(Course {
            id,
            start: z,
            end: z + length,
            od,
        });
        z += length;
    }
    let top = *rng.pick(&[
        HeadShape::Ellipsoidal,
        HeadShape::Torispherical,
        HeadShape::Hemispherical,
    ]);
    parts.push(head(rng, "H2", top, od, t));
    let mut v = blank(VesselKind::Vertical, parts);
    v.placement = Placement {
        position: [0.0, 0.0, skirt],
        rotation: rng.stepped(0.0, 345.0, 15.0),
    };
    let orientations = [(0.0, 180.0), (45.0, 225.0), (90.0, 270.0), (135.0, 315.0)];
    nozzles(rng, &mut v, &courses, &orientations, t, &[]);
    v.operating = Some(OperatingDesign {
        liquid_level: (rng.range(0.02, 0.3) * z).round(),
        liquid_density: Some(rng.stepped(600.0, 1100.0, 50.0)),
    });
    v
}

/// A storage tank: flat bottom, one course, a roof.
fn tank(rng: &mut SplitMix64) -> VesselDesign {
    let od = rng.stepped(4000.0, 14000.0, 500.0);
    let height = rng.stepped(5000.0, 15000.0, 500.0);
    let t = wall(od).min(16.0);
    let roof = *rng.pick(&[
        HeadShape::Conical,
        HeadShape::Torispherical,
        HeadShape::Flat,
    ]);
    let mut roof_part = head(rng, "ROOF", roof, od, t);
    if let PartDesign::Head(h) = &mut roof_part {
        h.straight_flange = 0.0;
        if roof == HeadShape::Conical {
            h.half_angle = Some(rng.stepped(75.0, 85.0, 5.0));
            h.small_od = None;
        }
    }
    let mut bottom = HeadDesign {
        id: "BTM".into(),
        shape: HeadShape::Flat,
        ratio: None,
        crown_radius: None,
        knuckle_radius: None,
        half_angle: None,
        small_od: None,
        straight_flange: 0.0,
        thickness: Some(t),
    };
    bottom.thickness = Some(t);
    let parts = vec![
        PartDesign::Head(bottom),
        PartDesign::Shell(ShellDesign {
            id: "S1".into(),
            od,
            length: height,
            thickness: Some(t),
        }),
        roof_part,
    ];
    let mut v = blank(VesselKind::Tank, parts);
    let orientations = [(0.0, 180.0), (30.0, 210.0), (60.0, 240.0), (120.0, 300.0)];
    let courses = [Course {
        id: "S1",
        start: 0.0,
        end: height,
        od,
    }];
    nozzles(rng, &mut v, &courses, &orientations, t, &[]);
    v.operating = Some(OperatingDesign {
        liquid_level: (rng.range(0.1, 0.9) * height).round(),
        liquid_density: Some(rng.stepped(700.0, 1050.0, 50.0)),
    });
    v
}

/// A vessel with no nozzles, notes or placement yet.
fn blank(kind: VesselKind, parts: Vec<PartDesign>) -> VesselDesign {
    VesselDesign {
        tag: String::new(),
        kind,
        placement: Placement::default(),
        design: DesignConditions::default(),
        parts,
        nozzles: Vec::new(),
        notes: Vec::new(),
        operating: None,
        drawing: DrawingInfo::default(),
    }
}

/// A shell course nozzles can go on: id, axial span (vessel frame) and OD, mm.
struct Course {
    id: &'static str,
    start: f64,
    end: f64,
    od: f64,
}

/// Adds 4–20 shell nozzles (one or two manways among them) on `courses`.
///
/// Each nozzle gets its own axial slot, slots spaced by the largest opening plus
/// clearance, so openings never overlap whatever their orientations. A slot at
/// the bottom (orientation 180° of a horizontal vessel) is left out where its
/// largest opening could reach one of the axial spans `saddles`.
fn nozzles(
    rng: &mut SplitMix64,
    v: &mut VesselDesign,
    courses: &[Course],
    orientations: &[(f64, f64)],
    t: f64,
    saddles: &[(f64, f64)],
) {
    let wanted = rng.int(4, 20) as usize;
    let manways = rng.int(1, 2) as usize;
    // Axial slots 800 mm apart, each with two orientations far enough apart
    // round the shell that their openings cannot meet.
    let mut slots = Vec::new();
    for c in courses {
        let mut z = c.start + 500.0;
        while z + 500.0 <= c.end {
            let (a, b) = *rng.pick(orientations);
            slots.push((c, z, a));
            slots.push((c, z, b));
            z += 800.0;
        }
    }
    // Spread the nozzles over the slots in a drawn order.
    for i in (1..slots.len()).rev() {
        let j = rng.int(0, i as u64) as usize;
        slots.swap(i, j);
    }
    // The largest opening's radius (a 24-inch manway) and some clearance.
    let reach = 0.5 * 610.0 + 50.0;
    let under_a_saddle = |&&(_, z, orientation): &&(&Course, f64, f64)| {
        orientation == 180.0 && saddles.iter().any(|&(a, b)| z + reach > a && z - reach < b)
    };
    let slots: Vec<(&Course, f64, f64)> = slots
        .iter()
        .filter(|s| !under_a_saddle(s))
        .copied()
        .collect();
    let count = wanted.min(slots.len());
    let services = [
        "inlet",
        "outlet",
        "vent",
        "drain",
        "level",
        "pressure",
        "temperature",
        "relief",
    ];
    let (mut n_mark, mut m_mark) = (0, 0);
    for (k, &(course, z, orientation)) in slots.iter().take(count).enumerate() {
        let manway = k < manways && course.od >= 1200.0;
        let size = if manway {
            *rng.pick(&[20.0, 24.0])
        } else {
            *rng.pick(&SIZES)
        };
        let mark = if manway {
            m_mark += 1;
            format!("M{m_mark}")
        } else {
            n_mark += 1;
            format!("N{n_mark}")
        };
        let pad = ((6.0..=10.0).contains(&size) && rng.chance(0.5)).then(|| PadDesign {
            od: (size * 25.4 * 1.9).round(),
            thickness: t,
        });
        v.nozzles.push(NozzleDesign {
            mark,
            service: if manway {
                "manway".to_string()
            } else {
                rng.pick(&services).to_string()
            },
            size,
            rating: if manway {
                150
            } else {
                *rng.pick(&[150, 300, 600])
            },
            facing: FacingDesign::RaisedFace,
            flange: if manway {
                FlangeDesign::Blind
            } else {
                FlangeDesign::WeldNeck
            },
            schedule: "STD".into(),
            host: course.id.into(),
            orientation,
            elevation: Some(z),
            offset: None,
            inclination: None,
            projection: (course.od / 2.0 + rng.stepped(400.0, 800.0, 50.0)).round(),
            pad,
        });
    }
}

/// One to three notes on the vessel, a part and a nozzle.
fn notes(rng: &mut SplitMix64, v: &mut VesselDesign) {
    let tag = v.tag.clone();
    v.notes.push(NoteDesign {
        id: "T1".into(),
        text: format!("{tag}: hydrotest before insulation"),
        target: tag.clone(),
        offset: [0.0, 0.0, 1500.0],
    });
    if rng.chance(0.6) {
        v.notes.push(NoteDesign {
            id: "T2".into(),
            text: "Shell course rolled from one plate".into(),
            target: v
                .parts
                .iter()
                .find(|p| p.kind() == "shell")
                .map_or(tag.clone(), |p| p.id().to_string()),
            offset: [0.0, 1200.0, 0.0],
        });
    }
    if let Some(n) = v.nozzles.first()
        && rng.chance(0.5)
    {
        v.notes.push(NoteDesign {
            id: "T3".into(),
            text: format!("{} with davit", n.mark),
            target: n.mark.clone(),
            offset: [0.0, 300.0, -200.0],
        });
    }
}
