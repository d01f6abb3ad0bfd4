//! The sheet's tables: title block, design-data block, nozzle schedule and notes
//! list, stacked bottom-up in the column at the sheet's right edge.
//!
//! Their content comes from the design file (drawing number, title, revision,
//! date, design conditions, nozzles, notes) and from the calculations (MAWP,
//! hydrotest, capacity, the weights of `weights`, deficiencies).

use glam::DVec2;

use super::data::VesselData;
use super::dimensions::format_mm;
use super::sheet::{Align, Item, Layer, Rect, ScheduleRow, SheetSize};
use super::text::text_width;
use crate::calc::mdmt::vessel_mdmt;
use crate::calc::{DEFAULT_JOINT_EFFICIENCY, MaterialTable, calculate, code_of};
use crate::design::{Design, FORMAT, Units, VesselKind};
use crate::parts::tables::pipe;
use crate::weights::weights;

/// Titles of the nozzle schedule's columns: mark, quantity, size, rating,
/// facing, flange type, neck schedule and wall, pad (OD × thickness), service,
/// orientation, elevation or position, projection.
pub const SCHEDULE_COLUMNS: [&str; 12] = [
    "MARK", "QTY", "SIZE", "RATING", "FACE", "FLG", "SCH/THK", "PAD", "SERVICE", "ORIENT",
    "EL/POS", "PROJ",
];

/// Relative widths of the schedule's columns.
const SCHEDULE_WIDTHS: [f64; 12] = [
    0.065, 0.045, 0.06, 0.085, 0.055, 0.055, 0.105, 0.11, 0.14, 0.085, 0.115, 0.08,
];

/// The smallest lettering a cell is condensed to before it is cut, as a
/// fraction of the table's lettering height.
const SMALLEST_CELL_LETTERING: f64 = 0.7;

/// `cell` fitted to `width` at lettering height `h`: whole at `h`, else whole at
/// a smaller height (down to [`SMALLEST_CELL_LETTERING`]·`h`), else cut with an
/// ellipsis at that height. Returns the text and its height.
fn fit_cell(cell: &str, width: f64, h: f64) -> (String, f64) {
    let full = text_width(cell, h);
    if full <= width {
        return (cell.to_string(), h);
    }
    let condensed = (h * width / full * (1.0 - 1e-9)).max(SMALLEST_CELL_LETTERING * h);
    if text_width(cell, condensed) <= width {
        return (cell.to_string(), condensed);
    }
    let mut t: String = cell.to_string();
    while !t.is_empty() && text_width(&t, condensed) + text_width("…", condensed) > width {
        t.pop();
    }
    t.push('…');
    (t, condensed)
}

/// A table cursor: draws rows upward from `bottom` across `[left, right]`.
struct Table<'a> {
    items: &'a mut Vec<Item>,
    left: f64,
    right: f64,
    top: f64,
    h: f64,
}

impl Table<'_> {
    fn row_height(&self) -> f64 {
        1.9 * self.h
    }

    /// A row of cells with the given relative widths; `bold` rows are headers.
    fn row(&mut self, cells: &[&str], widths: &[f64]) {
        let rh = self.row_height();
        let bottom = self.top;
        let top = bottom + rh;
        let total = self.right - self.left;
        let mut x = self.left;
        for (cell, w) in cells.iter().zip(widths) {
            let cw = w * total;
            let (text, height) = fit_cell(cell, cw - 1.6, self.h);
            self.items.push(Item::Text {
                at: DVec2::new(x + 0.8, bottom + 0.45 * self.h),
                height,
                align: Align::Start,
                rotation: 0.0,
                text,
            });
            x += cw;
            self.items.push(Item::Line {
                layer: Layer::Border,
                points: vec![DVec2::new(x, bottom), DVec2::new(x, top)],
                closed: false,
            });
        }
        self.items.push(Item::Line {
            layer: Layer::Border,
            points: vec![DVec2::new(self.left, top), DVec2::new(self.right, top)],
            closed: false,
        });
        self.top = top;
    }

    /// A full-width heading row.
    fn heading(&mut self, text: &str) {
        self.row(&[text], &[1.0]);
    }

    /// Closes the table with its outline from `bottom` to the current top.
    fn frame(&mut self, bottom: f64) {
        self.items.push(Item::Line {
            layer: Layer::Border,
            points: Rect::new(
                DVec2::new(self.left, bottom),
                DVec2::new(self.right, self.top),
            )
            .corners(),
            closed: true,
        });
    }
}

/// The design-data rows of a sheet after the design conditions: code, joint
/// efficiency, MAWP, hydrotest, capacity, the three weights of the one weight
/// model (`weights`, the figures `info` and `calc` print) and the
/// deficiencies, each labelled with what it includes.
pub fn design_data(data: &VesselData) -> Vec<(&'static str, String)> {
    let design = Design {
        format: FORMAT.to_string(),
        units: Units::Mm,
        vessels: vec![data.design.clone()],
    };
    let dash = || "—".to_string();
    let kpa = |mpa: f64| format!("{} kPa(g)", format_mm((mpa * 1e3).round()));
    let kg = |w: f64| format!("{} kg", format_mm(w.round()));
    let resolved = crate::design::resolve(&design).ok();
    let resolved = resolved.as_ref().and_then(|r| r.first());
    let weights = resolved.and_then(|r| weights(&data.design, r).ok());
    let calculation = resolved.map(|r| calculate(&data.design, r, &MaterialTable::builtin()));
    let mdmt = calculation.as_ref().and_then(|c| {
        vessel_mdmt(
            c.parts
                .iter()
                .filter_map(|p| p.mdmt.as_ref().map(|m| (p.id.as_str(), m))),
        )
    });
    let calc = calculation.map(|c| c.vessel);
    let e = match data.design.design.joint_efficiency {
        Some(e) => format_mm(e),
        None => format!("{} (default)", format_mm(DEFAULT_JOINT_EFFICIENCY)),
    };
    let deficiencies = calc.as_ref().map_or_else(dash, |c| {
        if c.deficiencies.is_empty() {
            "none".to_string()
        } else {
            let ids: Vec<&str> = c
                .deficiencies
                .iter()
                .filter_map(|d| d.split(':').next())
                .collect();
            format!("{}: {}", ids.len(), ids.join(", "))
        }
    });
    vec![
        ("CODE", code_of(data.design.kind).to_string()),
        ("JOINT EFFICIENCY", e),
        (
            "MAWP (HOT & CORRODED, TOP)",
            calc.as_ref().and_then(|c| c.mawp).map_or_else(dash, kpa),
        ),
        (
            "HYDROTEST (UG-99(b), TOP)",
            calc.as_ref()
                .and_then(|c| c.hydrotest.as_ref())
                .map_or_else(dash, |h| kpa(h.value)),
        ),
        (
            "CAPACITY (INSIDE)",
            weights
                .as_ref()
                .map_or_else(dash, |w| format!("{:.2} m³", w.capacity)),
        ),
        (
            "WEIGHT EMPTY (ALL METAL)",
            weights.as_ref().map_or_else(dash, |w| kg(w.empty)),
        ),
        (
            "WEIGHT OPERATING",
            weights.as_ref().map_or_else(dash, |w| kg(w.operating)),
        ),
        (
            "WEIGHT TEST (FULL OF WATER)",
            weights.as_ref().map_or_else(dash, |w| kg(w.test)),
        ),
        (
            "MDMT (UCS-66, NO IMPACT TEST)",
            mdmt.map_or_else(dash, |(_, t)| {
                format!("{} °C", format_mm((t * 10.0).round() / 10.0))
            }),
        ),
        ("DEFICIENCIES", deficiencies),
    ]
}

/// A nozzle's orientation as the schedule shows it: the angle, and for a
/// hillside or inclined shell nozzle its offset (`OFS`, mm) and inclination
/// (`INC`, degrees) when not zero.
fn orientation_cell(n: &crate::design::NozzleDesign) -> String {
    let mut cell = format!("{}°", format_mm(n.orientation));
    if n.elevation.is_some() {
        if let Some(offset) = n.offset.filter(|&o| o != 0.0) {
            cell.push_str(&format!(" OFS {}", format_mm(offset)));
        }
        if let Some(inclination) = n.inclination.filter(|&i| i != 0.0) {
            cell.push_str(&format!(" INC {}°", format_mm(inclination)));
        }
    }
    cell
}

/// The nozzle schedule's rows, in design order.
pub fn schedule(data: &VesselData) -> Vec<ScheduleRow> {
    let position = if data.design.kind == VesselKind::Horizontal {
        "POS"
    } else {
        "EL"
    };
    data.design
        .nozzles
        .iter()
        .map(|n| {
            let size = if n.size.fract() == 0.0 {
                format!("{}\"", n.size)
            } else {
                format!("{:.2}\"", n.size)
            };
            let facing = match n.facing {
                crate::design::FacingDesign::RaisedFace => "RF",
                crate::design::FacingDesign::FlatFace => "FF",
                crate::design::FacingDesign::RingJoint => "RTJ",
            };
            let elevation = match n.elevation {
                Some(e) => format!("{position} {}", format_mm(e)),
                None => format!("{} +{}", n.host, format_mm(n.offset.unwrap_or(0.0))),
            };
            let flange = match n.flange {
                crate::design::FlangeDesign::WeldNeck => "WN",
                crate::design::FlangeDesign::SlipOn => "SO",
                crate::design::FlangeDesign::Blind => "BLIND",
            };
            // The neck's wall from the B36.10M table for the resolved nozzle.
            let wall = data
                .nozzles
                .iter()
                .find(|r| r.design.mark == n.mark)
                .and_then(|r| pipe(r.geometry.nps).wall(r.geometry.schedule).ok());
            let schedule = match wall {
                Some(t) => format!("{} / {:.2}", n.schedule, t),
                None => n.schedule.clone(),
            };
            let pad = n.pad.as_ref().map_or_else(
                || "—".to_string(),
                |p| format!("{}×{}", format_mm(p.od), format_mm(p.thickness)),
            );
            ScheduleRow {
                cells: [
                    n.mark.clone(),
                    "1".to_string(),
                    size,
                    format!("CL {}", n.rating),
                    facing.to_string(),
                    flange.to_string(),
                    schedule,
                    pad,
                    if n.service.is_empty() {
                        "—".to_string()
                    } else {
                        n.service.clone()
                    },
                    orientation_cell(n),
                    elevation,
                    format_mm(n.projection),
                ],
            }
        })
        .collect()
}

/// The title block's fields.
pub struct TitleFields {
    /// Drawing number.
    pub number: String,
    /// Title.
    pub title: String,
    /// Revision.
    pub revision: String,
    /// Date.
    pub date: String,
}

/// Title-block fields with their defaults filled in.
pub fn title_fields(data: &VesselData) -> TitleFields {
    let info = &data.design.drawing;
    let kind = match data.design.kind {
        VesselKind::Horizontal => "HORIZONTAL VESSEL",
        VesselKind::Vertical => "VERTICAL VESSEL",
        VesselKind::Tank => "STORAGE TANK",
    };
    TitleFields {
        number: info
            .number
            .clone()
            .unwrap_or_else(|| data.design.tag.clone()),
        title: info
            .title
            .clone()
            .unwrap_or_else(|| format!("{kind} {}", data.design.tag)),
        revision: info.revision.clone().unwrap_or_else(|| "0".to_string()),
        date: info.date.clone().unwrap_or_else(|| "—".to_string()),
    }
}

/// What the title block says about the sheet itself.
pub struct Frame<'a> {
    /// Sheet size.
    pub size: SheetSize,
    /// The scale cell: `1:60`, or `AS SHOWN` on a sheet of details.
    pub scale: &'a str,
    /// The sheet's number and how many there are.
    pub number: (usize, usize),
    /// Whether the design data, schedule and notes follow the title block (the
    /// first sheet) or not.
    pub full: bool,
}

/// Draws the tables in the column from its lower-left corner `origin` to `right`,
/// bottom up; returns the rectangle they take and where the revision cell is (for
/// the triangle).
pub fn draw(
    data: &VesselData,
    rows: &[ScheduleRow],
    frame: &Frame,
    origin: DVec2,
    right: f64,
    items: &mut Vec<Item>,
) -> (Rect, DVec2) {
    let (left, bottom) = (origin.x, origin.y);
    let size = frame.size;
    let h = size.text_height();
    let mut t = Table {
        items,
        left,
        right,
        top: bottom,
        h,
    };
    let fields = title_fields(data);
    let two = [0.38, 0.62];
    let four = [0.19, 0.31, 0.19, 0.31];
    t.row(&["SIZE", size.name(), "SCALE", frame.scale], &four);
    let rev_y = t.top;
    t.row(&["REV.", &fields.revision, "DATE", &fields.date], &four);
    let sheet_no = format!("{} OF {}", frame.number.0, frame.number.1);
    t.row(&["SHEET", &sheet_no], &two);
    t.row(&["DWG. NO.", &fields.number], &two);
    t.row(&["TITLE", &fields.title], &two);
    t.row(&["VESSEL", &data.design.tag], &two);
    // Signatures are written by hand on the issued print: the fields are left
    // blank, never filled with invented names.
    let sign = [0.25, 0.35, 0.15, 0.25];
    t.row(&["APPROVED", "", "DATE", ""], &sign);
    t.row(&["CHECKED", "", "DATE", ""], &sign);
    t.row(&["DRAWN", "vesselcad", "DATE", &fields.date], &sign);
    t.heading("vesselcad — GENERATED FROM THE DESIGN MODEL");
    t.frame(bottom);
    // Revision history: the current revision, then blank rows for the next.
    let history_bottom = t.top + h;
    t.top = history_bottom;
    let rev = [0.12, 0.22, 0.48, 0.18];
    t.row(&["", "", "", ""], &rev);
    t.row(&[&fields.revision, &fields.date, "ISSUED", ""], &rev);
    t.row(&["REV", "DATE", "DESCRIPTION", "BY"], &rev);
    t.heading("REVISIONS");
    t.frame(history_bottom);
    let revision_at = DVec2::new(
        left + 0.19 * (right - left) + 0.8 + text_width(&fields.revision, h) + 2.0 * h,
        rev_y + 0.95 * h,
    );
    if !frame.full {
        return (
            Rect::new(DVec2::new(left, bottom), DVec2::new(right, t.top)),
            revision_at,
        );
    }
    // Design data.
    let data_bottom = t.top + h;
    t.top = data_bottom;
    let c = &data.design.design;
    let opt = |v: Option<f64>, unit: &str| {
        v.map_or("—".to_string(), |v| format!("{} {unit}", format_mm(v)))
    };
    let mut rows_data = vec![
        ("DESIGN PRESSURE", opt(c.pressure, "kPa(g)")),
        ("DESIGN TEMPERATURE", opt(c.temperature, "°C")),
        ("CORROSION ALLOWANCE", opt(c.corrosion_allowance, "mm")),
        (
            "MATERIAL",
            c.material.clone().unwrap_or_else(|| "—".to_string()),
        ),
    ];
    rows_data.extend(design_data(data));
    for (name, value) in rows_data.iter().rev() {
        t.row(&[name, value], &[0.45, 0.55]);
    }
    t.heading("DESIGN DATA");
    t.frame(data_bottom);
    // Nozzle schedule.
    let schedule_bottom = t.top + h;
    t.top = schedule_bottom;
    for row in rows.iter().rev() {
        let cells: Vec<&str> = row.cells.iter().map(String::as_str).collect();
        t.row(&cells, &SCHEDULE_WIDTHS);
    }
    t.row(&SCHEDULE_COLUMNS, &SCHEDULE_WIDTHS);
    t.heading("NOZZLE SCHEDULE");
    t.frame(schedule_bottom);
    // Notes.
    if !data.notes.is_empty() {
        let notes_bottom = t.top + h;
        t.top = notes_bottom;
        for (i, n) in data.notes.iter().enumerate().rev() {
            let text = format!("{}. {}", i + 1, n.text);
            t.row(&[&text], &[1.0]);
        }
        t.heading("NOTES");
        t.frame(notes_bottom);
    }
    (
        Rect::new(DVec2::new(left, bottom), DVec2::new(right, t.top)),
        revision_at,
    )
}
