//! Fabrication planning from the exact model: what a shop needs to build a
//! vessel, derived from its design and kept consistent with it (issue 38's flat
//! patterns, seams and plates; its bill of materials, weld map and operations).
//!
//! The pipeline for one vessel: the design is resolved by
//! [`crate::constraints::resolve_vessel`]; [`develop`] unrolls every rolled
//! part's mid-surface exactly and sizes head blanks; the [`Shop`] data (plate
//! sizes, seam stagger and clearance, bevel allowance, stock sheets) drive
//! the rest: [`openings`] develops every nozzle opening, pad and neck end
//! from the exact intersection curves ([`cone_openings`] on cones); [`seams`] splits parts into courses
//! and courses into plates, staggering and clearing the seams, and checks
//! loop validity; [`plates`] cuts the plates with their openings;
//! [`plate_dxf`] writes one DXF per plate and [`template_dxf`] one per pad
//! and neck template; [`oblique`] develops eccentric reducers; [`boot`]
//! develops a boot's plates from its host end; [`head_map`] maps head
//! openings onto the head blanks, which [`blank_dxf`] draws; [`nest`] nests
//! plates, pads and blanks onto stock sheets. [`plan`] runs it and returns a [`FabPlan`];
//! [`plan_vessel`] does the same keeping what a previous plan of the vessel
//! still holds (the live model's flat patterns, `vessel_plan`).
//!
//! The process plan of one vessel ([`process::process_plan`]): its bill of
//! materials ([`bom`]), the weld map ([`welds`]: UW-3 categories, lengths on the
//! exact curves of [`weld_curves`], weld metal by the preparations of
//! [`weld_prep`]), and its operations in precedence levels ([`operations`],
//! [`levels`]) from the shop rules as data ([`shop_rules`],
//! `data/shop_rules.json`); written as a traveler ([`traveler`]), a weld-map GLB
//! ([`weld_glb`]) and sheet ([`weld_svg`]). `vesselcad build --fab` puts the
//! levels on the main GLB's part and nozzle nodes ([`scene_levels`]) and the
//! seams in it as lines ([`seam_glb`]).

pub mod blank_dxf;
pub mod bom;
pub mod boot;
pub mod cone_openings;
pub mod cut;
pub mod develop;
pub mod error;
pub mod head_map;
pub mod levels;
pub mod neck_axis;
pub mod nest;
pub mod oblique;
pub mod oblique_openings;
pub mod openings;
pub mod operations;
pub mod plan_error;
pub mod plate_dxf;
pub mod plate_size;
pub mod plates;
pub mod process;
pub mod process_files;
pub mod scene_levels;
pub mod seam_glb;
pub mod seams;
pub mod shop;
pub mod shop_rules;
pub mod template_dxf;
pub mod traveler;
pub mod vessel_plan;
pub mod weld_curves;
pub mod weld_glb;
pub mod weld_prep;
pub mod weld_svg;
pub mod welds;

pub use develop::{BLANK_RULE, BootShell, Developments, HeadBlank, Outline, Rolled, RolledKind};
pub use error::FabError;
pub use nest::{Nesting, Piece};
pub use openings::{NozzleCut, Openings};
pub use plan_error::PlanError;
pub use plates::Plate;
pub use process::{ProcessPlan, plan_process, process_plan};
pub use seams::{Course, SeamLayout};
pub use shop::{Attachment, Shop};
pub use shop_rules::ShopRules;
pub use vessel_plan::{FabPlan, FabWork, plan, plan_vessel};
