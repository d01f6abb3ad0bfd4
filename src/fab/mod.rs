//! Fabrication planning from the exact model: what a shop needs to build a
//! vessel, derived from its design and kept consistent with it (issue 38's flat
//! patterns, seams and plates; its bill of materials, weld map and operations).
//!
//! The pipeline for one vessel: the design is resolved by
//! [`crate::constraints::resolve_vessel`]; [`develop`] unrolls every rolled
//! part's mid-surface exactly and sizes head blanks; the [`Shop`] data (plate
//! sizes, seam stagger and clearance, bevel allowance, stock sheets) drive
//! the rest: [`openings`] develops every nozzle opening, pad and neck end
//! from the exact intersection curves; [`seams`] splits parts into courses
//! and courses into plates, staggering and clearing the seams, and checks
//! loop validity; [`plates`] cuts the plates with their openings;
//! [`plate_dxf`] writes one DXF per plate; [`nest`] nests plates, pads and
//! blanks onto stock sheets. [`plan`] runs it and returns a [`FabPlan`].
//!
//! The process plan of one vessel ([`process::process_plan`]): its bill of
//! materials ([`bom`]), the weld map ([`welds`]: UW-3 categories, lengths on the
//! exact curves of [`weld_curves`], weld metal by the preparations of
//! [`weld_prep`]), and its operations in precedence levels ([`operations`],
//! [`levels`]) from the shop rules as data ([`shop_rules`],
//! `data/shop_rules.json`); written as a traveler ([`traveler`]), a weld-map GLB
//! ([`weld_glb`]) and sheet ([`weld_svg`]).

pub mod bom;
pub mod develop;
pub mod error;
pub mod levels;
pub mod nest;
pub mod openings;
pub mod operations;
pub mod plan_error;
pub mod plate_dxf;
pub mod plate_size;
pub mod plates;
pub mod process;
pub mod process_files;
pub mod seams;
pub mod shop;
pub mod shop_rules;
pub mod traveler;
pub mod weld_curves;
pub mod weld_glb;
pub mod weld_prep;
pub mod weld_svg;
pub mod welds;

pub use develop::{BLANK_RULE, Developments, HeadBlank, Outline, Rolled, RolledKind};
pub use error::FabError;
pub use nest::{Nesting, Piece};
pub use openings::{NozzleCut, Openings};
pub use plan_error::PlanError;
pub use plates::Plate;
pub use process::{ProcessPlan, process_plan};
pub use seams::{Course, SeamLayout};
pub use shop::{Attachment, Shop};
pub use shop_rules::ShopRules;

use glam::DVec2;

use crate::constraints::{ResolvedVessel, resolve_vessel};
use crate::format::Design;

/// The fabrication plan of one vessel.
#[derive(Clone, Debug, PartialEq)]
pub struct FabPlan {
    /// The vessel's tag.
    pub tag: String,
    /// The material grade of its plates (the design's material, or
    /// `"unspecified"`).
    pub grade: String,
    /// The vessel as resolved.
    pub resolved: ResolvedVessel,
    /// The developments of its parts.
    pub developments: Developments,
    /// Its openings, pads and neck ends.
    pub openings: Openings,
    /// Its courses and seams, with the deficiencies found.
    pub seams: SeamLayout,
    /// Its plates.
    pub plates: Vec<Plate>,
}

impl FabPlan {
    /// The pieces to nest: plates (net of openings), pads, head blanks.
    pub fn pieces(&self) -> Vec<Piece> {
        let mut out: Vec<Piece> = self
            .plates
            .iter()
            .map(|p| {
                let (w, h) = p.outline.extent();
                let holes: f64 = p
                    .openings
                    .iter()
                    .map(|o| openings::polygon_area(&o.contour).abs())
                    .sum();
                Piece {
                    id: p.id.clone(),
                    thickness: p.thickness,
                    size: DVec2::new(w, h),
                    area: p.outline.area() - holes,
                }
            })
            .collect();
        for cut in &self.openings.cuts {
            if let Some(pad) = &cut.pad {
                let (lo, hi) = pad.outline.iter().fold(
                    (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                    |(lo, hi), p| (lo.min(*p), hi.max(*p)),
                );
                out.push(Piece {
                    id: format!("{}-{}-PAD", self.tag, cut.mark),
                    thickness: pad.thickness,
                    size: hi - lo,
                    area: pad.area(),
                });
            }
        }
        for h in &self.developments.heads {
            out.push(Piece {
                id: format!("{}-{}-BLANK", self.tag, h.id),
                thickness: h.thickness,
                size: DVec2::splat(h.diameter),
                area: 0.25 * std::f64::consts::PI * h.diameter * h.diameter,
            });
        }
        out
    }

    /// Nests [`pieces`](Self::pieces) on the shop's stock sheets.
    pub fn nesting(&self, shop: &Shop) -> Nesting {
        nest::nest(
            &self.pieces(),
            shop.sheet_length,
            shop.sheet_width,
            shop.nest_gap,
        )
    }
}

/// Plans the fabrication of vessel `tag` of `design` with `shop` data.
///
/// # Errors
///
/// [`FabError::UnknownVessel`], or [`FabError::Rules`] with every broken
/// design or fabrication rule (a part without thickness, a neck that does
/// not lie on its course, loop validity). Seams that cannot keep their
/// clearance or stagger are not errors: they are the plan's
/// [`SeamLayout::deficiencies`].
pub fn plan(design: &Design, tag: &str, shop: &Shop) -> Result<FabPlan, FabError> {
    let (index, vessel) = design
        .vessels
        .iter()
        .enumerate()
        .find(|(_, v)| v.tag == tag)
        .ok_or_else(|| FabError::UnknownVessel { tag: tag.into() })?;
    let resolved = resolve_vessel(vessel, index).map_err(FabError::Rules)?;
    let developments = develop::develop(vessel, index, &resolved).map_err(FabError::Rules)?;
    let openings =
        openings::cut_openings(index, &resolved, &developments, shop).map_err(FabError::Rules)?;
    let seams = seams::lay_out(tag, &developments, &openings, shop);
    if !seams.errors.is_empty() {
        return Err(FabError::Rules(seams.errors));
    }
    let plates = plates::cut_plates(tag, &developments, &openings, &seams);
    let grade = vessel
        .design
        .material
        .clone()
        .unwrap_or_else(|| "unspecified".into());
    Ok(FabPlan {
        tag: tag.into(),
        grade,
        resolved,
        developments,
        openings,
        seams,
        plates,
    })
}
